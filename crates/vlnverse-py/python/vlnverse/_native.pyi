"""Type stubs of the native module (``crates/vlnverse-py/src``)."""

from os import PathLike
from typing import Any, Optional, Union

import numpy as np

_Path = Union[str, PathLike[str]]

__version__: str

class VLNVerseError(ValueError):
    """Bad input or a failed job; the message names the file, field and value."""

class NativeVecEnv:
    """A batch of environments stepped in Rust (wrapped by ``vlnverse.VectorEnv``)."""

    closed: bool
    def __init__(
        self,
        dataset: _Path,
        task: str,
        split: str,
        *,
        num_envs: int = 1,
        setting: str = "telhop",
        action_space: str = "discrete",
        profile: str = "vlnverse",
        sensors: Optional[_Path] = None,
        mode: str = "eval",
        seed: int = 0,
        max_steps: Optional[int] = None,
        success_distance: Optional[float] = None,
        reward: str = "sparse",
        episode_ids: Optional[list[int]] = None,
        render: bool = True,
        normalize_depth: bool = True,
        instruction_length: int = 200,
        backend: Optional[str] = None,
    ) -> None: ...
    def spec(self) -> dict[str, Any]: ...
    def buffers(self) -> dict[str, np.ndarray]: ...
    def vocab(self) -> list[str]: ...
    def reset(self, seed: Optional[int] = None) -> dict[str, Any]: ...
    def step(self, actions: np.ndarray, reset_mask: list[bool]) -> dict[str, Any]: ...
    def close(self) -> None: ...

class RunFolder:
    """An evaluation run folder opened for writing (locked, resumable)."""

    def __init__(
        self,
        out: _Path,
        dataset: _Path,
        task: str,
        split: str,
        *,
        agent: str,
        agent_fingerprint: Optional[str] = None,
        setting: str = "telhop",
        action_space: str = "discrete",
        profile: str = "vlnverse",
        sensors: Optional[_Path] = None,
        seed: int = 0,
        max_steps: Optional[int] = None,
        success_distance: Optional[float] = None,
        episodes: Optional[int] = None,
        fresh: bool = False,
        render: bool = True,
        backend: Optional[str] = None,
    ) -> None: ...
    def todo(self) -> list[int]: ...
    def finished(self) -> int: ...
    def record(self, record: str) -> None: ...
    def finish(self) -> str: ...
    def close(self) -> None: ...

def load_episodes(dataset: _Path, task: str, split: str) -> str: ...
def score(
    dataset: _Path,
    task: str,
    split: str,
    trajectories: _Path,
    out: _Path,
    *,
    success_distance: float = 3.0,
    fail_on_collision: bool = False,
    method: Optional[str] = None,
) -> str: ...
