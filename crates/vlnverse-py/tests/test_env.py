"""The Gymnasium environments: spaces, check_env, vector vs single, errors, the GIL."""

from __future__ import annotations

import sys
import threading
from pathlib import Path

import gymnasium
import numpy as np
import pytest
import vlnverse
from gymnasium.utils.env_checker import check_env
from vlnverse import VLNVerseError

TASKS = ["fine", "coarse", "visual_reference", "long_horizon", "dialogue"]


@pytest.mark.parametrize("space", ["discrete", "continuous", "waypoint"])
@pytest.mark.parametrize("task", TASKS)
def test_check_env_passes_for_every_task_and_action_space(dataset: Path, task: str,
                                                           space: str) -> None:
    setting = "strict" if space == "continuous" else "telhop"
    env = vlnverse.VLNEnv(dataset, task, "val_unseen", action_space=space, setting=setting)
    check_env(env, skip_render_check=True)
    obs, info = env.reset(seed=1)
    assert obs["rgb"].shape == (224, 224, 3) and obs["rgb"].dtype == np.uint8
    assert obs["depth"].shape == (256, 256, 1) and obs["depth"].dtype == np.float32
    assert 0.0 <= float(obs["depth"].min()) and float(obs["depth"].max()) <= 1.0
    # Tokens in the vocabulary (ids > 1); a word only val/test instructions use is <unk> (1).
    assert obs["instruction"] and int((obs["instruction_tokens"] > 1).sum()) >= 3
    expert = np.asarray(info["expert_action"], dtype=env.action_space.dtype)
    assert env.action_space.contains(expert)
    if task == "dialogue":
        assert "oracle_answer" in obs
        if space == "discrete":
            assert env.action_space == gymnasium.spaces.Discrete(7)
    env.close()


def test_registered_id_makes_the_env(dataset: Path) -> None:
    env = gymnasium.make(vlnverse.ENV_ID, dataset=dataset, task="fine", split="val_unseen")
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    envs = gymnasium.make_vec(vlnverse.ENV_ID, num_envs=2, vectorization_mode="vector_entry_point",
                              dataset=dataset, task="fine", split="val_unseen")
    obs, _ = envs.reset(seed=0)
    assert obs["rgb"].shape == (2, 224, 224, 3)
    envs.close()


def test_vector_env_equals_single_envs_step_by_step(dataset: Path) -> None:
    ids = [e["episode_id"] for e in vlnverse.load_episodes(dataset, "fine", "val_unseen")][:3]
    vec = vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs=3, episode_ids=ids)
    singles = [vlnverse.VLNEnv(dataset, "fine", "val_unseen", episode_ids=[i]) for i in ids]
    vobs, vinfo = vec.reset(seed=7)
    sobs = [s.reset(seed=7) for s in singles]
    live = [True] * 3
    rng = np.random.default_rng(0)
    steps = 0
    while any(live):
        for k in range(3):
            if not live[k]:
                continue
            o, info = sobs[k]
            assert info["episode_id"] == vinfo["episode_id"][k]
            for key in ("rgb", "depth", "pose", "compass", "gps", "instruction_tokens"):
                np.testing.assert_array_equal(o[key], vobs[key][k], err_msg=f"{key} env {k}")
            assert o["instruction"] == vobs["instruction"][k]
            assert info["expert_action"] == vinfo["expert_action"][k]
            assert info["distance_to_goal"] == pytest.approx(vinfo["distance_to_goal"][k], abs=0)
        # The teacher's action, now and then a random turn or a forward move into a wall.
        actions = np.where(rng.random(3) < 0.2, rng.integers(1, 4, 3), vinfo["expert_action"])
        vobs, _, vterm, vtrunc, vinfo = vec.step(actions)
        for k, s in enumerate(singles):
            if live[k]:
                o, r, term, trunc, info = s.step(int(actions[k]))
                assert (term, trunc) == (vterm[k], vtrunc[k])
                sobs[k] = (o, info)
                if term or trunc:
                    assert info["metrics"] == vinfo["metrics"][k]
                    live[k] = False
        steps += 1
        assert steps < 500
    vec.close()


def test_eval_mode_visits_every_episode_once_in_order(dataset: Path) -> None:
    ids = [e["episode_id"] for e in vlnverse.load_episodes(dataset, "coarse", "val_unseen")]
    # Count starts exactly: every reset (autoreset included) takes the next id in file order.
    envs = vlnverse.make_vec(dataset, "coarse", "val_unseen", num_envs=4, render=False)
    _, info = envs.reset(seed=0)
    starts = [int(x) for x in info["episode_id"]]
    autoreset = np.zeros(4, dtype=bool)
    while len(starts) < len(ids):
        _, _, term, trunc, info = envs.step(info["expert_action"])
        starts += [int(info["episode_id"][i]) for i in np.flatnonzero(autoreset)]
        autoreset = term | trunc
    assert sorted(starts[: len(ids)]) == sorted(ids)
    assert len(set(starts[: len(ids)])) == len(ids)
    envs.close()


def test_train_mode_stays_in_a_home_for_home_repeat_episodes(dataset: Path) -> None:
    # Episodes of 1 step (max_steps=1): every step after the first resets every environment.
    envs = vlnverse.make_vec(dataset, "fine", "train", num_envs=2, mode="train", seed=4,
                             home_repeat=3, max_steps=1, render=False)
    _, info = envs.reset(seed=4)
    homes: list[list[str]] = [[str(h)] for h in info["scene_id"]]
    for k in range(2 * 12 - 1):
        _, _, term, trunc, info = envs.step(info["expert_action"])
        if k % 2 == 1:  # an autoreset step: each environment began its next episode
            for i in range(2):
                homes[i].append(str(info["scene_id"][i]))
    visits = [h[j:j + 3] for h in homes for j in range(0, len(h), 3)]
    assert all(len(v) == 3 and len(set(v)) == 1 for v in visits), visits
    assert len({v[0] for v in visits}) > 1, visits
    envs.close()


def test_next_step_autoreset_follows_gymnasium(dataset: Path) -> None:
    envs = vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs=2, render=False)
    assert envs.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.NEXT_STEP
    _, info = envs.reset(seed=0)
    first = int(info["episode_id"][0])
    ended = False
    for _ in range(300):
        _, rew, term, trunc, info = envs.step(info["expert_action"])
        if term[0] or trunc[0]:
            ended = True
            assert info["_metrics"][0] and info["metrics"][0]["episode_id"] == first
            break
    assert ended
    # The next step resets env 0: reward 0, not done, a new episode at step 0.
    _, rew, term, trunc, info = envs.step(np.array([3, info["expert_action"][1]]))
    assert rew[0] == 0.0 and not term[0] and not trunc[0]
    assert info["steps"][0] == 0 and int(info["episode_id"][0]) != first
    envs.close()


def test_another_thread_runs_while_a_vector_step_runs(dataset: Path) -> None:
    envs = vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs=8, copy=False)
    _, info = envs.reset(seed=0)
    count = 0
    stop = False

    def spin() -> None:
        nonlocal count
        while not stop:
            count += 1
            # Yield the GIL each round, so only a released GIL lets this run during a step.
            threading.Event().wait(0)

    old = sys.getswitchinterval()
    sys.setswitchinterval(1.0)
    t = threading.Thread(target=spin)
    t.start()
    try:
        during = 0
        native = envs._native
        assert native is not None
        mask = [False] * 8
        acts = np.ones(8, dtype=np.int64)
        for _ in range(5):
            before = count
            native.step(acts, mask)
            during += count - before
    finally:
        stop = True
        t.join()
        sys.setswitchinterval(old)
        envs.close()
    assert during > 0, "no progress in another thread while stepping: the GIL was held"


def test_bad_input_raises_clear_errors(dataset: Path, tmp_path: Path) -> None:
    with pytest.raises(VLNVerseError, match="nowhere"):
        vlnverse.VLNEnv(tmp_path / "nowhere", "fine", "val_unseen")
    with pytest.raises(VLNVerseError, match="invalid task 'finest'"):
        vlnverse.VLNEnv(dataset, "finest", "val_unseen")
    with pytest.raises(VLNVerseError, match="num_envs must be an int"):
        vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs="4")
    env = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    env.reset(seed=0)
    with pytest.raises(VLNVerseError, match=r"actions\[0\] = 6: not in Discrete\(6\)"):
        env.step(6)
    with pytest.raises(VLNVerseError, match="integer action ids"):
        env.step("forward")
    env.close()
    with pytest.raises(VLNVerseError, match="closed"):
        env.step(1)
    cont = vlnverse.VLNEnv(dataset, "fine", "val_unseen", action_space="continuous",
                           setting="strict")
    cont.reset(seed=0)
    with pytest.raises(VLNVerseError, match=r"actions\[0\]\[0\] = NaN: actions must be finite"):
        cont.step(np.array([np.nan, 0.0, 0.0], dtype=np.float32))
    cont.close()


def test_finished_episode_must_be_reset(dataset: Path) -> None:
    env = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    env.reset(seed=0)
    _, _, term, _, info = env.step(0)
    assert term and info["metrics"]["steps"] == 1
    with pytest.raises(VLNVerseError, match="reset"):
        env.step(1)
    env.close()
