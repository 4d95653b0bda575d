"""The encoders shared by Seq2Seq and CMA, trained from scratch (no pretrained weights can be
downloaded here): small CNNs for RGB and depth, an LSTM over learned word embeddings."""

from __future__ import annotations

import torch
from torch import nn
from torch.nn.utils.rnn import pack_padded_sequence, pad_packed_sequence

# ImageNet statistics: a fixed, conventional normalisation of the RGB input.
_RGB_MEAN = (0.485, 0.456, 0.406)
_RGB_STD = (0.229, 0.224, 0.225)


class ImageEncoder(nn.Module):
    """Three convolutions (kernel 8 stride 4, kernel 4 stride 2, kernel 3; the Atari "nature"
    CNN's shape) and a linear layer.

    Returns the feature vector ``[N, out]`` and the spatial map ``[N, cells, channels]`` the
    CMA attention reads (a 56-pixel image gives 7 x 7 cells, 64 pixels 8 x 8)."""

    def __init__(self, in_channels: int, size: int, out: int, channels: int = 32) -> None:
        super().__init__()
        self.conv = nn.Sequential(
            nn.Conv2d(in_channels, 16, 8, stride=4, padding=2),
            nn.ReLU(inplace=True),
            nn.Conv2d(16, channels, 4, stride=2, padding=1),
            nn.ReLU(inplace=True),
            nn.Conv2d(channels, channels, 3, stride=1, padding=1),
            nn.ReLU(inplace=True),
        )
        with torch.no_grad():
            cells = self.conv(torch.zeros(1, in_channels, size, size)).shape[2:].numel()
        self.channels = channels
        self.fc = nn.Sequential(nn.Linear(channels * cells, out), nn.ReLU(inplace=True))

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """``x``: ``[N, C, H, W]`` float."""
        spatial = self.conv(x)
        vec = self.fc(spatial.flatten(1))
        return vec, spatial.flatten(2).transpose(1, 2)


class RGBEncoder(ImageEncoder):
    """RGB ``[N, h, w, 3]`` uint8 -> features (normalised with ImageNet statistics)."""

    mean: torch.Tensor
    std: torch.Tensor

    def __init__(self, size: int, out: int) -> None:
        super().__init__(3, size, out)
        self.register_buffer("mean", torch.tensor(_RGB_MEAN).view(1, 3, 1, 1), persistent=False)
        self.register_buffer("std", torch.tensor(_RGB_STD).view(1, 3, 1, 1), persistent=False)

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """``x``: ``[N, h, w, 3]`` uint8."""
        img = x.permute(0, 3, 1, 2).float().div_(255.0)
        return super().forward((img - self.mean) / self.std)


class DepthEncoder(ImageEncoder):
    """Depth ``[N, h, w, 1]`` in [0, 1] (float16 or float32) -> features."""

    def __init__(self, size: int, out: int) -> None:
        super().__init__(1, size, out)

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """``x``: ``[N, h, w, 1]``."""
        return super().forward(x.permute(0, 3, 1, 2).float())


class InstructionEncoder(nn.Module):
    """Learned word embeddings (id 0 is padding) and an LSTM over the instruction's words.

    Returns per-word features ``[U, L', D]`` (``L'`` = the longest instruction), their mask
    ``[U, L']`` and a summary ``[U, D]`` (the last hidden state of each direction)."""

    def __init__(self, vocab_size: int, embed_dim: int, hidden: int, bidirectional: bool) -> None:
        super().__init__()
        self.embedding = nn.Embedding(vocab_size, embed_dim, padding_idx=0)
        self.lstm = nn.LSTM(embed_dim, hidden, batch_first=True, bidirectional=bidirectional)
        self.out_dim = hidden * (2 if bidirectional else 1)

    def forward(self, tokens: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """``tokens``: ``[U, L]`` int64, 0-padded at the end."""
        tokens = tokens.clamp(0, self.embedding.num_embeddings - 1)
        lengths = (tokens != 0).sum(dim=1).clamp(min=1)
        longest = int(lengths.max())
        tokens = tokens[:, :longest]
        packed = pack_padded_sequence(self.embedding(tokens), lengths.cpu(), batch_first=True,
                                      enforce_sorted=False)
        out, (h, _) = self.lstm(packed)
        feats, _ = pad_packed_sequence(out, batch_first=True, total_length=longest)
        summary = torch.cat([h[-2], h[-1]], dim=1) if self.lstm.bidirectional else h[-1]
        mask = torch.arange(longest, device=tokens.device)[None, :] < lengths[:, None]
        return feats, mask, summary


def attend(query: torch.Tensor, keys: torch.Tensor, values: torch.Tensor,
           mask: torch.Tensor | None = None) -> torch.Tensor:
    """Scaled dot-product attention of one query per row: ``query`` ``[B, D]``, ``keys``
    ``[B, N, D]``, ``values`` ``[B, N, E]``, ``mask`` ``[B, N]`` (True = attend) -> ``[B, E]``."""
    scores = torch.einsum("bd,bnd->bn", query, keys) / keys.shape[-1] ** 0.5
    if mask is not None:
        scores = scores.masked_fill(~mask, float("-inf"))
    return torch.einsum("bn,bne->be", torch.softmax(scores, dim=1), values)
