"""Open an evaluation run in Replay and step through an episode in a real browser."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from playwright.sync_api import Page

# `cargo xtask test` runs pytest with --import-mode=importlib, which does not put this folder
# on sys.path: the helper module beside this file is found through it.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _web_support import Server, browser, dataset, run_xtask, screenshot_dir, serve  # noqa: E402


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    base = tmp_path_factory.mktemp("web-replay")
    run = base / "tiny-oracle"
    run_xtask(
        "evaluate",
        "--dataset",
        str(dataset()),
        "--task",
        "fine",
        "--split",
        "val_unseen",
        "--agent",
        "oracle",
        "--setting",
        "strict",
        "--episodes",
        "2",
        "--out",
        str(run),
    )
    with serve(base / "out", runs=[run]) as s:
        yield s


@pytest.fixture(scope="module")
def page(server: Server) -> Iterator[Page]:
    with browser() as ctx:
        p = ctx.new_page()
        p.goto(server.url + "#replay")
        p.wait_for_selector("body[data-ready='1']", timeout=30_000)
        yield p


def _view_loaded(page: Page) -> None:
    page.wait_for_function(
        "(() => { const i = document.querySelector('#r-view');"
        " return i.complete && i.naturalWidth > 0; })()"
    )


def test_web_replay_lists_episodes_and_steps_through_one(
    server: Server,
    page: Page,
) -> None:
    page.wait_for_selector("#r-episodes tr.ep", timeout=30_000)
    rows = page.query_selector_all("#r-episodes tr.ep")
    assert len(rows) == 2
    assert "SR 1," in page.inner_text("#r-summary")
    rows[1].click()
    page.wait_for_function("document.querySelector('#r-episodes tr.selected') !== null")
    second = page.get_attribute("#r-episodes tr.selected", "data-id")
    page.wait_for_function(
        f"window.vlnReplay.ep && window.vlnReplay.ep.episode.episode_id == {second}"
    )
    n = page.evaluate("window.vlnReplay.ep.trajectory.positions.length")
    assert n >= 3
    assert page.inner_text("#r-step-label") == f"step 0 / {n - 1}"
    _view_loaded(page)
    first_view = page.get_attribute("#r-view", "src")
    actions = page.evaluate("window.vlnReplay.ep.trajectory.actions")
    assert page.inner_text("#r-action") == f"action at step 0: {actions[0]}"
    page.keyboard.press("ArrowRight")
    page.click("#r-next")
    assert page.inner_text("#r-step-label") == f"step 2 / {n - 1}"
    assert page.inner_text("#r-action") == f"action at step 2: {actions[2]}"
    _view_loaded(page)
    assert page.get_attribute("#r-view", "src") != first_view
    # The map canvas has the top-down picture drawn.
    page.wait_for_function("document.querySelector('#r-map').width > 100")
    if d := screenshot_dir():
        page.screenshot(path=str(d / "web-replay.png"), full_page=True)
    # The last pose: where the agent stopped.
    page.evaluate(f"window.vlnReplay.show({n - 1})")
    assert page.inner_text("#r-action") == f"action at step {n - 1}: stop"


def test_web_replay_files_outside_the_run_are_refused(server: Server) -> None:
    import urllib.error
    import urllib.request

    for bad in ["files/runs/0/..%2f..%2fetc%2fpasswd", "files/dataset/..%2fsecret"]:
        try:
            urllib.request.urlopen(server.url + bad, timeout=10)
            raise AssertionError(f"{bad} was served")
        except urllib.error.HTTPError as e:
            assert e.code in (403, 404), bad
    assert Path(server.out).is_dir()
