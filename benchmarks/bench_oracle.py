"""Oracle success rate per task on random valid scenes, and seconds per episode.

    LP_NUM_THREADS=1 OMP_NUM_THREADS=1 python benchmarks/bench_oracle.py --per-task 20
    MS_ASSET_DIR=../shared/assets python benchmarks/bench_oracle.py --objects mesh

Scenes come from ``ladev_lib.scenes.sampling.sample_scene`` (valid scenes, 1-5 objects
besides the target, cycling through the counts), seeded by their index so every run
checks the same scenes. ``--objects standin`` builds procedural stand-ins,
``mesh`` the asset pack's meshes (needs MS_ASSET_DIR), ``both`` runs the two in turn.
Prints one line per (task, object set, objects), then every failed scene with the
oracle's reason: the issue's target is >= 90 % per task.
"""

from __future__ import annotations

import argparse
import os
import time
from collections import Counter

os.environ.setdefault("LP_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

TASKS = ("pick_up", "move_near", "put_on", "put_in")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-task", type=int, default=20, help="scenes per task and object set")
    parser.add_argument("--tasks", default=",".join(TASKS))
    parser.add_argument("--sets", default="simpler,ycb", help="catalog object sets")
    parser.add_argument("--objects", choices=("standin", "mesh", "both"), default="standin")
    parser.add_argument("--first-seed", type=int, default=0)
    args = parser.parse_args()

    import numpy as np

    from ladev_lib.assets import asset_dir
    from ladev_lib.catalog import load_catalog
    from ladev_lib.rollout.solvability import check_scenes
    from ladev_lib.scenes.sampling import sample_scene

    catalog = load_catalog()
    kinds = ["standin", "mesh"] if args.objects == "both" else [args.objects]
    if "mesh" in kinds and asset_dir() is None:
        raise SystemExit("--objects mesh needs MS_ASSET_DIR pointing at the asset pack")
    print(f"MS_ASSET_DIR: {asset_dir() or 'not set'}; {args.per_task} scenes per task and set\n")
    print(f"{'task':10s} {'set':8s} {'objects':8s} {'solved':>8s} {'rate':>6s} {'s/ep':>6s} {'steps':>6s}")
    failures: list[str] = []
    for kind in kinds:
        for task in args.tasks.split(","):
            for object_set in args.sets.split(","):
                seeds = range(args.first_seed, args.first_seed + args.per_task)
                specs = [
                    sample_scene(task, 1 + s % 5, object_set, np.random.default_rng(10_000 + s),  # type: ignore[arg-type]
                                 catalog, seed=s, scene_id=f"{task}-{object_set}-{s}")
                    for s in seeds
                ]
                start = time.perf_counter()
                results = list(check_scenes(specs, prefer_meshes=(kind == "mesh")))
                elapsed = time.perf_counter() - start
                solved = sum(r.solved for r in results)
                steps = np.mean([r.steps for r in results])
                print(f"{task:10s} {object_set:8s} {kind:8s} {solved:>4d}/{len(results):<3d} "
                      f"{100 * solved / len(results):5.0f}% {elapsed / len(results):6.2f} {steps:6.0f}",
                      flush=True)
                for r, spec in zip(results, specs, strict=True):
                    if not r.solved:
                        objs = ", ".join(o.id for o in spec.objects)
                        failures.append(f"  {r.scene_id} [{kind}] {spec.task.source}->{spec.task.target} "
                                        f"({objs}): {r.status}: {r.reason}")
    print(f"\n{len(failures)} scenes not solved" + (":" if failures else ""))
    print("\n".join(failures))
    reasons = Counter(line.split(": ", 2)[-1].split(";")[0][:60] for line in failures)
    if reasons:
        print("\nby reason:")
        for reason, n in reasons.most_common():
            print(f"  {n:3d}  {reason}")


if __name__ == "__main__":
    main()
