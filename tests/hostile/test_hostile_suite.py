"""The hostile-input suite: every case of ``_hostile_table`` run with a time bound, outcomes
counted and printed; no crash, hang, silent accept or partial output may remain."""

from __future__ import annotations

import importlib.util
import os
import sys
import warnings
from collections import Counter
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _hostile_cases import OUTCOMES, run_case  # noqa: E402
from _hostile_table import CASES  # noqa: E402

BAD = ("crash", "hang", "silent", "partial")


class HostileCounts(UserWarning):
    """The suite's outcome counts, shown in pytest's summary even when output is captured."""


def test_hostile_inputs_are_refused_clearly(tmp_path: Path) -> None:
    given = os.environ.get("VLNVERSE_TEST_DATASET")
    if not given:
        pytest.skip("needs VLNVERSE_TEST_DATASET (a tiny dataset; `cargo xtask test` sets it)")
    tiny = Path(given)
    python_ok = importlib.util.find_spec("vlnverse") is not None
    counts: Counter[str] = Counter()
    lines = []
    for case in CASES:
        if case.py is not None and not python_ok:
            continue
        outcome = run_case(case, tiny, tmp_path)
        counts[outcome] += 1
        lines.append(f"{outcome:8} {case.name}: {case.detail}")
    total = sum(counts.values())
    summary = f"hostile: {total} inputs: " + ", ".join(f"{counts[o]} {o}" for o in OUTCOMES)
    print("\n".join(lines))
    print(summary)
    bad = [line for line in lines if line.split()[0] in BAD]
    assert not bad, summary + "\n" + "\n".join(bad)
    warnings.warn(summary, HostileCounts, stacklevel=1)
