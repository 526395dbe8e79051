"""One versioning convention for every table, file and cache entry (see ``TableRow``)."""

from __future__ import annotations

import typing

import pyarrow.parquet as pq
import pytest
from pydantic import BaseModel

from ladev_lib import tables
from ladev_lib.catalog.catalog import Catalog
from ladev_lib.llm.base import LLMCacheRecord
from ladev_lib.rollout.jobs import EpisodeOutcome
from ladev_lib.rollout.solvability import SolvabilityResult
from ladev_lib.scenes.operations import SceneOperations
from ladev_lib.scenes.spec import SceneSpec

TABLE_MODELS = [m for m in vars(tables).values()
                if isinstance(m, type) and issubclass(m, tables.TableRow) and m is not tables.TableRow]
RECORD_MODELS = [SceneSpec, SceneOperations, EpisodeOutcome, LLMCacheRecord, SolvabilityResult, Catalog]


def test_the_table_models_are_found() -> None:
    assert {m.TABLE for m in TABLE_MODELS} >= {"scenes", "compiled_scenes", "instructions", "episodes"}


@pytest.mark.parametrize("model", TABLE_MODELS, ids=lambda m: m.__name__)
def test_a_table_carries_its_schema_version_in_the_footer(model: type[tables.TableRow], tmp_path) -> None:
    assert isinstance(model.SCHEMA_VERSION, int) and model.SCHEMA_VERSION >= 1
    assert not hasattr(model, "VERSION")
    path = tables.write_table([], tmp_path / "t.parquet", model)
    meta = pq.read_schema(path).metadata
    assert meta[tables.SCHEMA_KEY] == str(model.SCHEMA_VERSION).encode()
    assert tables.read_table(path, model).height == 0


@pytest.mark.parametrize("model", RECORD_MODELS, ids=lambda m: m.__name__)
def test_a_record_carries_a_literal_schema_version_field(model: type[BaseModel]) -> None:
    field = model.model_fields.get("schema_version")
    assert field is not None, f"{model.__name__} has no schema_version field"
    (allowed,) = typing.get_args(field.annotation)
    assert field.default == allowed and isinstance(allowed, int)
    assert not hasattr(model, "VERSION")


def test_a_table_written_before_the_key_was_renamed_still_reads(tmp_path) -> None:
    import pyarrow as pa

    model = tables.SceneDesignRow
    path = tables.write_table([], tmp_path / "old.parquet", model)
    table = pq.read_table(path)
    meta = {k: v for k, v in table.schema.metadata.items() if k != tables.SCHEMA_KEY}
    meta[b"ladev_version"] = str(model.SCHEMA_VERSION + 1).encode()
    pq.write_table(table.replace_schema_metadata(meta), path)
    assert isinstance(table, pa.Table)
    with pytest.raises(tables.TableError, match="newer than this LADEV reads"):
        tables.read_table(path, model)
