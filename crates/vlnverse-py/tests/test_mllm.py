"""``MLLMAgent`` under ``vlnverse.evaluate`` against a scripted chat endpoint on loopback."""

from __future__ import annotations

import json
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

import pytest
import vlnverse
from vlnverse import VLNVerseError
from vlnverse.agents import MLLMAgent

REPLIES = ["move forward 75 cm", "turn left 30 degrees", "move forward 50 cm", "stop"]


class Scripted(BaseHTTPRequestHandler):
    """Answers the k-th request of a conversation's step with a reply picked by the request's
    text (the same request always gets the same reply), with token counts."""

    requests: list[dict[str, Any]] = []
    lock = threading.Lock()

    def do_POST(self) -> None:  # noqa: N802 (the http.server name)
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        with self.lock:
            Scripted.requests.append(body)
        reply = REPLIES[sum(map(ord, json.dumps(body["messages"][-1])[:4000])) % len(REPLIES)]
        out = json.dumps({
            "choices": [{"index": 0, "message": {"role": "assistant", "content": reply}}],
            "usage": {"prompt_tokens": 100, "completion_tokens": 3},
        }).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(out)))
        self.end_headers()
        self.wfile.write(out)

    def log_message(self, *args: Any) -> None:
        """Quiet."""


@pytest.fixture()
def endpoint() -> Any:
    Scripted.requests = []
    server = ThreadingHTTPServer(("127.0.0.1", 0), Scripted)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{server.server_address[1]}/v1"
    server.shutdown()


def test_mllm_agent_runs_natively_counts_tokens_and_reruns_from_the_cache(
        dataset: Path, tmp_path: Path, endpoint: str) -> None:
    agent = MLLMAgent(endpoint=endpoint, model="scripted",
                      config={"image_size": 64, "retries": 0, "history": "map"})
    kw: dict[str, Any] = dict(dataset=dataset, task="coarse", split="val_unseen",
                              out=tmp_path / "run", episodes=2, max_steps=30, num_envs=2,
                              progress=False)
    s = vlnverse.evaluate(agent, **kw)
    sent = len(Scripted.requests)
    assert s["episodes"] == 2 and s["method"] == "mllm:scripted:map"
    assert sent > 0 and s["mllm"]["calls"] == sent
    assert s["mllm"]["prompt_tokens"] == 100 * sent
    assert s["mllm"]["completion_tokens"] == 3 * sent
    lines = (tmp_path / "run" / "mllm.jsonl").read_text().splitlines()
    assert len(lines) == 2
    # The rerun is served from the reply cache: nothing sent, the same summary.
    again = vlnverse.evaluate(agent, **{**kw, "fresh": True, "num_envs": 1})
    assert len(Scripted.requests) == sent
    assert again == s


def test_mllm_agent_errors_name_the_field(dataset: Path, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="endpoint"):
        MLLMAgent(endpoint="", model="m")
    agent = MLLMAgent(endpoint="http://127.0.0.1:9/v1", model="m", config={"image_size": 4})
    with pytest.raises(VLNVerseError, match="image_size"):
        vlnverse.evaluate(agent, dataset=dataset, task="coarse", split="val_unseen",
                          out=tmp_path / "bad", episodes=1, progress=False)
