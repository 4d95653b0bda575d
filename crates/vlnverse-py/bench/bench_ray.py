"""Overhead of the Ray path against the plain CLI on this machine: generation of a preset as
one run, shard by shard, and through ``vlnverse.distributed.generate`` on a local Ray cluster;
evaluation of a split with ``vlnverse.evaluate`` and ``vlnverse.distributed.evaluate``.

    python crates/vlnverse-py/bench/bench_ray.py [--preset vlnverse] [--shards 4] \
        [--xtask target/release/xtask] [--dataset datasets/tiny]

Figures move with machine load: compare runs taken on the same idle machine.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import ray
import vlnverse
from vlnverse import distributed


def timed(cmd: list[str]) -> float:
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="vlnverse")
    ap.add_argument("--shards", type=int, default=4)
    ap.add_argument("--xtask", default="target/release/xtask")
    ap.add_argument("--dataset", default="datasets/tiny", help="for the evaluation figures")
    ap.add_argument("--cpus", type=int, default=2)
    a = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench_ray_"))
    try:
        single = timed([a.xtask, "generate", "--preset", a.preset, "--out", str(tmp / "one")])
        per_shard = [
            timed([a.xtask, "generate", "--preset", a.preset, "--threads", "1", "--shard",
                   f"{k}/{a.shards}", "--out", str(tmp / f"s{k}")])
            for k in range(a.shards)
        ]
        parts = [str(tmp / f"s{k}") for k in range(a.shards)]
        merge = timed([a.xtask, "merge", "--out", str(tmp / "merged"), *parts])
        t = time.perf_counter()
        ray.init(num_cpus=a.cpus, log_to_driver=False)
        ray_start = time.perf_counter() - t
        r = distributed.generate(tmp / "ray", a.preset, shards=a.shards, progress=False)
        print(f"generate {a.preset}: CLI one run {single:.2f} s; CLI shards (1 thread each) "
              f"{', '.join(f'{s:.2f}' for s in per_shard)} s (sum {sum(per_shard):.2f} s) + "
              f"merge {merge:.2f} s; Ray start {ray_start:.2f} s, Ray {a.shards} shards on "
              f"{a.cpus} CPUs {r['seconds']:.2f} s (tasks + merge)")
        ev = {"dataset": a.dataset, "task": "fine", "split": "val_unseen", "setting": "telhop",
              "render": True, "progress": False}
        t = time.perf_counter()
        vlnverse.evaluate(vlnverse.TeacherAgent(), out=tmp / "ev1", num_envs=4, **ev)
        one = time.perf_counter() - t
        t = time.perf_counter()
        distributed.evaluate(vlnverse.TeacherAgent, out=tmp / "ev2", workers=a.cpus,
                             num_envs=2, chunk=4, **ev)
        dist = time.perf_counter() - t
        print(f"evaluate {a.dataset} fine val_unseen (RGB-D): vlnverse.evaluate {one:.2f} s; "
              f"distributed.evaluate ({a.cpus} actors) {dist:.2f} s")
    finally:
        ray.shutdown()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
