"""Gymnasium spaces built from the native layout (``NativeVecEnv.spec()``)."""

from __future__ import annotations

import string
from typing import Any

import numpy as np
from gymnasium import spaces

#: Characters an instruction or an oracle answer may hold.
CHARSET = frozenset(string.printable)
#: Longest instruction text (characters) the ``Text`` space admits.
MAX_TEXT = 8192


def observation_space(spec: dict[str, Any]) -> spaces.Dict:
    """The observation space of one environment."""
    out: dict[str, spaces.Space[Any]] = {}
    for key, dtype, shape in spec["fields"]:
        dt = np.dtype(dtype)
        shape = tuple(shape)
        if key in ("rgb",) or key.endswith("_rgb"):
            out[key] = spaces.Box(0, 255, shape, dt)
        elif key == "depth" or key.endswith("_depth"):
            out[key] = spaces.Box(0.0, np.inf, shape, dt)
        elif key == "compass":
            out[key] = spaces.Box(-np.pi, np.pi, shape, dt)
        elif key == "instruction_tokens":
            out[key] = spaces.Box(0, spec["vocab_size"] - 1, shape, dt)
        elif key == "sub_instruction_index":
            out[key] = spaces.Box(0, 64, shape, dt)
        elif dt.kind in "ui":
            info = np.iinfo(dt)
            out[key] = spaces.Box(info.min, info.max, shape, dt)
        else:
            out[key] = spaces.Box(-np.inf, np.inf, shape, dt)
    out["instruction"] = spaces.Text(MAX_TEXT, min_length=0, charset=CHARSET)
    if spec["task"] == "dialogue":
        out["oracle_answer"] = spaces.Text(MAX_TEXT, min_length=0, charset=CHARSET)
    return spaces.Dict(out)


def action_space(spec: dict[str, Any]) -> spaces.Space[Any]:
    """The action space of one environment (see ``vlnverse`` docs for the encodings)."""
    kind = spec["action_space"]
    if kind == "discrete":
        return spaces.Discrete(spec["discrete_actions"])
    if kind == "continuous":
        v, w = spec["max_linear_speed"], spec["max_angular_speed"]
        low = np.array([-v, -w, 0.0], dtype=np.float32)
        high = np.array([v, w, 1.0], dtype=np.float32)
        return spaces.Box(low, high, dtype=np.float32)
    big = np.float32(1e4)
    low = np.array([-big, -big, 0.0], dtype=np.float32)
    high = np.array([big, big, 1.0], dtype=np.float32)
    return spaces.Box(low, high, dtype=np.float32)
