"""Schedule sampling: which action the environment executes, the teacher's or the policy's."""

from __future__ import annotations

import numpy as np


def teacher_probability(epoch: int, ratio: float = 0.85, decay_every: int = 4) -> float:
    """Probability of executing the teacher's action in ``epoch`` (from 0): ``ratio`` for the
    first ``decay_every`` epochs, then ``ratio**2``, ``ratio**3``, ... (the paper's
    SCHEDULE_RATIO 0.85 with DECAY_TIME 4, as in the VLN-BERT/ETPNav trainers)."""
    if epoch < 0:
        raise ValueError(f"epoch: expected >= 0, got {epoch}")
    if decay_every < 1:
        raise ValueError(f"decay_every: expected >= 1, got {decay_every}")
    return float(ratio ** (epoch // decay_every + 1))


def mix_actions(teacher: np.ndarray, policy: np.ndarray, p_teacher: float,
                rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Per environment, the teacher's action with probability ``p_teacher``, else the
    policy's; returns the executed actions and the mask of those taken from the teacher."""
    teacher = np.asarray(teacher, dtype=np.int64)
    policy = np.asarray(policy, dtype=np.int64)
    if teacher.shape != policy.shape:
        raise ValueError(f"teacher/policy: shapes differ, {teacher.shape} vs {policy.shape}")
    use_teacher = rng.random(teacher.shape[0]) < p_teacher
    return np.where(use_teacher, teacher, policy), use_teacher
