"""Time the reference agent server's side of a step on the paper's rig (RGB 224x224, depth
256x256): base64 and pickle decoding of the observation, stacking it into the batched dict,
and encoding the reply. The agent itself is not in it.

    python3 crates/vlnverse-agent-http/benches/server_decode.py
"""

from __future__ import annotations

import base64
import pickle
import sys
import timeit
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "examples" / "python"))
import agent_server  # noqa: E402

rng = np.random.default_rng(0)
obs = [{
    "rgb": rng.integers(0, 256, (224, 224, 3), dtype=np.uint8),
    "depth": rng.random((256, 256, 1), dtype=np.float32),
    "instruction": "Walk past the sofa and stop at the lamp.",
    "globalgps": np.zeros(3, np.float32),
    "globalrotation": np.array([1, 0, 0, 0], np.float32),
    "pose": np.zeros(4, np.float32),
    "compass": np.zeros(1, np.float32),
    "gps": np.zeros(2, np.float32),
}]
text = base64.b64encode(pickle.dumps(obs, protocol=3)).decode()


def one() -> None:
    batch = agent_server.batch(agent_server.decode_observations(text))
    agent_server.encode_actions(np.ones(len(batch["rgb"]), np.int64), len(batch["rgb"]))


n = 300
best = min(timeit.repeat(one, number=n, repeat=5)) / n
print(f"server side of a step: {best * 1e3:.3f} ms (best of 5 x {n}; body {len(text)} bytes)")
