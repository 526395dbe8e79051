"""Simulator speed: scene build time, and steps/s with a 256x256 policy camera, side by side
with a bare ManiSkill PickCube-v1 rendering one 256x256 camera (same process, same run).

    LP_NUM_THREADS=1 OMP_NUM_THREADS=1 python benchmarks/bench_sim.py [--steps 100] [--size 256]

Steps are timed in alternating blocks (LADEV, PickCube, LADEV, PickCube) after a warm-up,
so both see the same machine load. A LADEV step = env.step + policy_image() (what a VLA
rollout does); PickCube's step renders its camera as part of the observation.
"""

from __future__ import annotations

import argparse
import os
import time
from typing import Any

os.environ.setdefault("LP_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402


def _spec(variant: int) -> Any:
    from ladev_lib.scenes.spec import SceneSpec

    names = [("coke_can", 0.05, 0.12), ("plate", -0.05, -0.1), ("apple", 0.1, -0.02), ("sponge", -0.08, 0.05)]
    if variant:
        names = [("pepsi_can", 0.05, 0.12), ("plate", -0.05, -0.1), ("orange", 0.1, -0.02), ("green_cube", -0.08, 0.05)]
    objects = [
        {"name": n, "id": n, "x": x, "y": y, "role": "source" if i == 0 else "target" if i == 1 else "distractor"}
        for i, (n, x, y) in enumerate(names)
    ]
    return SceneSpec.model_validate(
        {"objects": objects, "task": {"type": "put_on", "source": names[0][0], "target": "plate"}}
    )


def _timed(fn: Any) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100, help="steps per timed block (2 blocks each)")
    parser.add_argument("--size", type=int, default=256, help="camera width = height")
    args = parser.parse_args()

    import gymnasium as gym
    import mani_skill.envs  # noqa: F401 - registers PickCube-v1

    from ladev_lib.assets import asset_dir
    from ladev_lib.sim import SimConfig, make_env
    from ladev_lib.sim.env import resolve_render_backend

    size = (args.size, args.size)
    print(f"MS_ASSET_DIR: {asset_dir() or 'not set (stand-in objects)'}; camera {size[0]}x{size[1]}")

    spec_a, spec_b = _spec(0), _spec(1)
    t_make = time.perf_counter()
    env = make_env(spec_a, SimConfig(image_size=size))
    env.reset(seed=0)
    t_make = time.perf_counter() - t_make
    u = env.unwrapped
    t_first = _timed(u.policy_image)
    t_rebuild = _timed(lambda: env.reset(seed=0, options={"spec": spec_b.model_dump(mode="json")}))
    t_repose = _timed(lambda: env.reset(seed=1, options={"spec": spec_b.model_dump(mode="json")}))
    print(f"scene build (make env + first reset, {len(spec_a.objects)} objects): {t_make:.2f} s")
    print(f"first policy frame in the process:            {t_first:.2f} s")
    print(f"rebuild for a new spec (other objects):         {t_rebuild:.2f} s")
    print(f"reset for a new spec (same objects, re-posed):  {t_repose:.3f} s")

    pick = gym.make(
        "PickCube-v1",
        obs_mode="rgb",
        sensor_configs=dict(width=size[0], height=size[1]),
        render_backend=resolve_render_backend("auto"),
    )
    pick.reset(seed=0)
    zero_pick = np.zeros(pick.action_space.shape, dtype=np.float32)

    def ladev_block(n: int, image: bool = True) -> None:
        for _ in range(n):
            env.step(None)
            if image:
                u.policy_image()

    def pick_block(n: int) -> None:
        for _ in range(n):
            pick.step(zero_pick)

    ladev_block(5)  # warm-up (first frames)
    pick_block(5)
    t_l = t_p = 0.0
    for _ in range(2):
        t_l += _timed(lambda: ladev_block(args.steps))
        t_p += _timed(lambda: pick_block(args.steps))
    t_state = _timed(lambda: ladev_block(args.steps, image=False))
    n = 2 * args.steps
    ladev_sps, pick_sps = n / t_l, n / t_p
    print(f"LADEV-Scene-v1 steps/s, policy camera:          {ladev_sps:.1f}")
    print(f"PickCube-v1 steps/s, one camera:                {pick_sps:.1f}")
    print(f"ratio LADEV / PickCube:                         {ladev_sps / pick_sps:.2f}")
    print(f"LADEV-Scene-v1 steps/s, state only (no image):  {args.steps / t_state:.1f}")
    print(f"(control {u.control_freq} Hz, sim {u.sim_freq} Hz; PickCube control {pick.unwrapped.control_freq} Hz)")
    env.close()
    pick.close()


if __name__ == "__main__":
    main()
