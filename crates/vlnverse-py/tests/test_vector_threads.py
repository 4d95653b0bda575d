"""A VectorEnv used from several threads: ``close`` waits for a running ``step``, a concurrent
``step`` raises, and nothing deadlocks (issue 29: ``step`` held the native lock with the GIL
released while ``close`` and ``closed`` waited for that lock holding the GIL).

A deadlock there freezes the whole interpreter (the waiting thread holds the GIL), so no
``join(timeout)`` in the same process could report it: each scenario runs in a child Python
(this file run as a script) under a time limit, and the test fails when the child does not
finish in time (``faulthandler`` prints the child's threads first).
"""

from __future__ import annotations

import faulthandler
import json
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

CHILD_LIMIT_S = 240.0
# Bounded loops: a scenario never runs more steps than this per thread.
MAX_STEPS = 400


def _make(dataset: str, num_envs: int = 4) -> Any:
    import vlnverse

    return vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs=num_envs, render=False,
                             copy=False)


def _step_until_closed(envs: Any, started: threading.Event, out: dict[str, Any]) -> None:
    """Step (forward/turns, never stop) until the env is closed or MAX_STEPS; record errors."""
    from vlnverse import VLNVerseError

    rng = np.random.default_rng(0)
    out["steps"] = 0
    out["errors"] = []
    for _ in range(MAX_STEPS):
        try:
            envs.step(rng.integers(1, 4, size=envs.num_envs, dtype=np.int64))
        except VLNVerseError as e:
            out["errors"].append(str(e))
            if "closed" in str(e):
                break
            continue
        except Exception as e:  # reported to the test
            out["errors"].append(f"{type(e).__name__}: {e}")
            break
        out["steps"] += 1
        if out["steps"] >= 3:
            started.set()
    started.set()


def _close_while_stepping(dataset: str) -> dict[str, Any]:
    envs = _make(dataset)
    envs.reset(seed=0)
    started = threading.Event()
    stepper: dict[str, Any] = {}
    t = threading.Thread(target=_step_until_closed, args=(envs, started, stepper), daemon=True)
    t.start()
    started.wait(60)
    # The old code hung here: close() took the lock holding the GIL while step held the lock
    # and waited for the GIL.
    native = envs._native
    closed_during = native.closed
    native.close()
    t.join(60)
    return {
        "stepper_alive": t.is_alive(),
        "closed_during": closed_during,
        "closed_after": native.closed,
        "steps": stepper.get("steps", 0),
        "errors": stepper.get("errors", []),
    }


def _two_steppers(dataset: str) -> dict[str, Any]:
    envs = _make(dataset, num_envs=8)
    envs.reset(seed=0)
    native = envs._native
    mask = [False] * envs.num_envs
    acts = np.full(envs.num_envs, 2, dtype=np.int64)  # turn: episodes never end
    results: list[dict[str, Any]] = [{"ok": 0, "busy": 0, "other": []} for _ in range(2)]
    go = threading.Barrier(2)

    def run(r: dict[str, Any]) -> None:
        from vlnverse import VLNVerseError

        go.wait(30)
        for _ in range(MAX_STEPS):
            try:
                native.step(acts, mask)
                r["ok"] += 1
            except VLNVerseError as e:
                if "in progress" in str(e):
                    r["busy"] += 1
                else:
                    r["other"].append(str(e))
            # Reading while the other thread steps never hangs.
            _ = native.closed
            ok = sum(x["ok"] for x in results)
            # Stop well before the episodes' step limit (turning never ends them otherwise).
            if ok >= 150 or (ok >= 20 and all(x["ok"] for x in results)
                            and sum(x["busy"] for x in results) >= 3):
                break
            # Give the other thread its turns (sleeping releases the GIL).
            time.sleep(0.0005)

    threads = [threading.Thread(target=run, args=(r,), daemon=True) for r in results]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    alive = any(t.is_alive() for t in threads)
    spec_ok = native.spec()["num_envs"] == envs.num_envs
    envs.close()
    return {"alive": alive, "results": results, "spec_ok": spec_ok, "closed": native.closed}


SCENARIOS = {"close": _close_while_stepping, "two_steppers": _two_steppers}


def _child(scenario: str, dataset: Path) -> dict[str, Any]:
    """Run a scenario in a child Python; fail (not hang) when it does not finish in time."""
    try:
        p = subprocess.run(
            [sys.executable, __file__, scenario, str(dataset)],
            capture_output=True,
            text=True,
            timeout=CHILD_LIMIT_S + 30,
        )
    except subprocess.TimeoutExpired as e:
        pytest.fail(f"{scenario}: deadlock, the child did not finish ({e.stderr!r})")
    assert p.returncode == 0, f"{scenario}: child failed ({p.returncode}):\n{p.stderr}"
    return dict(json.loads(p.stdout.strip().splitlines()[-1]))


def test_close_from_another_thread_waits_for_the_running_step(dataset: Path) -> None:
    r = _child("close", dataset)
    assert not r["stepper_alive"], r
    assert r["closed_after"], r
    assert r["steps"] >= 3, r
    # The stepping thread saw only "closed" (its running step finished first).
    assert all("closed" in e for e in r["errors"]), r


def test_concurrent_step_raises_instead_of_blocking(dataset: Path) -> None:
    r = _child("two_steppers", dataset)
    assert not r["alive"], r
    assert r["spec_ok"] and r["closed"], r
    for t in r["results"]:
        assert t["other"] == [], r
        assert t["ok"] > 0, r
    busy = sum(t["busy"] for t in r["results"])
    assert busy > 0, f"the two threads never overlapped: {r}"


if __name__ == "__main__":
    # Child: print the stacks and exit if the scenario deadlocks, so the test fails, not hangs.
    faulthandler.dump_traceback_later(CHILD_LIMIT_S, exit=True)
    t0 = time.monotonic()
    result = SCENARIOS[sys.argv[1]](sys.argv[2])
    result["seconds"] = round(time.monotonic() - t0, 2)
    print(json.dumps(result))
