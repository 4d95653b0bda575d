"""Out-of-range Python arguments raise VLNVerseError naming the argument (issue 29 item 11)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import vlnverse
from vlnverse import VLNVerseError


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"num_envs": 4096}, r"invalid num_envs 4096: must be \[1, 256\]"),
        ({"seed": 2**70}, "invalid seed"),
        ({"max_steps": 10**12}, "invalid max_steps"),
        ({"episode_ids": [-1]}, r"invalid episode_ids\[0\] -1"),
        ({"episode_ids": [1, 1, 1]}, r"episode_ids\[1\] 1: repeats episode_ids\[0\]"),
        ({"episode_ids": []}, "invalid episode_ids"),
        ({"profile": 5}, "profile must be a str"),
        ({"success_distance": float("nan")}, "invalid success_distance"),
        ({"home_repeat": 0}, r"invalid home_repeat 0: must be \[1, 1000000\]"),
        ({"home_repeat": 2.5}, "home_repeat must be an int"),
    ],
)
def test_bad_arguments_are_named(dataset: Path, kwargs: dict[str, Any], match: str) -> None:
    with pytest.raises(VLNVerseError, match=match):
        vlnverse.make_vec(dataset, "fine", "val_unseen", render=False, **kwargs)


def test_unknown_reset_options_are_named(dataset: Path) -> None:
    env = vlnverse.make_vec(dataset, "fine", "val_unseen", render=False)
    try:
        with pytest.raises(VLNVerseError, match="teleport"):
            env.reset(options={"teleport": True})
        env.reset()
    finally:
        env.close()
