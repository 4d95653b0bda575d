"""Mark episodes in Review in a real browser, then apply the review file with `xtask review`."""

from __future__ import annotations

import gzip
import json
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import Page

# `cargo xtask test` runs pytest with --import-mode=importlib, which does not put this folder
# on sys.path: the helper module beside this file is found through it.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _web_support import Server, browser, dataset, run_xtask, screenshot_dir, serve  # noqa: E402


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    with serve(tmp_path_factory.mktemp("web-review")) as s:
        yield s


@pytest.fixture(scope="module")
def page(server: Server) -> Iterator[Page]:
    with browser() as ctx:
        p = ctx.new_page()
        p.goto(server.url + "#review")
        p.wait_for_selector("body[data-ready='1']", timeout=30_000)
        yield p


def _episodes(folder: Path) -> list[dict[str, Any]]:
    with gzip.open(folder / "fine" / "val_unseen" / "val_unseen.json.gz", "rt") as f:
        return list(json.load(f)["episodes"])


def test_web_review_reject_and_edit_then_apply(
    server: Server,
    page: Page,
    tmp_path: Path,
) -> None:
    page.select_option("#v-task", "fine")
    page.select_option("#v-split", "val_unseen")
    page.wait_for_function("window.vlnReview.loaded === 'fine/val_unseen'")
    original = _episodes(dataset())
    first = original[0]["episode_id"]
    assert page.inner_text("#v-pos") == f"1 / {len(original)}"
    page.wait_for_function(
        "['#v-start', '#v-goal', '#v-map'].every(s => {"
        " const i = document.querySelector(s); return i.complete && i.naturalWidth > 0; })"
    )
    assert page.inner_text("#v-decision") == "undecided"
    page.click("#v-reject")
    page.wait_for_function("document.querySelector('#v-decision').textContent === 'rejected'")
    page.click("#v-next")
    second = original[1]["episode_id"]
    page.wait_for_function("window.vlnReview.i === 1")
    page.fill("#v-edit", "Walk to the kitchen and stop by the table.")
    page.click("#v-save-edit")
    page.wait_for_function("document.querySelector('#v-decision').textContent === 'edited'")
    if d := screenshot_dir():
        page.evaluate("window.scrollTo(0, 0)")
        page.screenshot(path=str(d / "web-review.png"), full_page=True)

    review = server.out / "review.json"
    doc = json.loads(review.read_text())
    decided = {x["episode_id"]: x["decision"] for x in doc["decisions"]}
    assert decided == {first: "rejected", second: "edited"}

    out = tmp_path / "reviewed"
    printed = run_xtask(
        "review", "--dataset", str(dataset()), "--decisions", str(review), "--out", str(out)
    )
    assert "fine/val_unseen" in printed
    kept = _episodes(out)
    ids = [e["episode_id"] for e in kept]
    assert first not in ids and len(kept) == len(original) - 1
    edited = next(e for e in kept if e["episode_id"] == second)
    assert edited["instruction"]["instruction_text"] == "Walk to the kitchen and stop by the table."
    assert (out / "scenes").is_dir()
