"""An agent for the HTTP tests: its actions depend on what it sees (depth, colour, position,
instruction), so the same results through the agent server and in process show that the
observations arrive whole."""

from __future__ import annotations

from typing import Any

import numpy as np


class LookingAgent:
    """Walks on while the middle of the view is free, turns (left or right by the view's
    colour and the instruction) when it is not, stops 3 m from the start."""

    name = "http"

    def __init__(self, free: float = 0.12) -> None:
        self.free = free

    def reset(self) -> None:
        """Stateless: nothing to forget."""

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> Any:
        depth = observations["depth"]
        h, w = depth.shape[1:3]
        middle = depth[:, h // 3: 2 * h // 3, w // 3: 2 * w // 3, 0].mean(axis=(1, 2))
        colour = observations["rgb"].reshape(len(depth), -1).sum(axis=1)
        words = np.array([len(t.split()) for t in observations["instruction"]])
        turn = 2 + (colour + words) % 2
        far = np.hypot(observations["gps"][:, 0], observations["gps"][:, 1]) > 3.0
        return np.where(far, 0, np.where(middle > self.free, 1, turn)).astype(np.int64)
