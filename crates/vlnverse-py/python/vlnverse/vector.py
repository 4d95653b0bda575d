"""``VectorEnv``: a batch of VLN environments stepped natively, as a Gymnasium ``VectorEnv``."""

from __future__ import annotations

import json
import os
from typing import Any, Union

import numpy as np
from gymnasium.vector import AutoresetMode
from gymnasium.vector import VectorEnv as GymVectorEnv
from gymnasium.vector.utils import batch_space
from numpy.typing import NDArray

from vlnverse import _errors as check
from vlnverse import _spaces
from vlnverse._native import NativeVecEnv, VLNVerseError

PathLike = Union[str, "os.PathLike[str]"]

#: Keys of ``infos`` that hold one value per environment (each with its ``_key`` mask).
INFO_KEYS = (
    "episode_id",
    "scene_id",
    "pass",
    "steps",
    "distance_to_goal",
    "collided",
    "collision",
    "collisions",
    "questions_left",
    "expert_action",
    "reference_image",
    "sub_instruction",
)


class VectorEnv(GymVectorEnv):
    """``num_envs`` environments over one dataset split, stepped together in Rust.

    One ``step`` runs every environment on a Rust thread pool with the GIL released and
    writes the observations into preallocated batched arrays (``copy=False`` hands out those
    arrays themselves: they change at the next step). Autoreset follows Gymnasium's
    ``AutoresetMode.NEXT_STEP``: the step after an episode ends resets that environment and
    ignores its action.

    ``mode="eval"`` hands out the split's episodes in file order to whichever environment
    resets next, so the first ``len(split)`` episodes started by the batch are each episode
    once (``infos["pass"]`` counts later passes); ``mode="train"`` draws episodes with a
    per-environment generator seeded from ``seed``: every draw is uniform over the split, and an
    environment stays in one home for ``home_repeat`` episodes before it draws a home again
    (Habitat's ``group_by_scene``; none drawn twice in a pass over the home's episodes), so
    loading a home is paid once per ``home_repeat`` episodes. ``home_repeat=1`` draws every
    episode from the whole split.

    ``infos`` holds, per environment: ``episode_id``, ``scene_id``, geodesic
    ``distance_to_goal`` (m), ``collided`` / ``collision`` (a noticeable collision, counted
    in CR) / ``collisions``, ``expert_action`` (the shortest-path teacher's next action in this
    action space), ``steps``, ``pass``, ``sub_instruction``, ``reference_image``,
    ``questions_left``; and, for environments whose episode just ended, ``metrics`` (the same
    numbers ``cargo xtask evaluate`` computes) and ``record`` (the episode record as JSON).
    """

    metadata: dict[str, Any] = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(
        self,
        dataset: PathLike,
        task: str = "fine",
        split: str = "val_unseen",
        *,
        num_envs: int = 1,
        setting: str = "telhop",
        action_space: str = "discrete",
        sensors: PathLike | None = None,
        profile: str = "vlnverse",
        mode: str = "eval",
        seed: int = 0,
        max_steps: int | None = None,
        success_distance: float | None = None,
        reward: str = "sparse",
        render: bool = True,
        normalize_depth: bool = True,
        instruction_length: int = 200,
        episode_ids: list[int] | None = None,
        backend: str | None = None,
        copy: bool = True,
        home_repeat: int = 32,
    ) -> None:
        self._native: NativeVecEnv | None = None
        native = NativeVecEnv(
            check.check_path("dataset", dataset),
            check.check_choice("task", task, check.TASKS),
            check.check_choice("split", split, check.SPLITS),
            num_envs=check.check_int("num_envs", num_envs, 1, check.MAX_NUM_ENVS),
            setting=check.check_choice("setting", setting, check.SETTINGS),
            action_space=check.check_choice("action_space", action_space, check.ACTION_SPACES),
            profile=check.check_str("profile", profile),
            sensors=None if sensors is None else check.check_path("sensors", sensors),
            mode=check.check_choice("mode", mode, check.MODES),
            seed=check.check_int("seed", seed, 0, check.MAX_SEED),
            max_steps=(None if max_steps is None
                       else check.check_int("max_steps", max_steps, 1, check.MAX_STEPS)),
            success_distance=(None if success_distance is None
                              else check.check_float("success_distance", success_distance,
                                                     0.0, 1000.0)),
            reward=check.check_choice("reward", reward, ("sparse", "dense")),
            episode_ids=(None if episode_ids is None
                         else check.check_ids("episode_ids", episode_ids)),
            render=bool(render),
            normalize_depth=bool(normalize_depth),
            instruction_length=check.check_int("instruction_length", instruction_length, 1, 4096),
            backend=backend,
            home_repeat=check.check_int("home_repeat", home_repeat, 1, 1_000_000),
        )
        self._native = native
        self.spec_native: dict[str, Any] = native.spec()
        self.num_envs = int(self.spec_native["num_envs"])
        self.single_observation_space = _spaces.observation_space(self.spec_native)
        self.single_action_space = _spaces.action_space(self.spec_native)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._buffers: dict[str, NDArray[Any]] = dict(native.buffers())
        self._autoreset = np.zeros(self.num_envs, dtype=bool)
        self._copy = bool(copy)
        self._seed = int(seed)
        self._dialogue = self.spec_native["task"] == "dialogue"
        self._discrete = self.spec_native["action_space"] == "discrete"

    # -- Gymnasium API -------------------------------------------------------------------

    def reset(
        self,
        *,
        seed: int | list[int] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        """Reset every environment to its next episode; ``seed`` reseeds the episode draws
        (and restarts the eval order); a list gives the first element (environment ``i``
        uses ``seed + i``-derived draws)."""
        if options:
            raise VLNVerseError(
                f"reset: unknown options {sorted(map(str, options))}; reset takes none"
            )
        if isinstance(seed, (list, tuple)):
            seed = seed[0] if seed else None
        if seed is not None:
            seed = check.check_int("seed", seed, 0, check.MAX_SEED)
            self._seed = seed
        super().reset(seed=seed)
        raw = self._live().reset(seed)
        self._autoreset[:] = False
        return self._observations(raw), self._infos(raw)

    def step(
        self, actions: Any
    ) -> tuple[dict[str, Any], NDArray[Any], NDArray[Any], NDArray[Any], dict[str, Any]]:
        """Step every environment (environments that ended last step reset instead)."""
        native = self._live()
        raw = native.step(self._encode(actions), self._autoreset.tolist())
        terminated = np.asarray(raw["terminated"], dtype=bool)
        truncated = np.asarray(raw["truncated"], dtype=bool)
        rewards = np.asarray(raw["reward"], dtype=np.float64)
        self._autoreset = terminated | truncated
        return self._observations(raw), rewards, terminated, truncated, self._infos(raw)

    def close_extras(self, **kwargs: Any) -> None:
        """Release the native environments."""
        if self._native is not None:
            self._native.close()

    # -- helpers -------------------------------------------------------------------------

    def _live(self) -> NativeVecEnv:
        if self._native is None or self._native.closed:
            raise VLNVerseError("the environment is closed")
        return self._native

    def _encode(self, actions: Any) -> NDArray[Any]:
        n = self.num_envs
        try:
            arr = np.asarray(actions)
        except Exception as e:  # noqa: BLE001 - anything numpy cannot read is bad input
            raise VLNVerseError(f"actions: not an array ({e})") from e
        if self._discrete:
            if arr.dtype.kind not in "iub" and not (
                arr.dtype.kind == "f" and np.all(np.isfinite(arr)) and np.all(arr == np.round(arr))
            ):
                raise VLNVerseError(
                    f"actions: expected integer action ids for Discrete, got dtype {arr.dtype} "
                    f"({actions!r:.80})"
                )
            arr = arr.astype(np.int64).reshape(-1)
            if arr.shape != (n,):
                raise VLNVerseError(f"actions: expected {n} action ids, got shape {arr.shape}")
            return np.ascontiguousarray(arr)
        if arr.dtype.kind not in "iuf":
            raise VLNVerseError(f"actions: expected numbers, got dtype {arr.dtype}")
        arr = np.ascontiguousarray(arr, dtype=np.float32).reshape(n, -1)
        if arr.shape != (n, 3):
            raise VLNVerseError(f"actions: expected shape ({n}, 3), got {arr.shape}")
        return arr

    def _observations(self, raw: dict[str, Any]) -> dict[str, Any]:
        obs: dict[str, Any] = {
            k: (v.copy() if self._copy else v) for k, v in self._buffers.items()
        }
        obs["instruction"] = tuple(raw["instruction"])
        if self._dialogue:
            obs["oracle_answer"] = tuple(raw["oracle_answer"])
        return obs

    def _infos(self, raw: dict[str, Any]) -> dict[str, Any]:
        n = self.num_envs
        infos: dict[str, Any] = {}
        every = np.ones(n, dtype=bool)
        for k in INFO_KEYS:
            v = raw[k]
            infos[k] = np.asarray(v) if not isinstance(v, list) else np.array(v, dtype=object)
            infos[f"_{k}"] = every
        records = raw["record"]
        ended = np.array([r is not None for r in records], dtype=bool)
        if ended.any():
            infos["record"] = np.array(records, dtype=object)
            infos["_record"] = ended
            metrics = np.empty(n, dtype=object)
            for i, r in enumerate(records):
                if r is not None:
                    metrics[i] = json.loads(r)["metrics"]
            infos["metrics"] = metrics
            infos["_metrics"] = ended
        refused = raw["refused"]
        if any(r is not None for r in refused):
            infos["refused"] = np.array(refused, dtype=object)
            infos["_refused"] = np.array([r is not None for r in refused], dtype=bool)
        return infos

    @property
    def vocab(self) -> list[str]:
        """The instruction vocabulary (token id = index)."""
        return list(self._live().vocab())


def make_vec(dataset: PathLike, task: str = "fine", split: str = "val_unseen", *,
             num_envs: int = 1, **kwargs: Any) -> VectorEnv:
    """A natively vectorised environment: ``VectorEnv(dataset, task, split, num_envs=N, ...)``."""
    return VectorEnv(dataset, task, split, num_envs=num_envs, **kwargs)
