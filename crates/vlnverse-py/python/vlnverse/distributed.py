"""Generation and evaluation spread over a Ray cluster, with one result identical to a
single-machine run.

``generate`` runs one Ray task per shard (``vlnverse.generate(..., shard=(k, n))`` into
``OUT.shards/k``), retries a failed or lost shard (generation resumes, so a retry finishes
the scenes the dead one left), then merges the shards into ``OUT``: the bytes of
``vlnverse.generate(OUT)`` on one machine. ``evaluate`` spreads the episodes over Ray actors
(each holds its own vector environment and agent, made by ``agent_factory``), and the driver
writes every finished episode into one run folder, resumable as ``vlnverse.evaluate``'s; a dead
actor's unfinished chunk goes to a new actor. Folders must be on storage every node sees.

Ray is an optional dependency (``pip install ray``). Without a running cluster (no
``ray.init`` before, no ``RAY_ADDRESS``) a local one is started.
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path
from typing import Any, Callable

from vlnverse import _errors as check
from vlnverse._native import VLNVerseError
from vlnverse.evaluate import Agent, open_run_folder, run_episodes
from vlnverse.generate import generate as _generate_local
from vlnverse.generate import merge
from vlnverse.vector import PathLike, VectorEnv


def _ray() -> Any:
    try:
        import ray
    except ImportError as e:  # pragma: no cover - exercised where Ray is missing
        raise VLNVerseError(
            "vlnverse.distributed needs Ray: pip install 'ray>=2.40'") from e
    if not ray.is_initialized():
        ray.init(address=os.environ.get("RAY_ADDRESS"), log_to_driver=False)
    return ray


class _Progress:
    """A line on stderr at most every 2 s (and at the end)."""

    def __init__(self, what: str, total: int, enabled: bool) -> None:
        self.what, self.total, self.enabled = what, total, enabled
        self.started = self.last = time.monotonic()

    def __call__(self, done: int, note: str = "") -> None:
        now = time.monotonic()
        if self.enabled and (now - self.last > 2.0 or done == self.total):
            print(f"{self.what}: {done}/{self.total} ({now - self.started:.1f} s){note}",
                  file=sys.stderr, flush=True)
            self.last = now


def _generate_shard(out: str, preset: str, config: str | None, seed: int | None,
                    tasks: list[str] | None, shard: tuple[int, int],
                    threads: int | None, delay: float) -> dict[str, Any]:
    """One shard, in a Ray worker (resumes what an earlier attempt left)."""

    def on_scene(done: int, total: int) -> None:
        if delay > 0:
            time.sleep(delay)

    summary: dict[str, Any] = _generate_local(out, preset, config=config, seed=seed,
                                              tasks=tasks, shard=shard, threads=threads,
                                              progress=on_scene)
    return summary


def generate(
    out: PathLike,
    preset: str = "tiny",
    *,
    shards: int,
    config: PathLike | None = None,
    seed: int | None = None,
    tasks: list[str] | None = None,
    cpus_per_shard: int = 1,
    max_retries: int = 3,
    progress: bool = True,
    _scene_delay: float = 0.0,
) -> dict[str, Any]:
    """Generate ``preset`` (or ``config``) into ``out`` with one Ray task per shard, then merge.
    The result is byte-identical to ``vlnverse.generate(out, preset)`` on one machine. Shard
    folders live in ``<out>.shards/<k>`` until the merge succeeds (a rerun reuses finished
    ones); a shard whose worker dies is retried up to ``max_retries`` times. Returns
    ``episodes``, ``shards`` and ``seconds``. (``_scene_delay`` slows each scene, for tests
    that kill a worker mid-shard.)"""
    ray = _ray()
    shards = check.check_int("shards", shards, 1, 100_000)
    out_path = Path(check.check_path("out", out))
    if out_path.exists() and any(out_path.iterdir()):
        raise VLNVerseError(f"out {out_path}: already holds files; generate into a new folder")
    parts_root = Path(f"{out_path}.shards")
    parts = [parts_root / str(k) for k in range(shards)]
    cfg = None if config is None else os.path.abspath(check.check_path("config", config))
    task = ray.remote(num_cpus=cpus_per_shard, max_retries=max_retries,
                      retry_exceptions=False)(_generate_shard)
    started = time.monotonic()
    pending = {
        task.remote(str(p), preset, cfg, seed, tasks, (k, shards), cpus_per_shard,
                    _scene_delay): k
        for k, p in enumerate(parts)
    }
    report = _Progress("generate (ray)", shards, progress)
    done = 0
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1)
        k = pending.pop(ready[0])
        try:
            ray.get(ready[0])
        except Exception as e:
            raise VLNVerseError(f"shard {k}/{shards} failed after {max_retries} retries: {e}"
                                ) from e
        done += 1
        report(done)
    episodes = merge(out_path, [str(p) for p in parts])
    for p in parts:
        _remove_tree(p)
    try:
        parts_root.rmdir()
    except OSError:
        pass
    return {"episodes": episodes, "shards": shards, "seconds": time.monotonic() - started}


def _remove_tree(p: Path) -> None:
    import shutil

    shutil.rmtree(p, ignore_errors=True)


class _EvalWorker:
    """A Ray actor: one vector environment and one agent, running chunks of episodes."""

    def __init__(self, agent_factory: Callable[[], Agent], dataset: str, task: str,
                 split: str, protocol: dict[str, Any], num_envs: int) -> None:
        self.agent = agent_factory()
        self.args = (dataset, task, split)
        self.protocol = protocol
        self.num_envs = num_envs

    def pid(self) -> int:
        return os.getpid()

    def run(self, episode_ids: list[int]) -> list[str]:
        dataset, task, split = self.args
        envs = VectorEnv(dataset, task, split, num_envs=min(self.num_envs, len(episode_ids)),
                         mode="eval", episode_ids=episode_ids, copy=False, **self.protocol)
        records: list[str] = []
        try:
            run_episodes(self.agent, envs, episode_ids, int(self.protocol["seed"]),
                         lambda _done, rec: records.append(rec))
        finally:
            envs.close()
        return records


def evaluate(
    agent_factory: Callable[[], Agent],
    *,
    dataset: PathLike,
    task: str = "fine",
    split: str = "val_unseen",
    setting: str = "telhop",
    out: PathLike,
    workers: int = 2,
    num_envs: int = 4,
    chunk: int = 8,
    action_space: str = "discrete",
    sensors: PathLike | None = None,
    profile: str = "vlnverse",
    seed: int = 0,
    max_steps: int | None = None,
    success_distance: float | None = None,
    episodes: int | None = None,
    sample: int | None = None,
    name: str | None = None,
    version: str | None = None,
    fresh: bool = False,
    render: bool = True,
    cpus_per_worker: float = 1.0,
    max_restarts: int = 3,
    progress: bool = True,
) -> dict[str, Any]:
    """Evaluate the agents ``agent_factory()`` makes (one per Ray actor, ``workers`` actors,
    each with ``num_envs`` environments) and write one run folder, identical to
    ``vlnverse.evaluate`` on one machine with the same agent (summary, episodes, trajectories).
    Episodes go out in chunks of ``chunk``; every finished one is recorded in ``out`` at once
    (so an interrupted run resumes), and a chunk whose actor died is given to a new actor, at
    most ``max_restarts`` times in all. Returns ``summary.json`` as a dict."""
    ray = _ray()
    workers = check.check_int("workers", workers, 1, 100_000)
    chunk = check.check_int("chunk", chunk, 1, 1_000_000)
    probe = agent_factory()
    agent_name = name or getattr(probe, "name", None) or type(probe).__name__
    folder, protocol = open_run_folder(
        str(agent_name), version, dataset=dataset, task=task, split=split, out=out,
        episodes=episodes, sample=sample, fresh=fresh, setting=setting,
        action_space=action_space, sensors=sensors, profile=profile, seed=seed,
        max_steps=max_steps, success_distance=success_distance, render=render)
    task, split = protocol.pop("task"), protocol.pop("split")
    dataset_str = os.path.abspath(check.check_path("dataset", dataset))
    try:
        todo = list(folder.todo())
        if todo:
            _evaluate_chunks(ray, folder, todo, agent_factory, dataset_str, task, split,
                             protocol, workers, num_envs, chunk, cpus_per_worker,
                             max_restarts, progress)
        summary: dict[str, Any] = json.loads(folder.finish())
    finally:
        folder.close()
    return summary


def _evaluate_chunks(ray: Any, folder: Any, todo: list[int],
                     agent_factory: Callable[[], Agent], dataset: str, task: str, split: str,
                     protocol: dict[str, Any], workers: int, num_envs: int, chunk: int,
                     cpus: float, max_restarts: int, progress: bool) -> None:
    actor_cls = ray.remote(num_cpus=cpus, max_restarts=0)(_EvalWorker)
    chunks = [todo[i:i + chunk] for i in range(0, len(todo), chunk)]

    def new_actor() -> Any:
        return actor_cls.remote(agent_factory, dataset, task, split, protocol, num_envs)

    actors = [new_actor() for _ in range(min(workers, len(chunks)))]
    queue = list(range(len(chunks)))
    running: dict[Any, tuple[Any, int]] = {}
    left = set(todo)
    restarts = 0
    report = _Progress("evaluate (ray)", len(todo), progress)

    def give(actor: Any) -> None:
        if queue:
            c = queue.pop(0)
            running[actor.run.remote(chunks[c])] = (actor, c)

    for a in actors:
        give(a)
    while running:
        ready, _ = ray.wait(list(running), num_returns=1)
        ref = ready[0]
        actor, c = running.pop(ref)
        try:
            records: list[str] = ray.get(ref)
        except ray.exceptions.RayActorError as e:
            restarts += 1
            if restarts > max_restarts:
                raise VLNVerseError(
                    f"evaluation actors died {restarts} times (last: {e}); the finished "
                    f"episodes are recorded in the run folder: rerun to resume") from e
            queue.insert(0, c)
            give(new_actor())
            continue
        for rec in records:
            eid = int(json.loads(rec)["episode_id"])
            # A chunk run again after its actor died may repeat an episode: keep the first.
            if eid in left:
                folder.record(rec)
                left.discard(eid)
        report(len(todo) - len(left))
        give(actor)
    if left:
        raise VLNVerseError(f"{len(left)} episodes were not evaluated: {sorted(left)[:10]}")


__all__ = ["evaluate", "generate"]
