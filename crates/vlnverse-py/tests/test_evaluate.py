"""Evaluation from Python: the teacher's success, identity with the CLI, resume, scoring."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
import vlnverse
from vlnverse import VLNVerseError

from .conftest import ROOT, xtask


@pytest.mark.parametrize(("setting", "least"), [("telhop", 0.99), ("strict", 0.95)])
def test_teacher_from_python_succeeds(dataset: Path, tmp_path: Path, setting: str,
                                      least: float) -> None:
    for task in ("fine", "coarse"):
        s = vlnverse.evaluate(vlnverse.TeacherAgent(), dataset=dataset, task=task,
                              split="val_unseen", setting=setting, out=tmp_path / task,
                              num_envs=4, render=False, progress=False)
        assert s["episodes"] > 0
        assert s["sr"] >= least, (task, setting, s)


def test_python_evaluate_equals_xtask_evaluate(dataset: Path, tmp_path: Path) -> None:
    cli = tmp_path / "cli"
    subprocess.run([*xtask(), "evaluate", "--dataset", str(dataset), "--task", "fine",
                    "--split", "val_unseen", "--agent", "oracle", "--setting", "strict",
                    "--action-space", "discrete", "--out", str(cli)], check=True, cwd=ROOT)
    py = tmp_path / "py"
    vlnverse.evaluate(vlnverse.TeacherAgent(), dataset=dataset, task="fine", split="val_unseen",
                      setting="strict", out=py, num_envs=3, progress=False)
    for f in ("summary.json", "episodes.csv", "trajectories.jsonl"):
        assert (py / f).read_bytes() == (cli / f).read_bytes(), f


def test_evaluate_resumes_and_refuses_another_agent(dataset: Path, tmp_path: Path) -> None:
    out = tmp_path / "run"
    kw = dict(dataset=dataset, task="fine", split="val_unseen", out=out, render=False,
              progress=False)
    first = vlnverse.evaluate(vlnverse.TeacherAgent(), episodes=3, **kw)  # type: ignore[arg-type]
    assert first["episodes"] == 3
    lines = (out / "progress.jsonl").read_text().splitlines()
    full = vlnverse.evaluate(vlnverse.TeacherAgent(), **kw)  # type: ignore[arg-type]
    # The three finished episodes were kept, not run again.
    assert (out / "progress.jsonl").read_text().splitlines()[:3] == lines
    assert full["episodes"] > 3
    with pytest.raises(VLNVerseError, match="agent"):
        vlnverse.evaluate(vlnverse.TeacherAgent(), name="teacher-v2", **kw)  # type: ignore[arg-type]
    fresh = vlnverse.evaluate(vlnverse.TeacherAgent(), name="teacher-v2", fresh=True, **kw)  # type: ignore[arg-type]
    assert fresh["method"] == "teacher-v2"


def test_random_agent_runs_and_score_rescores_its_trajectories(dataset: Path,
                                                                tmp_path: Path) -> None:
    env = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    agent = vlnverse.RandomAgent(vlnverse.make_vec(dataset, "fine", "val_unseen",
                                                   num_envs=2).action_space, seed=3)
    env.close()
    s = vlnverse.evaluate(agent, dataset=dataset, task="fine", split="val_unseen",
                          out=tmp_path / "rnd", num_envs=2, episodes=4, progress=False)
    again = vlnverse.score(dataset, "fine", "val_unseen", tmp_path / "rnd" / "trajectories.jsonl",
                           tmp_path / "scored", allow_missing=True, method="random-py")
    assert again["episodes"] == len(vlnverse.load_episodes(dataset, "fine", "val_unseen"))
    assert s["episodes"] == 4 and again["method"] == "random-py"
    # The four run episodes score as in the run; the rest are failures.
    run_csv = (tmp_path / "rnd" / "episodes.csv").read_text().splitlines()
    scored_csv = (tmp_path / "scored" / "episodes.csv").read_text().splitlines()
    assert scored_csv[: len(run_csv)] == run_csv


def test_load_episodes_gives_the_split(dataset: Path) -> None:
    eps = vlnverse.load_episodes(dataset, "long_horizon", "val_unseen")
    assert eps and all(e["sub_goals"] for e in eps)
    with pytest.raises(VLNVerseError, match="test.json.gz|no such|not found|No such"):
        vlnverse.load_episodes(dataset / "missing", "fine", "test")


def test_the_example_runs(dataset: Path, tmp_path: Path) -> None:
    import sys

    out = subprocess.run([sys.executable, str(ROOT / "examples/python/evaluate_teacher.py"),
                          str(dataset)], cwd=tmp_path, check=True, capture_output=True, text=True)
    assert "teacher  SR 1.00" in out.stdout and "success: True" in out.stdout
    assert (tmp_path / "runs/py-teacher/summary.json").is_file()


def test_sampled_evaluation_equals_the_cli(dataset: Path, tmp_path: Path) -> None:
    cli = tmp_path / "cli"
    subprocess.run([*xtask(), "evaluate", "--dataset", str(dataset), "--task", "coarse",
                    "--split", "val_unseen", "--agent", "oracle", "--setting", "telhop",
                    "--action-space", "discrete", "--sample", "5", "--seed", "11",
                    "--no-render", "--out", str(cli)], check=True, cwd=ROOT)
    py = tmp_path / "py"
    s = vlnverse.evaluate(vlnverse.TeacherAgent(), dataset=dataset, task="coarse",
                          split="val_unseen", setting="telhop", out=py, num_envs=2, sample=5,
                          seed=11, render=False, progress=False)
    assert s["episodes"] == 5
    for f in ("summary.json", "episodes.csv", "trajectories.jsonl"):
        assert (py / f).read_bytes() == (cli / f).read_bytes(), f
