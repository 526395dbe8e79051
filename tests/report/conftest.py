"""Fixtures for the report tests: synthetic episode tables with known answers."""

from __future__ import annotations

from pathlib import Path

import polars as pl
import pytest

from ladev_lib.report.synthetic import CellCounts, PairedCounts, episodes_from_counts

# A small study whose every number is known:
#   oracle pick_up, 1 object:  6 successes, 2 failures, 1 error, 1 invalid scene
#   oracle pick_up, 3 objects: 2 successes, 6 failures
#   oracle pick_up, 2/4/5 objects: nothing (empty cells)
#   grounded move_near, 1 object: 0 successes, 5 failures, 2 errors
#   instruction (paired), oracle pick_up: both 3, basic only 8, paraphrase only 2, neither 7
#   object_set, oracle pick_up: simpler 7/10, ycb 1/10
KNOWN_CELLS = [
    CellCounts("oracle", "pick_up", "num_objects", "1", successes=6, failures=2, errors=1, invalid=1),
    CellCounts("oracle", "pick_up", "num_objects", "3", successes=2, failures=6),
    CellCounts("grounded", "move_near", "num_objects", "1", successes=0, failures=5, errors=2),
    CellCounts("oracle", "pick_up", "object_set", "simpler", successes=7, failures=3),
    CellCounts("oracle", "pick_up", "object_set", "ycb", successes=1, failures=9),
]
KNOWN_PAIRS = [PairedCounts("oracle", "pick_up", both=3, basic_only=8, paraphrase_only=2, neither=7)]


@pytest.fixture()
def known_episodes() -> pl.DataFrame:
    return episodes_from_counts(KNOWN_CELLS, KNOWN_PAIRS, study="known")


def write_png(path: Path, color: tuple[int, int, int]) -> Path:
    from PIL import Image

    path.parent.mkdir(parents=True, exist_ok=True)
    Image.new("RGB", (32, 24), color).save(path)
    return path
