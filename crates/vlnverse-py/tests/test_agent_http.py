"""``cargo xtask evaluate --agent http`` against ``examples/python/agent_server.py``: the same agent
gives the same run through the agent server as in process."""

from __future__ import annotations

import base64
import json
import pickle
import subprocess
import sys
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import vlnverse

from .conftest import ROOT, xtask
from .http_agents import LookingAgent

SERVER = ROOT / "examples" / "python" / "agent_server.py"
AGENTS = Path(__file__).with_name("http_agents.py")


@pytest.fixture()
def server() -> Iterator[str]:
    """The reference server around ``LookingAgent`` on a free port; its base URL."""
    proc = subprocess.Popen([sys.executable, str(SERVER), "--agent", f"{AGENTS}:LookingAgent",
                             "--port", "0", "--quiet"], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert "listening on" in line, line
        yield line.split()[-1]
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def post(url: str, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
    req = urllib.request.Request(url, data=json.dumps(body).encode(),
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def test_http_agent_equals_the_agent_in_process(dataset: Path, tmp_path: Path,
                                                server: str) -> None:
    cli = tmp_path / "cli"
    subprocess.run([*xtask(), "evaluate", "--dataset", str(dataset), "--task", "fine",
                    "--split", "val_unseen", "--setting", "strict", "--episodes", "8",
                    "--agent", "http", "--agent-url", server, "--agent-name", "looking",
                    "--out", str(cli)], check=True, cwd=ROOT)
    py = tmp_path / "py"
    vlnverse.evaluate(LookingAgent(), dataset=dataset, task="fine", split="val_unseen",
                      setting="strict", out=py, num_envs=1, episodes=8, name="http",
                      progress=False)
    trajectories = (cli / "trajectories.jsonl").read_text().splitlines()
    assert len(trajectories) == 8
    # The agent walked and turned both ways: depth and colour steered it (eight episodes, as
    # in four a home's colours can send every turn the same way).
    actions = {a for t in trajectories for a in json.loads(t)["actions"]}
    assert {"move_forward", "turn_left", "turn_right"} <= actions, actions
    for f in ("summary.json", "episodes.csv", "trajectories.jsonl"):
        assert (py / f).read_bytes() == (cli / f).read_bytes(), f


def test_the_server_speaks_the_protocol_and_refuses_bad_requests(server: str) -> None:
    status, reply = post(f"{server}/agent/init", {"agent_config": {"model_name": "a"}})
    assert (status, reply) == (201, {"status": "success", "agent_name": "a"})
    obs = [{"rgb": np.zeros((4, 4, 3), np.uint8), "depth": np.ones((4, 4, 1), np.float32),
            "instruction": "go", "gps": np.zeros(2, np.float32)}]
    data = base64.b64encode(pickle.dumps(obs)).decode()
    assert post(f"{server}/agent/a/reset", {"reset_index": [0]}) == (200, {"status": "success"})
    # numpy's own pickles (the original client's) are read too.
    assert post(f"{server}/agent/a/step", {"observation": data}) == (200, {"action": [[1]]})
    status, reply = post(f"{server}/agent/b/step", {"observation": data})
    assert status == 404 and reply["detail"] == "Agent not found"

    class Evil:
        def __reduce__(self) -> tuple[Any, ...]:
            return (print, ("ran",))

    evil = base64.b64encode(pickle.dumps([{"x": Evil()}])).decode()
    status, reply = post(f"{server}/agent/a/step", {"observation": evil})
    assert status == 400 and "builtins.print" in reply["detail"], reply
    status, reply = post(f"{server}/agent/a/step", {"observation": "not base64!"})
    assert status == 400 and "base64" in reply["detail"], reply
    status, reply = post(f"{server}/agent/init", {"agent_config": {}})
    assert status == 400 and "model_name" in reply["detail"], reply


def test_a_missing_server_is_a_clear_error(dataset: Path, tmp_path: Path) -> None:
    out = subprocess.run([*xtask(), "evaluate", "--dataset", str(dataset), "--task", "fine",
                          "--split", "val_unseen", "--episodes", "1", "--agent", "http",
                          "--agent-url", "http://127.0.0.1:9", "--out", str(tmp_path / "run")],
                         cwd=ROOT, capture_output=True, text=True)
    assert out.returncode != 0
    assert "http://127.0.0.1:9" in out.stderr and "/agent/init" in out.stderr, out.stderr
