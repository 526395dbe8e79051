"""The tables stages exchange, with explicit, versioned schemas.

Each artifact is a pydantic row model: one documented field per column. The
Arrow/Parquet schema is derived from the model, written with the table's name
and version in the file's metadata, and checked when the file is read back, so
a stage never consumes a table it does not understand. Add fields; never
reorder, rename or reuse them.

    write_table(rows, path, EpisodeRow)      # rows: list of models, dicts, or a polars frame
    df = read_table(path, EpisodeRow)        # polars DataFrame, columns checked
"""

from __future__ import annotations

import json
import types
import typing
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any, ClassVar, Literal

import polars as pl
import pyarrow as pa
import pyarrow.parquet as pq
from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.errors import LadevError
from ladev_lib.vocabulary import (
    ControlKind,
    Environment,
    EpisodeStatus,
    Factor,
    InstructionKind,
    ObjectSetName,
    Robot,
)

SCHEMA_KEY = b"ladev_schema_version"
"""Parquet footer key of a table's schema version (``ladev_version`` before; still read)."""


class TableRow(BaseModel):
    """Base of every table row model.

    Versioning, the one convention of every file LADEV writes: a schema version
    named ``schema_version``, bumped when a field is added or its meaning changes.
    A table's rows share it, so it is a class constant (``SCHEMA_VERSION``) written
    to the Parquet footer; a record stored on its own (a scene spec, an episode
    outcome, an LLM cache entry) carries it as a field, ``schema_version: Literal[N]``.
    """

    model_config = ConfigDict(extra="forbid")
    TABLE: ClassVar[str] = ""
    SCHEMA_VERSION: ClassVar[int] = 1


class SceneDesignRow(TableRow):
    """One scene of a study: the ``generate`` stage's output (``scenes.parquet``)."""

    TABLE: ClassVar[str] = "scenes"

    scene_id: str = Field(description="Unique id within the study, e.g. 'pick_up-num_objects-3-007'.")
    study: str = Field(description="Study name (conf/study/<name>.yaml).")
    task: str = Field(description="pick_up | move_near | put_on | put_in")
    factor: Factor = Field(description="The factor this scene belongs to.")
    level: str = Field(description="The factor's level: '1'..'5', 'basic+paraphrase', 'simpler', 'ycb', 'default', ...")
    num_objects: int = Field(
        description="Objects the policy chooses among: the source plus distractors. The target of "
        "move_near/put_on/put_in comes in addition (the paper's one-object scenes hold only the "
        "object to manipulate)."
    )
    object_set: ObjectSetName = Field(description="Object set the scene draws from.")
    environment: Environment = Field(description="default | lighting | camera")
    robot: Robot = Field(description="Robot the scene is laid out for (the workspace is shared).")
    seed: int = Field(description="Seed derived from the study seed and the scene id.")
    description: str | None = Field(description="Natural-language scene description (null if generation failed).")
    base_instruction: str | None = Field(description="Basic instruction in the standard short form.")
    status: Literal["ok", "failed"] = Field(description="'failed' when the LLM gave no usable description.")
    reason: str | None = Field(default=None, description="Why generation failed.")
    llm_call_ids: list[str] = Field(default_factory=list, description="Cache keys of the LLM calls used.")


class CompiledSceneRow(TableRow):
    """One compiled scene: the ``compile`` stage's output (``compiled.parquet``)."""

    TABLE: ClassVar[str] = "compiled_scenes"
    SCHEMA_VERSION: ClassVar[int] = 2
    """2: no physical-validity columns; the check runs at the start of each episode (with
    the policy's robot and camera), and its verdict is the episode's ``invalid_scene``."""

    scene_id: str = Field(description="Scene id from scenes.parquet (or the user's file).")
    status: Literal["ok", "rejected"] = Field(description="'rejected' when no valid spec could be made.")
    reason: str | None = Field(default=None, description="Why the scene was rejected.")
    operations_json: str | None = Field(default=None, description="The LLM's operations, as JSON.")
    spec_json: str | None = Field(default=None, description="The SceneSpec, as JSON (null if rejected).")
    notes: list[str] = Field(default_factory=list, description="Adjustments made: clamped values, random picks.")
    llm_call_ids: list[str] = Field(default_factory=list, description="Cache keys of the LLM calls used.")


class InstructionRow(TableRow):
    """One instruction for a scene: the ``paraphrase`` stage's output (``instructions.parquet``)."""

    TABLE: ClassVar[str] = "instructions"
    SCHEMA_VERSION: ClassVar[int] = 2  # 2: control instructions (kind 'control', column 'control')

    instruction_id: str = Field(
        description="Unique id: '<scene_id>/basic', '<scene_id>/para-<k>' or '<scene_id>/control-<kind>'."
    )
    scene_id: str = Field(description="Scene the instruction belongs to.")
    kind: InstructionKind = Field(
        description="basic | paraphrase | control (an instruction that does not ask for the scene's "
        "task, run to see whether the policy follows language)"
    )
    text: str = Field(description="The instruction given to the policy.")
    similarity: float | None = Field(default=None, description="Cosine similarity to the basic instruction (null for basic).")
    parsed_task: str | None = Field(default=None, description="Task type read back from the text.")
    parsed_source: str | None = Field(default=None, description="Catalog id of the source read back from the text.")
    parsed_target: str | None = Field(default=None, description="Catalog id of the target read back from the text.")
    valid: bool = Field(description="Both checks passed (always true for basic, false for control).")
    reason: str | None = Field(default=None, description="Why the candidate was rejected.")
    selected: bool = Field(
        default=False,
        description="Used in rollout (basic, the one paraphrase drawn per scene, and controls).",
    )
    llm_call_ids: list[str] = Field(default_factory=list, description="Cache keys of the LLM calls used.")
    canonical_similarity: float | None = Field(
        default=None,
        description="Cosine similarity with object names replaced by display names, computed when "
        "'similarity' is below the threshold (the better of the two must reach it); null otherwise "
        "and for basic.",
    )
    control: ControlKind | None = Field(
        default=None,
        description="For kind 'control': empty (no instruction), unrelated (a sentence about "
        "something else) or other_object (the same task on another object); null otherwise.",
    )


class EpisodeRow(TableRow):
    """One rolled-out episode: the ``rollout`` stage's output (``episodes/<policy>.parquet``)."""

    TABLE: ClassVar[str] = "episodes"
    SCHEMA_VERSION: ClassVar[int] = 2
    """2: success at the end and at any step, trials, controls; timings moved to the
    ``episode_timings`` table so that this table is the same on every machine."""

    episode_id: str = Field(
        description="Content hash of (spec, instruction, policy+config, seed, sim and rollout config)."
    )
    study: str = Field(description="Study name.")
    scene_id: str = Field(description="Scene id.")
    instruction_id: str = Field(description="Instruction id.")
    policy: str = Field(description="Policy name (the registry name or the config's label).")
    task: str = Field(description="pick_up | move_near | put_on | put_in")
    factor: str = Field(description="Study factor of the scene.")
    level: str = Field(description="Level of the factor for this episode (for 'instruction': basic | paraphrase).")
    num_objects: int = Field(description="Source plus distractors (the target not counted), as in scenes.parquet.")
    object_set: str = Field(description="simpler | ycb")
    environment: str = Field(description="default | lighting | camera")
    instruction_kind: InstructionKind = Field(description="basic | paraphrase | control")
    instruction: str = Field(description="Instruction text given to the policy.")
    robot: str = Field(description="Robot used.")
    seed: int = Field(description="Episode seed (derived from the scene's seed and the trial).")
    status: EpisodeStatus = Field(
        description="success | failure | error | invalid_scene; success/failure follow success "
        "at the final step (success_end)."
    )
    success: bool | None = Field(description="Task success at the final step (= success_end); null for error and invalid_scene.")
    predicates_json: str = Field(default="{}", description="Final values of the task's named predicates, as JSON.")
    steps: int = Field(default=0, description="Control steps taken.")
    error: str | None = Field(default=None, description="Error or invalid-scene reason.")
    video_path: str | None = Field(default=None, description="MP4 of the episode, relative to the repo.")
    first_frame_path: str | None = Field(default=None, description="PNG of the first policy-camera frame.")
    last_frame_path: str | None = Field(default=None, description="PNG of the last policy-camera frame.")
    trial: int = Field(default=0, description="Trial of this (scene, instruction): 0, 1, ... (study.trials_per_scene).")
    control: ControlKind | None = Field(
        default=None, description="The control instruction's kind (instruction_kind 'control'); null otherwise."
    )
    success_end: bool | None = Field(
        default=None, description="Task success at the final step; null for error and invalid_scene."
    )
    success_any: bool | None = Field(
        default=None, description="Task success at any step (the episode need not end there)."
    )
    first_success_step: int | None = Field(
        default=None, description="First step (1-based) after which the task held; null if it never did."
    )

    def predicates(self) -> dict[str, bool]:
        return dict(json.loads(self.predicates_json))


class EpisodeTimingRow(TableRow):
    """Where an episode's time went: the ``rollout`` stage's ``timings/<policy>.parquet``.

    Kept apart from the episode table because it differs on every run and machine;
    DVC tracks it without caching it, and no outcome depends on it.
    """

    TABLE: ClassVar[str] = "episode_timings"

    episode_id: str = Field(description="Episode id (episodes/<policy>.parquet).")
    policy: str = Field(description="Policy label.")
    steps: int = Field(default=0, description="Control steps taken.")
    from_store: bool = Field(description="The outcome came from the episode store; its timings are from the run that made it.")
    sim_seconds: float = Field(default=0.0, description="Time in simulation and rendering.")
    policy_seconds: float = Field(default=0.0, description="Time in the policy.")
    total_seconds: float = Field(default=0.0, description="Wall time of the episode.")
    host: str = Field(default="", description="Machine that ran the episode (hostname, CPU), when known.")


# -- schema derivation ---------------------------------------------------------

_SCALARS: dict[Any, pa.DataType] = {str: pa.string(), int: pa.int64(), float: pa.float64(), bool: pa.bool_()}


def _arrow_type(annotation: Any) -> pa.DataType:
    origin = typing.get_origin(annotation)
    args = typing.get_args(annotation)
    if origin in (typing.Union, types.UnionType):
        non_null = [a for a in args if a is not type(None)]
        if len(non_null) != 1:
            raise TypeError(f"unsupported union {annotation}")
        return _arrow_type(non_null[0])
    if origin is Literal:
        return _SCALARS[type(args[0])]
    if origin in (list, Sequence):
        return pa.list_(_arrow_type(args[0]))
    if annotation in _SCALARS:
        return _SCALARS[annotation]
    raise TypeError(f"unsupported column type {annotation}")


def arrow_schema(model: type[TableRow]) -> pa.Schema:
    """The Arrow schema of a table, with its name and version in the metadata."""
    hints = typing.get_type_hints(model)
    fields = []
    for name in model.model_fields:
        annotation = hints[name]
        nullable = type(None) in typing.get_args(annotation)
        fields.append(pa.field(name, _arrow_type(annotation), nullable=nullable))
    meta = {b"ladev_table": model.TABLE.encode(), SCHEMA_KEY: str(model.SCHEMA_VERSION).encode()}
    return pa.schema(fields, metadata=meta)


def polars_schema(model: type[TableRow]) -> dict[str, pl.DataType]:
    empty = pl.from_arrow(arrow_schema(model).empty_table())
    assert isinstance(empty, pl.DataFrame)
    return dict(empty.schema)


class TableError(LadevError):
    """A table file does not match the schema the reader expects."""


def write_table(
    rows: Iterable[TableRow | dict[str, Any]] | pl.DataFrame,
    path: str | Path,
    model: type[TableRow],
) -> Path:
    """Validate rows against ``model`` and write them as Parquet, atomically."""
    schema = arrow_schema(model)
    if isinstance(rows, pl.DataFrame):
        table = rows.select(list(model.model_fields)).to_arrow().cast(schema)
    else:
        records = [
            (r if isinstance(r, model) else model.model_validate(r)).model_dump() for r in rows
        ]
        table = pa.Table.from_pylist(records, schema=schema)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    pq.write_table(table, tmp)
    tmp.replace(path)
    return path


def read_table(path: str | Path, model: type[TableRow]) -> pl.DataFrame:
    """Read a table written by :func:`write_table`, checking its name, version and columns."""
    path = Path(path)
    if not path.exists():
        raise TableError(f"{path}: missing; run the stage that writes the {model.TABLE!r} table first")
    file_schema = pq.read_schema(path)
    meta = file_schema.metadata or {}
    name = meta.get(b"ladev_table", b"").decode()
    version = int((meta.get(SCHEMA_KEY) or meta.get(b"ladev_version") or b"0").decode() or 0)
    if name != model.TABLE:
        raise TableError(f"{path}: holds table {name!r}, expected {model.TABLE!r}")
    if version > model.SCHEMA_VERSION:
        raise TableError(
            f"{path}: table schema version {version} is newer than this LADEV reads ({model.SCHEMA_VERSION})"
        )
    missing = [f for f in model.model_fields if f not in file_schema.names]
    if missing:
        raise TableError(f"{path}: missing columns {missing}")
    df = pl.read_parquet(path)
    return df.select(list(model.model_fields))


def rows_of(df: pl.DataFrame, model: type[TableRow]) -> list[Any]:
    """The rows of a frame as validated models (for small tables)."""
    return [model.model_validate(r) for r in df.iter_rows(named=True)]
