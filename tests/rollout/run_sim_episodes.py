"""Run a few real episodes (oracle, grounded) in this process and print their outcomes as JSON.

    python -m tests.rollout.run_sim_episodes [--reverse]

Timings and the host are left out: the rest must be the same in every process,
whatever order the episodes run in.
"""

from __future__ import annotations

import json
import sys
import tempfile

import numpy as np

from ladev_lib.catalog import load_catalog
from ladev_lib.rollout.jobs import EpisodeJob, MediaOptions, WorkerSpec
from ladev_lib.rollout.worker import EpisodeWorker
from ladev_lib.scenes.sampling import sample_scene

TIMING = ("sim_seconds", "policy_seconds", "total_seconds", "host")


def episodes() -> list[tuple[str, EpisodeJob]]:
    catalog = load_catalog()
    out = []
    for i, (task, n) in enumerate([("pick_up", 3), ("put_on", 2)]):
        spec = sample_scene(task, n, "simpler", np.random.default_rng(10 + i), catalog,
                            seed=100 + i, scene_id=f"repro-{task}")
        src = catalog.get(spec.source.id).display_name
        text = f"pick up the {src}" if task == "pick_up" else "put it there"
        for trial_seed in (spec.seed, spec.seed + 1):
            for policy in ("oracle", "grounded"):
                out.append((policy, EpisodeJob(f"{spec.scene_id}-{trial_seed}-{policy}", spec,
                                               text, trial_seed)))
    return out


def main() -> int:
    jobs = episodes()
    if "--reverse" in sys.argv:
        jobs.reverse()
    results = {}
    with tempfile.TemporaryDirectory() as media:
        workers = {
            p: EpisodeWorker(WorkerSpec(p, {}, {"image_size": [64, 64]}, {"name": "panda"},
                                        MediaOptions(media, "media", frames=False)))
            for p in ("oracle", "grounded")
        }
        try:
            for policy, job in jobs:
                outcome = workers[policy].run(job).model_dump(mode="json", exclude=set(TIMING))
                results[job.episode_id] = outcome
        finally:
            for w in workers.values():
                w.close()
    print("RESULTS " + json.dumps(results, sort_keys=True))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
