"""Trajectories for teacher forcing: from a LeRobot export, or rendered through the vector env.

A ``Trajectory`` is one episode's frames (downsampled), the instruction tokens, the teacher's
action at every frame and the action executed before each frame (the teacher's own in offline
data, the schedule-sampled one in online/DAgger data)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import torch

from vlnverse_baselines.config import NUM_ACTIONS
from vlnverse_baselines.obs import SeqBatch, downsample_depth, downsample_rgb


@dataclass
class Trajectory:
    """One episode: ``T`` frames, teacher actions and previous actions (0 = start)."""

    episode_id: int
    rgb: np.ndarray  # uint8 [T, h, w, 3]
    depth: np.ndarray  # float16 [T, h, w, 1]
    tokens: np.ndarray  # int64 [L]
    actions: np.ndarray  # int64 [T], the teacher's
    prev_actions: np.ndarray  # int64 [T], 0 then executed action + 1

    def __len__(self) -> int:
        return int(self.actions.shape[0])

    def capped(self, max_steps: int) -> Trajectory:
        """The first ``max_steps`` frames."""
        if len(self) <= max_steps:
            return self
        return Trajectory(self.episode_id, self.rgb[:max_steps], self.depth[:max_steps],
                          self.tokens, self.actions[:max_steps], self.prev_actions[:max_steps])


def teacher_prev_actions(actions: np.ndarray) -> np.ndarray:
    """Previous-action inputs under teacher forcing: 0, then ``actions[:-1] + 1``."""
    prev = np.zeros_like(actions, dtype=np.int64)
    prev[1:] = actions[:-1] + 1
    return prev


def inflection_weights(actions: np.ndarray, weight: float) -> np.ndarray:
    """VLN-CE's inflection weighting: ``weight`` where the teacher's action changes (and at
    the first step), 1 elsewhere."""
    w = np.ones(actions.shape[0], dtype=np.float32)
    if weight != 1.0 and actions.shape[0]:
        change = np.ones(actions.shape[0], dtype=bool)
        change[1:] = actions[1:] != actions[:-1]
        w[change] = weight
    return w


def collate(trajectories: list[Trajectory], inflection_weight: float = 1.0) -> SeqBatch:
    """Pad ``B`` trajectories to the longest (time first); padding has weight 0."""
    if not trajectories:
        raise ValueError("collate: no trajectories")
    t = max(len(tr) for tr in trajectories)
    b = len(trajectories)
    first = trajectories[0]
    rgb = np.zeros((t, b, *first.rgb.shape[1:]), dtype=np.uint8)
    depth = np.zeros((t, b, *first.depth.shape[1:]), dtype=np.float16)
    tokens = np.zeros((t, b, first.tokens.shape[0]), dtype=np.int64)
    prev = np.zeros((t, b), dtype=np.int64)
    starts = np.zeros((t, b), dtype=bool)
    targets = np.zeros((t, b), dtype=np.int64)
    weights = np.zeros((t, b), dtype=np.float32)
    for j, tr in enumerate(trajectories):
        n = len(tr)
        rgb[:n, j], depth[:n, j] = tr.rgb, tr.depth
        tokens[:n, j] = tr.tokens[None, :]
        prev[:n, j], targets[:n, j] = tr.prev_actions, tr.actions
        weights[:n, j] = inflection_weights(tr.actions, inflection_weight)
        starts[0, j] = True
    return SeqBatch(torch.from_numpy(rgb), torch.from_numpy(depth), torch.from_numpy(tokens),
                    torch.from_numpy(prev), torch.from_numpy(starts), torch.from_numpy(targets),
                    torch.from_numpy(weights))


class EpisodeRecorder:
    """Accumulates each environment's frames of the running episode (for DAgger and for
    rendering teacher trajectories); ``finish(i)`` returns environment ``i``'s trajectory."""

    def __init__(self, num_envs: int) -> None:
        self.frames: list[list[tuple[np.ndarray, np.ndarray, int, int]]] = [
            [] for _ in range(num_envs)]
        self.tokens: list[np.ndarray | None] = [None] * num_envs
        self.episode: list[int] = [-1] * num_envs

    def add(self, i: int, episode_id: int, rgb: np.ndarray, depth: np.ndarray,
            tokens: np.ndarray, teacher: int, prev: int) -> None:
        """Record one frame of environment ``i`` (a new episode id restarts its list)."""
        if self.episode[i] != episode_id:
            self.frames[i] = []
            self.episode[i] = episode_id
            self.tokens[i] = np.array(tokens, dtype=np.int64)
        self.frames[i].append((rgb, depth, teacher, prev))

    def finish(self, i: int) -> Trajectory | None:
        """Environment ``i``'s episode as a trajectory (None if nothing was recorded)."""
        frames, tokens, episode = self.frames[i], self.tokens[i], self.episode[i]
        self.frames[i] = []
        self.episode[i] = -1
        if not frames or tokens is None:
            return None
        return Trajectory(
            episode_id=episode,
            rgb=np.stack([f[0] for f in frames]),
            depth=np.stack([f[1] for f in frames]),
            tokens=tokens,
            actions=np.array([f[2] for f in frames], dtype=np.int64),
            prev_actions=np.array([f[3] for f in frames], dtype=np.int64),
        )


def render_teacher_trajectories(dataset: str, task: str, split: str, *, rgb_size: int,
                                depth_size: int, episode_ids: list[int] | None = None,
                                setting: str = "telhop", max_steps: int = 200,
                                num_envs: int = 4, seed: int = 0) -> list[Trajectory]:
    """Follow the teacher through each episode once (eval order) and record the downsampled
    frames: the offline data without an export (what ``cargo xtask export`` writes, in
    memory). Returns the trajectories sorted by episode id."""
    import vlnverse

    envs = vlnverse.VectorEnv(dataset, task, split, num_envs=num_envs, mode="eval",
                              setting=setting, max_steps=max_steps, seed=seed,
                              episode_ids=episode_ids, copy=False)
    try:
        total = len(episode_ids) if episode_ids is not None else len(
            vlnverse.load_episodes(dataset, task, split))
        envs = _shrink(envs, total, dataset, task, split, setting, max_steps, seed, episode_ids)
        return _record_teacher(envs, total, rgb_size, depth_size, seed)
    finally:
        envs.close()


def _shrink(envs: Any, total: int, dataset: str, task: str, split: str, setting: str,
            max_steps: int, seed: int, episode_ids: list[int] | None) -> Any:
    """Fewer environments than episodes: a second pass would otherwise start early."""
    import vlnverse

    if envs.num_envs <= total:
        return envs
    envs.close()
    return vlnverse.VectorEnv(dataset, task, split, num_envs=total, mode="eval", setting=setting,
                              max_steps=max_steps, seed=seed, episode_ids=episode_ids,
                              copy=False)


def _record_teacher(envs: Any, total: int, rgb_size: int, depth_size: int,
                    seed: int) -> list[Trajectory]:
    obs, infos = envs.reset(seed=seed)
    n = envs.num_envs
    rec = EpisodeRecorder(n)
    prev = np.zeros(n, dtype=np.int64)
    pending = np.zeros(n, dtype=bool)
    done: dict[int, Trajectory] = {}
    while len(done) < total:
        rgb = downsample_rgb(np.asarray(obs["rgb"]), rgb_size)
        depth = downsample_depth(np.asarray(obs["depth"]), depth_size)
        teacher = np.asarray(infos["expert_action"], dtype=np.int64)
        steps = np.asarray(infos["steps"])
        for i in range(n):
            if pending[i] or int(infos["pass"][i]) > 0:
                continue
            if steps[i] == 0:
                prev[i] = 0
            a = int(teacher[i]) if 0 <= int(teacher[i]) < NUM_ACTIONS else 0
            rec.add(i, int(infos["episode_id"][i]), rgb[i], depth[i],
                    obs["instruction_tokens"][i], a, int(prev[i]))
        actions = np.clip(teacher, 0, NUM_ACTIONS - 1)
        prev = actions + 1
        ids = np.asarray(infos["episode_id"]).copy()
        obs, _, term, trunc, infos = envs.step(actions)
        pending = term | trunc
        for i in np.flatnonzero(pending):
            tr = rec.finish(int(i))
            if tr is not None and int(ids[i]) not in done:
                tr.episode_id = int(ids[i])
                done[int(ids[i])] = tr
    return [done[k] for k in sorted(done)]
