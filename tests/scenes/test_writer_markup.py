"""The offline writer's annotated descriptions: the same text, with what each phrase says marked."""

from __future__ import annotations

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.tagging.markup import parse_markup
from ladev_lib.scenes.writer import STYLES, write_scene


@pytest.mark.parametrize("style", STYLES)
def test_annotated_text_is_the_description_with_markup(style):
    catalog = load_catalog(None)
    for seed in range(40):
        task = ("pick_up", "move_near", "put_on", "put_in")[seed % 4]
        env = ("default", "lighting", "camera")[seed % 3]
        plain = write_scene(task, 1 + seed % 5, "ycb" if seed % 2 else "simpler", env, seed, catalog, style=style)
        marked = write_scene(task, 1 + seed % 5, "ycb" if seed % 2 else "simpler", env, seed, catalog, style=style,
                             annotate=True)
        assert marked.description == plain.description and plain.annotated is None
        text, spans = parse_markup(marked.annotated or "")
        assert text == plain.description
        tags = {s.tag for s in spans}
        assert "OBJ" in tags
        if env == "lighting":
            assert "LIGHT" in tags
        if env == "camera":
            assert "CAM" in tags
