"""``python -m vlnverse_baselines train|evaluate|info``.

train: ``--model seq2seq|cma --task T --dataset DIR --out RUN`` with ``--mode online`` (the
vector env, schedule sampling) or ``--mode offline --data EXPORT`` (a ``cargo xtask export
--format lerobot`` folder; ``--data render`` renders the teacher trajectories in memory
instead). evaluate: ``--checkpoint CKPT --dataset DIR --task T --split S --out RUN`` writes the
standard run folder through ``vlnverse.evaluate``. Errors print one line and exit 2."""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

from vlnverse_baselines.config import MODELS, ConfigError, ModelConfig, TrainConfig


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m vlnverse_baselines",
                                description="Seq2Seq and CMA baselines for VLNVerse-rs")
    sub = p.add_subparsers(dest="command", required=True)

    t = sub.add_parser("train", help="train a policy (online or offline)")
    t.add_argument("--model", required=True, help=f"one of {', '.join(MODELS)}")
    t.add_argument("--dataset", required=True, help="dataset folder (cargo xtask generate)")
    t.add_argument("--task", default="fine")
    t.add_argument("--split", default="train")
    t.add_argument("--out", required=True, help="run folder (resumed if it exists)")
    t.add_argument("--mode", default="online", choices=("online", "offline"))
    t.add_argument("--data", default="",
                   help="offline: a LeRobot export folder (cargo xtask export), or 'render'")
    t.add_argument("--setting", default="telhop", choices=("telhop", "strict", "lenient"))
    t.add_argument("--epochs", type=int, default=20)
    t.add_argument("--updates-per-epoch", type=int, default=50,
                   help="online: updates per epoch")
    t.add_argument("--rollout-length", type=int, default=32,
                   help="online: environment steps per update (truncated BPTT)")
    t.add_argument("--num-envs", type=int, default=4)
    t.add_argument("--home-repeat", type=int, default=32,
                   help="online: episodes an environment runs in one home before it draws "
                        "another (1: every episode drawn from the whole split)")
    t.add_argument("--batch-size", type=int, default=4, help="offline: trajectories per update")
    t.add_argument("--lr", type=float, default=1e-4)
    t.add_argument("--no-cosine", action="store_true", help="constant learning rate")
    t.add_argument("--schedule-ratio", type=float, default=0.85)
    t.add_argument("--decay-every", type=int, default=4)
    t.add_argument("--max-steps", type=int, default=200)
    t.add_argument("--inflection-weight", type=float, default=1.0)
    t.add_argument("--dagger", action="store_true", help="online: aggregate visited episodes")
    t.add_argument("--episodes", type=int, default=None,
                   help="train on the split's first N episodes only")
    t.add_argument("--init", default="", help="start from this checkpoint (fine-tuning)")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--threads", type=int, default=1,
                   help="torch threads (1 is fastest on a shared 2-core machine)")
    t.add_argument("--hidden", type=int, default=128)
    t.add_argument("--rgb-size", type=int, default=56)
    t.add_argument("--depth-size", type=int, default=64)
    t.add_argument("--fresh", action="store_true", help="start over in an existing --out")

    e = sub.add_parser("evaluate", help="evaluate a checkpoint into a run folder")
    e.add_argument("--checkpoint", required=True)
    e.add_argument("--dataset", required=True)
    e.add_argument("--task", default="fine")
    e.add_argument("--split", default="val_unseen")
    e.add_argument("--out", required=True)
    e.add_argument("--setting", default="telhop")
    e.add_argument("--num-envs", type=int, default=4)
    e.add_argument("--episodes", type=int, default=None)
    e.add_argument("--sample", type=int, default=None)
    e.add_argument("--seed", type=int, default=0)
    e.add_argument("--threads", type=int, default=1)
    e.add_argument("--name", default=None, help="agent name in the run folder")
    e.add_argument("--fresh", action="store_true")

    i = sub.add_parser("info", help="print a checkpoint's config and size")
    i.add_argument("checkpoint")
    return p


def _episode_ids(dataset: str, task: str, split: str, first: int | None) -> list[int] | None:
    if first is None:
        return None
    import vlnverse

    eps = vlnverse.load_episodes(dataset, task, split)
    return [int(ep["episode_id"]) for ep in eps[:first]]


def train(args: argparse.Namespace) -> int:
    """The ``train`` command."""
    from vlnverse_baselines.train import Trainer, read_vocab

    if args.model not in MODELS:
        raise ConfigError(f"--model: unknown model {args.model!r}; expected one of "
                          f"{', '.join(MODELS)}")
    vocab_size, vocab_sha = read_vocab(args.dataset)
    mc = ModelConfig(model=args.model, vocab_size=vocab_size, vocab_sha256=vocab_sha,
                     hidden=args.hidden, rgb_size=args.rgb_size,
                     depth_size=args.depth_size).validate()
    if args.mode == "offline" and not args.data:
        raise ConfigError("--data: offline training needs a LeRobot export folder "
                          "(cargo xtask export --format lerobot) or 'render'")
    tc = TrainConfig(mode=args.mode, dataset=str(args.dataset), task=args.task, split=args.split,
                     setting=args.setting, data=args.data, epochs=args.epochs,
                     updates_per_epoch=args.updates_per_epoch,
                     rollout_length=args.rollout_length, num_envs=args.num_envs,
                     home_repeat=args.home_repeat,
                     batch_size=args.batch_size, lr=args.lr, cosine=not args.no_cosine,
                     schedule_ratio=args.schedule_ratio, decay_every=args.decay_every,
                     max_steps=args.max_steps, inflection_weight=args.inflection_weight,
                     dagger=args.dagger, episodes=args.episodes, seed=args.seed,
                     threads=args.threads, init=args.init).validate()
    started = time.monotonic()
    trainer = Trainer(mc, tc, args.out, fresh=args.fresh)
    ids = _episode_ids(args.dataset, args.task, args.split, args.episodes)
    if args.mode == "offline":
        from vlnverse_baselines.data import render_teacher_trajectories

        if args.data == "render":
            trajs = render_teacher_trajectories(
                args.dataset, args.task, args.split, rgb_size=mc.rgb_size,
                depth_size=mc.depth_size, episode_ids=ids, setting=args.setting,
                max_steps=args.max_steps, seed=args.seed)
        else:
            from vlnverse_baselines.lerobot_data import load_lerobot_trajectories

            trajs = load_lerobot_trajectories(args.data, rgb_size=mc.rgb_size,
                                              depth_size=mc.depth_size, episodes=args.episodes)
        print(f"train: {len(trajs)} trajectories, {sum(len(t) for t in trajs)} frames",
              file=sys.stderr)
        trainer.fit_offline(trajs)
    else:
        import vlnverse

        envs = vlnverse.VectorEnv(args.dataset, args.task, args.split, num_envs=args.num_envs,
                                  mode="train", setting=args.setting, max_steps=args.max_steps,
                                  seed=args.seed, episode_ids=ids, copy=False,
                                  home_repeat=tc.home_repeat)
        try:
            trainer.fit_online(envs)
        finally:
            envs.close()
    print(json.dumps({"checkpoint": str(Path(args.out) / "model.safetensors"),
                      "epochs": trainer.epoch, "updates": trainer.update,
                      "wall_s": round(time.monotonic() - started, 1)}))
    return 0


def evaluate(args: argparse.Namespace) -> int:
    """The ``evaluate`` command."""
    import torch
    import vlnverse

    from vlnverse_baselines.agent import PolicyAgent
    from vlnverse_baselines.checkpoint import file_sha256, load_checkpoint
    from vlnverse_baselines.train import read_vocab

    torch.set_num_threads(args.threads)
    model, _ = load_checkpoint(args.checkpoint)
    vocab_size, vocab_sha = read_vocab(args.dataset)
    want = model.config.vocab_sha256
    if want and want != vocab_sha:
        raise ConfigError(
            f"{args.checkpoint}: trained with another vocabulary (sha256 {want[:12]}, "
            f"{model.config.vocab_size} words) than {args.dataset}/vocab.txt "
            f"(sha256 {vocab_sha[:12]}, {vocab_size} words)")
    name = args.name or model.config.model
    agent = PolicyAgent(model, name=name)
    summary: dict[str, Any] = vlnverse.evaluate(
        agent, dataset=args.dataset, task=args.task, split=args.split, setting=args.setting,
        out=args.out, num_envs=args.num_envs, seed=args.seed, episodes=args.episodes,
        sample=args.sample, name=name, version=file_sha256(args.checkpoint)[:16],
        fresh=args.fresh)
    print(json.dumps(summary, sort_keys=True))
    return 0


def info(args: argparse.Namespace) -> int:
    """The ``info`` command."""
    from vlnverse_baselines.checkpoint import load_checkpoint
    from vlnverse_baselines.models import count_parameters

    model, extra = load_checkpoint(args.checkpoint)
    print(json.dumps({"config": json.loads(model.config.to_json()), "info": extra,
                      "parameters": count_parameters(model)}, indent=1, sort_keys=True))
    return 0


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = _parser().parse_args(argv)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    try:
        if args.command == "train":
            return train(args)
        if args.command == "evaluate":
            return evaluate(args)
        return info(args)
    except (ValueError, OSError) as e:  # VLNVerseError, ConfigError, CheckpointError are these
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted (the run folder keeps the last finished epoch)", file=sys.stderr)
        return 130
