"""`cargo xtask export --format lerobot` on the tiny preset: LeRobot's own reader opens it, its
frames are what the `vlnverse` env renders at the same poses, and the teacher labels match."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import cast

import numpy as np
import pytest

# `cargo xtask test` runs pytest with --import-mode=importlib, which does not put this folder
# on sys.path: the helper module beside this file is found through it.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _export_helpers import column, dataset, episodes_meta, export, frames  # noqa: E402

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


def test_stats_json_is_lerobots_aggregate_of_the_episode_stats(exported: Path) -> None:
    import pyarrow.parquet as pq
    from lerobot.datasets.compute_stats import aggregate_stats

    rows = pq.read_table(exported / "meta" / "episodes" / "chunk-000" / "file-000.parquet")
    per_episode: list[dict[str, dict[str, np.ndarray]]] = []
    for row in rows.to_pylist():
        stats: dict[str, dict[str, np.ndarray]] = {}
        for key, value in row.items():
            if key.startswith("stats/"):
                feature, stat = key.removeprefix("stats/").rsplit("/", 1)
                stats.setdefault(feature, {})[stat] = np.asarray(value, dtype=np.float64)
        per_episode.append(stats)
    assert len(per_episode) == EPISODES
    assert per_episode[0]["observation.images.rgb"]["mean"].shape == (3, 1, 1)
    # (LeRobot annotates the result as a flat dict; it is per feature, per statistic.)
    expected = cast(dict[str, dict[str, np.ndarray]], aggregate_stats(per_episode))
    written = json.loads((exported / "meta" / "stats.json").read_text())
    assert set(written) == set(expected)
    for feature, feature_stats in expected.items():
        for stat, value in feature_stats.items():
            got = np.asarray(written[feature][stat], dtype=np.float64)
            np.testing.assert_allclose(got, value, rtol=1e-9, atol=1e-12, err_msg=feature + stat)
    rgb = written["observation.images.rgb"]
    assert 0.0 <= rgb["min"][0][0][0] <= rgb["mean"][0][0][0] <= rgb["max"][0][0][0] <= 1.0
