"""Learned VLN baselines for VLNVerse-rs: Seq2Seq and CMA (after VLN-CE and the VLNVerse paper).

Offline teacher forcing on ``cargo xtask export --format lerobot`` data, online imitation
learning through the ``vlnverse`` vector environment with schedule sampling (and DAgger-style
aggregation as an option), safetensors checkpoints, and an agent for ``vlnverse.evaluate``.

>>> from vlnverse_baselines import ModelConfig, build_model
>>> model = build_model(ModelConfig(model="cma", vocab_size=100))
>>> sum(p.numel() for p in model.parameters()) > 0
True
"""

from __future__ import annotations

from vlnverse_baselines.agent import PolicyAgent
from vlnverse_baselines.checkpoint import load_checkpoint, save_checkpoint
from vlnverse_baselines.config import MODELS, ModelConfig, TrainConfig
from vlnverse_baselines.models import Policy, build_model
from vlnverse_baselines.schedule import teacher_probability

__version__ = "0.1.0"

__all__ = [
    "MODELS",
    "ModelConfig",
    "Policy",
    "PolicyAgent",
    "TrainConfig",
    "__version__",
    "build_model",
    "load_checkpoint",
    "save_checkpoint",
    "teacher_probability",
]
