"""Print the docs/baselines.md results table from run folders (each with summary.json and, for
trained models, the training run's train_log.jsonl / train_config.json).

    python baselines/bench/results_table.py runs/baselines/eval/*
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def row(run: Path) -> str:
    """One markdown row: method, setting, split, episodes, TL, NE, SR, OSR, SPL, nDTW, CR."""
    s = json.loads((run / "summary.json").read_text())
    pct = [f"{100 * float(s[k]):.1f}" for k in ("sr", "osr", "spl")]
    return (f"| {run.name} | {s['setting']} | {s['split']} | {s['episodes']} | "
            f"{float(s['tl']):.2f} | {float(s['ne']):.2f} | {pct[0]} | {pct[1]} | {pct[2]} | "
            f"{100 * float(s['ndtw']):.1f} | {float(s['cr']):.3f} |")


def main() -> int:
    """Print the header and one row per folder given."""
    print("| run | setting | split | episodes | TL | NE | SR | OSR | SPL | nDTW | CR |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for arg in sys.argv[1:]:
        run = Path(arg)
        if (run / "summary.json").is_file():
            print(row(run))
    return 0


if __name__ == "__main__":
    sys.exit(main())
