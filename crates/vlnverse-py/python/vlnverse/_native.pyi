"""Type stubs of the native module (``crates/vlnverse-py/src``)."""

from os import PathLike
from typing import Any, Callable

from numpy.typing import NDArray

_Path = str | PathLike[str]

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
        sensors: _Path | None = None,
        mode: str = "eval",
        seed: int = 0,
        max_steps: int | None = None,
        success_distance: float | None = None,
        reward: str = "sparse",
        episode_ids: list[int] | None = None,
        render: bool = True,
        normalize_depth: bool = True,
        instruction_length: int = 200,
        backend: str | None = None,
        home_repeat: int = 32,
    ) -> None: ...
    def spec(self) -> dict[str, Any]: ...
    def buffers(self) -> dict[str, NDArray[Any]]: ...
    def vocab(self) -> list[str]: ...
    def reset(self, seed: int | None = None) -> dict[str, Any]: ...
    def step(self, actions: NDArray[Any], reset_mask: list[bool]) -> dict[str, Any]: ...
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
        agent_fingerprint: str | None = None,
        setting: str = "telhop",
        action_space: str = "discrete",
        profile: str = "vlnverse",
        sensors: _Path | None = None,
        seed: int = 0,
        max_steps: int | None = None,
        success_distance: float | None = None,
        episodes: int | None = None,
        sample: int | None = None,
        fresh: bool = False,
        render: bool = True,
        backend: str | None = None,
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
    allow_missing: bool = False,
    method: str | None = None,
    force: bool = False,
) -> str: ...
def generate(
    out: _Path,
    *,
    preset: str = "tiny",
    config: _Path | None = None,
    seed: int | None = None,
    tasks: list[str] | None = None,
    shard: tuple[int, int] | None = None,
    threads: int | None = None,
    scenes_from: _Path | None = None,
    on_scene: Callable[[int, int], None] | None = None,
) -> dict[str, Any]: ...
def merge(out: _Path, parts: list[_Path]) -> int: ...
def evaluate_mllm(
    dataset: _Path,
    task: str,
    split: str,
    out: _Path,
    *,
    endpoint: str,
    model: str,
    config_path: _Path | None = None,
    config_json: str | None = None,
    setting: str = "telhop",
    action_space: str = "discrete",
    profile: str = "vlnverse",
    sensors: _Path | None = None,
    seed: int = 0,
    max_steps: int | None = None,
    success_distance: float | None = None,
    episodes: int | None = None,
    sample: int | None = None,
    threads: int | None = None,
    version: str | None = None,
    fresh: bool = False,
    render: bool = True,
) -> str: ...
