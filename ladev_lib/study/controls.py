"""Control instructions: run on the same scenes as the real ones, they do not ask for the task.

    rows = control_rows(scenes, compiled, study, catalog)   # InstructionRow, kind "control"

A policy that follows language succeeds less under a control than under the
real instruction; one that ignores language (the privileged oracle, a policy
that learnt the scene and not the words) succeeds as often. Three kinds:

- ``empty``: no instruction at all ("");
- ``unrelated``: a sentence about something else, drawn per scene;
- ``other_object``: the scene's task in the standard short form, on another
  object: a distractor of the scene when it has one (a graspable one first),
  else a graspable catalog object of the scene's set that is not on the table
  (noted in ``reason``).

Which scenes get them is the study's choice (``study.controls``,
``study.control_factors``); the rollout runs every control row like the real
instructions, with the same trials.
"""

from __future__ import annotations

import random
from collections.abc import Sequence

from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.study.design import StudyConfig
from ladev_lib.tables import CompiledSceneRow, InstructionRow, SceneDesignRow

UNRELATED_SENTENCES: tuple[str, ...] = (
    "what is the weather like today",
    "tell me a story about the sea",
    "how many days are there in a leap year",
    "the train to the city leaves at noon",
    "please sing a song about the mountains",
    "write a poem about the autumn wind",
)
"""Sentences that name no object and no action on the table."""


def _rng(seed: int, scene_id: str, kind: str) -> random.Random:
    return random.Random(f"ladev-control:{seed}:{scene_id}:{kind}")


def _other_object(
    spec: SceneSpec, catalog: Catalog, rng: random.Random
) -> tuple[CatalogObject, bool] | None:
    """Another object than the task's (a graspable one where there is a choice), and whether
    it is on the table."""
    roles = {spec.task.source, spec.task.target}
    on_table = {o.id for o in spec.objects}
    role_ids = {o.id for o in spec.objects if o.name in roles}
    present = sorted(
        {o.id for o in spec.objects if o.name not in roles and o.id not in role_ids and o.id in catalog}
    )
    graspable = [i for i in present if catalog.get(i).graspable]
    if graspable or present:  # one the task could be done with, if the table has one
        return catalog.get(rng.choice(graspable or present)), True
    sets = {catalog.get(i).set for i in on_table if i in catalog}
    absent = sorted(o.id for o in catalog if o.graspable and o.id not in on_table and (not sets or o.set in sets))
    if not absent:
        return None
    return catalog.get(rng.choice(absent)), False


def control_instruction(
    kind: str, spec: SceneSpec, catalog: Catalog, seed: int, scene_id: str
) -> tuple[str, str | None] | None:
    """(text, note) of one control for a scene; None when the scene cannot have it."""
    rng = _rng(seed, scene_id, kind)
    if kind == "empty":
        return "", None
    if kind == "unrelated":
        return rng.choice(UNRELATED_SENTENCES), None
    if kind == "other_object":
        picked = _other_object(spec, catalog, rng)
        if picked is None:
            return None
        obj, on_table = picked
        target = spec.target
        target_name = None
        if target is not None:
            target_name = catalog.get(target.id).display_name if target.id in catalog else target.name
        text = basic_instruction(spec.task.type, obj.display_name, target_name)
        note = None if on_table else f"control: no other object on the table; {obj.id} is not on it"
        return text, note
    raise ValueError(f"unknown control {kind!r}; known: empty, unrelated, other_object")


def control_rows(
    scenes: Sequence[SceneDesignRow],
    compiled: Sequence[CompiledSceneRow],
    study: StudyConfig,
    catalog: Catalog,
) -> list[InstructionRow]:
    """Control rows for every generated and compiled scene the study gives controls."""
    by_id = {c.scene_id: c for c in compiled}
    rows: list[InstructionRow] = []
    for s in scenes:
        kinds = study.controls_for(s.factor)
        comp = by_id.get(s.scene_id)
        if not kinds or s.status != "ok" or comp is None or comp.status != "ok" or not comp.spec_json:
            continue
        spec = SceneSpec.model_validate_json(comp.spec_json)
        for kind in kinds:
            made = control_instruction(kind, spec, catalog, study.seed, s.scene_id)
            if made is None:
                continue
            text, note = made
            rows.append(
                InstructionRow(
                    instruction_id=f"{s.scene_id}/control-{kind}",
                    scene_id=s.scene_id,
                    kind="control",
                    text=text,
                    valid=False,
                    reason=note,
                    selected=True,
                    control=kind,
                )
            )
    return rows
