"""Print the docs/baselines.md results table from run folders (each with summary.json and, for
trained models, the training run's train_log.jsonl / train_config.json), with the agent's
fingerprint (a model's is its checkpoint's SHA-256) and the benchmark version of each run; runs
of different benchmark versions are not comparable, so mixing them is warned about on stderr.

    python baselines/bench/results_table.py runs/baselines/eval/*
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def version(run: Path) -> str:
    """The run's benchmark version (`run.json`, else `summary.json`); `0` before there was one."""
    for name in ("run.json", "summary.json"):
        f = run / name
        if f.is_file():
            v = json.loads(f.read_text()).get("benchmark_version")
            return str(v) if v is not None else "0"
    return "0"


def fingerprint(run: Path) -> str:
    """The agent's fingerprint from `run.json` (`-` when there is none)."""
    f = run / "run.json"
    if not f.is_file():
        return "-"
    return str(json.loads(f.read_text()).get("agent_fingerprint") or "-")


def row(run: Path) -> str:
    """One markdown row: method, setting, split, episodes, TL, NE, SR, OSR, SPL, nDTW, CR,
    agent fingerprint, benchmark version."""
    s = json.loads((run / "summary.json").read_text())
    pct = [f"{100 * float(s[k]):.1f}" for k in ("sr", "osr", "spl")]
    return (f"| {run.name} | {s['setting']} | {s['split']} | {s['episodes']} | "
            f"{float(s['tl']):.2f} | {float(s['ne']):.2f} | {pct[0]} | {pct[1]} | {pct[2]} | "
            f"{100 * float(s['ndtw']):.1f} | {float(s['cr']):.3f} | {fingerprint(run)} | "
            f"{version(run)} |")


def main() -> int:
    """Print the header and one row per folder given."""
    print("| run | setting | split | episodes | TL | NE | SR | OSR | SPL | nDTW | CR | agent "
          "fingerprint | benchmark |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    runs = [Path(a) for a in sys.argv[1:] if (Path(a) / "summary.json").is_file()]
    for run in runs:
        print(row(run))
    versions = {version(r) for r in runs}
    if len(versions) > 1:
        print(f"warning: these runs were made at different benchmark versions "
              f"({', '.join(sorted(versions))}); their figures are not comparable",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
