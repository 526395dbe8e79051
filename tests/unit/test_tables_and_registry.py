from __future__ import annotations

import polars as pl
import pytest

from ladev_lib.errors import MissingExtraError, UnknownNameError
from ladev_lib.registry import Registry
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    InstructionRow,
    SceneDesignRow,
    TableError,
    arrow_schema,
    read_table,
    write_table,
)


def episode(**over):
    row = dict(
        episode_id="e1", study="smoke", scene_id="s1", instruction_id="s1/basic", policy="oracle",
        task="pick_up", factor="num_objects", level="1", num_objects=1, object_set="simpler",
        environment="default", instruction_kind="basic", instruction="pick up the coke can",
        robot="panda", seed=0, status="success", success=True, predicates_json='{"is_grasped": true}',
    )
    row.update(over)
    return row


def test_episode_table_round_trip(tmp_path):
    path = write_table([episode(), episode(episode_id="e2", status="error", success=None, error="boom")],
                       tmp_path / "e.parquet", EpisodeRow)
    df = read_table(path, EpisodeRow)
    assert df.height == 2
    assert df["success"].to_list() == [True, None]
    assert df.schema["steps"] == pl.Int64


def test_reading_the_wrong_table_fails(tmp_path):
    path = write_table([episode()], tmp_path / "e.parquet", EpisodeRow)
    with pytest.raises(TableError, match="holds table 'episodes', expected 'instructions'"):
        read_table(path, InstructionRow)


def test_rows_are_validated_on_write(tmp_path):
    with pytest.raises(ValueError, match="status"):
        write_table([episode(status="crashed")], tmp_path / "e.parquet", EpisodeRow)


@pytest.mark.parametrize("model", [SceneDesignRow, CompiledSceneRow, InstructionRow, EpisodeRow])
def test_every_table_has_a_schema_with_version(model):
    schema = arrow_schema(model)
    assert schema.metadata[b"ladev_table"] == model.TABLE.encode()
    assert list(schema.names) == list(model.model_fields)
    for name, field in model.model_fields.items():
        assert field.description, f"{model.__name__}.{name} has no description"


def test_registry_names_known_entries_and_extras():
    reg: Registry[object] = Registry("widget")
    reg.add("a", object())
    reg.add_lazy("heavy", "surely_not_installed_pkg.mod:Thing", extra="heavy")
    with pytest.raises(UnknownNameError, match="unknown widget 'b'; known: a, heavy"):
        reg.get("b")
    with pytest.raises(MissingExtraError, match=r"pip install 'ladev\[heavy\]'"):
        reg.get("heavy")
