"""Shared fixtures: a generated ``tiny`` dataset and the xtask binary."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def xtask() -> list[str]:
    """The command that runs ``cargo xtask`` (the binary itself under ``cargo xtask test``)."""
    exe = os.environ.get("VLNVERSE_XTASK")
    return [exe] if exe else ["cargo", "xtask"]


@pytest.fixture(scope="session")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The ``tiny`` preset (given by ``cargo xtask test``, else generated here)."""
    given = os.environ.get("VLNVERSE_TEST_DATASET")
    if given:
        return Path(given)
    out = tmp_path_factory.mktemp("data") / "tiny"
    subprocess.run([*xtask(), "generate", "--preset", "tiny", "--out", str(out)], check=True,
                   cwd=ROOT)
    return out


@pytest.fixture()
def fresh_copy(dataset: Path, tmp_path: Path) -> Path:
    """A private copy of the dataset (for tests that write beside it)."""
    dst = tmp_path / "tiny"
    shutil.copytree(dataset, dst)
    return dst
