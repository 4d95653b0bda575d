"""``PolicyAgent``: a trained policy as an agent for ``vlnverse.evaluate`` (greedy actions)."""

from __future__ import annotations

from typing import Any

import numpy as np
import torch

from vlnverse_baselines.models import InstructionCache, Policy
from vlnverse_baselines.obs import downsample_depth, downsample_rgb, step_batch


class PolicyAgent:
    """Steps a recurrent policy over a batch of environments.

    An environment whose ``infos["steps"]`` is 0 starts an episode: its recurrent state and
    previous action are cleared. Actions are the argmax of the logits unless ``sample``."""

    def __init__(self, model: Policy, name: str = "policy", sample: bool = False,
                 seed: int = 0) -> None:
        self.model = model.eval()
        self.name = name
        self.sample = sample
        self.generator = torch.Generator().manual_seed(seed)
        self.state: torch.Tensor | None = None
        self.prev: np.ndarray | None = None
        self.cache = InstructionCache()

    def reset(self) -> None:
        """Forget every environment's state."""
        self.state = None
        self.prev = None
        self.cache.clear()

    @torch.no_grad()
    def logits(self, observations: dict[str, Any], infos: dict[str, Any]) -> torch.Tensor:
        """Logits ``[B, 4]`` of this step (advances the recurrent state)."""
        c = self.model.config
        steps = np.asarray(infos["steps"])
        b = steps.shape[0]
        if self.state is None or self.prev is None or self.state.shape[1] != b:
            self.state = self.model.initial_state(b)
            self.prev = np.zeros(b, dtype=np.int64)
        starts = steps == 0
        self.prev[starts] = 0
        batch = step_batch(
            downsample_rgb(np.asarray(observations["rgb"]), c.rgb_size),
            downsample_depth(np.asarray(observations["depth"]), c.depth_size),
            np.asarray(observations["instruction_tokens"]), self.prev, starts)
        logits, self.state = self.model.forward_sequence(batch, self.state, self.cache)
        return logits[0]

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> np.ndarray:
        """One action per environment (``vlnverse`` Discrete ids 0..3)."""
        logits = self.logits(observations, infos)
        if self.sample:
            actions = torch.multinomial(torch.softmax(logits, 1), 1, generator=self.generator)[:, 0]
        else:
            actions = logits.argmax(dim=1)
        out = actions.numpy().astype(np.int64)
        assert self.prev is not None
        self.prev = out + 1
        return out
