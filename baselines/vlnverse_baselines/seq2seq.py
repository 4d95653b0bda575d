"""Seq2Seq (VLN-CE's baseline, as the VLNVerse paper's appendix writes it):
``h_t = GRU([V_t, D_t, I], h_{t-1})``, ``a_t = argmax softmax(W h_t + b)``, with ``I`` the
instruction LSTM's last hidden state."""

from __future__ import annotations

import torch
from torch import nn

from vlnverse_baselines.config import ModelConfig
from vlnverse_baselines.models import Policy


class Seq2Seq(Policy):
    """RGB CNN + depth CNN + instruction LSTM -> one GRU -> action logits."""

    def __init__(self, config: ModelConfig) -> None:
        super().__init__(config, bidirectional=False)
        c = self.config
        self.gru = nn.GRUCell(self.visual_dim + self.instruction.out_dim, c.hidden)
        self.head = nn.Linear(c.hidden, self.num_actions)

    def state_layers(self) -> int:
        """One GRU."""
        return 1

    def recurrent_step(self, t: int, state: torch.Tensor, frame: dict[str, torch.Tensor]
                       ) -> tuple[torch.Tensor, torch.Tensor]:
        """``GRU([V, D, I])``, then the linear head."""
        x = torch.cat([frame["visual"], frame["instr_summary"]], dim=1)
        h = self.gru(x, state[0])
        return self.head(h), h[None]
