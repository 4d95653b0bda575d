"""Cross-modal attention (CMA, after VLN-CE and the VLNVerse paper's appendix):

- first GRU over the observations: ``h1_t = GRU([V_t, D_t, a_{t-1}], h1_{t-1})``;
- ``h1_t`` queries, by scaled dot-product attention, the instruction's word features
  (``I^_t``), the RGB cells (``V^_t``) and the depth cells (``D^_t``);
- second GRU: ``h2_t = GRU([I^_t, V^_t, D^_t, a_{t-1}, h1_t], h2_{t-1})``;
- ``a_t = argmax softmax(W h2_t + b)``.

The previous action is a 32-dimensional embedding (0 = episode start)."""

from __future__ import annotations

import torch
from torch import nn

from vlnverse_baselines.config import ModelConfig
from vlnverse_baselines.encoders import attend
from vlnverse_baselines.models import Policy


class CMA(Policy):
    """Two GRUs with cross-modal attention between them."""

    def __init__(self, config: ModelConfig) -> None:
        super().__init__(config, bidirectional=True)
        c = self.config
        h = c.hidden
        self.prev_action = nn.Embedding(self.num_actions + 1, c.action_embed)
        self.gru1 = nn.GRUCell(self.visual_dim + c.action_embed, h)
        d_instr = self.instruction.out_dim
        self.instr_key = nn.Linear(d_instr, h)
        attended = d_instr
        self.queries = 1
        if self.rgb is not None:
            self.rgb_key = nn.Linear(self.rgb.channels, h)
            attended += self.rgb.channels
            self.queries += 1
        if self.depth is not None:
            self.depth_key = nn.Linear(self.depth.channels, h)
            attended += self.depth.channels
            self.queries += 1
        # The three queries (instruction, RGB, depth) from h1 in one matrix product.
        self.query = nn.Linear(h, h * self.queries)
        self.gru2 = nn.GRUCell(attended + c.action_embed + h, h)
        self.head = nn.Linear(h, self.num_actions)

    def state_layers(self) -> int:
        """Two GRUs."""
        return 2

    def prepare(self, enc: dict[str, torch.Tensor]) -> None:
        """The attention keys of every instruction word and image cell, once per call."""
        enc["instr_keys"] = self.instr_key(enc["instr_feats"])
        if self.rgb is not None:
            enc["rgb_keys"] = self.rgb_key(enc["rgb_spatial"])
        if self.depth is not None:
            enc["depth_keys"] = self.depth_key(enc["depth_spatial"])

    def recurrent_step(self, t: int, state: torch.Tensor, frame: dict[str, torch.Tensor]
                       ) -> tuple[torch.Tensor, torch.Tensor]:
        """First GRU, three attentions queried by its state, second GRU, head."""
        a = self.prev_action(frame["prev_actions"].clamp(0, self.num_actions))
        h1 = self.gru1(torch.cat([frame["visual"], a], dim=1), state[0])
        q = self.query(h1).chunk(self.queries, dim=1)
        parts = [attend(q[0], frame["instr_keys"], frame["instr_feats"], frame["instr_mask"])]
        k = 1
        if self.rgb is not None:
            parts.append(attend(q[k], frame["rgb_keys"], frame["rgb_spatial"]))
            k += 1
        if self.depth is not None:
            parts.append(attend(q[k], frame["depth_keys"], frame["depth_spatial"]))
        h2 = self.gru2(torch.cat([*parts, a, h1], dim=1), state[1])
        return self.head(h2), torch.stack([h1, h2])
