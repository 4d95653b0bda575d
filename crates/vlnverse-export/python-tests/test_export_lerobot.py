"""`cargo xtask export --format lerobot` on the tiny preset: LeRobot's own reader opens it, its
frames are what the `vlnverse` env renders at the same poses, and the teacher labels match."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from _export_helpers import column, dataset, episodes_meta, export, frames

os.environ.setdefault("HF_HUB_OFFLINE", "1")

TASK, SPLIT, EPISODES = "fine", "val_unseen", 3


@pytest.fixture(scope="module")
def exported(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("lerobot") / "tiny"
    os.environ["HF_DATASETS_CACHE"] = str(tmp_path_factory.mktemp("hf-cache"))
    export(root, "--task", TASK, "--split", SPLIT, "--episodes", str(EPISODES), "--threads", "2")
    return root


def test_lerobot_dataset_opens_the_export(exported: Path) -> None:
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    ds = LeRobotDataset(repo_id="vlnverse/tiny", root=exported)
    info = json.loads((exported / "meta" / "info.json").read_text())
    meta = episodes_meta(exported)
    assert ds.num_episodes == EPISODES == len(meta)
    assert len(ds) == ds.num_frames == info["total_frames"] == sum(m["length"] for m in meta)
    assert ds.fps == 10
    first = ds[0]
    assert first["observation.images.rgb"].shape == (3, 224, 224)
    assert first["observation.depth"].shape == (256, 256, 1)
    assert first["observation.pose"].shape == (4,)
    assert first["observation.gps"].shape == (2,)
    assert first["observation.instruction_tokens"].shape == (200,)
    assert ds.meta.stats is not None and "observation.depth" in ds.meta.stats
    for m in meta:
        end = m["from_index"] + m["length"]
        last = ds[end - 1]
        assert int(last["action"]) == 0, "the last frame's action is STOP"
        assert last["task"] == m["instruction"]
        assert int(last["episode_index"]) == m["episode_index"]
        assert int(last["frame_index"]) == m["length"] - 1
        assert float(last["timestamp"]) == pytest.approx((m["length"] - 1) / 10)
        actions = [int(a) for a in column(exported, m["episode_index"], "action")]
        assert len(actions) == m["length"] >= 2
        assert actions[-1] == 0 and set(actions[:-1]) <= {1, 2, 3}, actions
        assert 1 in actions, "the teacher moves forward at least once"
    depth = first["observation.depth"].numpy()
    assert 0.0 <= depth.min() and depth.max() <= 1.0 and depth.std() > 0


def test_frames_equal_the_env_at_the_same_poses(exported: Path) -> None:
    import vlnverse

    meta = episodes_meta(exported)[0]
    data = frames(exported, 0)
    env = vlnverse.VLNEnv(
        dataset(), TASK, SPLIT, episode_ids=[meta["episode_id"]], setting="telhop", seed=0
    )
    try:
        obs, info = env.reset(seed=0)
        n = meta["length"]
        for t in range(n):
            assert np.array_equal(obs["rgb"], data["rgb"][t]), f"rgb differs at frame {t}"
            assert np.array_equal(obs["depth"], data["depth"][t]), f"depth differs at frame {t}"
            np.testing.assert_array_equal(obs["pose"], data["observation.pose"][t])
            np.testing.assert_array_equal(obs["gps"], data["observation.gps"][t])
            assert float(obs["compass"][0]) == float(data["observation.compass"][t])
            np.testing.assert_array_equal(
                obs["instruction_tokens"], data["observation.instruction_tokens"][t]
            )
            action = int(data["action"][t])
            assert int(info["expert_action"]) == action, f"teacher differs at frame {t}"
            obs, _, terminated, truncated, info = env.step(action)
            if t < n - 1:
                assert not (terminated or truncated), f"the env ended early, at frame {t}"
        assert terminated or truncated, "the env goes on after the exported STOP"
    finally:
        env.close()
    assert list(data["frame_index"]) == list(range(meta["length"]))
    assert list(data["index"]) == list(range(meta["from_index"], meta["from_index"] + n))
