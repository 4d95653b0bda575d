"""Two reference agents for ``vlnverse.evaluate``: random actions and the teacher."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces


class RandomAgent:
    """Uniform random actions (stop included), seeded."""

    name = "random-py"

    def __init__(self, action_space: spaces.Space[Any], seed: int = 0) -> None:
        self.action_space = action_space
        self.action_space.seed(seed)

    def reset(self) -> None:
        """Nothing to forget between episodes."""

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> Any:
        """One random action per environment."""
        return self.action_space.sample()


class TeacherAgent:
    """Follows ``infos["expert_action"]``: the shortest-path teacher (``oracle`` in the CLI)."""

    name = "oracle"

    def reset(self) -> None:
        """Nothing to forget between episodes."""

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> Any:
        """The teacher's action for every environment."""
        return np.asarray(infos["expert_action"])
