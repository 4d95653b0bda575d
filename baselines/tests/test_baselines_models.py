"""Models, schedule sampling, checkpoints and the CLI's errors (no environment stepping)."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

from vlnverse_baselines import (
    ModelConfig,
    build_model,
    load_checkpoint,
    save_checkpoint,
    teacher_probability,
)
from vlnverse_baselines.checkpoint import CheckpointError
from vlnverse_baselines.cli import main
from vlnverse_baselines.config import ConfigError
from vlnverse_baselines.data import Trajectory, collate, inflection_weights, teacher_prev_actions
from vlnverse_baselines.obs import downsample_depth, downsample_rgb
from vlnverse_baselines.schedule import mix_actions

torch.set_num_threads(1)


def _trajectory(rng: np.random.Generator, steps: int, vocab: int = 50) -> Trajectory:
    actions = rng.integers(0, 4, size=steps)
    tokens = np.zeros(200, dtype=np.int64)
    tokens[: 12] = rng.integers(2, vocab, size=12)
    return Trajectory(
        episode_id=int(rng.integers(1000)),
        rgb=rng.integers(0, 256, size=(steps, 56, 56, 3), dtype=np.uint8),
        depth=rng.random((steps, 64, 64, 1)).astype(np.float16),
        tokens=tokens, actions=actions, prev_actions=teacher_prev_actions(actions))


@pytest.mark.parametrize("name", ["seq2seq", "cma"])
def test_forward_shapes_and_state_reset(name: str) -> None:
    torch.manual_seed(0)
    model = build_model(ModelConfig(model=name, vocab_size=50)).eval()
    rng = np.random.default_rng(0)
    trajs = [_trajectory(rng, 7), _trajectory(rng, 4)]
    batch = collate(trajs)
    with torch.no_grad():
        logits, state = model.forward_sequence(batch, model.initial_state(2))
    assert logits.shape == (7, 2, 4)
    assert state.shape == (model.state_layers(), 2, 128)
    assert batch.weights[4:, 1].sum() == 0  # padding carries no loss
    # A start step zeroes the state: the same sequence from a garbage state gives the same
    # logits because step 0 is marked as a start.
    with torch.no_grad():
        again, _ = model.forward_sequence(batch, torch.randn_like(state) * 5)
    assert torch.allclose(logits, again, atol=1e-5)


def test_teacher_probability_decays_every_four_epochs() -> None:
    got = [teacher_probability(e, 0.85, 4) for e in range(9)]
    assert got[:4] == [0.85] * 4
    assert got[4:8] == [pytest.approx(0.85**2)] * 4
    assert got[8] == pytest.approx(0.85**3)
    with pytest.raises(ValueError, match="epoch"):
        teacher_probability(-1)


@pytest.mark.parametrize("p", [0.85, 0.3])
def test_mix_actions_uses_the_teacher_with_the_configured_probability(p: float) -> None:
    rng = np.random.default_rng(7)
    n, rounds = 16, 2000
    teacher = np.ones(n, dtype=np.int64)
    policy = np.full(n, 3, dtype=np.int64)
    used_total = 0
    for _ in range(rounds):
        actions, used = mix_actions(teacher, policy, p, rng)
        assert np.array_equal(actions[used], teacher[used])
        assert np.array_equal(actions[~used], policy[~used])
        used_total += int(used.sum())
    draws = n * rounds
    sigma = math.sqrt(draws * p * (1 - p))
    assert abs(used_total - draws * p) < 4 * sigma  # binomial, 4 standard deviations


def test_downsampling_is_an_area_average() -> None:
    rgb = np.zeros((1, 224, 224, 3), dtype=np.uint8)
    rgb[0, :4, :4] = 200  # one 4x4 block -> one output pixel
    small = downsample_rgb(rgb, 56)
    assert small.shape == (1, 56, 56, 3) and small[0, 0, 0, 0] == 200 and small[0, 0, 1, 0] == 0
    depth = np.full((2, 256, 256, 1), 0.5, dtype=np.float32)
    depth[0, 0, 0, 0] = np.nan
    d = downsample_depth(depth, 64)
    assert d.shape == (2, 64, 64, 1) and d.dtype == np.float16
    assert np.isfinite(d).all() and d[1].min() == pytest.approx(0.5)


def test_inflection_weights_mark_changes() -> None:
    w = inflection_weights(np.array([1, 1, 2, 2, 0]), 3.2)
    assert w.tolist() == pytest.approx([3.2, 1.0, 3.2, 1.0, 3.2])


@pytest.mark.parametrize("name", ["seq2seq", "cma"])
def test_checkpoint_round_trip_gives_the_same_outputs(tmp_path: Path, name: str) -> None:
    torch.manual_seed(1)
    model = build_model(ModelConfig(model=name, vocab_size=50, hidden=32)).eval()
    path = save_checkpoint(tmp_path / "m.safetensors", model, {"epochs": 3})
    loaded, info = load_checkpoint(path)
    assert info == {"epochs": 3}
    assert loaded.config == model.config
    batch = collate([_trajectory(np.random.default_rng(2), 5)])
    with torch.no_grad():
        a, _ = model.forward_sequence(batch, model.initial_state(1))
        b, _ = loaded.forward_sequence(batch, loaded.initial_state(1))
    assert torch.equal(a, b)
    assert (tmp_path / "m.json").is_file()


def test_bad_checkpoints_are_refused_with_the_file_named(tmp_path: Path) -> None:
    with pytest.raises(CheckpointError, match="no such checkpoint"):
        load_checkpoint(tmp_path / "missing.safetensors")
    junk = tmp_path / "junk.safetensors"
    junk.write_bytes(b"not a safetensors file")
    with pytest.raises(CheckpointError, match=r"junk\.safetensors"):
        load_checkpoint(junk)


def test_config_validation_names_the_field() -> None:
    with pytest.raises(ConfigError, match="model: unknown model 'rnn'"):
        ModelConfig(model="rnn", vocab_size=10).validate()
    with pytest.raises(ConfigError, match="vocab_size"):
        ModelConfig(model="cma", vocab_size=0).validate()


def test_cli_errors_are_one_clear_line(tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    class Result:
        def __init__(self, code: int, err: str) -> None:
            self.returncode, self.stderr = code, err

    def _cli(*args: str) -> Result:
        code = main(list(args))
        return Result(code, capsys.readouterr().err)


    dataset = tmp_path / "ds"
    dataset.mkdir()
    (dataset / "vocab.txt").write_text("<pad>\n<unk>\nthe\n")
    r = _cli("evaluate", "--checkpoint", str(tmp_path / "nope.safetensors"), "--dataset",
             str(dataset), "--out", str(tmp_path / "run"))
    assert r.returncode == 2
    assert "nope.safetensors: no such checkpoint file" in r.stderr
    assert "Traceback" not in r.stderr
    r = _cli("train", "--model", "transformer", "--dataset", str(dataset), "--out",
             str(tmp_path / "t"))
    assert r.returncode == 2
    assert "--model: unknown model 'transformer'" in r.stderr and "seq2seq, cma" in r.stderr
    r = _cli("train", "--model", "cma", "--mode", "offline", "--dataset", str(dataset),
             "--out", str(tmp_path / "t"))
    assert r.returncode == 2 and "--data" in r.stderr
    r = _cli("train", "--model", "cma", "--dataset", str(tmp_path / "nowhere"), "--out",
             str(tmp_path / "t"))
    assert r.returncode == 2 and "vocab.txt" in r.stderr


def test_module_entry_point_runs() -> None:
    r = subprocess.run([sys.executable, "-m", "vlnverse_baselines", "--help"],
                       capture_output=True, text=True, timeout=120, check=False)
    assert r.returncode == 0 and "train" in r.stdout and "evaluate" in r.stdout
