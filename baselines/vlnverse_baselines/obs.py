"""Observations as the policies see them: downsampled images, tokens, previous actions.

Images are shrunk once, when they are recorded (area average, ``torch`` adaptive pooling), and
kept small: RGB as uint8 ``[h, w, 3]``, depth as float16 ``[h, w, 1]`` in [0, 1]."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch
import torch.nn.functional as F


def downsample_rgb(rgb: np.ndarray, size: int) -> np.ndarray:
    """``[N, H, W, 3]`` uint8 -> ``[N, size, size, 3]`` uint8 (area average)."""
    if rgb.ndim != 4 or rgb.shape[-1] != 3:
        raise ValueError(f"rgb: expected [N, H, W, 3], got shape {rgb.shape}")
    if rgb.shape[1] == size and rgb.shape[2] == size:
        return np.ascontiguousarray(rgb, dtype=np.uint8)
    x = torch.from_numpy(np.ascontiguousarray(rgb)).permute(0, 3, 1, 2).float()
    y = F.adaptive_avg_pool2d(x, size).round_().clamp_(0, 255).to(torch.uint8)
    return y.permute(0, 2, 3, 1).contiguous().numpy()


def downsample_depth(depth: np.ndarray, size: int) -> np.ndarray:
    """``[N, H, W, 1]`` float in [0, 1] -> ``[N, size, size, 1]`` float16 (area average)."""
    if depth.ndim == 3:
        depth = depth[..., None]
    if depth.ndim != 4 or depth.shape[-1] != 1:
        raise ValueError(f"depth: expected [N, H, W, 1], got shape {depth.shape}")
    x = torch.from_numpy(np.ascontiguousarray(depth, dtype=np.float32)).permute(0, 3, 1, 2)
    x = torch.nan_to_num(x, nan=0.0).clamp_(0.0, 1.0)
    if x.shape[2] != size or x.shape[3] != size:
        x = F.adaptive_avg_pool2d(x, size)
    return x.permute(0, 2, 3, 1).contiguous().to(torch.float16).numpy()


@dataclass
class SeqBatch:
    """``T`` steps of ``B`` sequences (time first), what ``Policy.forward_sequence`` reads.

    ``prev_actions`` holds 0 at the start of an episode and ``a + 1`` after action ``a``;
    ``starts`` marks the first step of an episode (the recurrent state is zeroed there);
    ``targets`` / ``weights`` are the teacher's actions and the loss weight of each step (0 on
    padding and on steps whose action the environment ignores)."""

    rgb: torch.Tensor  # uint8 [T, B, h, w, 3]
    depth: torch.Tensor  # float16 [T, B, h, w, 1]
    tokens: torch.Tensor  # int64 [T, B, L]
    prev_actions: torch.Tensor  # int64 [T, B]
    starts: torch.Tensor  # bool [T, B]
    targets: torch.Tensor  # int64 [T, B]
    weights: torch.Tensor  # float32 [T, B]

    @property
    def steps(self) -> int:
        """``T``."""
        return int(self.prev_actions.shape[0])

    @property
    def batch(self) -> int:
        """``B``."""
        return int(self.prev_actions.shape[1])


def step_batch(rgb: np.ndarray, depth: np.ndarray, tokens: np.ndarray, prev_actions: np.ndarray,
               starts: np.ndarray) -> SeqBatch:
    """One step of ``B`` environments (already downsampled) as a ``T = 1`` batch."""
    b = prev_actions.shape[0]
    return SeqBatch(
        rgb=torch.from_numpy(np.ascontiguousarray(rgb))[None],
        depth=torch.from_numpy(np.ascontiguousarray(depth))[None],
        tokens=torch.from_numpy(np.ascontiguousarray(tokens, dtype=np.int64))[None],
        prev_actions=torch.from_numpy(np.asarray(prev_actions, dtype=np.int64))[None],
        starts=torch.from_numpy(np.asarray(starts, dtype=bool))[None],
        targets=torch.zeros((1, b), dtype=torch.int64),
        weights=torch.zeros((1, b), dtype=torch.float32),
    )
