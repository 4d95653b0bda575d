"""Training: offline teacher forcing and online imitation with schedule sampling.

Both write into a run folder ``OUT``: ``model.safetensors`` (+ ``model.json``) after every
epoch, ``train_state.safetensors`` (optimizer moments, random generators, epoch) so a killed
run resumes at its last finished epoch with the same numbers, ``train_config.json`` and
``train_log.jsonl`` (one line per epoch: loss, teacher fraction, steps, samples, wall time).
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from vlnverse_baselines.checkpoint import (
    CheckpointError,
    atomic_write_text,
    load_checkpoint,
    read_metadata,
    save_checkpoint,
    save_tensors,
)
from vlnverse_baselines.config import NUM_ACTIONS, ConfigError, ModelConfig, TrainConfig
from vlnverse_baselines.data import EpisodeRecorder, Trajectory, collate
from vlnverse_baselines.models import InstructionCache, Policy, build_model, count_parameters
from vlnverse_baselines.obs import SeqBatch, downsample_depth, downsample_rgb, step_batch
from vlnverse_baselines.schedule import mix_actions, teacher_probability

STATE_FORMAT = "vlnverse-baselines/train-state-1"

Log = Callable[[str], None]


def _stderr(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def imitation_loss(logits: torch.Tensor, batch: SeqBatch) -> torch.Tensor:
    """Cross-entropy against the teacher's actions, weighted (0 on padding / ignored steps),
    averaged over the weights."""
    ce = F.cross_entropy(logits.reshape(-1, logits.shape[-1]), batch.targets.reshape(-1),
                         reduction="none")
    w = batch.weights.reshape(-1)
    return (ce * w).sum() / w.sum().clamp(min=1e-6)


class Trainer:
    """Holds the model, optimizer, cosine schedule, generators and the run folder."""

    def __init__(self, model_config: ModelConfig, config: TrainConfig, out: str | os.PathLike[str],
                 *, fresh: bool = False, log: Log = _stderr) -> None:
        self.config = config.validate()
        self.out = Path(out)
        self.log = log
        torch.set_num_threads(config.threads)
        torch.manual_seed(config.seed)
        self.rng = np.random.default_rng(config.seed)
        if config.init:
            self.model: Policy = load_checkpoint(config.init)[0]
            if self.model.config.vocab_size != model_config.vocab_size:
                raise ConfigError(
                    f"init: {config.init} has a vocabulary of {self.model.config.vocab_size} "
                    f"words, the dataset {model_config.vocab_size}")
        else:
            self.model = build_model(model_config)
        self.model.train()
        self.optimizer = torch.optim.AdamW(self.model.parameters(), lr=config.lr,
                                           weight_decay=config.weight_decay)
        self.total_updates = 1
        self.update = 0
        self.epoch = 0
        self.out.mkdir(parents=True, exist_ok=True)
        self._open_run(fresh)

    # -- run folder ----------------------------------------------------------------------

    def _identity(self) -> str:
        c = json.loads(self.config.to_json())
        c.pop("threads", None)
        return json.dumps({"train": c, "model": json.loads(self.model.config.to_json())},
                          sort_keys=True)

    def _open_run(self, fresh: bool) -> None:
        state_path = self.out / "train_state.safetensors"
        if fresh:
            for name in ("train_state.safetensors", "train_log.jsonl", "model.safetensors",
                         "model.json"):
                (self.out / name).unlink(missing_ok=True)
        if state_path.exists():
            meta = read_metadata(state_path)
            if meta.get("format") != STATE_FORMAT or meta.get("identity") != self._identity():
                raise CheckpointError(
                    f"{state_path}: this folder holds a run with another configuration; "
                    "pass --fresh to start over or choose another --out")
            self._restore(state_path, meta)
            self.log(f"train: resuming {self.out} at epoch {self.epoch}")
        atomic_write_text(self.out / "train_config.json", json.dumps(
            {"train": json.loads(self.config.to_json()),
             "model": json.loads(self.model.config.to_json()),
             "parameters": count_parameters(self.model)}, indent=1, sort_keys=True))

    def _restore(self, path: Path, meta: dict[str, str]) -> None:
        from safetensors.torch import load_file

        tensors = load_file(str(path))
        model = {k[len("model."):]: v for k, v in tensors.items() if k.startswith("model.")}
        self.model.load_state_dict(model, strict=True)
        opt = self.optimizer.state_dict()
        groups = json.loads(meta["param_groups"])
        state: dict[int, dict[str, torch.Tensor]] = {}
        for k, v in tensors.items():
            if k.startswith("opt."):
                _, idx, name = k.split(".", 2)
                state.setdefault(int(idx), {})[name] = v
        opt["state"] = state
        opt["param_groups"] = groups
        self.optimizer.load_state_dict(opt)
        torch.set_rng_state(tensors["rng.torch"])
        self.rng.bit_generator.state = json.loads(meta["rng_numpy"])
        self.epoch = int(meta["epoch"])
        self.update = int(meta["update"])

    def _save(self, info: dict[str, Any]) -> None:
        save_checkpoint(self.out / "model.safetensors", self.model, info)
        tensors: dict[str, torch.Tensor] = {
            f"model.{k}": v for k, v in self.model.state_dict().items()}
        opt = self.optimizer.state_dict()
        for idx, st in opt["state"].items():
            for name, v in st.items():
                tensors[f"opt.{idx}.{name}"] = torch.as_tensor(v)
        tensors["rng.torch"] = torch.get_rng_state()
        meta = {"format": STATE_FORMAT, "identity": self._identity(),
                "param_groups": json.dumps(opt["param_groups"]),
                "rng_numpy": json.dumps(self.rng.bit_generator.state),
                "epoch": str(self.epoch), "update": str(self.update)}
        save_tensors(self.out / "train_state.safetensors", tensors, meta)

    def _log_epoch(self, record: dict[str, Any]) -> None:
        line = json.dumps(record, sort_keys=True)
        with open(self.out / "train_log.jsonl", "a", encoding="utf-8") as f:
            f.write(line + "\n")
        self.log(f"train: epoch {record['epoch']}: loss {record['loss']:.4f}, "
                 f"{record.get('samples', 0)} samples, {record['wall_s']:.1f} s")

    # -- optimisation --------------------------------------------------------------------

    def lr_at(self, update: int) -> float:
        """Cosine annealing from ``lr`` to 0 over all updates (constant without ``cosine``)."""
        base = self.config.lr
        if not self.config.cosine:
            return base
        return 0.5 * base * (1.0 + math.cos(math.pi * min(update, self.total_updates)
                                            / self.total_updates))

    def step(self, loss: torch.Tensor) -> None:
        """One AdamW update at the scheduled learning rate."""
        for group in self.optimizer.param_groups:
            group["lr"] = self.lr_at(self.update)
        self.optimizer.zero_grad(set_to_none=True)
        loss.backward()  # type: ignore[no-untyped-call]
        torch.nn.utils.clip_grad_norm_(self.model.parameters(), 10.0)
        self.optimizer.step()
        self.update += 1

    # -- offline -------------------------------------------------------------------------

    def fit_offline(self, trajectories: list[Trajectory]) -> list[dict[str, Any]]:
        """Teacher forcing over ``trajectories`` (each capped at ``max_steps``) for the
        remaining epochs; returns the epoch records."""
        c = self.config
        if not trajectories:
            raise ConfigError("offline training: no trajectories to train on")
        data = [t.capped(c.max_steps) for t in trajectories]
        per_epoch = math.ceil(len(data) / c.batch_size)
        self.total_updates = max(1, c.epochs * per_epoch)
        records = []
        while self.epoch < c.epochs:
            started = time.monotonic()
            order = self.rng.permutation(len(data))
            losses, samples = [], 0
            for k in range(per_epoch):
                chosen = [data[int(i)] for i in order[k * c.batch_size:(k + 1) * c.batch_size]]
                batch = collate(chosen, c.inflection_weight)
                logits, _ = self.model.forward_sequence(batch, self.model.initial_state(
                    batch.batch))
                loss = imitation_loss(logits, batch)
                self.step(loss)
                losses.append(float(loss.detach()))
                samples += int((batch.weights > 0).sum())
            self.epoch += 1
            rec = {"epoch": self.epoch, "mode": "offline", "loss": float(np.mean(losses)),
                   "samples": samples, "updates": self.update,
                   "wall_s": time.monotonic() - started, "lr": self.lr_at(self.update)}
            self._save({"epochs": self.epoch, "mode": "offline"})
            self._log_epoch(rec)
            records.append(rec)
        return records

    # -- online --------------------------------------------------------------------------

    def fit_online(self, envs: Any) -> list[dict[str, Any]]:
        """Imitation through ``envs`` (a ``vlnverse.VectorEnv`` in train mode) with schedule
        sampling, for the remaining epochs; returns the epoch records."""
        c = self.config
        self.total_updates = max(1, c.epochs * c.updates_per_epoch)
        buffer: deque[Trajectory] = deque(maxlen=c.dagger_capacity)
        records = []
        while self.epoch < c.epochs:
            rec = self._online_epoch(envs, buffer)
            self.epoch += 1
            self._save({"epochs": self.epoch, "mode": "online"})
            self._log_epoch(rec)
            records.append(rec)
        return records

    def _online_epoch(self, envs: Any, buffer: deque[Trajectory]) -> dict[str, Any]:
        c = self.config
        mc = self.model.config
        n = envs.num_envs
        p_teacher = teacher_probability(self.epoch, c.schedule_ratio, c.decay_every)
        started = time.monotonic()
        obs, infos = envs.reset(seed=c.seed * 100_003 + self.epoch)
        state = self.model.initial_state(n)
        prev = np.zeros(n, dtype=np.int64)
        pending = np.zeros(n, dtype=bool)
        recorder = EpisodeRecorder(n) if c.dagger else None
        losses: list[float] = []
        teacher_used = decisions = samples = env_steps = 0
        finished: list[dict[str, Any]] = []
        t_env = t_model = 0.0
        cache = InstructionCache()
        for _ in range(c.updates_per_epoch):
            chunk: dict[str, list[np.ndarray]] = {k: [] for k in (
                "rgb", "depth", "tokens", "prev", "starts", "targets", "weights")}
            state0 = state
            for _k in range(c.rollout_length):
                t0 = time.monotonic()
                rgb = downsample_rgb(np.asarray(obs["rgb"]), mc.rgb_size)
                depth = downsample_depth(np.asarray(obs["depth"]), mc.depth_size)
                tokens = np.asarray(obs["instruction_tokens"], dtype=np.int64)
                starts = np.asarray(infos["steps"]) == 0
                prev[starts] = 0
                teacher = np.asarray(infos["expert_action"], dtype=np.int64)
                valid = ~pending & (teacher >= 0) & (teacher < NUM_ACTIONS)
                policy, state = self._act(rgb, depth, tokens, prev, starts, state, cache)
                actions, used = mix_actions(np.clip(teacher, 0, NUM_ACTIONS - 1), policy,
                                            p_teacher, self.rng)
                teacher_used += int(used[valid].sum())
                decisions += int(valid.sum())
                for key, v in (("rgb", rgb), ("depth", depth), ("tokens", tokens),
                               ("prev", prev.copy()), ("starts", starts),
                               ("targets", np.clip(teacher, 0, NUM_ACTIONS - 1)),
                               ("weights", valid.astype(np.float32))):
                    chunk[key].append(v)
                if recorder is not None:
                    ids = np.asarray(infos["episode_id"])
                    for i in np.flatnonzero(valid):
                        recorder.add(int(i), int(ids[i]), rgb[i], depth[i], tokens[i],
                                     int(teacher[i]), int(prev[i]))
                prev = actions + 1
                t1 = time.monotonic()
                obs, _, term, trunc, infos = envs.step(actions)
                t_env += time.monotonic() - t1
                t_model += t1 - t0
                env_steps += n
                pending = term | trunc
                for i in np.flatnonzero(pending):
                    if "metrics" in infos and infos["_metrics"][i]:
                        finished.append(dict(infos["metrics"][i]))
                    if recorder is not None:
                        tr = recorder.finish(int(i))
                        if tr is not None:
                            buffer.append(tr.capped(c.max_steps))
            t0 = time.monotonic()
            batch = SeqBatch(*(torch.from_numpy(np.stack(chunk[k])) for k in (
                "rgb", "depth", "tokens", "prev", "starts", "targets", "weights")))
            loss, n_samples = self._update(batch, state0, buffer)
            samples += n_samples
            cache.clear()  # the weights changed
            losses.append(loss)
            t_model += time.monotonic() - t0
        wall = time.monotonic() - started
        rec: dict[str, Any] = {
            "epoch": self.epoch + 1, "mode": "online", "loss": float(np.mean(losses)),
            "p_teacher": p_teacher, "teacher_used": teacher_used, "decisions": decisions,
            "teacher_fraction": teacher_used / max(1, decisions), "env_steps": env_steps,
            "samples": samples, "updates": self.update, "wall_s": wall,
            "env_s": t_env, "model_s": t_model, "lr": self.lr_at(self.update),
            "episodes_finished": len(finished), "dagger_buffer": len(buffer),
        }
        if finished:
            for key in ("success", "ne", "spl"):
                # `ne` is None for an episode that ended where the goal cannot be reached.
                vals = [float(m[key]) for m in finished if m.get(key) is not None]
                if vals:
                    rec[f"mean_{key}"] = float(np.mean(vals))
        return rec

    @torch.no_grad()
    def _act(self, rgb: np.ndarray, depth: np.ndarray, tokens: np.ndarray, prev: np.ndarray,
             starts: np.ndarray, state: torch.Tensor, cache: InstructionCache
             ) -> tuple[np.ndarray, torch.Tensor]:
        """The policy's greedy action for every environment (no gradient)."""
        logits, state = self.model.forward_sequence(
            step_batch(rgb, depth, tokens, prev, starts), state, cache=cache)
        return logits[0].argmax(dim=1).numpy().astype(np.int64), state

    def _update(self, batch: SeqBatch, state0: torch.Tensor, buffer: deque[Trajectory]
                ) -> tuple[float, int]:
        """One update on the rollout just collected (from its initial recurrent state), plus
        a teacher-forced batch of aggregated episodes with DAgger; returns loss, samples."""
        c = self.config
        logits, _ = self.model.forward_sequence(batch, state0)
        loss = imitation_loss(logits, batch)
        samples = int((batch.weights > 0).sum())
        if c.dagger and len(buffer) >= c.dagger_batch:
            picks = self.rng.choice(len(buffer), size=c.dagger_batch, replace=False)
            replay = collate([buffer[int(i)] for i in picks], c.inflection_weight)
            r_logits, _ = self.model.forward_sequence(replay, self.model.initial_state(
                replay.batch))
            loss = loss + imitation_loss(r_logits, replay)
            samples += int((replay.weights > 0).sum())
        self.step(loss)
        return float(loss.detach()), samples


def read_vocab(dataset: str) -> tuple[int, str]:
    """Size and SHA-256 of ``DIR/vocab.txt`` (the token ids of every instruction)."""
    import hashlib

    path = Path(dataset) / "vocab.txt"
    if not path.is_file():
        raise ConfigError(f"{path}: no vocabulary file (generate the dataset with "
                          "`cargo xtask generate`, which writes it)")
    data = path.read_bytes()
    words = data.decode("utf-8").splitlines()
    return len(words), hashlib.sha256(data).hexdigest()
