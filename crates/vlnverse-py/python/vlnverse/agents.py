"""Agents for ``vlnverse.evaluate``: random actions, the teacher, and the zero-shot MLLM agent."""

from __future__ import annotations

import json
import os
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


class MLLMAgent:
    """A zero-shot agent driven by a multimodal chat model over any OpenAI-compatible
    endpoint (vLLM, Ollama, llama.cpp, a hosted API): ``cargo xtask evaluate --agent mllm``
    from Python. ``config`` is a TOML file or a dict of its fields (docs/mllm.md); the
    endpoint and model given here win over the config's. It runs inside the native evaluator:
    pass it to ``vlnverse.evaluate`` (``num_envs`` is the thread count); the run folder gets
    ``mllm.jsonl`` and ``summary.json`` an ``mllm`` block of token and call totals."""

    def __init__(self, endpoint: str, model: str,
                 config: str | os.PathLike[str] | dict[str, Any] | None = None) -> None:
        if not isinstance(endpoint, str) or not endpoint.strip():
            raise ValueError(f"invalid endpoint {endpoint!r}: give the base URL, e.g. "
                             "http://127.0.0.1:8000/v1")
        if not isinstance(model, str) or not model.strip():
            raise ValueError(f"invalid model {model!r}: give the model name the server serves")
        if config is not None and not isinstance(config, (str, os.PathLike, dict)):
            raise ValueError(f"invalid config {config!r}: a TOML file path or a dict")
        self.endpoint = endpoint
        self.model = model
        self.config = config
        self.name = f"mllm:{model}"

    def reset(self) -> None:
        """Nothing to do: the agent lives in the native evaluator."""

    def act(self, observations: dict[str, Any], infos: dict[str, Any]) -> Any:
        """Not stepped from Python; use ``vlnverse.evaluate``."""
        raise TypeError("MLLMAgent runs in the native evaluator: pass it to vlnverse.evaluate")

    def _evaluate_native(self, *, dataset: Any, task: str, split: str, setting: str, out: Any,
                         num_envs: int, action_space: str, sensors: Any, profile: str,
                         seed: int, max_steps: int | None, success_distance: float | None,
                         episodes: int | None, sample: int | None, version: str | None,
                         fresh: bool, render: bool) -> dict[str, Any]:
        """``vlnverse.evaluate`` for this agent: the native run, its summary as a dict."""
        from vlnverse import _errors as check
        from vlnverse._native import evaluate_mllm

        path = None if not isinstance(self.config, (str, os.PathLike)) else os.fspath(self.config)
        text = evaluate_mllm(
            check.check_path("dataset", dataset), check.check_choice("task", task, check.TASKS),
            check.check_choice("split", split, check.SPLITS), check.check_path("out", out),
            endpoint=self.endpoint, model=self.model, config_path=path,
            config_json=json.dumps(self.config) if isinstance(self.config, dict) else None,
            setting=check.check_choice("setting", setting, check.SETTINGS),
            action_space=check.check_choice("action_space", action_space, check.ACTION_SPACES),
            profile=profile, sensors=None if sensors is None else check.check_path("sensors",
                                                                                sensors),
            seed=seed, max_steps=max_steps, success_distance=success_distance,
            episodes=None if episodes is None else check.check_int("episodes", episodes, 1),
            sample=None if sample is None else check.check_int("sample", sample, 1),
            threads=check.check_int("num_envs", num_envs, 1, 1024), version=version,
            fresh=bool(fresh), render=bool(render))
        summary: dict[str, Any] = json.loads(text)
        return summary
