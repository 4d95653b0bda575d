"""Online training throughput: environment steps/s and training samples/s with N environments,
and where the time goes, measured with cProfile (cumulative time of each function):

- ``VectorEnv.step``: the native step (simulation + rendering in Rust, GIL released);
- ``downsample_rgb`` / ``downsample_depth``: shrinking the observations for the encoders;
- ``Trainer._act``: the policy's forward pass while acting (no gradient);
- ``Trainer._update``: the training update (forward over the rollout, backward, AdamW);
- the rest: Python glue (schedule sampling, rollout bookkeeping, infos).

    python baselines/bench/bench_train.py target/py-test-data/tiny --envs 4 16 --updates 10
"""

from __future__ import annotations

import argparse
import cProfile
import json
import os
import pstats
import sys
import tempfile
import time
from typing import Any

import torch
import vlnverse

from vlnverse_baselines import ModelConfig, TrainConfig
from vlnverse_baselines.models import count_parameters
from vlnverse_baselines.train import Trainer, read_vocab

#: (label, [(file suffix, function name), ...]): disjoint parts of an online epoch.
PARTS = (
    ("native env step", [("vector.py", "step")]),
    ("downsampling", [("obs.py", "downsample_rgb"), ("obs.py", "downsample_depth")]),
    ("policy acting", [("train.py", "_act")]),
    ("training update", [("train.py", "_update")]),
)


def _cumulative(stats: pstats.Stats, keys: list[tuple[str, str]]) -> float:
    raw: dict[Any, Any] = stats.stats  # type: ignore[attr-defined]
    total = 0.0
    for (file, _line, name), (_cc, _nc, _tt, ct, _callers) in raw.items():
        if any(file.endswith(f) and name == n for f, n in keys):
            total += ct
    return total


def bench(dataset: str, task: str, model: str, num_envs: int, updates: int, rollout: int,
          setting: str) -> dict[str, Any]:
    """One online epoch of ``updates`` updates; returns the rates and the time split."""
    size, sha = read_vocab(dataset)
    mc = ModelConfig(model=model, vocab_size=size, vocab_sha256=sha)
    tc = TrainConfig(mode="online", epochs=1, updates_per_epoch=updates, rollout_length=rollout,
                     num_envs=num_envs, setting=setting, seed=0, threads=torch.get_num_threads())
    with tempfile.TemporaryDirectory() as out:
        trainer = Trainer(mc, tc, out, log=lambda _: None)
        envs = vlnverse.VectorEnv(dataset, task, "train", num_envs=num_envs, mode="train",
                                  setting=setting, seed=0, copy=False)
        prof = cProfile.Profile()
        started = time.perf_counter()
        prof.enable()
        rec = trainer.fit_online(envs)[0]
        prof.disable()
        wall = time.perf_counter() - started
        envs.close()
    stats = pstats.Stats(prof)
    parts = {label: _cumulative(stats, keys) for label, keys in PARTS}
    parts["python glue (rest)"] = max(0.0, wall - sum(parts.values()))
    return {
        "model": model, "parameters": count_parameters(trainer.model), "num_envs": num_envs,
        "updates": updates, "rollout_length": rollout, "env_steps": rec["env_steps"],
        "samples": rec["samples"], "wall_s": wall, "env_steps_per_s": rec["env_steps"] / wall,
        "samples_per_s": rec["samples"] / wall, "time_s": parts,
        "time_share": {k: v / wall for k, v in parts.items()},
    }


def main() -> int:
    """Print a markdown table (and one JSON line per run on stderr)."""
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dataset")
    p.add_argument("--task", default="fine")
    p.add_argument("--model", default="cma")
    p.add_argument("--envs", type=int, nargs="+", default=[4, 16])
    p.add_argument("--updates", type=int, default=10)
    p.add_argument("--rollout", type=int, default=32)
    p.add_argument("--setting", default="telhop")
    p.add_argument("--threads", type=int, default=1)
    a = p.parse_args()
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    torch.set_num_threads(a.threads)
    labels = [label for label, _ in PARTS] + ["python glue (rest)"]
    print("| envs | env steps/s | samples/s | " + " | ".join(labels) + " |")
    print("|---" * (3 + len(labels)) + "|")
    for n in a.envs:
        r = bench(a.dataset, a.task, a.model, n, a.updates, a.rollout, a.setting)
        print(json.dumps(r), file=sys.stderr)
        shares = " | ".join(f"{r['time_share'][k]:.0%}" for k in labels)
        print(f"| {n} | {r['env_steps_per_s']:.0f} | {r['samples_per_s']:.0f} | {shares} |",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
