from __future__ import annotations

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.catalog.catalog import normalize_name


def test_catalog_has_both_sets(catalog):
    simpler = catalog.select(sets=["simpler"])
    ycb = catalog.select(sets=["ycb"])
    assert len(simpler) == 18
    assert len(ycb) >= 65
    assert len(catalog) == len(simpler) + len(ycb)


def test_every_task_has_candidates_in_each_set(catalog):
    for s in ("simpler", "ycb"):
        assert len(catalog.select(sets=[s], graspable=True)) >= 10, s
        assert catalog.select(sets=[s], support=True), s
        assert catalog.select(sets=[s], container=True), s


def test_lookup_by_name_and_synonym(catalog):
    assert catalog.by_name("Coke can").id == "coke_can"
    assert catalog.by_name("Coca-Cola can").id == "coke_can"
    assert catalog.by_name("can of pepsi").id == "pepsi_can"
    assert catalog.by_name("rubiks cube").id == "077_rubiks_cube"
    assert catalog.by_name("rubik's cube").id == "077_rubiks_cube"
    assert catalog.by_name("teapot") is None


def test_unknown_id_suggests_close_ones(catalog):
    with pytest.raises(KeyError, match="did you mean.*coke_can"):
        catalog.get("coke")


def test_names_are_unique_across_catalog(catalog):
    seen = {}
    for obj in catalog:
        for n in obj.names:
            key = normalize_name(n)
            assert seen.setdefault(key, obj.id) == obj.id, (n, obj.id, seen[key])


def test_coke_can_stands_upright_at_its_real_size(catalog):
    can = catalog.get("coke_can")
    assert can.size_m[2] == pytest.approx(0.123, abs=0.002)  # upright height
    assert can.size_m[0] == pytest.approx(0.066, abs=0.002)
    assert can.shape == "cylinder"
    assert can.color[0] > 0.5 > can.color[1]  # red


def test_duplicate_names_are_rejected(tmp_path):
    bad = tmp_path / "objects.yaml"
    bad.write_text(
        """
objects:
- {id: a, set: simpler, display_name: cup, category: cup, shape: cylinder, size_m: [0.05, 0.05, 0.1],
   color: [1, 0, 0], mass_kg: 0.1, graspable: true, support: false, container: false}
- {id: b, set: ycb, display_name: mug, synonyms: [Cup], category: cup, shape: cylinder,
   size_m: [0.05, 0.05, 0.1], color: [1, 0, 0], mass_kg: 0.1, graspable: true, support: false, container: false}
"""
    )
    with pytest.raises(ValueError, match="already a name of 'a'"):
        load_catalog(bad)


@pytest.mark.assets
def test_every_listed_mesh_is_in_the_asset_dir(catalog):
    from ladev_lib.assets import asset_dir

    missing = [o.id for o in catalog if o.mesh is not None and o.mesh_dir(asset_dir()) is None]
    assert missing == []
