"""Drive an episode of the tiny dataset to success in a real browser with key presses, then
check the drive log, the trajectories file and `xtask score`."""

from __future__ import annotations

import csv
import json
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from playwright.sync_api import Page

# `cargo xtask test` runs pytest with --import-mode=importlib, which does not put this folder
# on sys.path: the helper module beside this file is found through it.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _web_support import Server, browser, dataset, run_xtask, screenshot_dir, serve  # noqa: E402

KEYS = {"w": "w", "a": "a", "d": "d", "q": "q", "e": "e", "space": " "}


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    with serve(tmp_path_factory.mktemp("web-drive")) as s:
        yield s


@pytest.fixture(scope="module")
def page(server: Server) -> Iterator[Page]:
    with browser() as ctx:
        p = ctx.new_page()
        p.goto(server.url + "#drive")
        p.wait_for_selector("body[data-ready='1']", timeout=30_000)
        yield p


def test_web_drive_to_success_logs_csv_and_scores_sr_1(
    server: Server,
    page: Page,
    tmp_path: Path,
) -> None:
    eps = server.get_json("/api/episodes?task=fine&split=val_unseen")["episodes"]
    ep = min(eps, key=lambda e: e["geodesic_distance"])
    page.select_option("#d-task", "fine")
    page.wait_for_selector("#d-split option[value='val_unseen']", state="attached")
    page.select_option("#d-split", "val_unseen")
    page.wait_for_selector(f"#d-episode option[value='{ep['episode_id']}']", state="attached")
    # The task and split changes each reload the episode list; a reload that lands after the
    # episode is chosen resets the choice (seen once under load), so wait for them to settle.
    page.wait_for_load_state("networkidle")
    page.select_option("#d-episode", str(ep["episode_id"]))
    page.wait_for_function(f"document.querySelector('#d-episode').value === '{ep['episode_id']}'")
    page.select_option("#d-setting", "telhop")
    page.click("#d-start")
    page.wait_for_function("window.vlnDrive.state && window.vlnDrive.frames > 0")
    assert page.inner_text("#d-instruction") == ep["instruction"]
    assert page.inner_text("#d-s-setting") == "telhop"
    steps = 0
    for _ in range(300):
        state = page.evaluate("window.vlnDrive.state")
        if state["done"]:
            break
        key = state["expert_key"]
        page.keyboard.press(" " if key == "space" else key)
        steps += 1
        page.wait_for_function(f"window.vlnDrive.state.step === {state['step'] + 1}")
        shot = screenshot_dir()
        if shot and steps >= 8 and key == "w" and not (shot / "web-drive.png").exists():
            page.wait_for_function(
                f"window.vlnDrive.frames === {steps + 1}"
                " && document.querySelector('#d-view').complete"
            )
            page.wait_for_timeout(600)  # the frames/s counter updates twice a second
            page.screenshot(path=str(shot / "web-drive.png"))
    state = page.evaluate("window.vlnDrive.state")
    assert state["done"] and state["metrics"]["success"], state
    assert "Success" in page.inner_text("#d-result")
    # One frame per key and the first view.
    page.wait_for_function(f"window.vlnDrive.frames === {steps + 1}")
    frames = steps + 1
    # Depth toggle: a new frame, same step.
    page.check("#d-depth")
    page.wait_for_function(f"window.vlnDrive.frames === {frames + 1}")
    assert page.evaluate("window.vlnDrive.state.view") == "depth"

    out = server.out / "drives" / "fine" / "val_unseen"
    trajs = [json.loads(x) for x in (out / "trajectories.jsonl").read_text().splitlines()]
    assert [t["episode_id"] for t in trajs] == [ep["episode_id"]]
    assert trajs[0]["stopped"] and trajs[0]["steps"] == steps
    logs = list(out.glob(f"ep{ep['episode_id']}-*.csv"))
    assert len(logs) == 1
    with logs[0].open() as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["time_s", "step", "x", "y", "z", "heading_rad", "key"]
    times = [float(r["time_s"]) for r in rows]
    # A row every 50 ms (the last one is written when the episode ends).
    assert all(abs(b - a - 0.05) < 1e-3 for a, b in zip(times, times[1:-1], strict=False))
    pressed = [k for r in rows for k in r["key"].split("+") if k]
    assert len(pressed) == steps and pressed[-1] == "space"
    assert int(rows[-1]["step"]) == steps

    report = tmp_path / "score"
    run_xtask(
        "score",
        "--dataset",
        str(dataset()),
        "--task",
        "fine",
        "--split",
        "val_unseen",
        "--trajectories",
        str(out / "trajectories.jsonl"),
        "--out",
        str(report),
        "--allow-missing",
        "--method",
        "human",
    )
    with (report / "episodes.csv").open() as f:
        scored = {int(r["episode_id"]): r for r in csv.DictReader(f)}
    assert scored[ep["episode_id"]]["success"] == "1"
    summary = json.loads((report / "summary.json").read_text())
    # Every other episode is missing (a failure), so SR is exactly 1 / episodes.
    assert summary["sr"] == pytest.approx(1 / summary["episodes"])
    # The human baseline of a split holding just this episode (a reviewed copy keeping only
    # it): SR 1 with nothing missing.
    review = tmp_path / "review.json"
    decision = {"task": "fine", "split": "val_unseen", "episode_id": ep["episode_id"]}
    review.write_text(
        json.dumps(
            {
                "format": "vlnverse-review/1",
                "dataset": str(dataset()),
                "decisions": [{**decision, "decision": "accepted"}],
            }
        )
    )
    one = tmp_path / "one-episode"
    run_xtask(
        "review",
        "--dataset",
        str(dataset()),
        "--decisions",
        str(review),
        "--out",
        str(one),
        "--require-all",
    )
    run_xtask(
        "score",
        "--dataset",
        str(one),
        "--task",
        "fine",
        "--split",
        "val_unseen",
        "--trajectories",
        str(out / "trajectories.jsonl"),
        "--out",
        str(tmp_path / "score1"),
    )
    summary = json.loads((tmp_path / "score1" / "summary.json").read_text())
    assert (summary["episodes"], summary["sr"]) == (1, 1.0)


def _start(page: Page, task: str, episode: int) -> None:
    page.select_option("#d-task", task)
    page.wait_for_selector("#d-split option[value='val_unseen']", state="attached")
    page.select_option("#d-split", "val_unseen")
    page.wait_for_selector(f"#d-episode option[value='{episode}']", state="attached")
    page.select_option("#d-episode", str(episode))
    page.select_option("#d-setting", "strict")
    page.click("#d-start")
    page.wait_for_function("window.vlnDrive.state && window.vlnDrive.frames > 0")


def test_web_drive_shows_reference_image_question_box_and_sub_instruction(
    server: Server, page: Page
) -> None:
    def first(task: str) -> int:
        eps = server.get_json(f"/api/episodes?task={task}&split=val_unseen")["episodes"]
        return int(eps[0]["episode_id"])

    # Visual reference: the goal image is shown.
    _start(page, "visual_reference", first("visual_reference"))
    assert page.is_visible("#d-ref") and not page.is_visible("#d-dialogue")
    page.wait_for_function(
        "document.querySelector('#d-ref-img').complete"
        " && document.querySelector('#d-ref-img').naturalWidth > 0"
    )
    # Dialogue: a question is answered by the oracle and costs no step.
    _start(page, "dialogue", first("dialogue"))
    assert page.is_visible("#d-dialogue") and not page.is_visible("#d-ref")
    left = page.evaluate("window.vlnDrive.state.questions_left")
    page.fill("#d-question", "which way?")
    page.click("#d-ask-form button")
    page.wait_for_function(f"window.vlnDrive.state.questions_left === {left - 1}")
    assert len(page.inner_text("#d-answer")) > 3
    assert page.evaluate("window.vlnDrive.state.step") == 0
    # Long horizon: the current sub-instruction.
    _start(page, "long_horizon", first("long_horizon"))
    ep = server.get_json(
        f"/api/episode?task=long_horizon&split=val_unseen&id={first('long_horizon')}"
    )
    sub = page.inner_text("#d-sub")
    assert sub.startswith("Now (1/") and ep["sub_instructions"][0] in sub
