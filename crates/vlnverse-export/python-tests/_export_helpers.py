"""Shared helpers of the export tests: run `cargo xtask export` on the tiny dataset."""

from __future__ import annotations

import io
import json
import os
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow.parquet as pq
from PIL import Image


def xtask() -> str:
    """The xtask binary (`VLNVERSE_XTASK`)."""
    path = os.environ.get("VLNVERSE_XTASK")
    if not path:
        raise RuntimeError("VLNVERSE_XTASK is not set (cargo xtask test sets it)")
    return path


def dataset() -> Path:
    """The tiny dataset (`VLNVERSE_TEST_DATASET`)."""
    path = os.environ.get("VLNVERSE_TEST_DATASET")
    if not path:
        raise RuntimeError("VLNVERSE_TEST_DATASET is not set (cargo xtask test sets it)")
    return Path(path)


def export(out: Path, *args: str) -> str:
    """Run the export into `out`; returns its stdout."""
    cmd = [xtask(), "export", "--dataset", str(dataset()), "--out", str(out), *args]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)} failed:\n{done.stdout}\n{done.stderr}")
    return done.stdout


def episodes_meta(root: Path) -> list[dict[str, Any]]:
    """`meta/vlnverse_episodes.jsonl`."""
    lines = (root / "meta" / "vlnverse_episodes.jsonl").read_text().splitlines()
    return [json.loads(line) for line in lines if line.strip()]


def data_file(root: Path, episode_index: int) -> Path:
    """Episode `episode_index`'s data file (one per episode)."""
    chunk, file = divmod(episode_index, 1000)
    return root / "data" / f"chunk-{chunk:03d}" / f"file-{file:03d}.parquet"


def column(root: Path, episode_index: int, key: str) -> np.ndarray:
    """One scalar or fixed-length column of an episode as a NumPy array."""
    col = pq.read_table(data_file(root, episode_index), columns=[key]).column(key)
    return np.asarray(col.to_pylist())


def frames(root: Path, episode_index: int) -> dict[str, Any]:
    """One episode's data file as raw arrays: `rgb` uint8 [T, H, W, 3] (PNG decoded), `depth`
    float32 [T, H, W, 1], the other columns as NumPy arrays."""
    table = pq.read_table(data_file(root, episode_index))
    n = table.num_rows
    out: dict[str, Any] = {}
    out["rgb"] = np.stack(
        [
            np.asarray(Image.open(io.BytesIO(img["bytes"])).convert("RGB"))
            for img in table.column("observation.images.rgb").to_pylist()
        ]
    )
    depth = table.column("observation.depth").combine_chunks()
    flat = depth.flatten().flatten().flatten().to_numpy(zero_copy_only=False)
    out["depth"] = flat.astype(np.float32).reshape(n, 256, 256, 1)
    for key in [
        "observation.pose",
        "observation.compass",
        "observation.gps",
        "observation.instruction_tokens",
        "action",
        "frame_index",
        "index",
    ]:
        out[key] = np.asarray(table.column(key).to_pylist())
    return out
