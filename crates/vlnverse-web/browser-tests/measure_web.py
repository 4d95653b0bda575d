"""Measure the web app as a browser sees it (not a test; figures for docs/web.md).

    VLNVERSE_XTASK=target/release/xtask \\
        .venv/bin/python crates/vlnverse-web/browser-tests/measure_web.py datasets/tiny 8

Starts `xtask serve` on the dataset, opens a page in Debian's Chromium and drives episodes of
fine/val_unseen with the teacher's keys as fast as the page gets frames (one key in flight),
printing the frames per second the page received; then opens N pages, each with a drive
connected (one simulator each), and prints the server's resident memory per connected driver
(`/api/stats`).
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

from playwright.sync_api import Page

# Run as a script (not under pytest), so the helper module beside this file is put on sys.path.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _web_support import browser, serve  # noqa: E402


def main() -> None:
    data = Path(sys.argv[1] if len(sys.argv) > 1 else "datasets/tiny")
    drivers = int(sys.argv[2]) if len(sys.argv) > 2 else 8
    os.environ["VLNVERSE_TEST_DATASET"] = str(data)
    with tempfile.TemporaryDirectory() as out, serve(Path(out)) as srv, browser() as ctx:
        eps = srv.get_json("/api/episodes?task=fine&split=val_unseen")["episodes"]
        page = ctx.new_page()
        page.goto(srv.url + "#drive")
        page.wait_for_selector("body[data-ready='1']")

        def start(p: Page, episode: int, setting: str) -> None:
            p.select_option("#d-task", "fine")
            p.select_option("#d-split", "val_unseen")
            p.wait_for_selector(f"#d-episode option[value='{episode}']", state="attached")
            p.select_option("#d-episode", str(episode))
            p.select_option("#d-setting", setting)
            p.click("#d-start")
            p.wait_for_function("window.vlnDrive.state && window.vlnDrive.frames > 0")

        # The page drives itself: the next key leaves as soon as the previous frame arrived.
        loop_js = """async () => {
          const d = window.vlnDrive;
          let wake = null;
          const orig = d.message.bind(d);
          d.message = (m) => { orig(m); if (typeof m.data !== "string" && wake) wake(); };
          const f0 = d.frames, t0 = performance.now();
          while (!d.state.done) {
            const k = d.state.expert_key;
            const got = new Promise((r) => { wake = r; });
            d.send({ key: k });
            await got;
          }
          d.message = orig;
          return [d.frames - f0, (performance.now() - t0) / 1000];
        }"""
        for setting in ["telhop", "strict"]:
            frames = 0
            seconds = 0.0
            for ep in eps[:4]:
                start(page, ep["episode_id"], setting)
                f, sec = page.evaluate(loop_js)
                frames += f
                seconds += sec
            print(
                f"{setting}, page-driven: {frames} frames in {seconds:.2f} s: "
                f"{frames / seconds:.1f} frames/s"
            )
        for setting in ["telhop", "strict"]:
            frames = 0
            seconds = 0.0
            for ep in eps[:4]:
                start(page, ep["episode_id"], setting)
                t0 = time.perf_counter()
                n0 = page.evaluate("window.vlnDrive.frames")
                while not page.evaluate("window.vlnDrive.state.done"):
                    s = page.evaluate("window.vlnDrive.state")
                    page.keyboard.press(" " if s["expert_key"] == "space" else s["expert_key"])
                    page.wait_for_function(f"window.vlnDrive.state.step === {s['step'] + 1}")
                page.wait_for_function("window.vlnDrive.inflight === 0")
                seconds += time.perf_counter() - t0
                frames += page.evaluate("window.vlnDrive.frames") - n0
            print(
                f"{setting}, key presses from Playwright: {frames} frames in {seconds:.2f} s: "
                f"{frames / seconds:.1f} frames/s"
            )
        page.close()
        time.sleep(0.5)
        base = srv.get_json("/api/stats")
        pages = []
        for i in range(drivers):
            p = ctx.new_page()
            p.goto(srv.url + "#drive")
            p.wait_for_selector("body[data-ready='1']")
            start(p, eps[i % len(eps)]["episode_id"], "strict")
            pages.append(p)
        time.sleep(0.5)
        loaded = srv.get_json("/api/stats")
        assert loaded["drivers"] == drivers, loaded
        per = (loaded["rss_bytes"] - base["rss_bytes"]) / drivers
        mib = 2**20
        print(
            f"server RSS {base['rss_bytes'] / mib:.1f} MiB with no driver, "
            f"{loaded['rss_bytes'] / mib:.1f} MiB with {drivers}: {per / mib:.1f} MiB per driver"
        )


if __name__ == "__main__":
    main()
