"""``evaluate``, ``score`` and ``load_episodes``: the CLI's jobs from Python."""

from __future__ import annotations

import json
import sys
import time
from typing import Any, Callable, Protocol

import numpy as np

from vlnverse import _errors as check
from vlnverse._native import RunFolder, VLNVerseError
from vlnverse._native import load_episodes as _load_episodes
from vlnverse._native import score as _score
from vlnverse.vector import PathLike, VectorEnv


class Agent(Protocol):
    """A batched policy: ``act`` answers every environment's observation at once."""

    def reset(self) -> None:
        """Called once before the first step."""

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> Any:
        """Actions for all environments (shape ``(N,)`` or ``(N, 3)``)."""


def evaluate(
    agent: Agent,
    *,
    dataset: PathLike,
    task: str = "fine",
    split: str = "val_unseen",
    setting: str = "telhop",
    out: PathLike,
    num_envs: int = 4,
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
    progress: bool = True,
) -> dict[str, Any]:
    """Evaluate a Python agent on a split and write the run folder ``xtask evaluate`` writes
    (``summary.json``, ``episodes.csv``, ``trajectories.jsonl``, ``report.md``, ``run.json``,
    ``progress.jsonl``). ``episodes=N`` runs the first N episodes, ``sample=N`` a random sample
    of N spread over the split's scenes, drawn with ``seed`` (the zero-shot protocol; the
    same episodes as ``xtask evaluate --sample N --seed S``). Resumable: episodes already in
    ``out`` are kept, a run with another agent ``name`` / ``version`` or protocol is refused,
    ``fresh=True`` starts over.
    Returns ``summary.json`` as a dict."""
    native = getattr(agent, "_evaluate_native", None)
    if native is not None:
        # Agents that run inside the native evaluator (MLLMAgent): the same run folder.
        result: dict[str, Any] = native(
            dataset=dataset, task=task, split=split, setting=setting, out=out,
            num_envs=num_envs, action_space=action_space, sensors=sensors, profile=profile,
            seed=seed, max_steps=max_steps, success_distance=success_distance,
            episodes=episodes, sample=sample, version=version, fresh=fresh, render=render)
        return result
    agent_name = name or getattr(agent, "name", None) or type(agent).__name__
    num_envs = check.check_int("num_envs", num_envs, 1, check.MAX_NUM_ENVS)
    folder, protocol = open_run_folder(
        str(agent_name), version, dataset=dataset, task=task, split=split, out=out,
        episodes=episodes, sample=sample, fresh=fresh, setting=setting,
        action_space=action_space, sensors=sensors, profile=profile, seed=seed,
        max_steps=max_steps, success_distance=success_distance, render=render)
    task, split = protocol.pop("task"), protocol.pop("split")
    try:
        todo = list(folder.todo())
        if todo:
            envs = VectorEnv(dataset, task, split, num_envs=min(num_envs, len(todo)),
                             mode="eval", episode_ids=todo, copy=False, **protocol)
            try:
                _run(agent, folder, todo, envs, seed, progress)
            finally:
                envs.close()
        summary: dict[str, Any] = json.loads(folder.finish())
    finally:
        folder.close()
    return summary


def open_run_folder(
    agent_name: str, version: str | None, *, dataset: PathLike, task: str, split: str,
    out: PathLike, episodes: int | None, sample: int | None, fresh: bool, setting: str,
    action_space: str, sensors: PathLike | None, profile: str, seed: int,
    max_steps: int | None, success_distance: float | None, render: bool,
) -> tuple[RunFolder, dict[str, Any]]:
    """Check the arguments and open (lock) the run folder; returns it and the protocol the
    environments must use (plus the checked ``task`` and ``split``)."""
    fingerprint = version if version is None else f"version {version}"
    task = check.check_choice("task", task, check.TASKS)
    split = check.check_choice("split", split, check.SPLITS)
    # The protocol, the same for the run folder's identity and the environments.
    protocol: dict[str, Any] = dict(
        setting=check.check_choice("setting", setting, check.SETTINGS),
        action_space=check.check_choice("action_space", action_space, check.ACTION_SPACES),
        profile=check.check_str("profile", profile),
        sensors=None if sensors is None else check.check_path("sensors", sensors),
        seed=check.check_int("seed", seed, 0, check.MAX_SEED),
        max_steps=(None if max_steps is None
                   else check.check_int("max_steps", max_steps, 1, check.MAX_STEPS)),
        success_distance=(None if success_distance is None
                          else check.check_float("success_distance", success_distance,
                                                 0.0, 1000.0)),
        render=bool(render),
    )
    folder = RunFolder(
        check.check_path("out", out),
        check.check_path("dataset", dataset),
        task,
        split,
        agent=agent_name,
        agent_fingerprint=fingerprint,
        episodes=None if episodes is None else check.check_int("episodes", episodes, 1),
        sample=None if sample is None else check.check_int("sample", sample, 1),
        fresh=fresh,
        **protocol,
    )
    return folder, {**protocol, "task": task, "split": split}


def _run(agent: Agent, folder: RunFolder, todo: list[int], envs: VectorEnv, seed: int,
         progress: bool) -> None:
    """Step ``envs`` with ``agent`` until every episode of ``todo`` is recorded in ``folder``."""
    started = time.monotonic()
    last_report = [started]

    def on_record(done: int, record: str) -> None:
        folder.record(record)
        now = time.monotonic()
        if progress and (now - last_report[0] > 2.0 or done == len(todo)):
            print(f"evaluate: {done}/{len(todo)} episodes ({now - started:.1f} s)",
                  file=sys.stderr, flush=True)
            last_report[0] = now

    run_episodes(agent, envs, todo, seed, on_record)


def run_episodes(agent: Agent, envs: VectorEnv, todo: list[int], seed: int,
                 on_record: Callable[[int, str], None]) -> None:
    """Step ``envs`` (an eval-mode vector env over ``todo``) with ``agent`` until each episode
    of ``todo`` has finished once, calling ``on_record(finished_so_far, record_json)`` for each
    (first pass only: environments that wrap around are ignored)."""
    obs, infos = envs.reset(seed=seed)
    agent.reset()
    left = set(todo)
    while left:
        obs, _, term, trunc, infos = envs.step(agent.act(obs, infos))
        for i in np.flatnonzero(term | trunc):
            eid = int(infos["episode_id"][i])
            if int(infos["pass"][i]) == 0 and eid in left:
                left.discard(eid)
                on_record(len(todo) - len(left), infos["record"][i])


def load_episodes(dataset: PathLike, task: str, split: str) -> list[dict[str, Any]]:
    """The episodes of ``DIR/<task>/<split>/<split>.json.gz`` as dicts (the file's fields)."""
    text = _load_episodes(check.check_path("dataset", dataset),
                          check.check_choice("task", task, check.TASKS),
                          check.check_choice("split", split, check.SPLITS))
    out: list[dict[str, Any]] = json.loads(text)
    return out


def score(dataset: PathLike, task: str, split: str, trajectories: PathLike, out: PathLike, *,
          success_distance: float = 3.0, fail_on_collision: bool = False,
          allow_missing: bool = False, method: str | None = None,
          force: bool = False) -> dict[str, Any]:
    """Score a trajectory file like ``cargo xtask score``; returns ``summary.json``. ``out``
    may not hold an evaluation, nor a ``summary.json`` that no score wrote (unless
    ``force=True``)."""
    text = _score(check.check_path("dataset", dataset),
                  check.check_choice("task", task, check.TASKS),
                  check.check_choice("split", split, check.SPLITS),
                  check.check_path("trajectories", trajectories), check.check_path("out", out),
                  success_distance=success_distance, fail_on_collision=fail_on_collision,
                  allow_missing=allow_missing, method=method, force=bool(force))
    summary: dict[str, Any] = json.loads(text)
    return summary


__all__ = ["Agent", "VLNVerseError", "evaluate", "load_episodes", "score"]
