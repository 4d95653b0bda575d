"""Offline data: the LeRobot dataset ``cargo xtask export --format lerobot`` writes, read with
the ``lerobot`` package's own ``LeRobotDataset`` (no network: ``HF_HUB_OFFLINE=1``).

Each LeRobot episode is one VLN episode, one frame per teacher step (the last frame's action is
STOP); the features used here are ``observation.images.rgb``, ``observation.depth``,
``observation.instruction_tokens`` and ``action`` (docs/export.md)."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from vlnverse_baselines.config import NUM_ACTIONS, ConfigError
from vlnverse_baselines.data import Trajectory, teacher_prev_actions
from vlnverse_baselines.obs import downsample_depth, downsample_rgb

RGB_KEY = "observation.images.rgb"
DEPTH_KEY = "observation.depth"
TOKENS_KEY = "observation.instruction_tokens"
ACTION_KEY = "action"


def open_lerobot(root: str | os.PathLike[str], episodes: list[int] | None = None) -> Any:
    """``LeRobotDataset(repo_id="vlnverse/<folder name>", root=root)``, offline."""
    path = Path(root)
    if not (path / "meta" / "info.json").is_file():
        raise ConfigError(f"{path}: not a LeRobot dataset (no meta/info.json); write one with "
                          "`cargo xtask export --format lerobot --out DIR`")
    os.environ.setdefault("HF_HUB_OFFLINE", "1")
    try:
        from lerobot.datasets.lerobot_dataset import LeRobotDataset
    except ImportError as e:
        raise ConfigError(f"offline data needs the lerobot package (pip install "
                          f"lerobot==0.4.4): {e}") from e
    ds = LeRobotDataset(repo_id=f"vlnverse/{path.name}", root=path, episodes=episodes)
    missing = [k for k in (RGB_KEY, DEPTH_KEY, TOKENS_KEY, ACTION_KEY) if k not in ds.features]
    if missing:
        raise ConfigError(f"{path}: LeRobot dataset lacks feature(s) {', '.join(missing)}")
    return ds


def _hwc(x: np.ndarray, channels: int) -> np.ndarray:
    """Frames as ``[N, H, W, C]`` whether they come channel-first or last."""
    if x.ndim == 3:
        return x[..., None]
    if x.shape[-1] == channels:
        return x
    return np.moveaxis(x, 1, -1)


def _rows(ds: Any, chunk: int) -> Iterator[dict[str, Any]]:
    """The frames in chunks, as NumPy arrays straight from Arrow (LeRobot's own per-item
    transform turns every depth map into nested Python lists first: 100x slower)."""
    hf = ds.hf_dataset.with_format("numpy")
    for start in range(0, len(hf), chunk):
        yield hf[start:start + chunk]


def load_lerobot_trajectories(root: str | os.PathLike[str], *, rgb_size: int, depth_size: int,
                              episodes: int | None = None, chunk: int = 128) -> list[Trajectory]:
    """The export's episodes as downsampled trajectories (ordered by LeRobot episode index),
    with teacher-forcing previous actions. ``episodes=N`` reads the first N only."""
    path = Path(root)
    if not (path / "meta" / "info.json").is_file():
        raise ConfigError(f"{path}: not a LeRobot dataset (no meta/info.json); write one with "
                          "`cargo xtask export --format lerobot --out DIR`")
    total = _total_episodes(path)
    chosen = None if episodes is None else list(range(min(episodes, total)))
    ds = open_lerobot(path, chosen)
    ids = _vln_episode_ids(path)
    frames: dict[int, list[tuple[int, np.ndarray, np.ndarray, np.ndarray, int]]] = {}
    for rows in _rows(ds, chunk):
        ep = [int(v) for v in rows["episode_index"]]
        fi = [int(v) for v in rows["frame_index"]]
        rgb_f = _hwc(np.asarray(rows[RGB_KEY]), 3)
        if rgb_f.dtype != np.uint8:  # floats in [0, 1]
            rgb_f = np.clip(np.round(rgb_f * 255.0), 0, 255).astype(np.uint8)
        rgb = downsample_rgb(rgb_f, rgb_size)
        depth = downsample_depth(_hwc(np.asarray(rows[DEPTH_KEY], dtype=np.float32), 1),
                                 depth_size)
        actions = np.asarray(rows[ACTION_KEY], dtype=np.int64).reshape(len(ep), -1)[:, 0]
        tokens = np.asarray(rows[TOKENS_KEY], dtype=np.int64).reshape(len(ep), -1)
        for j in range(len(ep)):
            action = int(actions[j])
            if not 0 <= action < NUM_ACTIONS:
                raise ConfigError(f"{path}: episode {ep[j]} frame {fi[j]}: action {action} "
                                  f"outside 0..{NUM_ACTIONS - 1}")
            frames.setdefault(ep[j], []).append((fi[j], rgb[j], depth[j], tokens[j], action))
    out = []
    for ep_index in sorted(frames):
        fr = sorted(frames[ep_index], key=lambda f: f[0])
        actions = np.array([f[4] for f in fr], dtype=np.int64)
        out.append(Trajectory(
            episode_id=ids.get(ep_index, ep_index),
            rgb=np.stack([f[1] for f in fr]), depth=np.stack([f[2] for f in fr]),
            tokens=fr[0][3], actions=actions, prev_actions=teacher_prev_actions(actions)))
    return out


def _total_episodes(path: Path) -> int:
    try:
        info = json.loads((path / "meta" / "info.json").read_text(encoding="utf-8"))
        return int(info["total_episodes"])
    except (OSError, KeyError, ValueError, TypeError) as e:
        raise ConfigError(f"{path}/meta/info.json: field 'total_episodes': {e}") from e


def _vln_episode_ids(path: Path) -> dict[int, int]:
    """LeRobot episode index -> VLN episode id, from ``meta/vlnverse_episodes.jsonl``."""
    f = path / "meta" / "vlnverse_episodes.jsonl"
    out: dict[int, int] = {}
    if not f.is_file():
        return out
    for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip():
            continue
        try:
            rec = json.loads(line)
            out[int(rec["episode_index"])] = int(rec["episode_id"])
        except (ValueError, KeyError, TypeError):
            # Metadata is informative only: a malformed line keeps the LeRobot index.
            _ = n
    return out
