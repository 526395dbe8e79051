"""Plan a policy's episodes from the study's tables.

Each compiled scene (status ``ok``) is rolled out with its basic instruction,
for scenes of the ``instruction`` factor with its selected paraphrase
(``selected`` in instructions.parquet), and with its control instructions
(kind ``control``) where the paraphrase stage wrote them. Each of these runs
``trials`` times (:class:`TrialPlan`), trial ``t`` with the seed
``trial_seed(scene seed, t)``. The episode's study metadata (factor,
level, object set, ...) comes from scenes.parquet; for the instruction factor
the level is the instruction's kind. Physical validity is checked by the
episode itself, at its start (an ``invalid_scene`` row when the check fails).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import polars as pl

from ladev_lib.catalog import load_catalog
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.rollout.identity import episode_id
from ladev_lib.rollout.jobs import EpisodeJob
from ladev_lib.scenes import SceneSpec
from ladev_lib.seeding import trial_seed


@dataclass(frozen=True)
class EpisodePlan:
    """One planned episode: the job to run and the row metadata it gets in the table."""

    job: EpisodeJob
    meta: dict[str, Any]
    """The row's study fields (ids, factor, level, instruction, seed, ...); the run adds the rest."""
    scene_robot: str

    @property
    def sort_key(self) -> tuple[str, int, int, str]:
        kind_order = {"basic": 0, "paraphrase": 1}.get(str(self.meta["instruction_kind"]), 2)
        return (
            str(self.meta["scene_id"]), int(self.meta.get("trial", 0)), kind_order,
            str(self.meta["instruction_id"]),
        )


@dataclass(frozen=True)
class TrialPlan:
    """How many times each scene's instructions run, and how episodes end."""

    trials_per_scene: int = 1
    trial_factors: tuple[str, ...] | None = None
    """Factors whose scenes get ``trials_per_scene`` trials (the others one); None: all."""
    stop_on_success: bool = False

    def trials_for(self, factor: str) -> int:
        if self.trial_factors is None or factor in self.trial_factors:
            return self.trials_per_scene
        return 1


@dataclass(frozen=True)
class PolicyIdentity:
    """What of a policy enters its episodes' ids."""

    label: str
    """The ``policy.<label>`` key: the name in the table and the output files."""
    name: str
    config: dict[str, Any]
    code: str
    """Code fingerprint (``identity.code_fingerprint``)."""


def _design_for(spec: SceneSpec, scene_id: str, study: str) -> dict[str, Any]:
    """Study metadata for a scene that is not in scenes.parquet (a user's own spec file)."""
    n_target = 1 if spec.task.target else 0
    catalog = load_catalog()
    sets = {catalog.get(o.id).set for o in spec.objects if o.id in catalog}
    environment = (
        "lighting"
        if spec.lighting.intensity_delta
        else "camera"
        if not spec.camera.is_default
        else "default"
    )
    return {
        "study": study,
        "task": spec.task.type,
        "factor": "custom",
        "level": "custom",
        "num_objects": len(spec.objects) - n_target,
        "object_set": "ycb" if sets == {"ycb"} else "simpler",
        "environment": environment,
    }


def default_instruction(spec: SceneSpec) -> str:
    """The basic instruction of the spec's task, with the objects' display names."""
    catalog = load_catalog()

    def display(name: str | None) -> str | None:
        if name is None:
            return None
        obj_id = spec.object(name).id
        return catalog.get(obj_id).display_name if obj_id in catalog else name

    return basic_instruction(spec.task.type, display(spec.task.source) or "", display(spec.task.target))


def plan_episodes(
    compiled: pl.DataFrame,
    instructions: pl.DataFrame | None,
    scenes: pl.DataFrame | None,
    *,
    study: str,
    policy: PolicyIdentity,
    sim_config: dict[str, Any],
    robot_config: dict[str, Any],
    trials: TrialPlan | None = None,
) -> list[EpisodePlan]:
    """Every episode of ``policy`` the tables call for, sorted by scene, trial and instruction."""
    trials = trials or TrialPlan()
    design = {r["scene_id"]: r for r in scenes.iter_rows(named=True)} if scenes is not None else {}
    by_scene: dict[str, list[dict[str, Any]]] = {}
    if instructions is not None:
        for r in instructions.iter_rows(named=True):
            by_scene.setdefault(r["scene_id"], []).append(r)

    plans: list[EpisodePlan] = []
    for row in compiled.iter_rows(named=True):
        if row["status"] != "ok" or not row["spec_json"]:
            continue
        scene_id = row["scene_id"]
        spec = SceneSpec.model_validate_json(row["spec_json"])
        d = design.get(scene_id)
        meta_scene = (
            {k: d[k] for k in ("study", "task", "factor", "level", "num_objects", "object_set", "environment")}
            if d
            else _design_for(spec, scene_id, study)
        )
        texts = by_scene.get(scene_id, [])
        chosen = [r for r in texts if r["kind"] == "basic"][:1]
        if not chosen:
            chosen = [{"instruction_id": f"{scene_id}/basic", "kind": "basic", "text": default_instruction(spec)}]
        if meta_scene["factor"] == "instruction":
            chosen += [r for r in texts if r["kind"] == "paraphrase" and r.get("selected")]
        chosen += [r for r in texts if r["kind"] == "control" and r.get("selected")]
        for trial in range(trials.trials_for(str(meta_scene["factor"]))):
            seed = trial_seed(spec.seed, trial)
            for ins in chosen:
                eid = episode_id(
                    spec=spec,
                    instruction=ins["text"],
                    policy_name=policy.name,
                    policy_config=policy.config,
                    seed=seed,
                    sim_config=sim_config,
                    robot_config=robot_config,
                    code=policy.code,
                    options={"trial": trial, "stop_on_success": trials.stop_on_success},
                )
                meta = {
                    **meta_scene,
                    "study": meta_scene.get("study") or study,
                    "episode_id": eid,
                    "scene_id": scene_id,
                    "instruction_id": ins["instruction_id"],
                    "policy": policy.label,
                    "instruction_kind": ins["kind"],
                    "instruction": ins["text"],
                    "seed": seed,
                    "trial": trial,
                    "control": ins.get("control"),
                }
                if meta_scene["factor"] == "instruction":
                    meta["level"] = ins["kind"]
                job = EpisodeJob(
                    episode_id=eid, spec=spec, instruction=ins["text"], seed=seed,
                    stop_on_success=trials.stop_on_success,
                )
                plans.append(EpisodePlan(job, meta, spec.robot))
    plans.sort(key=lambda p: p.sort_key)
    return plans
