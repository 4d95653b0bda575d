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
