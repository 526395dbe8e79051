"""Operations -> SceneSpec: placement, task objects, clamping, and rejections with reasons."""

from __future__ import annotations

import math

import pytest

from ladev_lib.scenes.compiler import (
    CompileConfig,
    DesignExpectation,
    compile_operations,
    region_box,
)
from ladev_lib.scenes.operations import SceneOperations
from ladev_lib.scenes.placement import footprint, overlaps
from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.scenes.text_to_scene import SceneText


def ops(*operations, task=None, **extra) -> SceneOperations:
    return SceneOperations.model_validate({"operations": list(operations), "task": task, **extra})


def add(obj=None, **position):
    op = {"op": "add_object", "object": obj}
    if position:
        op["position"] = position
    return op


def compile_(o, catalog, resolver, **kw):
    return compile_operations(o, catalog, resolver=resolver, **kw)


def test_random_objects_fill_the_count_and_the_task_objects_are_placed_without_collision(catalog, exact_resolver):
    out = compile_(ops(add("carrot"), add(), add(), add(), task={"type": "put_on", "source": "carrot",
                                                                 "target": "plate"}), catalog, exact_resolver, seed=4)
    assert out.ok, out.reason
    spec = out.spec
    assert len(spec.objects) == 4  # the plate took a random object's place
    assert spec.source.id == "carrot" and spec.target.id == "plate"
    assert len({o.id for o in spec.objects}) == 4
    prints = [footprint(catalog.get(o.id), o.x, o.y, o.yaw_deg, 0.0099) for o in spec.objects]
    assert not any(overlaps(a, b) for i, a in enumerate(prints) for b in prints[i + 1:])
    assert any("plate" in n and "random" in n for n in out.notes)


def test_a_task_object_the_description_left_out_is_added_with_a_note(catalog, exact_resolver):
    out = compile_(ops(add("apple"), task={"type": "pick_up", "source": "sponge"}), catalog, exact_resolver)
    assert out.ok and {o.id for o in out.spec.objects} == {"apple", "sponge"}
    assert out.spec.source.id == "sponge" and any("added" in n for n in out.notes)


def test_same_seed_same_scene_other_seed_other_scene(catalog, exact_resolver):
    o = ops(add(), add(), add(), task={"type": "pick_up"})
    a, b, c = (compile_(o, catalog, exact_resolver, seed=s).spec for s in (1, 1, 2))
    assert a == b and a != c


def test_regions_coordinates_and_relations_are_respected(catalog, exact_resolver):
    bounds = SceneBounds()
    o = ops(
        add("coke can", region="left"),
        add("apple", x=0.1, y=-0.2),
        add("sponge", relation="near", reference="apple"),
        add("plate", relation="left_of", reference="apple"),
        task={"type": "pick_up", "source": "coke can"},
    )
    for seed in range(10):
        out = compile_(o, catalog, exact_resolver, seed=seed)
        assert out.ok, out.reason
        s = out.spec
        (_, _), (ly0, ly1) = region_box("left", bounds)
        assert ly0 <= s.object("coke_can").y <= ly1
        assert (s.object("apple").x, s.object("apple").y) == (0.1, -0.2)
        sponge, apple, plate = s.object("sponge"), s.object("apple"), s.object("plate")
        edge_gap = math.dist((sponge.x, sponge.y), (apple.x, apple.y)) - catalog.get("sponge").footprint_radius_m \
            - catalog.get("apple").footprint_radius_m
        assert edge_gap <= CompileConfig().near_distance_m + 1e-6
        assert plate.y > apple.y


def test_a_reference_that_is_not_among_the_objects_is_added(catalog, exact_resolver):
    out = compile_(ops(add("apple", relation="near", reference="bowl"), add(), task={"type": "pick_up",
                   "source": "apple"}), catalog, exact_resolver)
    assert out.ok and "024_bowl" in {o.id for o in out.spec.objects} and len(out.spec.objects) == 2


def test_lighting_and_camera_are_clamped_to_the_bounds_with_notes(catalog, exact_resolver):
    out = compile_(
        ops(add("apple"), {"op": "set_lighting", "intensity_delta": -0.9},
            {"op": "move_camera", "translation_m": [0.0, 0.12, 0.0], "rotation_deg": [0, 12, -3]},
            task={"type": "pick_up"}),
        catalog, exact_resolver, bounds=SceneBounds(camera_max_translation_m=0.05, camera_max_rotation_deg=5),
    )
    assert out.ok
    assert out.spec.lighting.intensity_delta == -0.5
    assert out.spec.camera.translation_m == pytest.approx((0.0, 0.05, 0.0))
    assert out.spec.camera.rotation_deg == (0.0, 5.0, -3.0)
    joined = " ".join(out.notes)
    assert "lighting change -0.90 clamped to -0.50" in joined
    assert "camera move 12.0 cm clamped to 5.0 cm" in joined and "pitch +12.0 deg clamped" in joined


def test_random_lighting_and_camera_stay_within_the_bounds(catalog, exact_resolver):
    out = compile_(ops(add(), {"op": "set_lighting", "random": True}, {"op": "move_camera", "random": True},
                       task={"type": "pick_up"}), catalog, exact_resolver, seed=3)
    assert out.ok and 0.1 <= abs(out.spec.lighting.intensity_delta) <= 0.5
    assert not out.spec.camera.is_default and out.spec.camera.translation_norm_m <= 0.05 + 1e-9


def test_categories_pick_a_member_and_the_object_set_is_honoured(catalog, exact_resolver):
    out = compile_(ops(add("fruit"), add(), add(), task={"type": "pick_up", "source": "fruit"}, object_set="ycb"),
                   catalog, exact_resolver, seed=5)
    assert out.ok and catalog.get(out.spec.source.id).category == "fruit"
    assert {catalog.get(o.id).set for o in out.spec.objects} == {"ycb"}


# -- rejections: data, with reasons -------------------------------------------------


def test_unknown_object_is_left_out_and_reported_rejected_or_substituted(catalog, exact_resolver):
    o = ops(add("purple elephant"), add("apple"), task={"type": "pick_up", "source": "apple"})
    omitted = compile_(o, catalog, exact_resolver)  # the default: reported by name, never substituted
    assert omitted.ok and [p.id for p in omitted.spec.objects] == ["apple"]
    assert any("unavailable" in n and "purple elephant" in n and "left out" in n for n in omitted.notes)
    out = compile_(o, catalog, exact_resolver, config=CompileConfig(unknown_objects="reject"))
    assert not out.ok and "unknown object" in out.reason and "purple elephant" in out.reason
    sub = compile_(o, catalog, exact_resolver, config=CompileConfig(unknown_objects="substitute"))
    assert sub.ok and len(sub.spec.objects) == 2 and any("unavailable" in n for n in sub.notes)


@pytest.mark.parametrize(
    "task, why",
    [
        ({"type": "put_in", "source": "apple", "target": "plate"}, "not a container"),
        ({"type": "put_in", "source": "cracker box", "target": "mug"}, "does not fit"),
        ({"type": "put_on", "source": "apple", "target": "coke can"}, "cannot hold objects on top"),
        ({"type": "pick_up", "source": "plate"}, "not graspable"),
        ({"type": "move_near", "source": "apple", "target": "apple"}, "same object"),
    ],
)
def test_impossible_tasks_are_rejected_with_the_reason(catalog, exact_resolver, task, why):
    out = compile_(ops(add(), add(), task=task), catalog, exact_resolver)
    assert not out.ok and why in out.reason, out.reason


def test_too_many_objects_are_rejected(catalog, exact_resolver):
    out = compile_(ops(*[add() for _ in range(9)], task={"type": "pick_up"}), catalog, exact_resolver)
    assert not out.ok and out.reason.startswith("too many objects: 9 requested")


def test_objects_that_cannot_be_placed_are_rejected(catalog, exact_resolver):
    big = ["skillet lid", "toy airplane", "red plate", "peg board", "orange lego board"]
    out = compile_(ops(*[add(b) for b in big], add("dice"), task={"type": "pick_up", "source": "dice"}),
                   catalog, exact_resolver)
    assert not out.ok and out.reason.startswith("cannot place the objects without collision"), out.reason


def test_overlapping_coordinates_are_rejected(catalog, exact_resolver):
    out = compile_(ops(add("apple", x=0.0, y=0.0), add("orange", x=0.01, y=0.0), task={"type": "pick_up",
                   "source": "apple"}), catalog, exact_resolver)
    assert not out.ok and "overlaps" in out.reason


def test_a_descriptions_colliding_coordinates_are_moved_to_the_nearest_clear_point(catalog, exact_resolver):
    # a plate 26 cm across at 11 cm from a banana: read from text, the plate moves (and says so)
    o = ops(add("banana", x=0.0, y=0.0), add("plate", x=-0.1, y=0.05),
            task={"type": "put_on", "source": "banana", "target": "plate"})
    exact = compile_(o, catalog, exact_resolver)
    assert not exact.ok and "overlaps" in exact.reason
    out = compile_(o, catalog, exact_resolver, approximate_coordinates=True)
    assert out.ok, out.reason
    plate = next(ob for ob in out.spec.objects if ob.id == "plate")
    moved = math.hypot(plate.x + 0.1, plate.y - 0.05)
    assert 0 < moved <= 0.15 + 1e-6
    assert any("moved" in n and "plate" in n for n in out.notes), out.notes
    banana = next(ob for ob in out.spec.objects if ob.id == "011_banana")
    assert (banana.x, banana.y) == pytest.approx((0.0, 0.0))  # the first object keeps its point


def test_a_described_point_off_the_workspace_goes_to_its_edge(catalog, exact_resolver):
    o = ops(add("apple", x=0.0, y=0.0), add("bowl", x=0.3, y=-0.1),
            task={"type": "put_in", "source": "apple", "target": "bowl"})
    exact = compile_(o, catalog, exact_resolver)
    assert not exact.ok and "outside the workspace" in exact.reason  # operations given as data are exact
    out = compile_(o, catalog, exact_resolver, approximate_coordinates=True)
    assert out.ok, out.reason
    bowl = next(ob for ob in out.spec.objects if ob.id == "024_bowl")
    assert bowl.x == pytest.approx(0.15) and bowl.y == pytest.approx(-0.1)
    assert any("off the workspace" in n and "bowl" in n for n in out.notes), out.notes


def test_a_study_scene_must_match_its_design(catalog, exact_resolver):
    o = ops(add("apple"), add(), task={"type": "pick_up", "source": "apple"})
    ok = compile_(o, catalog, exact_resolver, expected=DesignExpectation("pick_up", 2, "simpler", "default"))
    assert ok.ok
    bad = compile_(o, catalog, exact_resolver, expected=DesignExpectation("pick_up", 3, "simpler", "lighting"))
    assert not bad.ok and "does not match the study design" in bad.reason
    assert "the design wants 3" in bad.reason and "environment level 'lighting'" in bad.reason


def test_an_error_from_the_llm_is_a_rejection(catalog, exact_resolver):
    out = compile_(SceneOperations(error="not a scene"), catalog, exact_resolver)
    assert not out.ok and "could not be read as a scene: not a scene" in out.reason


# -- through the offline backend, from text ---------------------------------------------


@pytest.mark.parametrize(
    "description, instruction, reason",
    [
        ("an apple and a purple elephant", "put the apple near the purple elephant", "unknown object: 'purple elephant'"),
        ("a cracker box and a mug", "put the cracker box in the mug", "impossible task"),
        ("an apple and a plate", "put the apple in the plate", "not a container"),
        ("twelve objects including an apple", "pick up the apple", "too many objects: 12 requested"),
        ("a skillet lid, a toy airplane, a red plate, a peg board and an orange lego board", "pick up the dice",
         "cannot place the objects"),
        ("asdf qwerty zxcv", "pick up the apple", "could not be read"),
        ("!!! ??? ...", "pick up the apple", "could not be read"),
        ("lorem ipsum dolor sit amet", None, "could not be read"),
        ("an apple", "dance with the apple", "none of the four task forms"),
    ],
)
def test_compile_rejects_bad_descriptions_with_reasons(offline_compiler, description, instruction, reason):
    result = offline_compiler.compile(SceneText("r", description, instruction=instruction, seed=1))
    assert result.status == "rejected" and reason in (result.reason or ""), result.reason
    row = result.row()
    assert row.status == "rejected" and row.spec_json is None and row.reason == result.reason


@pytest.mark.parametrize(
    "description, count, name",
    [
        ("two objects, one of them a purple elephant", 1, "purple elephant"),
        ("an apple and a pink unicorn on the left", 1, "pink unicorn"),
    ],
)
def test_compile_leaves_unavailable_objects_out_and_names_them(offline_compiler, description, count, name):
    result = offline_compiler.compile(SceneText("u", description, instruction="pick up the apple", seed=1))
    assert result.status == "ok", result.reason
    assert len(result.spec.objects) == count
    assert any(name in n and "unavailable" in n for n in result.notes), result.notes


def test_an_unknown_object_the_task_names_rejects_the_scene(catalog, exact_resolver):
    o = ops(add("apple"), task={"type": "put_in", "source": "apple", "target": "wine glass"})
    out = compile_(o, catalog, exact_resolver)
    assert not out.ok and "wine glass" in out.reason and "target" in out.reason


def test_two_of_the_source_object_is_a_valid_scene(catalog, exact_resolver):
    o = ops(add("apple"), add("apple"), add("basket"), task={"type": "put_in", "source": "apple", "target": "basket"})
    out = compile_(o, catalog, exact_resolver)
    assert out.ok, out.reason
    assert sorted(p.id for p in out.spec.objects) == ["apple", "apple", "basket"]
    assert out.spec.source.id == "apple"


def test_a_named_object_that_fits_only_across_the_opening_may_go_in(catalog, exact_resolver):
    """A banana does not fit a bowl lying along its side, but across the diagonal it does."""
    o = ops(add("banana"), add("bowl"), task={"type": "put_in", "source": "banana", "target": "bowl"})
    out = compile_(o, catalog, exact_resolver)
    assert out.ok, out.reason
