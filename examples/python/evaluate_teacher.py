"""Evaluate the shortest-path teacher and a random agent from Python, the loop any trained
policy plugs into. Run after `pip install ./crates/vlnverse-py` and
`cargo xtask generate --preset tiny --out datasets/tiny`:

    python examples/python/evaluate_teacher.py [DATASET]
"""

from __future__ import annotations

import sys

import vlnverse


def main() -> None:
    dataset = sys.argv[1] if len(sys.argv) > 1 else "datasets/tiny"
    common = dict(dataset=dataset, task="fine", split="val_unseen", setting="telhop", num_envs=4)

    teacher = vlnverse.evaluate(vlnverse.TeacherAgent(), out="runs/py-teacher", **common)
    envs = vlnverse.make_vec(dataset, "fine", "val_unseen", num_envs=4)
    rnd = vlnverse.evaluate(vlnverse.RandomAgent(envs.action_space, seed=0),
                            out="runs/py-random", **common)
    envs.close()
    for name, s in (("teacher", teacher), ("random", rnd)):
        print(f"{name:8s} SR {s['sr']:.2f}  SPL {s['spl']:.2f}  NE {s['ne']:.2f} m"
              f"  over {s['episodes']} episodes")

    # The loop by hand: one environment, following the teacher's action.
    env = vlnverse.VLNEnv(dataset, "fine", "val_unseen")
    obs, info = env.reset(seed=0)
    print("instruction:", obs["instruction"])
    done = False
    while not done:
        obs, reward, terminated, truncated, info = env.step(info["expert_action"])
        done = terminated or truncated
    print("success:", info["metrics"]["success"], "steps:", info["metrics"]["steps"])
    env.close()


if __name__ == "__main__":
    main()
