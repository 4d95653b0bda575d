"""Argument checks shared by the environments; errors name the argument and the value."""

from __future__ import annotations

import os
from typing import Any

from vlnverse._native import VLNVerseError

TASKS = ("fine", "coarse", "visual_reference", "long_horizon", "dialogue")
SPLITS = ("train", "val_seen", "val_unseen", "test")
SETTINGS = ("strict", "telhop", "lenient")
ACTION_SPACES = ("discrete", "continuous", "waypoint")
MODES = ("eval", "train")
#: Most environments one ``VectorEnv`` (or ``evaluate``) runs: each holds a simulator and a
#: renderer (1024 rendering ones took 3.5 GB), so a mistyped count is refused.
MAX_NUM_ENVS = 256
#: Largest seed (seeds are unsigned 64-bit integers).
MAX_SEED = 2**64 - 1
#: Most actions per episode (the protocol's ``max_steps`` range).
MAX_STEPS = 100_000


def check_choice(name: str, value: Any, choices: tuple[str, ...]) -> str:
    """``value`` if it is one of ``choices`` (a str), else a VLNVerseError naming both."""
    if not isinstance(value, str):
        raise VLNVerseError(
            f"{name} must be a str, one of {', '.join(choices)}; got {type(value).__name__} "
            f"{value!r}"
        )
    v = value.replace("-", "_")
    if v == "tel_hop":
        v = "telhop"
    if v not in choices:
        raise VLNVerseError(f"invalid {name} {value!r}: expected one of {', '.join(choices)}")
    return v


def check_path(name: str, value: Any) -> str:
    """A path argument as str (str or os.PathLike)."""
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise VLNVerseError(f"{name} must be a path (str or os.PathLike); got {type(value).__name__}")


def check_int(name: str, value: Any, low: int, high: int | None = None) -> int:
    """An int argument within [low, high]."""
    if isinstance(value, bool) or not isinstance(value, int):
        import numpy as np

        if not isinstance(value, np.integer):
            raise VLNVerseError(f"{name} must be an int; got {type(value).__name__} {value!r}")
        value = int(value)
    if value < low or (high is not None and value > high):
        rng = f"[{low}, {high}]" if high is not None else f">= {low}"
        raise VLNVerseError(f"invalid {name} {value}: must be {rng}")
    return int(value)


def check_str(name: str, value: Any) -> str:
    """A str argument (not empty)."""
    if not isinstance(value, str):
        raise VLNVerseError(f"{name} must be a str; got {type(value).__name__} {value!r:.80}")
    if not value.strip():
        raise VLNVerseError(f"invalid {name} {value!r}: must not be empty")
    return value


def check_float(name: str, value: Any, low: float, high: float) -> float:
    """A finite number in (low, high]."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        import numpy as np

        if not isinstance(value, (np.integer, np.floating)):
            raise VLNVerseError(
                f"{name} must be a number; got {type(value).__name__} {value!r:.80}"
            )
    v = float(value)
    if not (low < v <= high):
        raise VLNVerseError(f"invalid {name} {value!r}: must be in ({low}, {high}]")
    return v


def check_ids(name: str, value: Any) -> list[int]:
    """A list of distinct episode ids (unsigned 64-bit integers)."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise VLNVerseError(f"{name} must be a list of ints; got {type(value).__name__}")
    ids = [check_int(f"{name}[{i}]", v, 0, MAX_SEED) for i, v in enumerate(value)]
    seen: dict[int, int] = {}
    for i, v in enumerate(ids):
        if v in seen:
            raise VLNVerseError(
                f"invalid {name}[{i}] {v}: repeats {name}[{seen[v]}]; list each episode once"
            )
        seen[v] = i
    if not ids:
        raise VLNVerseError(f"invalid {name} []: name at least one episode (or leave it out)")
    return ids
