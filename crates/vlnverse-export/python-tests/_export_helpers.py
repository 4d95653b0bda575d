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


def frames(root: Path, episode_index: int) -> dict[str, Any]:
    """One episode's data file as raw arrays: `rgb` uint8 [T, H, W, 3] (PNG decoded), `depth`
    float32 [T, H, W, 1], the other columns as NumPy arrays."""
    path = root / "data" / f"chunk-{episode_index // 1000:03d}" / (
        f"file-{episode_index % 1000:03d}.parquet"
    )
    table = pq.read_table(path).to_pydict()
    out: dict[str, Any] = {}
    out["rgb"] = np.stack([
        np.asarray(Image.open(io.BytesIO(img["bytes"])).convert("RGB"))
        for img in table["observation.images.rgb"]
    ])
    out["depth"] = np.asarray(table["observation.depth"], dtype=np.float32)
    for key in ["observation.pose", "observation.compass", "observation.gps",
                "observation.instruction_tokens", "action", "frame_index", "index"]:
        out[key] = np.asarray(table[key])
    return out
