"""``vlnverse.distributed`` on a local Ray cluster (a head and two worker nodes on this
machine): results identical to single-machine runs, also when a worker is killed mid-job."""

from __future__ import annotations

import os
import signal
import subprocess
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import vlnverse
from vlnverse import distributed

from .conftest import ROOT, xtask
from .test_generate import _same_tree

ray = pytest.importorskip("ray")


@pytest.fixture(scope="module")
def cluster() -> Iterator[Any]:
    from ray.cluster_utils import Cluster

    c = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    c.add_node(num_cpus=1)
    c.add_node(num_cpus=1)
    ray.init(address=c.address, log_to_driver=False)
    yield c
    ray.shutdown()
    c.shutdown()


def _kill_first(title: str, timeout: float = 60.0) -> int:
    """SIGKILL the first process whose title (Ray sets ``ray::<function>``) starts with
    ``title``; returns its pid."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        for pid in os.listdir("/proc"):
            if not pid.isdigit():
                continue
            try:
                cmd = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
            except OSError:
                continue
            if cmd.startswith(title):
                os.kill(int(pid), signal.SIGKILL)
                return int(pid)
        time.sleep(0.05)
    raise AssertionError(f"no process {title!r} appeared")


def test_distributed_generate_equals_a_single_run(cluster: Any, dataset: Path,
                                                  tmp_path: Path) -> None:
    out = tmp_path / "ray"
    s = distributed.generate(out, "tiny", shards=3, progress=False)
    assert s["shards"] == 3 and s["episodes"] > 0
    assert _same_tree(dataset, out) == []
    assert not Path(f"{out}.shards").exists(), "shard folders are removed after the merge"


def test_a_killed_generation_worker_is_retried(cluster: Any, dataset: Path,
                                               tmp_path: Path) -> None:
    out = tmp_path / "ray_killed"
    result: dict[str, Any] = {}

    def run() -> None:
        result.update(distributed.generate(out, "tiny", shards=2, progress=False,
                                           _scene_delay=0.4))

    t = threading.Thread(target=run)
    t.start()
    # Wait until a shard has written a scene, then kill that worker.
    end = time.monotonic() + 60
    while time.monotonic() < end and not list(Path(f"{out}.shards").glob("*/.parts/*/*.json")):
        time.sleep(0.05)
    _kill_first("ray::_generate_shard")
    t.join(timeout=300)
    assert not t.is_alive()
    assert result["episodes"] > 0
    assert _same_tree(dataset, out) == []


def _single(dataset: Path, out: Path) -> None:
    vlnverse.evaluate(vlnverse.TeacherAgent(), dataset=dataset, task="fine", split="val_unseen",
                      setting="telhop", out=out, num_envs=2, render=False, progress=False)


def _same_run(a: Path, b: Path) -> None:
    for f in ("summary.json", "episodes.csv", "trajectories.jsonl"):
        assert (a / f).read_bytes() == (b / f).read_bytes(), f


def test_distributed_evaluate_equals_a_single_run(cluster: Any, dataset: Path,
                                                  tmp_path: Path) -> None:
    single = tmp_path / "single"
    _single(dataset, single)
    out = tmp_path / "ray"
    s = distributed.evaluate(vlnverse.TeacherAgent, dataset=dataset, task="fine",
                             split="val_unseen", setting="telhop", out=out, workers=2,
                             num_envs=2, chunk=3, render=False, progress=False)
    assert s["episodes"] == 8
    _same_run(single, out)


def test_a_killed_evaluation_actor_leaves_complete_identical_results(
        cluster: Any, dataset: Path, tmp_path: Path) -> None:
    single = tmp_path / "single"
    _single(dataset, single)
    out = tmp_path / "ray_killed"
    errors: list[BaseException] = []

    def run() -> None:
        try:
            # Rendering makes the chunks long enough to kill an actor in the middle of one.
            distributed.evaluate(vlnverse.TeacherAgent, dataset=dataset, task="fine",
                                 split="val_unseen", setting="telhop", out=out, workers=2,
                                 num_envs=1, chunk=2, render=True, progress=False)
        except BaseException as e:  # noqa: BLE001 - re-raised in the test thread
            errors.append(e)

    t = threading.Thread(target=run)
    t.start()
    _kill_first("ray::_EvalWorker.run")
    t.join(timeout=300)
    assert not t.is_alive() and not errors, errors
    _same_run(single, out)
    lines = (out / "progress.jsonl").read_text().splitlines()
    assert len(lines) == 8, "every episode recorded once, nothing duplicated"


def test_the_slurm_array_script_equals_a_single_run(dataset: Path, tmp_path: Path) -> None:
    script = ROOT / "deploy" / "slurm" / "generate.sh"
    exe = xtask()
    env = {**os.environ, "XTASK": " ".join(exe), "VLNVERSE_PRESET": "tiny",
           "VLNVERSE_SHARDS": "3", "VLNVERSE_OUT": str(tmp_path / "slurm")}
    for k in range(3):
        subprocess.run(["bash", str(script)], check=True, cwd=ROOT,
                       env={**env, "SLURM_ARRAY_TASK_ID": str(k)})
    subprocess.run(["bash", str(ROOT / "deploy" / "slurm" / "merge.sh")], check=True, cwd=ROOT,
                   env=env)
    assert _same_tree(dataset, tmp_path / "slurm") == []
