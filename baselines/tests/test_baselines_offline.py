"""Offline training on `cargo xtask export --format lerobot` data (read with LeRobotDataset)."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
import torch
import vlnverse

from vlnverse_baselines.cli import main
from vlnverse_baselines.data import render_teacher_trajectories
from vlnverse_baselines.lerobot_data import load_lerobot_trajectories

DATASET = os.environ.get("VLNVERSE_TEST_DATASET", "")
XTASK = os.environ.get("VLNVERSE_XTASK", "")
pytestmark = pytest.mark.skipif(not (DATASET and XTASK),
                                reason="VLNVERSE_TEST_DATASET / VLNVERSE_XTASK are not set")

torch.set_num_threads(1)
EPISODES = 3


@pytest.fixture(scope="module")
def export(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("lerobot") / "tiny-fine-train"
    subprocess.run([XTASK, "export", "--dataset", DATASET, "--task", "fine", "--split", "train",
                    "--format", "lerobot", "--episodes", str(EPISODES), "--out", str(out)],
                   check=True, capture_output=True, timeout=300)
    return out


def test_export_loads_as_the_trajectories_the_env_renders(export: Path) -> None:
    """The LeRobot frames, downsampled, equal the vector env's along the teacher's path, with
    the same teacher actions, previous actions and instruction tokens."""
    got = load_lerobot_trajectories(export, rgb_size=56, depth_size=64)
    ids = [int(e["episode_id"]) for e in vlnverse.load_episodes(DATASET, "fine", "train")]
    want = render_teacher_trajectories(DATASET, "fine", "train", rgb_size=56, depth_size=64,
                                       episode_ids=ids[:EPISODES])
    assert [t.episode_id for t in got] == [t.episode_id for t in want] == sorted(ids[:EPISODES])
    for a, b in zip(got, want, strict=True):
        assert np.array_equal(a.actions, b.actions) and a.actions[-1] == 0
        assert np.array_equal(a.prev_actions, b.prev_actions)
        assert np.array_equal(a.tokens, b.tokens)
        assert np.array_equal(a.rgb, b.rgb)
        assert np.array_equal(a.depth, b.depth)
    assert len(load_lerobot_trajectories(export, rgb_size=56, depth_size=64, episodes=1)) == 1


def test_offline_training_on_the_export_lowers_the_loss(export: Path, tmp_path: Path) -> None:
    out = tmp_path / "s2s"
    assert main(["train", "--model", "seq2seq", "--mode", "offline", "--data", str(export),
                 "--dataset", DATASET, "--task", "fine", "--out", str(out), "--epochs", "10",
                 "--batch-size", "1", "--lr", "3e-3"]) == 0
    log = [json.loads(line) for line in (out / "train_log.jsonl").read_text().splitlines()]
    assert [r["epoch"] for r in log] == list(range(1, 11))
    assert log[-1]["loss"] < 0.85 * log[0]["loss"], log
    assert all(r["samples"] == log[0]["samples"] for r in log)  # every frame, every epoch
    cfg = json.loads((out / "train_config.json").read_text())
    assert cfg["model"]["model"] == "seq2seq" and cfg["parameters"] > 0


def test_not_an_export_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["train", "--model", "cma", "--mode", "offline", "--data", str(tmp_path),
                 "--dataset", DATASET, "--out", str(tmp_path / "o")]) == 2
    assert "not a LeRobot dataset (no meta/info.json)" in capsys.readouterr().err
