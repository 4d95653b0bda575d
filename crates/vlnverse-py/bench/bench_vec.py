"""Environment steps per second from Python: the native ``VectorEnv`` against Gymnasium's
``SyncVectorEnv`` and ``AsyncVectorEnv`` (one subprocess per environment) over ``VLNEnv``,
and the Rust-only rate, all with the default RGB-D rig (RGB 224x224, depth 256x256) in the
generated homes of a dataset, every environment following the teacher's action.

    python crates/vlnverse-py/bench/bench_vec.py datasets/tiny [--envs 1 8 32] [--steps 200]

Figures move with machine load: compare runs taken on the same idle machine.
"""

from __future__ import annotations

import argparse
import functools
import subprocess
import time
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np
import vlnverse


def rate(envs: Any, steps: int, n: int) -> float:
    """Steps/s of ``envs`` (a vector env) following the teacher, after a warm-up."""
    _, info = envs.reset(seed=0)
    for _ in range(10):
        _, _, _, _, info = envs.step(np.asarray(info["expert_action"]))
    t0 = time.perf_counter()
    for _ in range(steps):
        _, _, _, _, info = envs.step(np.asarray(info["expert_action"]))
    return n * steps / (time.perf_counter() - t0)


def make_single(dataset: str) -> Any:
    # A partial (not a lambda), so spawned worker processes can unpickle it.
    return functools.partial(vlnverse.VLNEnv, dataset, "fine", "train", mode="train")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("dataset")
    ap.add_argument("--envs", type=int, nargs="+", default=[1, 8, 32])
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--skip-async", action="store_true")
    ap.add_argument("--rust-exe", help="a built vec_env_rate example (default: cargo run)")
    a = ap.parse_args()
    root = Path(__file__).resolve().parents[3]
    print(f"{'envs':>5} {'native':>9} {'sync':>9} {'async':>9} {'rust':>9}  (steps/s)")
    for n in a.envs:
        native = vlnverse.make_vec(a.dataset, "fine", "train", num_envs=n, mode="train",
                                   copy=False)
        r_native = rate(native, a.steps, n)
        native.close()
        sync = gymnasium.vector.SyncVectorEnv([make_single(a.dataset)] * n)
        r_sync = rate(sync, max(a.steps // 4, 20), n)
        sync.close()
        r_async = float("nan")
        if not a.skip_async:
            # spawn: forking a process that runs native thread pools is unsafe.
            asy = gymnasium.vector.AsyncVectorEnv([make_single(a.dataset)] * n, context="spawn")
            r_async = rate(asy, max(a.steps // 4, 20), n)
            asy.close()
        cmd = [a.rust_exe] if a.rust_exe else [
            "cargo", "run", "-q", "--release", "-p", "vlnverse-eval", "--example",
            "vec_env_rate", "--"]
        out = subprocess.run([*cmd, a.dataset, str(n), str(a.steps)], cwd=root, check=True,
                             capture_output=True, text=True).stdout
        r_rust = float(out.split(":")[1].split()[0])
        print(f"{n:>5} {r_native:>9.0f} {r_sync:>9.0f} {r_async:>9.0f} {r_rust:>9.0f}",
              flush=True)


if __name__ == "__main__":
    main()
