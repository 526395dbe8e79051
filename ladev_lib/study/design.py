"""From a study config (``conf/study/*.yaml``) to the scenes to generate.

A study crosses tasks with factors; each factor has levels and a number of
scenes per level:

    scenes = design_scenes(section(params, "study", StudyConfig))

- ``num_objects``: the level is the count (source + distractors; the target of
  move_near / put_on / put_in comes in addition).
- ``instruction``: one set of scenes, each later run with the basic and a
  paraphrased instruction, so its level is ``basic+paraphrase``.
- ``object_set``: the level is the set (simpler | ycb).
- ``environment``: the level is default | lighting | camera.

Measurement options (see the README's Measurement section):

- ``trials_per_scene``: each (scene, instruction) is run this many times, each
  trial with its own seed for everything the simulator and the policy
  randomise; ``trial_factors`` limits the extra trials to the scenes of some
  factors (null: every scene).
- ``controls``: control instructions run on the same scenes (``empty``,
  ``unrelated``, ``other_object``: the same task on another object), on the
  scenes of ``control_factors`` (null: every scene).

Factors other than ``num_objects`` draw each scene's count from ``num_objects``
(a number, or a ``[low, high]`` range) with the scene's seed. A scene's id is
``<task>-<factor>-<level>-<index>`` and its seed is derived from the study
seed and that id alone, so neither changes when the study grows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, model_validator

from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.seeding import derive_seed
from ladev_lib.vocabulary import (
    ENVIRONMENTS,
    OBJECT_SETS,
    ControlKind,
    Environment,
    Factor,
    ObjectSetName,
    TaskType,
    as_environment,
    as_factor,
    as_object_set,
)

INSTRUCTION_LEVEL = "basic+paraphrase"
_LEVELS: dict[str, set[str]] = {
    "instruction": {"basic", "paraphrase"},
    "object_set": set(OBJECT_SETS),
    "environment": set(ENVIRONMENTS),
}


class FactorConfig(BaseModel):
    """One factor of the study."""

    model_config = ConfigDict(extra="forbid")

    levels: list[int | str] = Field(min_length=1)
    scenes_per_level: int = Field(ge=0, description="Scenes per level (per task).")
    num_objects: int | tuple[int, int] | None = Field(
        default=None,
        description="Objects per scene (source + distractors) for factors other than num_objects: "
        "a number or a [low, high] range drawn per scene.",
    )


class StudyConfig(BaseModel):
    """The ``study:`` section."""

    model_config = ConfigDict(extra="forbid")

    name: str = Field(min_length=1, pattern=r"^[A-Za-z0-9_.-]+$")
    seed: int = Field(default=0, ge=0)
    tasks: list[TaskType] = Field(min_length=1)
    default_object_set: ObjectSetName = "simpler"
    factors: dict[Factor, FactorConfig]
    batch_size: int = Field(default=10, ge=1, le=100, description="Scene descriptions asked per LLM call.")
    paraphrases_per_instruction: int = Field(default=10, ge=1)
    bounds: SceneBounds = SceneBounds()
    trials_per_scene: int = Field(
        default=1, ge=1, le=1000,
        description="Runs of each (scene, instruction), each trial with its own seed.",
    )
    trial_factors: list[Factor] | None = Field(
        default=None,
        description="Factors whose scenes get trials_per_scene trials (the others one); null: all.",
    )
    controls: list[ControlKind] = Field(
        default_factory=list,
        description="Control instructions run on the same scenes: empty | unrelated | other_object.",
    )
    control_factors: list[Factor] | None = Field(
        default=None, description="Factors whose scenes get the controls; null: all."
    )

    def trials_for(self, factor: str) -> int:
        """Trials of a scene of ``factor`` ('custom' for a user's own spec: as null factors)."""
        if self.trial_factors is None or factor in self.trial_factors:
            return self.trials_per_scene
        return 1

    def controls_for(self, factor: str) -> list[ControlKind]:
        """The control instructions scenes of ``factor`` get."""
        if self.control_factors is None or factor in self.control_factors:
            return list(self.controls)
        return []

    @model_validator(mode="after")
    def _check_levels(self) -> StudyConfig:
        if len(set(self.controls)) != len(self.controls):
            raise ValueError(f"controls: each at most once, got {self.controls}")
        max_count = self.bounds.max_objects - 1  # room for the target
        for name, factor in self.factors.items():
            if name == "num_objects":
                for level in factor.levels:
                    if not isinstance(level, int) or not 1 <= level <= max_count:
                        raise ValueError(
                            f"factors.num_objects.levels: {level!r} must be a whole number 1..{max_count} "
                            f"(bounds.max_objects={self.bounds.max_objects} includes the target)"
                        )
                continue
            unknown = [lv for lv in factor.levels if str(lv) not in _LEVELS[name]]
            if unknown:
                raise ValueError(
                    f"factors.{name}.levels: unknown {unknown}; allowed {sorted(_LEVELS[name])}"
                )
            count = factor.num_objects
            if count is None:
                raise ValueError(f"factors.{name}.num_objects: required (a number or [low, high])")
            lo, hi = (count, count) if isinstance(count, int) else count
            if not 1 <= lo <= hi <= max_count:
                raise ValueError(f"factors.{name}.num_objects: {count!r} must lie within 1..{max_count}")
        return self


@dataclass(frozen=True)
class DesignedScene:
    """One scene the study asks for (before any LLM call)."""

    scene_id: str
    task: str
    factor: Factor
    level: str
    index: int
    num_objects: int
    object_set: ObjectSetName
    environment: Environment
    seed: int

    @property
    def total_objects(self) -> int:
        """Objects on the table: the target comes on top of ``num_objects``."""
        return self.num_objects + (0 if self.task == "pick_up" else 1)


def scene_id(task: str, factor: str, level: str, index: int) -> str:
    return f"{task}-{factor}-{level}-{index:03d}"


def cell_levels(study: StudyConfig, factor: str) -> list[str]:
    """The levels scenes are generated for (``instruction`` has one: basic+paraphrase)."""
    if factor == "instruction":
        return [INSTRUCTION_LEVEL]
    return [str(level) for level in study.factors[as_factor(factor)].levels]


def designed_scene(study: StudyConfig, task: str, factor: str, level: str, index: int) -> DesignedScene:
    """Scene ``index`` of a (task, factor, level) cell; defined for any index, even beyond the study."""
    sid = scene_id(task, factor, level, index)
    seed = derive_seed(study.seed, sid)
    cfg = study.factors[as_factor(factor)]
    if factor == "num_objects":
        count = int(level)
    else:
        spec = cfg.num_objects
        assert spec is not None
        lo, hi = (spec, spec) if isinstance(spec, int) else spec
        count = int(np.random.default_rng(derive_seed(seed, "num_objects")).integers(lo, hi + 1))
    return DesignedScene(
        scene_id=sid,
        task=task,
        factor=as_factor(factor),
        level=level,
        index=index,
        num_objects=count,
        object_set=as_object_set(level) if factor == "object_set" else study.default_object_set,
        environment=as_environment(level) if factor == "environment" else "default",
        seed=seed,
    )


def cells(study: StudyConfig) -> list[tuple[str, str, str, int]]:
    """(task, factor, level, scenes) for every cell of the study, in a stable order."""
    out: list[tuple[str, str, str, int]] = []
    for task in study.tasks:
        for factor, cfg in study.factors.items():
            for level in cell_levels(study, factor):
                out.append((task, factor, level, cfg.scenes_per_level))
    return out


def design_scenes(study: StudyConfig) -> list[DesignedScene]:
    """Every scene of the study."""
    return [
        designed_scene(study, task, factor, level, i)
        for task, factor, level, n in cells(study)
        for i in range(n)
    ]


@dataclass(frozen=True)
class Batch:
    """One describe_scenes call: always ``batch_size`` items; the first ``used`` are in the study.

    Asking for full batches keeps each call's content fixed as the study
    grows: going from 1 to 2 scenes per level reuses the first call, and
    from 100 to 200 adds only the new calls.
    """

    items: tuple[DesignedScene, ...]
    used: int

    @property
    def scenes(self) -> tuple[DesignedScene, ...]:
        return self.items[: self.used]


def plan_batches(study: StudyConfig) -> list[Batch]:
    size = study.batch_size
    batches = []
    for task, factor, level, n in cells(study):
        for start in range(0, n, size):
            items = tuple(designed_scene(study, task, factor, level, i) for i in range(start, start + size))
            batches.append(Batch(items, min(size, n - start)))
    return batches
