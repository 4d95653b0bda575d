"""``generate``: build a dataset like ``cargo xtask generate``."""

from __future__ import annotations

import sys
import time
from typing import Any, Callable

from vlnverse import _errors as check
from vlnverse._native import VLNVerseError
from vlnverse._native import generate as _generate
from vlnverse._native import merge as _merge
from vlnverse.vector import PathLike


def generate(
    out: PathLike,
    preset: str = "tiny",
    *,
    config: PathLike | None = None,
    seed: int | None = None,
    tasks: list[str] | None = None,
    shard: tuple[int, int] | None = None,
    threads: int | None = None,
    scenes_from: PathLike | None = None,
    progress: bool | Callable[[int, int], None] = True,
) -> dict[str, Any]:
    """Generate a VLN dataset (scenes, the five tasks' episodes, reference images,
    ``vocab.txt``) into ``out``, exactly as ``cargo xtask generate`` does: the same ``preset``
    (``tiny`` or ``vlnverse``) or TOML ``config`` gives the same bytes on any number of
    ``threads``; an interrupted run resumes; ``shard=(k, n)`` handles the scenes with
    ``index % n == k`` (join the shard folders with ``cargo xtask merge``); ``scenes_from``
    builds episodes on the scene folders under a directory instead of procedural homes.

    ``progress``: ``True`` prints a line to stderr every few seconds, a callable is called as
    ``progress(done, total)`` after each scene. Returns ``scenes_done``, ``scenes_skipped``
    (of them, already complete), ``episodes``, ``assembled`` and ``skipped`` (scene, task,
    reason)."""
    if tasks is not None:
        if isinstance(tasks, str) or not isinstance(tasks, (list, tuple)):
            raise VLNVerseError(f"tasks must be a list of task names; got {tasks!r}")
        tasks = [check.check_choice("tasks", t, check.TASKS) for t in tasks]
    if shard is not None:
        if not isinstance(shard, (list, tuple)) or len(shard) != 2:
            raise VLNVerseError(f"shard must be a pair (k, n); got {shard!r}")
        shard = (check.check_int("shard[0]", shard[0], 0),
                 check.check_int("shard[1]", shard[1], 1))
    callback: Callable[[int, int], None] | None
    if callable(progress):
        callback = progress
    elif progress:
        callback = _Printer()
    else:
        callback = None
    summary: dict[str, Any] = _generate(
        check.check_path("out", out),
        preset=check.check_choice("preset", preset, ("tiny", "vlnverse")),
        config=None if config is None else check.check_path("config", config),
        seed=None if seed is None else check.check_int("seed", seed, 0),
        tasks=tasks,
        shard=shard,
        threads=None if threads is None else check.check_int("threads", threads, 1, 1024),
        scenes_from=None if scenes_from is None else check.check_path("scenes_from", scenes_from),
        on_scene=callback,
    )
    return summary


def merge(out: PathLike, parts: list[PathLike]) -> int:
    """Join shard folders (``generate(..., shard=(k, n))`` for every ``k``) into ``out``, a new
    folder, byte-identical to a single run (``cargo xtask merge``). Returns the episode count.
    """
    if isinstance(parts, (str, bytes)) or not isinstance(parts, (list, tuple)):
        raise VLNVerseError(f"parts must be a list of folders; got {parts!r}")
    return int(_merge(check.check_path("out", out),
                      [check.check_path("parts", p) for p in parts]))


class _Printer:
    """A progress line on stderr at most every 2 s (and at the end)."""

    def __init__(self) -> None:
        self.started = time.monotonic()
        self.last = self.started

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if now - self.last > 2.0 or done == total:
            print(f"generate: {done}/{total} scenes ({now - self.started:.1f} s)",
                  file=sys.stderr, flush=True)
            self.last = now


__all__ = ["generate", "merge"]
