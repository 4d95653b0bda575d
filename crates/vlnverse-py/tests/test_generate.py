"""``vlnverse.generate``, the vocabulary it writes, and the reference-image observation."""

from __future__ import annotations

import filecmp
import gzip
import json
import re
from pathlib import Path

import numpy as np
import pytest
import vlnverse
from PIL import Image
from vlnverse import VLNVerseError


def _same_tree(a: Path, b: Path) -> list[str]:
    """Relative paths that differ between two folders (missing on one side or other bytes)."""
    diff: list[str] = []
    cmp = filecmp.dircmp(a, b, ignore=[".lock"])

    def walk(c: filecmp.dircmp[str], rel: str) -> None:
        diff.extend(f"{rel}{n}" for n in c.left_only + c.right_only)
        _, mismatch, errors = filecmp.cmpfiles(c.left, c.right, c.common_files, shallow=False)
        diff.extend(f"{rel}{n}" for n in mismatch + errors)
        for name, sub in c.subdirs.items():
            walk(sub, f"{rel}{name}/")

    walk(cmp, "")
    return diff


def test_python_generate_equals_xtask_generate(dataset: Path, tmp_path: Path) -> None:
    calls: list[tuple[int, int]] = []
    out = tmp_path / "tiny"
    summary = vlnverse.generate(out, "tiny", threads=1,
                                progress=lambda done, total: calls.append((done, total)))
    assert summary["assembled"] and summary["scenes_done"] == 5 and summary["episodes"] > 0
    assert sorted(calls) == [(k, 5) for k in range(1, 6)]
    assert _same_tree(dataset, out) == []
    # A rerun finds every scene done and rewrites the same bytes.
    again = vlnverse.generate(out, "tiny", progress=False)
    assert again["scenes_skipped"] == 5
    assert _same_tree(dataset, out) == []


def test_vocab_file_is_written_and_used_for_tokens(dataset: Path) -> None:
    vocab = (dataset / "vocab.txt").read_text().splitlines()
    assert vocab[:2] == ["<pad>", "<unk>"] and len(vocab) > 50
    with gzip.open(dataset / "fine" / "train" / "train.json.gz", "rt") as f:
        train = json.load(f)["episodes"]
    texts = [e["instruction"]["instruction_text"] for e in train]
    # The vocabulary's tokens: words (apostrophes and hyphens inside) and single punctuation.
    words = {w for t in texts for w in re.findall(r"[^\W_][\w'-]*|[^\w\s]", t.lower())}
    assert words <= set(vocab), sorted(words - set(vocab))[:10]
    env = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    obs, _ = env.reset(seed=0)
    assert env.vocab == vocab
    ids = [int(t) for t in obs["instruction_tokens"] if t != 0]
    text = obs["instruction"].lower()
    decoded = [vocab[i] for i in ids if i != 1]
    assert decoded and all(w in text for w in decoded)
    env.close()


def test_reference_image_is_an_observation(dataset: Path) -> None:
    env = vlnverse.VLNEnv(dataset, "visual_reference", "val_unseen")
    assert env.observation_space["reference_image"].shape == (224, 224, 3)
    seen: list[np.ndarray] = []
    for k in range(4):
        obs, info = env.reset(seed=None if k else 0)
        png = np.asarray(Image.open(info["reference_image"]).convert("RGB"))
        assert np.array_equal(obs["reference_image"], png)
        seen.append(obs["reference_image"].copy())
        # It stays the episode's image while the agent moves.
        obs, *_ = env.step(1)
        assert np.array_equal(obs["reference_image"], png)
    # Episodes with other goals show other images.
    assert any(not np.array_equal(seen[0], s) for s in seen[1:])
    env.close()
    other = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    assert "reference_image" not in other.observation_space.spaces
    other.close()


def test_generate_bad_input(tmp_path: Path) -> None:
    with pytest.raises(VLNVerseError, match="preset 'huge'"):
        vlnverse.generate(tmp_path / "a", "huge")
    with pytest.raises(VLNVerseError, match="missing.toml"):
        vlnverse.generate(tmp_path / "a", config=tmp_path / "missing.toml")
    with pytest.raises(VLNVerseError, match="K counts from 0"):
        vlnverse.generate(tmp_path / "a", shard=(3, 3))
    with pytest.raises(VLNVerseError, match="tasks"):
        vlnverse.generate(tmp_path / "a", tasks="fine")  # type: ignore[arg-type]
    bad = tmp_path / "bad.toml"
    bad.write_text("seed = 'x'\n")
    with pytest.raises(VLNVerseError, match="bad.toml"):
        vlnverse.generate(tmp_path / "a", config=bad)

    def boom(done: int, total: int) -> None:
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        vlnverse.generate(tmp_path / "b", tasks=["fine"], progress=boom)
