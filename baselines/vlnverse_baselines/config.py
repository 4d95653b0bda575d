"""Model and training configurations: plain dataclasses, validated once, stored as JSON."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from typing import Any

#: The model names ``build_model`` knows.
MODELS = ("seq2seq", "cma")

#: Number of policy actions: 0 stop, 1 forward, 2 turn left, 3 turn right (``vlnverse`` ids).
NUM_ACTIONS = 4


class ConfigError(ValueError):
    """A configuration value out of range; the message names the field and the value."""


@dataclass
class ModelConfig:
    """The architecture of a policy (stored in every checkpoint).

    Observations are downsampled before the encoders (area average): RGB 224 -> ``rgb_size``,
    depth 256 -> ``depth_size``; the CPU budget of the baselines needs it."""

    model: str = "cma"
    vocab_size: int = 0
    embed_dim: int = 64
    instruction_hidden: int = 128
    hidden: int = 128
    rgb_size: int = 56
    depth_size: int = 64
    rgb_features: int = 128
    depth_features: int = 128
    action_embed: int = 32
    use_rgb: bool = True
    use_depth: bool = True
    vocab_sha256: str = ""

    def validate(self) -> ModelConfig:
        """Check every field; returns ``self``."""
        if self.model not in MODELS:
            raise ConfigError(
                f"model: unknown model {self.model!r}; expected one of {', '.join(MODELS)}")
        if self.vocab_size < 2:
            raise ConfigError(f"vocab_size: expected at least 2 words, got {self.vocab_size}")
        for name in ("embed_dim", "instruction_hidden", "hidden", "rgb_features",
                     "depth_features", "action_embed"):
            value = getattr(self, name)
            if not 1 <= value <= 4096:
                raise ConfigError(f"{name}: expected 1..4096, got {value}")
        for name in ("rgb_size", "depth_size"):
            value = getattr(self, name)
            if not 16 <= value <= 512:
                raise ConfigError(f"{name}: expected 16..512 pixels, got {value}")
        if not (self.use_rgb or self.use_depth):
            raise ConfigError("use_rgb/use_depth: a policy needs at least one image")
        return self

    def to_json(self) -> str:
        """The config as one JSON object (sorted keys)."""
        return json.dumps(dataclasses.asdict(self), sort_keys=True)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ModelConfig:
        """Read a config, refusing unknown fields."""
        known = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise ConfigError(f"model config: unknown field(s) {', '.join(unknown)}")
        return cls(**data).validate()


@dataclass
class TrainConfig:
    """How a policy is trained (stored in the run folder's ``train_config.json``).

    Defaults follow the paper's recipe: AdamW, learning rate 1e-4, cosine schedule,
    4 environments, schedule sampling ratio 0.85 decayed every 4 epochs, trajectories capped
    at 200 steps."""

    mode: str = "online"
    dataset: str = ""
    task: str = "fine"
    split: str = "train"
    setting: str = "telhop"
    data: str = ""
    epochs: int = 20
    updates_per_epoch: int = 50
    rollout_length: int = 32
    num_envs: int = 4
    # Online: episodes an environment runs in one home before it draws another (VectorEnv).
    home_repeat: int = 32
    batch_size: int = 4
    lr: float = 1e-4
    weight_decay: float = 1e-2
    cosine: bool = True
    schedule_ratio: float = 0.85
    decay_every: int = 4
    max_steps: int = 200
    inflection_weight: float = 1.0
    dagger: bool = False
    dagger_capacity: int = 256
    dagger_batch: int = 4
    episodes: int | None = None
    seed: int = 0
    threads: int = 1
    init: str = ""
    extra: dict[str, Any] = field(default_factory=dict)

    def validate(self) -> TrainConfig:
        """Check every field; returns ``self``."""
        if self.mode not in ("online", "offline"):
            raise ConfigError(f"mode: expected online or offline, got {self.mode!r}")
        if self.setting not in ("telhop", "strict", "lenient"):
            raise ConfigError(f"setting: expected telhop, strict or lenient, got {self.setting!r}")
        for name in ("epochs", "updates_per_epoch", "rollout_length", "num_envs", "batch_size",
                     "decay_every", "max_steps", "dagger_capacity", "dagger_batch", "threads",
                     "home_repeat"):
            value = getattr(self, name)
            if not isinstance(value, int) or value < 1:
                raise ConfigError(f"{name}: expected a positive integer, got {value!r}")
        if self.episodes is not None and self.episodes < 1:
            raise ConfigError(f"episodes: expected a positive integer, got {self.episodes}")
        if not 0.0 <= self.schedule_ratio <= 1.0:
            raise ConfigError(f"schedule_ratio: expected 0..1, got {self.schedule_ratio}")
        if not 0.0 < self.lr < 1.0:
            raise ConfigError(f"lr: expected 0 < lr < 1, got {self.lr}")
        if self.inflection_weight < 1.0:
            raise ConfigError(f"inflection_weight: expected >= 1, got {self.inflection_weight}")
        if self.seed < 0:
            raise ConfigError(f"seed: expected >= 0, got {self.seed}")
        return self

    def to_json(self) -> str:
        """The config as one JSON object (sorted keys)."""
        return json.dumps(dataclasses.asdict(self), sort_keys=True, indent=1)
