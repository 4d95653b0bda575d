#!/usr/bin/env python3
"""A reference agent server: any ``vlnverse`` Python agent behind the original VLNVerse
agent-server protocol, so ``cargo xtask evaluate --agent http`` (or the original evaluator's
client) can drive it.

    python3 examples/python/agent_server.py --agent vlnverse.agents:RandomAgent --port 8087
    cargo xtask evaluate --dataset datasets/tiny --task fine --split val_unseen \\
        --agent http --agent-url http://127.0.0.1:8087 --out runs/http

``--agent`` is ``module:Class`` or ``path/to/file.py:Class``: a batched agent with
``reset()`` and ``act(observations, infos)`` (``vlnverse.Agent``). It is built on ``init``
with the request's ``model_settings`` as keyword arguments (plus ``action_space``, a
``gymnasium.spaces.Discrete(6)``, when the class takes one and none was given).

Routes (JSON bodies; errors are ``{"detail": "..."}`` with 400, 404 or 500):

- ``POST /agent/init`` ``{"agent_config": {"model_name": NAME, "model_settings": {...}}}``
  -> 201 ``{"status": "success", "agent_name": NAME}``; a second init of NAME replaces it.
- ``POST /agent/NAME/reset`` ``{"reset_index": [...] | null}`` -> ``{"status": "success"}``;
  calls the agent's ``reset()`` (a new episode starts).
- ``POST /agent/NAME/step`` ``{"observation": base64(pickle(list of dicts))}``
  -> ``{"action": [[a], ...]}``, one list per environment (0 stop, 1 forward, 2 left,
  3 right, 4 look up, 5 look down).

The observation dicts are stacked into the batched dict a ``vlnverse`` agent gets in process
(arrays stacked along a first axis, strings into a tuple); ``infos`` is empty, so agents that
read privileged infos (``TeacherAgent``'s ``expert_action``) cannot run behind it.

Pickles are read with an unpickler that builds nothing but numpy arrays, dtypes and
bytearrays (what the Rust client and the original client send): a pickle that names any
other callable is refused, so a request cannot run code on this machine. Standard library
plus numpy (and gymnasium for the default action space); connections on threads, one
request at a time reaches the agents.
"""

from __future__ import annotations

import argparse
import base64
import binascii
import importlib
import importlib.util
import inspect
import io
import json
import pickle
import socket
import sys
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any, Callable

import numpy as np

#: The callables a pickled observation may name: numpy arrays and their parts, nothing else.
_ALLOWED = {
    ("numpy", "ndarray"),
    ("numpy", "dtype"),
    ("builtins", "bytearray"),
    # numpy's own array pickles (the original client pickles with numpy).
    ("numpy.core.multiarray", "_reconstruct"),
    ("numpy._core.multiarray", "_reconstruct"),
    ("numpy.core.multiarray", "scalar"),
    ("numpy._core.multiarray", "scalar"),
}

#: Largest request body accepted (bytes).
MAX_BODY = 256 * 1024 * 1024


class BadRequest(Exception):
    """A request the server cannot serve; ``status`` is the HTTP status to answer."""

    def __init__(self, status: int, detail: str) -> None:
        super().__init__(detail)
        self.status = status
        self.detail = detail


class _ArrayUnpickler(pickle.Unpickler):
    """Builds only the callables of ``_ALLOWED``."""

    def find_class(self, module: str, name: str) -> Any:
        if (module, name) not in _ALLOWED:
            raise pickle.UnpicklingError(f"observation names {module}.{name}, which is not "
                                         "a numpy array part")
        return super().find_class(module, name)


def decode_observations(text: Any) -> list[dict[str, Any]]:
    """The list of observation dicts in a step request's ``observation`` field."""
    if not isinstance(text, str):
        raise BadRequest(400, "`observation` must be a base64 string")
    try:
        raw = base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError) as e:
        raise BadRequest(400, f"`observation` is not base64: {e}") from None
    try:
        obs = _ArrayUnpickler(io.BytesIO(raw)).load()
    except Exception as e:  # noqa: BLE001 - any unpickling failure is the client's
        raise BadRequest(400, f"`observation` is not a readable pickle: {e}") from None
    if isinstance(obs, dict):
        obs = [obs]
    if not isinstance(obs, list) or not obs or not all(isinstance(o, dict) for o in obs):
        raise BadRequest(400, "`observation` must hold a non-empty list of dicts")
    return obs


def batch(obs: list[dict[str, Any]]) -> dict[str, Any]:
    """Stack per-environment dicts into one batched dict (the in-process layout)."""
    keys = [k for k in obs[0] if all(k in o for o in obs)]
    out: dict[str, Any] = {}
    for k in keys:
        vals = [o[k] for o in obs]
        if all(isinstance(v, str) for v in vals):
            out[k] = tuple(vals)
        else:
            try:
                out[k] = np.stack([np.asarray(v) for v in vals])
            except ValueError:
                out[k] = vals
    return out


def encode_actions(actions: Any, n: int) -> list[list[Any]]:
    """One list per environment: ``[a]`` for discrete actions, the row otherwise."""
    arr = np.asarray(actions)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.shape[0] != n:
        raise BadRequest(500, f"the agent answered {arr.shape[0]} actions for {n} "
                              "environments")
    if arr.ndim == 1:
        if not np.issubdtype(arr.dtype, np.integer):
            if not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)):
                raise BadRequest(500, f"the agent answered non-integer actions {arr.tolist()}")
            arr = arr.astype(np.int64)
        return [[int(a)] for a in arr]
    return [[float(x) for x in row] for row in arr.reshape(n, -1)]


def load_class(spec: str) -> Callable[..., Any]:
    """``module:Class`` or ``file.py:Class``."""
    where, sep, name = spec.rpartition(":")
    if not sep or not where or not name:
        raise SystemExit(f"--agent {spec!r}: expected module:Class or path/to/file.py:Class")
    if where.endswith(".py"):
        path = Path(where)
        if not path.is_file():
            raise SystemExit(f"--agent {spec!r}: no file {path}")
        mod_spec = importlib.util.spec_from_file_location(path.stem, path)
        if mod_spec is None or mod_spec.loader is None:
            raise SystemExit(f"--agent {spec!r}: cannot load {path}")
        module = importlib.util.module_from_spec(mod_spec)
        sys.modules[path.stem] = module
        mod_spec.loader.exec_module(module)
    else:
        module = importlib.import_module(where)
    cls = getattr(module, name, None)
    if cls is None:
        raise SystemExit(f"--agent {spec!r}: {where} has no {name}")
    return cls


def build(cls: Callable[..., Any], settings: dict[str, Any]) -> Any:
    """An agent from the init request's ``model_settings``."""
    kwargs = dict(settings)
    try:
        params = inspect.signature(cls).parameters
    except (TypeError, ValueError):
        params = {}
    if "action_space" in params and "action_space" not in kwargs:
        from gymnasium import spaces

        kwargs["action_space"] = spaces.Discrete(6)
    return cls(**kwargs)


class AgentServer:
    """The named agents and what the routes do with them."""

    def __init__(self, cls: Callable[..., Any]) -> None:
        self.cls = cls
        self.agents: dict[str, Any] = {}
        # Connections are served on threads; the agents see one request at a time.
        self.lock = threading.Lock()

    def handle(self, path: str, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        """Serve one POST; returns the status and the JSON reply."""
        with self.lock:
            return self._handle(path, body)

    def _handle(self, path: str, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        parts = [p for p in path.split("?")[0].split("/") if p]
        if parts == ["agent", "init"]:
            cfg = body.get("agent_config")
            if not isinstance(cfg, dict) or not isinstance(cfg.get("model_name"), str):
                raise BadRequest(400, "init needs {\"agent_config\": {\"model_name\": NAME}}")
            settings = cfg.get("model_settings") or {}
            if not isinstance(settings, dict):
                raise BadRequest(400, "`agent_config.model_settings` must be an object")
            name = cfg["model_name"]
            try:
                self.agents[name] = build(self.cls, settings)
            except Exception as e:  # noqa: BLE001 - reported to the client
                raise BadRequest(500, f"cannot build the agent: {type(e).__name__}: {e}") from e
            return 201, {"status": "success", "agent_name": name}
        if len(parts) == 3 and parts[0] == "agent" and parts[2] in ("step", "reset"):
            agent = self.agents.get(parts[1])
            if agent is None:
                raise BadRequest(404, "Agent not found")
            if parts[2] == "reset":
                agent.reset()
                return 200, {"status": "success"}
            obs = decode_observations(body.get("observation"))
            try:
                actions = agent.act(batch(obs), {})
            except Exception as e:  # noqa: BLE001 - reported to the client
                raise BadRequest(500, f"the agent raised {type(e).__name__}: {e}") from e
            return 200, {"action": encode_actions(actions, len(obs))}
        raise BadRequest(404, f"no route POST {path}")


def make_handler(server: AgentServer, quiet: bool) -> type[BaseHTTPRequestHandler]:
    """A request handler bound to ``server``."""

    class Handler(BaseHTTPRequestHandler):
        # Keep-alive: the client sends every step over one connection.
        protocol_version = "HTTP/1.1"

        def setup(self) -> None:
            super().setup()
            # Replies are small: without TCP_NODELAY each waits for the client's delayed ACK
            # (about 40 ms a step).
            self.connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

        def _reply(self, status: int, payload: dict[str, Any]) -> None:
            data = json.dumps(payload).encode()
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        def do_POST(self) -> None:  # noqa: N802 - http.server's name
            try:
                length = int(self.headers.get("Content-Length") or 0)
                if length < 0 or length > MAX_BODY:
                    raise BadRequest(400, f"body of {length} bytes (at most {MAX_BODY})")
                raw = self.rfile.read(length)
                try:
                    body = json.loads(raw or b"{}")
                except ValueError as e:
                    raise BadRequest(400, f"body is not JSON: {e}") from None
                if not isinstance(body, dict):
                    raise BadRequest(400, "body must be a JSON object")
                status, payload = server.handle(self.path, body)
            except BadRequest as e:
                status, payload = e.status, {"detail": e.detail}
            self._reply(status, payload)

        def do_GET(self) -> None:  # noqa: N802 - http.server's name
            self._reply(404, {"detail": f"no route GET {self.path}"})

        def log_message(self, format: str, *args: Any) -> None:  # noqa: A002
            if not quiet:
                super().log_message(format, *args)

    return Handler


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--agent", required=True, help="module:Class or path/to/file.py:Class")
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=8087, help="0 picks a free port")
    p.add_argument("--quiet", action="store_true", help="no line per request on stderr")
    args = p.parse_args(argv)
    server = AgentServer(load_class(args.agent))
    httpd = ThreadingHTTPServer((args.host, args.port), make_handler(server, args.quiet))
    httpd.daemon_threads = True
    host, port = httpd.server_address[:2]
    # The first line on stdout says where it listens (tests read the port from it).
    print(f"agent server listening on http://{host}:{port}", flush=True)
    try:
        httpd.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        httpd.server_close()


if __name__ == "__main__":
    main()
