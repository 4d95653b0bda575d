#!/usr/bin/env python3
"""A random policy for `cargo xtask evaluate --agent external` (standard library only).

It speaks the JSON-lines protocol of docs/agents.md on stdin/stdout: one `episode` message per
episode, then one `step` message per step, each answered with one action line. Replace
`choose_action` with a call to your own policy (e.g. a PyTorch model reading the `.npy` depth
and the PNG image) to evaluate it.

    cargo xtask evaluate --dataset datasets/tiny --task fine --split test \
        --agent external --agent-cmd "python3 examples/python/random_agent.py" --out runs/ext
"""

from __future__ import annotations

import base64
import json
import os
import random
import struct
import sys
from typing import Any


def read_npy_header(path: str) -> tuple[str, tuple[int, ...]]:
    """Return (dtype, shape) of a .npy file (enough to check what arrived)."""
    with open(path, "rb") as f:
        magic = f.read(6)
        if magic != b"\x93NUMPY":
            raise ValueError(f"{path}: not a .npy file")
        f.read(2)
        (hlen,) = struct.unpack("<H", f.read(2))
        header = f.read(hlen).decode("latin1")
    # The header is a Python dict literal such as {'descr': '<f4', 'shape': (256, 256), ...}.
    descr = header.split("'descr':")[1].split("'")[1]
    shape = header.split("'shape':")[1].split(")")[0].strip(" (")
    return descr, tuple(int(x) for x in shape.split(",") if x.strip())


def check_observations(obs: dict[str, Any]) -> None:
    """Make sure every image is readable: files exist, base64 payloads have the right size."""
    for name, o in obs.items():
        if o.get("encoding") == "file":
            if not os.path.exists(o["path"]):
                raise FileNotFoundError(f"observation {name}: {o['path']}")
            if o["path"].endswith(".npy"):
                dtype, shape = read_npy_header(o["path"])
                if list(shape) != o["shape"]:
                    raise ValueError(f"observation {name}: shape {shape} != {o['shape']}")
        elif o.get("encoding") == "base64":
            size = len(base64.b64decode(o["data"]))
            itemsize = int(o["dtype"][2:])
            expected = itemsize
            for d in o["shape"]:
                expected *= d
            if size != expected:
                raise ValueError(f"observation {name}: {size} bytes, expected {expected}")


def choose_action(rng: random.Random, episode: dict[str, Any] | None,
                  step: dict[str, Any]) -> dict[str, str]:
    """The policy: forward 70 %, turns 28 %, stop 2 %."""
    r = rng.random()
    if r < 0.02:
        return {"action": "stop"}
    if r < 0.72:
        return {"action": "move_forward"}
    if r < 0.86:
        return {"action": "turn_left"}
    return {"action": "turn_right"}


def main() -> None:
    rng = random.Random(0)
    episode: dict[str, Any] | None = None
    for line in sys.stdin:
        line = line.strip()
        if not line:
            continue
        msg = json.loads(line)
        kind = msg.get("type")
        if kind == "episode":
            episode = msg
            rng = random.Random(msg.get("seed", 0))
        elif kind == "step":
            check_observations(msg.get("observations", {}))
            action = choose_action(rng, episode, msg)
            sys.stdout.write(json.dumps(action) + "\n")
            sys.stdout.flush()
        elif kind == "episode_end":
            episode = None
        # "answer" messages only follow an "ask" action, which this agent never sends.


if __name__ == "__main__":
    main()
