"""The hostile inputs: a table of bad configs, bad episodes, bad Python calls, kills and
concurrent jobs, each run in its own process with a time bound and its outcome classified.

Outcomes: ``clear`` (refused, the message names what is wrong), ``unclear`` (refused, but the
message misses the words it should have), ``silent`` (accepted), ``partial`` (refused, but
files were left behind), ``crash`` (a panic, a signal, an unexpected Python exception type)
and ``hang`` (past its time bound). Cases that must succeed (a resume after a kill) are
``clear`` when they do."""

from __future__ import annotations

import gzip
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

ROOT = Path(__file__).resolve().parents[2]
OUTCOMES = ("clear", "unclear", "silent", "partial", "crash", "hang")


def xtask() -> list[str]:
    """The xtask binary (``cargo xtask test`` sets ``VLNVERSE_XTASK``)."""
    exe = os.environ.get("VLNVERSE_XTASK")
    return [exe] if exe else ["cargo", "xtask"]


@dataclass
class Ctx:
    """The case's private folder and the shared tiny dataset it may copy."""

    work: Path
    tiny: Path

    def dataset(self, name: str = "ds") -> Path:
        """A dataset folder of the case whose scenes are the tiny dataset's (a symlink) and
        whose split files are copies, free to spoil."""
        d = self.work / name
        if not d.exists():
            d.mkdir(parents=True)
            (d / "scenes").symlink_to(self.tiny / "scenes")
            for f in ("vocab.txt",):
                shutil.copy(self.tiny / f, d / f)
            for task in ("fine", "coarse", "long_horizon"):
                shutil.copytree(self.tiny / task, d / task)
        return d

    def spoil(self, task: str, split: str, how: Callable[[list[dict[str, Any]]], None],
              raw: Callable[[str], str] | None = None) -> Path:
        """Rewrite ``task/split`` of the case's dataset with ``how`` applied to its episodes
        (and ``raw`` to the JSON text); returns the dataset folder."""
        d = self.dataset()
        path = d / task / split / f"{split}.json.gz"
        eps = json.loads(gzip.decompress(path.read_bytes()))["episodes"]
        how(eps)
        text = json.dumps({"episodes": eps})
        if raw is not None:
            text = raw(text)
        path.write_bytes(gzip.compress(text.encode()))
        return d


@dataclass
class Case:
    """One hostile input: CLI arguments for xtask or Python code, the words a clear error
    names, and the folder that must stay as it was."""

    name: str
    cli: Callable[[Ctx], list[str]] | None = None
    py: Callable[[Ctx], str] | None = None
    expect: tuple[str, ...] = ()
    watch: Callable[[Ctx], Path] | None = None
    setup: Callable[[Ctx], None] | None = None
    timeout: float = 60.0
    custom: Callable[[Ctx, Case], tuple[str, str]] | None = None
    detail: str = field(default="", init=False)


def listing(p: Path) -> list[str] | None:
    """Every path under ``p`` (hidden ones included), or None when ``p`` is absent."""
    if not p.exists():
        return None
    if p.is_file():
        return ["<file>"]
    return sorted(str(q.relative_to(p)) for q in p.rglob("*"))


PY_PRELUDE = """
import sys
import vlnverse
from vlnverse import VLNVerseError
try:
{body}
except (VLNVerseError, ValueError) as e:
    print(f"REFUSED {{type(e).__name__}}: {{e}}", file=sys.stderr)
    sys.exit(3)
print("ACCEPTED")
"""


def run(cmd: list[str], timeout: float, cwd: Path) -> tuple[int | None, str]:
    """Run ``cmd`` in its own process group; None as the status when it ran past ``timeout``
    (the group is killed)."""
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         env={**os.environ, "RUST_LOG": "warn", "NO_COLOR": "1"},
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
        return p.returncode, out.decode(errors="replace")
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        return None, out.decode(errors="replace")


def classify(case: Case, rc: int | None, out: str, before: list[str] | None,
             after: list[str] | None) -> str:
    """The outcome of a case that must be refused."""
    if rc is None:
        return "hang"
    if rc < 0 or rc >= 128 or rc == 101 or "panicked at" in out or "PanicException" in out:
        return "crash"
    if rc == 0:
        return "silent"
    if before != after:
        return "partial"
    if case.py is not None and rc != 3:
        # A Python exception other than VLNVerseError / ValueError: the wrong kind of error.
        return "unclear"
    low = out.lower()
    return "clear" if all(w.lower() in low for w in case.expect) else "unclear"


def run_case(case: Case, tiny: Path, base: Path) -> str:
    """Run one case in ``base/<name>`` and return its outcome (details in ``case.detail``)."""
    ctx = Ctx(work=base / case.name, tiny=tiny)
    ctx.work.mkdir(parents=True, exist_ok=True)
    if case.setup is not None:
        case.setup(ctx)
    if case.custom is not None:
        outcome, case.detail = case.custom(ctx, case)
        return outcome
    watched = case.watch(ctx) if case.watch else None
    before = listing(watched) if watched else None
    if case.cli is not None:
        cmd = [*xtask(), *case.cli(ctx)]
    else:
        assert case.py is not None
        body = "\n".join("    " + line for line in case.py(ctx).strip().splitlines())
        cmd = [sys.executable, "-c", PY_PRELUDE.format(body=body)]
    t0 = time.monotonic()
    rc, out = run(cmd, case.timeout, ROOT)
    after = listing(watched) if watched else None
    outcome = classify(case, rc, out, before, after)
    tail = out.strip().splitlines()[-3:]
    case.detail = f"rc {rc} in {time.monotonic() - t0:.1f} s: {' | '.join(tail)[:400]}"
    if outcome == "partial":
        case.detail += f" | left: {sorted(set(after or []) - set(before or []))[:8]}"
    return outcome
