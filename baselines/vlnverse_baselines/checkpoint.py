"""Checkpoints as safetensors: the weights, with the model config (and training facts) in the
file's metadata and, for people, the same JSON beside it (``model.json``). Writes are atomic
(temporary file + rename)."""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

import torch
from safetensors import safe_open
from safetensors.torch import load_file, save_file

from vlnverse_baselines.config import ConfigError, ModelConfig
from vlnverse_baselines.models import Policy, build_model

#: The ``format`` metadata value of a policy checkpoint.
FORMAT = "vlnverse-baselines/policy-1"


class CheckpointError(ValueError):
    """A checkpoint that cannot be read; the message names the file and what is wrong."""


def atomic_write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename."""
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


def save_tensors(path: Path, tensors: dict[str, torch.Tensor], metadata: dict[str, str]) -> None:
    """``safetensors`` file written atomically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    save_file({k: v.detach().contiguous().cpu() for k, v in tensors.items()}, str(tmp),
              metadata=metadata)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # safetensors creates the file owner-only
    os.replace(tmp, path)


def save_checkpoint(path: str | os.PathLike[str], model: Policy,
                    info: dict[str, Any] | None = None) -> Path:
    """Write ``model`` to ``path`` (``.safetensors``) and its config plus ``info`` to the
    ``.json`` beside it; returns the path."""
    out = Path(path)
    meta = {"format": FORMAT, "config": model.config.to_json(),
            "info": json.dumps(info or {}, sort_keys=True)}
    save_tensors(out, dict(model.state_dict()), meta)
    beside = {"format": FORMAT, "config": json.loads(meta["config"]), "info": info or {},
              "sha256": file_sha256(out)}
    atomic_write_text(out.with_suffix(".json"), json.dumps(beside, indent=1, sort_keys=True))
    return out


def file_sha256(path: str | os.PathLike[str]) -> str:
    """SHA-256 of a file, hex."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def read_metadata(path: str | os.PathLike[str]) -> dict[str, str]:
    """The metadata of a safetensors file (``CheckpointError`` if it is not one)."""
    p = Path(path)
    if not p.is_file():
        raise CheckpointError(f"{p}: no such checkpoint file")
    try:
        with safe_open(str(p), framework="pt") as f:
            meta = f.metadata() or {}
    except Exception as e:  # safetensors raises its own error type, which varies by version
        raise CheckpointError(f"{p}: not a safetensors file ({e})") from e
    return dict(meta)


def load_checkpoint(path: str | os.PathLike[str]) -> tuple[Policy, dict[str, Any]]:
    """The policy stored in ``path`` (in eval mode) and its ``info``."""
    p = Path(path)
    meta = read_metadata(p)
    if meta.get("format") != FORMAT:
        raise CheckpointError(
            f"{p}: metadata field 'format' is {meta.get('format')!r}, expected {FORMAT!r} "
            "(not a vlnverse-baselines policy)")
    try:
        config = ModelConfig.from_dict(json.loads(meta["config"]))
        info: dict[str, Any] = json.loads(meta.get("info", "{}"))
    except (KeyError, json.JSONDecodeError, ConfigError, TypeError) as e:
        raise CheckpointError(f"{p}: metadata field 'config': {e}") from e
    model = build_model(config)
    state = load_file(str(p))
    try:
        model.load_state_dict(state, strict=True)
    except RuntimeError as e:
        raise CheckpointError(f"{p}: weights do not match the config: {e}") from e
    model.eval()
    return model, info
