"""Shared helpers of the browser tests: the real `cargo xtask serve` binary on a free port,
and Debian's Chromium driven by Playwright.

Environment: `VLNVERSE_XTASK` (the xtask binary), `VLNVERSE_TEST_DATASET` (the tiny dataset),
optionally `VLNVERSE_WEB_SCREENSHOTS` (a folder: the tests then save screenshots of the three
modes there, e.g. `docs/img`).
"""

from __future__ import annotations

import json
import os
import queue
import re
import shutil
import subprocess
import tempfile
import threading
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import BrowserContext

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def xtask() -> str:
    """The xtask binary (skips the test when it is not given)."""
    path = os.environ.get("VLNVERSE_XTASK")
    if not path or not Path(path).exists():
        pytest.skip("VLNVERSE_XTASK is not set to the xtask binary")
    return path


def dataset() -> Path:
    """The tiny dataset (skips the test when it is not given)."""
    path = os.environ.get("VLNVERSE_TEST_DATASET")
    if not path or not Path(path).is_dir():
        pytest.skip("VLNVERSE_TEST_DATASET is not set to a dataset folder")
    return Path(path)


def screenshot_dir() -> Path | None:
    """Where to save screenshots, when asked for."""
    d = os.environ.get("VLNVERSE_WEB_SCREENSHOTS")
    return Path(d) if d else None


class Server:
    """A running `xtask serve`."""

    def __init__(self, proc: subprocess.Popen[str], url: str, out: Path) -> None:
        self.proc = proc
        self.url = url
        self.out = out

    def get_json(self, path: str) -> Any:  # noqa: ANN401 - JSON of any shape
        with urllib.request.urlopen(self.url + path.lstrip("/"), timeout=30) as r:
            return json.loads(r.read())


@contextmanager
def serve(out: Path, runs: list[Path] | None = None) -> Iterator[Server]:
    """Start `xtask serve` on a free port of 127.0.0.1 with teacher hints; stop it after."""
    cmd = [
        xtask(),
        "serve",
        "--dataset",
        str(dataset()),
        "--port",
        "0",
        "--out",
        str(out),
        "--teacher-hints",
    ]
    if runs:
        cmd += ["--runs", *[str(r) for r in runs]]
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1
    )
    lines: queue.Queue[str] = queue.Queue()

    def pump() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.put(line)

    threading.Thread(target=pump, daemon=True).start()
    try:
        try:
            line = lines.get(timeout=60)
        except queue.Empty:
            proc.kill()
            err = proc.stderr.read() if proc.stderr else ""
            raise AssertionError(f"xtask serve printed no URL in 60 s: {err}") from None
        m = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
        assert m, f"unexpected first line of xtask serve: {line!r}"
        yield Server(proc, m.group(1), out)
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


@contextmanager
def browser() -> Iterator[BrowserContext]:
    """A headless Chromium context with a fresh profile."""
    from playwright.sync_api import sync_playwright

    if not Path(CHROMIUM).exists():
        # On CI (.ci/run installs it) a missing browser is a failure, not a skip.
        message = f"{CHROMIUM} is not installed (apt-get install chromium)"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    profile = tempfile.mkdtemp(prefix="vlnverse-web-chromium-")
    pw = sync_playwright().start()
    try:
        ctx = pw.chromium.launch_persistent_context(
            profile,
            executable_path=CHROMIUM,
            headless=True,
            args=CHROMIUM_ARGS,
            viewport={"width": 1280, "height": 860},
        )
        try:
            yield ctx
        finally:
            ctx.close()
    finally:
        pw.stop()
        shutil.rmtree(profile, ignore_errors=True)


def run_xtask(*args: str) -> str:
    """Run an xtask command; its stdout (fails with its stderr)."""
    r = subprocess.run([xtask(), *args], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"xtask {' '.join(args)} failed: {r.stderr}"
    return r.stdout
