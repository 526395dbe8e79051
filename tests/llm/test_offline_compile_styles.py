"""The offline backend on descriptions written the way people write them (not by our writer).

Each case is compiled through the real path (prompt -> offline backend ->
operations -> compiler) and checked field by field: the number of objects,
objects that must be there, the task, the lighting direction and the camera move.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from ladev_lib.scenes.text_to_scene import SceneText

CAMERA_AXES = {"x": (0, 0), "y": (0, 1), "z": (0, 2), "roll": (1, 0), "pitch": (1, 1), "yaw": (1, 2)}


@dataclass(frozen=True)
class Case:
    description: str
    instruction: str | None = None
    task: str = "pick_up"
    count: int | None = None
    has: tuple[str, ...] = ()
    source: str | None = None
    target: str | None = None
    light: str = "default"  # default | darker | brighter
    camera: dict[str, int] = field(default_factory=dict)  # axis -> sign; empty: default camera
    object_set: str | None = None


CASES = [
    # The paper's structured form.
    Case("Number and details of objects: 3 objects, one of them is a plastic bottle on the left. "
         "Environmental setup: slightly darker lighting, camera moved 3 cm left.",
         "pick up the plastic bottle", count=3, source="blue_plastic_bottle", light="darker", camera={"y": 1}),
    Case("Number and details of objects: 2 objects, one is a carrot, one is a plate. Environmental setup: default.",
         "put the carrot on the plate", "put_on", count=2, source="carrot", target="plate"),
    Case("Number and details of objects: . Environmental setup: camera rotated 3 degrees to the left.",
         "pick up the apple", source="apple", camera={"yaw": 1}),
    Case("Environmental setup: much brighter lighting. Number and details of objects: 2 objects.",
         "pick up the yellow cube", count=2, source="yellow_cube", light="brighter"),
    Case("Number and details of objects: four objects, one is a sponge in the front left, one is an apple. "
         "Environmental setup: lighting a bit brighter, camera tilted 2 degrees down.",
         "move the apple near the sponge", "move_near", count=4, source="apple", target="sponge",
         light="brighter", camera={"pitch": 1}),
    # Free prose.
    Case("three objects, one of them a plastic bottle on the left; lighting a bit darker",
         None, "pick_up", count=3, source="blue_plastic_bottle", light="darker"),
    Case("Two cans: a pepsi can and a sprite can. The lights are much brighter.",
         "pick up the pepsi can", count=2, has=("sprite_can",), source="pepsi_can", light="brighter"),
    Case("A table with five things on it, including a sponge and a carrot. Default lighting and camera.",
         "put the carrot on the sponge", "put_on", count=5, source="carrot", target="sponge"),
    Case("Put an orange and a bowl on the table, nothing else. Camera rotated 4 degrees down.",
         "put the orange in the bowl", "put_in", count=2, source="orange", target="024_bowl", camera={"pitch": 1}),
    Case("a single object: a banana, in the middle of the table", "pick up the banana",
         count=1, source="011_banana"),
    Case("six objects, all random, lighting slightly brighter", "move the apple near the plate", "move_near",
         count=6, source="apple", target="plate", light="brighter"),
    Case("There's a mug at the front right and an orange cup beside it. The scene is dimly lit.",
         "put the orange cup in the mug", "put_in", count=2, source="065-a_cups", target="025_mug", light="darker"),
    Case("3 YCB objects including a tennis ball; camera shifted 2 cm to the right and tilted up 3 degrees",
         "pick up the tennis ball", count=3, source="056_tennis_ball", camera={"y": -1, "pitch": -1},
         object_set="ycb"),
    Case("Scene: a coke can near the bowl and a knife. Lighting +0.3.", "pick up the knife",
         count=3, has=("coke_can", "024_bowl"), source="032_knife", light="brighter"),
    Case("An apple, a sponge and a towel. Make it much darker.", "put the apple on the towel", "put_on",
         count=3, has=("sponge",), source="apple", target="towel", light="darker"),
    Case("Two objects. Nothing special about lighting or camera.", "pick up the coke can",
         count=2, source="coke_can"),
    Case("five objects on the table: a spoon in the front left corner, a carrot, a plate, a fanta can and an "
         "eggplant at the back", "put the spoon on the plate", "put_on", count=5,
         has=("carrot", "fanta_can", "eggplant"), source="spoon", target="plate"),
    Case("We need a strawberry, a lemon and a peach, plus one random YCB object.", "pick up the lemon",
         count=4, has=("012_strawberry", "015_peach"), source="014_lemon", object_set="ycb"),
    Case("The lighting should be 20% dimmer and the camera should be moved 2 cm up. Objects: an apple and a pear.",
         "move the apple near the pear", "move_near", count=2, source="apple", target="016_pear",
         light="darker", camera={"z": 1}),
    Case("A cluttered table with 4 items, one of which is a rubik's cube.", "move the sugar box near the rubik's cube",
         "move_near", count=4, source="004_sugar_box", target="077_rubiks_cube"),
    Case("coke can on the left, pepsi can on the right, sprite can in the middle", "pick up the sprite can",
         count=3, has=("coke_can", "pepsi_can"), source="sprite_can"),
    Case("Place a green cube on the front right and a yellow cube to the left of it.",
         "put the green cube on the yellow cube", "put_on", count=2, source="green_cube", target="yellow_cube"),
    Case("Bright lighting, 3 objects including a peach", "pick up the peach", count=3, source="015_peach",
         light="brighter"),
    Case("a bowl, two tennis balls and a sponge", "move the sponge near the bowl", "move_near",
         count=4, has=("056_tennis_ball",), source="sponge", target="024_bowl"),
    Case("Three things: a scrub sponge, a spam can, a wooden block. Slightly brighter light.",
         "put the spam can on the wooden block", "put_on", count=3, has=("026_sponge",),
         source="010_potted_meat_can", target="036_wood_block", light="brighter"),
    Case("4 random objects and a basket", "put the carrot in the basket", "put_in", count=5,
         source="carrot", target="basket"),
    Case("A coffee mug and a tennis ball. The room is darker than usual.", "put the tennis ball in the mug",
         "put_in", count=2, source="056_tennis_ball", target="025_mug", light="darker"),
    Case("Camera pulled back by 4 cm. 2 objects: an apple and a plate.", "put the apple on the plate", "put_on",
         count=2, source="apple", target="plate", camera={"x": -1}),
    Case("A coke can next to a plate, camera moved slightly to the left", "move the coke can near the plate",
         "move_near", count=2, source="coke_can", target="plate", camera={"y": 1}),
    Case("Generate a scene with 3 objects. The lighting is unchanged but the camera is rolled 2 degrees clockwise.",
         "pick up the spoon", count=3, source="spoon", camera={"roll": -1}),
    Case("a padlock, a baseball and a dice. Lighting slightly dimmer.", "pick up the padlock", count=3,
         has=("055_baseball", "062_dice"), source="038_padlock", light="darker"),
    Case("Create a scene with a sugar box at the back and a cracker box at the front. Make the camera look "
         "2 degrees more to the right.", "pick up the sugar box", count=2, has=("003_cracker_box",),
         source="004_sugar_box", camera={"yaw": -1}),
    Case("4 objects, 2 of them are fanta cans", "pick up the coke can", count=4, has=("fanta_can",),
         source="coke_can"),
    Case("A pitcher and a strawberry; the camera is 3 cm higher", "put the strawberry in the pitcher", "put_in",
         count=2, source="012_strawberry", target="019_pitcher_base", camera={"z": 1}),
    Case("Lay out four objects, among them a fork and a knife on the right.", "pick up the knife", count=4,
         has=("030_fork",), source="032_knife"),
    Case("Please set up 5 objects with a peach among them and brighten the scene a lot", "pick up the peach",
         count=5, source="015_peach", light="brighter"),
    Case("the camera was nudged 1 cm to the left; nothing on the table except a green cube",
         "pick up the green cube", count=1, source="green_cube", camera={"y": 1}),
    Case("two objects: a marker and a knife, both in the back", "pick up the marker", count=2,
         has=("032_knife",), source="040_large_marker"),
    Case("Five objects from the YCB set, one of which is a softball; the view is moved 3 cm up",
         "pick up the tennis ball", count=5, has=("054_softball",), source="056_tennis_ball",
         camera={"z": 1}, object_set="ycb"),
    Case("a blue water bottle and a bowl", "move the blue water bottle near the bowl", "move_near", count=2,
         source="blue_plastic_bottle", target="024_bowl"),
    Case("Please put 3 objects on the table. One of them should be an apple. Lights dimmed a lot.",
         "pick up the apple", count=3, source="apple", light="darker"),
    Case("a table with a plate on the right and an eggplant on the left, and much stronger lighting",
         "put the eggplant on the plate", "put_on", count=2, source="eggplant", target="plate",
         light="brighter"),
    Case("I'd like a scene with an apple, a banana and a mug. Please make the room a little darker.",
         "pick up the banana", count=3, has=("apple", "025_mug"), source="011_banana", light="darker"),
    Case("Scene contains 4 objects (one coke can, rest random). Camera slightly higher than default.",
         "pick up the coke can", count=4, source="coke_can", camera={"z": 1}),
    Case("Put the bowl in the center and an apple right next to it; lights at 120%.", "put the apple in the bowl",
         "put_in", count=2, source="apple", target="024_bowl", light="brighter"),
    Case("There should be exactly three objects on the table: a yellow cube, a green cube, and a red cup.",
         "put the yellow cube on the green cube", "put_on", count=3, has=("065-e_cups",), source="yellow_cube",
         target="green_cube"),
    Case("A scene where a pear sits behind a plum, and the camera pans 3° left.", "pick up the pear", count=2,
         has=("018_plum",), source="016_pear", camera={"yaw": 1}),
    Case("No objects besides the eggplant and the basket. Lighting reduced by half.",
         "put the eggplant in the basket", "put_in", count=2, source="eggplant", target="basket", light="darker"),
    Case("Set up two fruits and a bowl.", "put the orange in the bowl", "put_in", count=3, source="orange",
         target="024_bowl"),
    Case("The view is tilted upward by 2 degrees and the scene is bright.", "pick up the apple", source="apple",
         light="brighter", camera={"pitch": -1}),
    Case("A redbull can, a 7up can and a fanta can are on the table, with the light dimmed slightly",
         "pick up the fanta can", count=3, has=("redbull_can", "7up_can"), source="fanta_can", light="darker"),
    # Terse lists.
    Case("4 objects: coke can (left), plate, 2 random; light -0.2", "put the coke can on the plate", "put_on",
         count=4, source="coke_can", target="plate", light="darker"),
    Case("objects: 2; lighting: default; camera: default", "pick up the apple", count=2, source="apple"),
    Case("3 objects: pear, plum, lemon; lighting -10%", "pick up the plum", count=3,
         has=("016_pear", "014_lemon"), source="018_plum", light="darker"),
    Case("Lighting x1.3. 2 objects: a red apple and a lemon", "pick up the red apple", count=2,
         has=("014_lemon",), source="013_apple", light="brighter"),
    Case("camera: move 2 cm left, rotate 3 degrees left", "pick up the coke can", source="coke_can",
         camera={"y": 1, "yaw": 1}),
    Case("Objects: sponge, plate. Lighting: 0.8x. Camera: +2 cm in y.", "put the sponge on the plate", "put_on",
         count=2, source="sponge", target="plate", light="darker", camera={"x": 1}),
    Case("apple @ (0.0, 0.1); orange @ (0.05, -0.1)", "move the apple near the orange", "move_near", count=2,
         source="apple", target="orange"),
    Case("1 object: a carrot. lights 30% brighter.", "pick up the carrot", count=1, source="carrot",
         light="brighter"),
    Case("3 objects. lighting: -0.35. camera: pitch 4", "pick up the orange", count=3, source="orange",
         light="darker", camera={"pitch": -1}),
    Case("objects = 4, light = +0.2, cam = 3 cm right", "pick up the apple", count=4, source="apple",
         light="brighter", camera={"y": -1}),
    # "1 deg roll" is "roll 1" said value first: + is clockwise in the camera's frame, - in the spec's
    Case("Two objects: bowl (front), apple (back). Camera: 2cm down, 1 deg roll.", "put the apple in the bowl",
         "put_in", count=2, source="apple", target="024_bowl", camera={"z": -1, "roll": -1}),
    Case("lighting intensity 0.7", "pick up the sponge", source="sponge", light="darker"),
    # Signed axis values are the camera's own frame (x right, y forward; yaw + pans right, pitch + tilts up).
    Case("camera: yaw +3 deg, pitch -2 deg", "pick up the orange", source="orange", camera={"yaw": -1, "pitch": 1}),
    Case("a dice, a golf ball and a marble on the right side", "pick up the golf ball", count=3,
         has=("062_dice", "063-b_marbles"), source="058_golf_ball"),
    Case("3 SimplerEnv objects, including the eggplant", "pick up the eggplant", count=3, source="eggplant",
         object_set="simpler"),
    Case("lemon on the left, bowl on the right", "put the lemon in the bowl", "put_in", count=2,
         source="014_lemon", target="024_bowl"),
    # Command lines.
    Case("ADD coke can to (0.1, 0.2)\nADD apple to (-0.05, -0.1)", "move the coke can near the apple",
         "move_near", count=2, source="coke_can", target="apple"),
    Case("ADD tomato soup can to (5 cm, -10 cm)\nADD plate\nSET LIGHTING -0.4",
         "put the tomato soup can on the plate", "put_on", count=2, source="005_tomato_soup_can",
         target="plate", light="darker"),
    Case("ADD banana\nADD random object\nADD random object\nMOVE CAMERA 4 cm right\nROTATE CAMERA 2 degrees up",
         "pick up the banana", count=3, source="011_banana", camera={"y": -1, "pitch": -1}),
    Case("add a coke can and a pepsi can, and lower the lights by 0.25", "pick up the pepsi can", count=2,
         has=("coke_can",), source="pepsi_can", light="darker"),
    Case("ADD 2 random YCB objects\nADD mustard bottle to (0, 0)\nSET_LIGHTING(+0.15)",
         "pick up the mustard bottle", count=3, source="006_mustard_bottle", light="brighter", object_set="ycb"),
    Case("add apple at x=0.05, y=-0.1 and add basket", "put the apple in the basket", "put_in", count=2,
         source="apple", target="basket"),
    # Bulleted lists.
    Case("Objects:\n- an orange, on the left\n- a bowl\n- 2 random objects\nLighting: much darker\nCamera: default",
         "put the orange in the bowl", "put_in", count=4, source="orange", target="024_bowl", light="darker"),
    Case("* sponge (front)\n* plate (back)\n* towel\nCamera: tilted 3 degrees down and moved 1 cm up",
         "put the sponge on the plate", "put_on", count=3, has=("towel",), source="sponge", target="plate",
         camera={"pitch": 1, "z": 1}),
    Case("1. apple\n2. orange\n3. basket\nlighting: slightly brighter", "put the orange in the basket", "put_in",
         count=3, has=("apple",), source="orange", target="basket", light="brighter"),
]


def _sign(value: float) -> int:
    return (value > 1e-9) - (value < -1e-9)


@pytest.mark.parametrize("case", CASES, ids=[f"{i:02d}" for i in range(len(CASES))])
def test_offline_backend_reads_the_description(case: Case, offline_compiler, catalog):
    item = SceneText("t", case.description, instruction=case.instruction, task=case.task, seed=11,
                     object_set=case.object_set)
    result = offline_compiler.compile(item)
    assert result.status == "ok", (result.reason, result.operations)
    spec = result.spec
    assert spec is not None
    ids = [o.id for o in spec.objects]
    if case.count is not None:
        assert len(spec.objects) == case.count, (ids, result.operations)
    for required in case.has:
        assert required in ids, (required, ids)
    assert spec.task.type == case.task
    if case.source is not None:
        assert spec.source.id == case.source
    if case.target is not None:
        assert spec.target is not None and spec.target.id == case.target
    assert _sign(spec.lighting.intensity_delta) == {"default": 0, "darker": -1, "brighter": 1}[case.light]
    if not case.camera:
        assert spec.camera.is_default, spec.camera
    else:
        values = (spec.camera.translation_m, spec.camera.rotation_deg)
        for axis, sign in case.camera.items():
            kind, k = CAMERA_AXES[axis]
            assert _sign(values[kind][k]) == sign, (axis, spec.camera)
        moved = {a for a, (kind, k) in CAMERA_AXES.items() if _sign(values[kind][k]) != 0}
        assert moved == set(case.camera), (moved, spec.camera)
    if case.object_set is not None:
        assert {catalog.get(i).set for i in ids} == {case.object_set}


def test_there_are_at_least_sixty_cases_in_several_styles():
    assert len(CASES) >= 60
    commands = sum("ADD " in c.description or c.description.startswith("add ") for c in CASES)
    structured = sum("Number and details of objects" in c.description for c in CASES)
    lists = sum(c.description.startswith(("Objects:\n", "* ", "1. ")) for c in CASES)
    assert commands >= 5 and structured >= 4 and lists >= 3
