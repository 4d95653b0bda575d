"""``VLNEnv``: one VLN environment as a ``gymnasium.Env``."""

from __future__ import annotations

from typing import Any, SupportsFloat

import gymnasium
import numpy as np

from vlnverse._native import VLNVerseError
from vlnverse.vector import PathLike, VectorEnv


class VLNEnv(gymnasium.Env):
    """One environment over a dataset split (the single-environment view of ``VectorEnv``).

    Observations: the rig's images (``rgb`` uint8 HxWx3, ``depth`` float32 HxWx1 normalised
    to [0, 1] at the camera's far plane, 10 m by default; ``semantic`` / ``instance`` /
    LiDAR / panorama when the rig has them), ``pose`` (x, y, z, yaw), ``compass``, ``gps``
    (forward, right of the start, in metres), ``instruction`` (text), ``instruction_tokens``
    (ids in the dataset's ``vocab.txt``, 0-padded), ``sub_instruction_index``, and for
    dialogue episodes ``oracle_answer``. Actions: ``Discrete`` (0 stop, 1 forward, 2 left,
    3 right, 4 look up, 5 look down, 6 ask in dialogue) or a ``Box`` of ``[v, omega, stop]``
    (continuous) or ``[x, z, stop]`` (waypoint). See ``VectorEnv`` for the arguments and
    ``infos``; here every info value is the environment's own (not an array).

    After ``terminated`` or ``truncated``, call ``reset()``; stepping a finished episode
    raises ``VLNVerseError``.
    """

    metadata: dict[str, Any] = {"render_modes": []}

    def __init__(self, dataset: PathLike, task: str = "fine", split: str = "val_unseen",
                 **kwargs: Any) -> None:
        if "num_envs" in kwargs:
            raise VLNVerseError("VLNEnv is one environment; use vlnverse.make_vec for num_envs")
        self._vec = VectorEnv(dataset, task, split, num_envs=1, copy=True, **kwargs)
        self.observation_space = self._vec.single_observation_space
        self.action_space = self._vec.single_action_space
        self._over = False

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        """Start the next episode (``seed`` restarts the episode order / draws)."""
        super().reset(seed=seed)
        obs, infos = self._vec.reset(seed=seed, options=options)
        self._over = False
        return self._one(obs), self._one_info(infos)

    def step(
        self, action: Any
    ) -> tuple[dict[str, Any], SupportsFloat, bool, bool, dict[str, Any]]:
        """Apply one action."""
        if self._over:
            raise VLNVerseError("the episode is over; call reset() before stepping again")
        batched = np.asarray(action)[None, ...]
        obs, rew, term, trunc, infos = self._vec.step(batched)
        self._over = bool(term[0] or trunc[0])
        return (
            self._one(obs),
            float(rew[0]),
            bool(term[0]),
            bool(trunc[0]),
            self._one_info(infos),
        )

    def close(self) -> None:
        """Release the native environment."""
        self._vec.close()

    @staticmethod
    def _one(obs: dict[str, Any]) -> dict[str, Any]:
        return {k: v[0] for k, v in obs.items()}

    @staticmethod
    def _one_info(infos: dict[str, Any]) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for k, v in infos.items():
            if k.startswith("_"):
                continue
            mask = infos.get(f"_{k}")
            if mask is not None and not mask[0]:
                continue
            x = v[0]
            out[k] = x.item() if isinstance(x, np.generic) else x
        return out

    @property
    def vocab(self) -> list[str]:
        """The instruction vocabulary (token id = index)."""
        return self._vec.vocab
