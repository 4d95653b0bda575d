"""The policy interface both baselines implement, and ``build_model``."""

from __future__ import annotations

import torch
from torch import nn

from vlnverse_baselines.config import NUM_ACTIONS, ModelConfig
from vlnverse_baselines.encoders import DepthEncoder, InstructionEncoder, RGBEncoder
from vlnverse_baselines.obs import SeqBatch


class InstructionCache:
    """Encoded instructions by token row, for stepping without gradients (an instruction is
    encoded once per episode instead of once per step). Clear it when the weights change."""

    def __init__(self, capacity: int = 4096) -> None:
        self.capacity = capacity
        self.rows: dict[bytes, tuple[torch.Tensor, torch.Tensor, torch.Tensor]] = {}

    def clear(self) -> None:
        """Forget every entry."""
        self.rows.clear()


class Policy(nn.Module):
    """A recurrent VLN policy over discrete actions (0 stop, 1 forward, 2 left, 3 right).

    ``forward_sequence`` runs ``T`` steps of ``B`` sequences from a recurrent state (zeroed
    wherever ``starts`` is set) and returns the action logits ``[T, B, 4]`` and the state after
    the last step. Encoders run once over all ``T * B`` frames; each distinct instruction is
    encoded once per call."""

    def __init__(self, config: ModelConfig, bidirectional: bool) -> None:
        super().__init__()
        self.config = config.validate()
        c = config
        self.rgb = RGBEncoder(c.rgb_size, c.rgb_features) if c.use_rgb else None
        self.depth = DepthEncoder(c.depth_size, c.depth_features) if c.use_depth else None
        self.instruction = InstructionEncoder(c.vocab_size, c.embed_dim, c.instruction_hidden,
                                              bidirectional)
        self.visual_dim = (c.rgb_features if c.use_rgb else 0) + (
            c.depth_features if c.use_depth else 0)
        self.num_actions = NUM_ACTIONS

    # -- what each model defines ---------------------------------------------------------

    def state_layers(self) -> int:
        """How many ``[B, hidden]`` recurrent states the model carries."""
        raise NotImplementedError

    def prepare(self, enc: dict[str, torch.Tensor]) -> None:
        """Add to ``enc`` whatever the recurrent steps need computed once for all frames
        (CMA: the attention keys); ``enc`` holds ``[T, B, ...]`` frame features and
        ``[U, ...]`` instruction features."""

    def recurrent_step(self, t: int, state: torch.Tensor, frame: dict[str, torch.Tensor]
                       ) -> tuple[torch.Tensor, torch.Tensor]:
        """One step for all ``B`` rows: ``frame`` holds this step's encoded inputs; returns
        the logits ``[B, 4]`` and the new state."""
        raise NotImplementedError

    # -- shared --------------------------------------------------------------------------

    def initial_state(self, batch: int) -> torch.Tensor:
        """The zero recurrent state ``[layers, B, hidden]``."""
        return torch.zeros(self.state_layers(), batch, self.config.hidden)

    def encode_frames(self, batch: SeqBatch, cache: InstructionCache | None = None
                      ) -> dict[str, torch.Tensor]:
        """Image features of every frame and instruction features of every step."""
        t, b = batch.steps, batch.batch
        out: dict[str, torch.Tensor] = {}
        vecs = []
        if self.rgb is not None:
            v, s = self.rgb(batch.rgb.reshape(t * b, *batch.rgb.shape[2:]))
            vecs.append(v)
            out["rgb_spatial"] = s.reshape(t, b, *s.shape[1:])
        if self.depth is not None:
            v, s = self.depth(batch.depth.reshape(t * b, *batch.depth.shape[2:]))
            vecs.append(v)
            out["depth_spatial"] = s.reshape(t, b, *s.shape[1:])
        out["visual"] = torch.cat(vecs, dim=1).reshape(t, b, -1)
        rows = batch.tokens.reshape(t * b, -1)
        unique, inverse = torch.unique(rows, dim=0, return_inverse=True)
        feats, mask, summary = self._encode_instructions(unique, cache)
        out["instr_index"] = inverse.reshape(t, b)
        out["instr_feats"], out["instr_mask"], out["instr_summary"] = feats, mask, summary
        return out

    def _encode_instructions(self, unique: torch.Tensor, cache: InstructionCache | None
                             ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        if cache is None or torch.is_grad_enabled():
            out: tuple[torch.Tensor, torch.Tensor, torch.Tensor] = self.instruction(unique)
            return out
        keys = [row.numpy().tobytes() for row in unique]
        missing = [i for i, k in enumerate(keys) if k not in cache.rows]
        if missing:
            if len(cache.rows) + len(missing) > cache.capacity:
                cache.clear()
            feats, mask, summary = self.instruction(unique[missing])
            for j, i in enumerate(missing):
                n = int(mask[j].sum())
                cache.rows[keys[i]] = (feats[j, :n], mask[j, :n], summary[j])
        entries = [cache.rows[k] for k in keys]
        longest = max(int(e[0].shape[0]) for e in entries)
        d = entries[0][0].shape[1]
        feats = torch.zeros(len(entries), longest, d)
        mask = torch.zeros(len(entries), longest, dtype=torch.bool)
        for j, (f, m, _) in enumerate(entries):
            feats[j, :f.shape[0]] = f
            mask[j, :m.shape[0]] = m
        return feats, mask, torch.stack([e[2] for e in entries])

    def forward_sequence(self, batch: SeqBatch, state: torch.Tensor,
                         cache: InstructionCache | None = None
                         ) -> tuple[torch.Tensor, torch.Tensor]:
        """Logits ``[T, B, 4]`` and the final state (see the class doc); ``cache`` reuses
        encoded instructions when no gradient is recorded."""
        enc = self.encode_frames(batch, cache)
        self.prepare(enc)
        per_instruction = [k for k in enc if k.startswith("instr_") and k != "instr_index"]
        # Unbind once: indexing v[t] per step would make autograd fill a full-size zero
        # gradient for every step.
        per_step = {k: v.unbind(0) for k, v in enc.items() if k not in per_instruction}
        prev_actions = batch.prev_actions.unbind(0)
        logits = []
        for t in range(batch.steps):
            keep = (~batch.starts[t]).to(state.dtype)[None, :, None]
            state = state * keep
            frame = {k: v[t] for k, v in per_step.items()}
            idx = frame["instr_index"]
            for k in per_instruction:
                frame[k] = enc[k][idx]
            frame["prev_actions"] = prev_actions[t]
            step_logits, state = self.recurrent_step(t, state, frame)
            logits.append(step_logits)
        return torch.stack(logits), state


def build_model(config: ModelConfig) -> Policy:
    """The policy named by ``config.model`` (``seq2seq`` or ``cma``)."""
    from vlnverse_baselines.cma import CMA
    from vlnverse_baselines.seq2seq import Seq2Seq

    config.validate()
    if config.model == "seq2seq":
        return Seq2Seq(config)
    return CMA(config)


def count_parameters(model: nn.Module) -> int:
    """Number of trainable parameters."""
    return sum(p.numel() for p in model.parameters() if p.requires_grad)
