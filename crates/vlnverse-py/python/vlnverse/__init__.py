"""VLNVerse-rs for Python: vision-language navigation environments (Gymnasium), a native
vector environment, teacher actions, and the benchmark's evaluation and scoring.

>>> import vlnverse
>>> env = vlnverse.VLNEnv("datasets/tiny", task="fine", split="val_unseen")  # doctest: +SKIP
>>> envs = vlnverse.make_vec("datasets/tiny", "fine", "val_unseen", num_envs=8)  # doctest: +SKIP
"""

from __future__ import annotations

import gymnasium

from vlnverse._native import VLNVerseError, __version__
from vlnverse.agents import RandomAgent, TeacherAgent
from vlnverse.env import VLNEnv
from vlnverse.evaluate import Agent, evaluate, load_episodes, score
from vlnverse.generate import generate, merge
from vlnverse.vector import VectorEnv, make_vec

#: The Gymnasium id: ``gymnasium.make(ENV_ID, dataset=..., task=..., split=...)`` and
#: ``gymnasium.make_vec(ENV_ID, num_envs=N, vectorization_mode="vector_entry_point", ...)``.
ENV_ID = "vlnverse/VLN-v0"

if ENV_ID not in gymnasium.registry:
    gymnasium.register(
        id=ENV_ID,
        entry_point="vlnverse.env:VLNEnv",
        vector_entry_point="vlnverse.vector:VectorEnv",
        disable_env_checker=True,
    )

__all__ = [
    "ENV_ID",
    "Agent",
    "RandomAgent",
    "TeacherAgent",
    "VLNEnv",
    "VLNVerseError",
    "VectorEnv",
    "__version__",
    "evaluate",
    "generate",
    "load_episodes",
    "make_vec",
    "merge",
    "score",
]
