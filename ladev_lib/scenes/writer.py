"""Rule-based writer of scene descriptions, for the offline ``describe_scenes`` job.

For each requested scene it samples a valid scene with the scene's seed
(:func:`ladev_lib.scenes.sampling.sample_scene`), then describes it in one of
several styles people write, as the paper's batch generation asks an LLM to:

- ``structured``: "Number and details of objects: ... Environmental setup: ..."
- ``prose``: free sentences
- ``terse``: "4 objects: coke can (left), plate, 2 random; light -0.2"
- ``commands``: "ADD coke can to (0.05, 0.12)" lines
- ``list``: a bulleted list with "Lighting:" and "Camera:" lines

The source and target are always named; other objects are named or left
random; positions are given as words or coordinates or not at all; lighting
and camera changes in words or numbers. The basic instruction uses display
names. Everything is drawn from the scene's seed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.scenes.sampling import sample_scene
from ladev_lib.scenes.spec import CameraOffset, ObjectPlacement, SceneBounds
from ladev_lib.vocabulary import as_object_set

STYLES = ("structured", "prose", "terse", "commands", "list")
_WORDS = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"]
_WRITER_GAP_M = 0.035
"""Sampled scenes keep more than the compiler's minimum gap, so rounded coordinates still fit."""


@dataclass(frozen=True)
class WrittenScene:
    description: str
    instruction: str
    style: str
    annotated: str | None = None
    """The description with the reader's markup (``[[words|TAG]]``), when asked for: what each phrase says,
    known by construction (training rows for the span tagger)."""


_ANNOTATE = False


def _m(text: str, tag: str) -> str:
    """``text`` marked as ``tag`` when writing annotated text, else as is."""
    return f"[[{text}|{tag}]]" if _ANNOTATE and text else text


@dataclass
class _Item:
    obj: CatalogObject
    placement: ObjectPlacement
    name: str
    named: bool
    where: str | None  # words or coordinates, already phrased


def _count(n: int, rng: np.random.Generator) -> str:
    return _WORDS[n] if n < len(_WORDS) and rng.random() < 0.5 else str(n)


def _plural(n: int, word: str) -> str:
    return word if n == 1 else word + "s"


def region_words(x: float, y: float, bounds: SceneBounds) -> str:
    """Where (x, y) is on the table, in words from the robot's point of view."""
    (x0, x1), (y0, y1) = bounds.workspace_x_m, bounds.workspace_y_m
    fx = (x - x0) / (x1 - x0)
    fy = (y - y0) / (y1 - y0)
    vertical = "front" if fx > 2 / 3 else "back" if fx < 1 / 3 else ""
    horizontal = "left" if fy > 2 / 3 else "right" if fy < 1 / 3 else ""
    if vertical and horizontal:
        return f"{vertical} {horizontal}"
    return vertical or horizontal or "middle"


def _where(p: ObjectPlacement, style: str, rng: np.random.Generator, bounds: SceneBounds) -> str | None:
    r = rng.random()
    if style == "commands" or (style == "terse" and r < 0.3):
        return f"({p.x:.3f}, {p.y:.3f})" if style == "commands" or r < 0.15 else None
    if r < 0.4:
        words = region_words(p.x, p.y, bounds)
        if words == "middle":
            return str(rng.choice(["in the middle", "in the center"]))
        if words in ("left", "right"):
            return str(rng.choice([f"on the {words}", f"on the {words} side", f"to the {words}"]))
        if words in ("front", "back"):
            return str(rng.choice([f"at the {words}", f"in the {words}"]))
        return str(rng.choice([f"in the {words} corner", f"at the {words}", f"{words}"]))
    if r < 0.5:
        return f"at ({p.x:.3f}, {p.y:.3f})"
    return None


def _name(obj: CatalogObject, rng: np.random.Generator) -> str:
    # Synonyms of a few letters ('die', 'lid') read as ordinary words; use longer ones.
    synonyms = [s for s in obj.synonyms if len(s) >= 5 and " " in s]
    if synonyms and rng.random() < 0.25:
        return str(rng.choice(synonyms))
    return obj.display_name


# -- environment in words or numbers -------------------------------------------------


def lighting_phrase(delta: float, style: str, rng: np.random.Generator) -> str:
    if delta == 0:
        return ""
    darker = delta < 0
    magnitude = abs(delta)
    if style in ("commands",):
        return f"SET LIGHTING {delta:+.2f}"
    if style == "terse" or rng.random() < 0.3:
        choice = rng.integers(3)
        if choice == 0:
            return f"lighting {delta:+.2f}"
        if choice == 1:
            return f"lighting {round(magnitude * 100)}% {'darker' if darker else 'brighter'}"
        return f"light intensity x{1 + delta:.2f}"
    modifier = "slightly " if magnitude < 0.2 else "much " if magnitude >= 0.35 else ""
    word = str(rng.choice(["darker", "dimmer"])) if darker else "brighter"
    templates = [
        f"{modifier}{word} lighting",
        f"the lighting is {modifier}{word} than usual",
        f"lights {modifier}{word}",
    ]
    return str(rng.choice(templates))


def camera_phrases(camera: CameraOffset, style: str, bounds: SceneBounds | None = None) -> list[str]:
    """The camera change as short phrases (rounded to cm and degrees, kept within the bounds)."""
    if camera.is_default:
        return []
    bounds = bounds or SceneBounds()
    cm = [round(v * 100) for v in camera.translation_m]
    deg = [round(v) for v in camera.rotation_deg]
    while math.hypot(*cm) > bounds.camera_max_translation_m * 100 + 1e-9:
        k = max(range(3), key=lambda i: abs(cm[i]))
        cm[k] -= 1 if cm[k] > 0 else -1  # rounding up must not leave the bound
    deg = [max(-int(bounds.camera_max_rotation_deg), min(int(bounds.camera_max_rotation_deg), d)) for d in deg]
    if not any(cm) and not any(deg):
        k = int(np.argmax(np.abs(camera.translation_m)))
        cm[k] = 1 if camera.translation_m[k] > 0 else -1
    moves: list[str] = []
    for axis, (pos, neg) in enumerate((("forward", "back"), ("left", "right"), ("up", "down"))):
        if cm[axis]:
            moves.append(f"{abs(cm[axis])} cm {pos if cm[axis] > 0 else neg}")
    turns: list[str] = []
    verbs = (("rolled", "counterclockwise", "clockwise"), ("tilted", "down", "up"), ("panned", "left", "right"))
    for axis, (verb, pos, neg) in enumerate(verbs):
        if deg[axis]:
            unit = "degree" if abs(deg[axis]) == 1 else "degrees"
            turns.append(f"{verb} {abs(deg[axis])} {unit} {pos if deg[axis] > 0 else neg}")
    if style == "commands":
        out = [f"MOVE CAMERA {m}" for m in moves]
        out += [f"ROTATE CAMERA {t.split(' ', 1)[1]}" if not t.startswith("rolled") else f"ROLL CAMERA {t.split(' ', 1)[1]}" for t in turns]
        return out
    phrases = []
    if moves:
        phrases.append("camera moved " + " and ".join(moves))
    if turns:
        phrases.append(("camera " if not moves else "") + ", ".join(turns))
    return phrases


# -- styles ----------------------------------------------------------------------------


def _object_phrase(item: _Item) -> str:
    article = "an" if item.name[0] in "aeiou" else "a"
    return _m(f"{article} {item.name}", "OBJ") + (f" {_where_mark(item.where)}" if item.where else "")


def _where_mark(where: str) -> str:
    """A position phrase, marked: "at (0.1, 0.2)" marks the coordinates, words mark whole."""
    if where.startswith("at ("):
        return "at " + _m(where[3:], "POS")
    return _m(where, "POS")


def _structured(items: list[_Item], randoms: int, env: list[str], set_word: str, rng: np.random.Generator) -> str:
    n = len(items)
    named = [i for i in items if i.named]
    parts = [_m(f"{_count(n, rng)} {set_word}{_plural(n, 'object')}", "TOTAL")]
    if rng.random() < 0.5:
        parts += [f"one is {_object_phrase(i)}" for i in named]
    else:
        parts.append("including " + ", ".join(_object_phrase(i) for i in named))
    env_text = ", ".join(env) if env else "default lighting and camera"
    return f"Number and details of objects: {', '.join(parts)}. Environmental setup: {env_text}."


def _prose(items: list[_Item], randoms: int, env: list[str], set_word: str, rng: np.random.Generator) -> str:
    n = len(items)
    named = [_object_phrase(i) for i in items if i.named]
    if randoms:
        named.append(_m(f"{_count(randoms, rng)} other {set_word}{_plural(randoms, 'object')}", "ANY"))
    listing = named[0] if len(named) == 1 else ", ".join(named[:-1]) + " and " + named[-1]
    opener = str(rng.choice(["On the table there are", "The scene holds", "Place", "A table with"]))
    if n == 1:
        opener = str(rng.choice(["On the table there is", "The scene holds", "A table with"]))
        text = f"{opener} {listing}."
    else:
        total = _m(f"{_count(n, rng)} {set_word}{_plural(n, 'object')}", "TOTAL")
        text = f"{opener} {total}: {listing}."
    if env:
        first = ", ".join(env)
        text += " " + (_capitalised(first) if first.startswith("[[") else first[0].upper() + first[1:]) + "."
    return text


def _capitalised(marked: str) -> str:
    return marked[:2] + marked[2].upper() + marked[3:]


def _terse(items: list[_Item], randoms: int, env: list[str], set_word: str, rng: np.random.Generator) -> str:
    n = len(items)
    parts = [_m(i.name, "OBJ") + _terse_where(i.where) for i in items if i.named]
    if randoms:
        parts.append(_m(f"{randoms} random", "ANY"))
    text = _m(f"{n} {set_word}{_plural(n, 'object')}", "TOTAL") + ": " + ", ".join(parts)
    if env:
        text += "; " + "; ".join(env)
    return text


def _terse_where(where: str | None) -> str:
    if not where:
        return ""
    where = where.removeprefix("at ").removeprefix("on the ")
    return f" {_m(where, 'POS')}" if where.startswith("(") else f" ({_m(where, 'POS')})"


def _commands(items: list[_Item], randoms: int, env: list[str], set_word: str, rng: np.random.Generator) -> str:
    lines = []
    for i in items:
        if i.named:
            lines.append(f"ADD {_m(i.name, 'OBJ')}" + (f" to {_m(i.where, 'POS')}" if i.where else ""))
    lines += [f"ADD {_m(f'random {set_word}object', 'ANY')}"] * randoms
    lines += env
    return "\n".join(lines)


def _list(items: list[_Item], randoms: int, env: list[str], set_word: str, rng: np.random.Generator) -> str:
    lines = ["Objects:"]
    lines += [f"- {_m(i.name, 'OBJ')}" + (f", {_where_mark(i.where)}" if i.where else "") for i in items if i.named]
    if randoms:
        lines.append("- " + _m(f"{randoms} random {set_word}{_plural(randoms, 'object')}", "ANY"))
    lighting = [e for e in env if "light" in e]
    camera = [e for e in env if "camera" in e or e.lstrip("[").startswith(("tilted", "panned", "rolled"))]
    lines.append("Lighting: " + (lighting[0] if lighting else "default"))
    lines.append("Camera: " + (", ".join(camera) if camera else "default"))
    return "\n".join(lines)


_WRITERS = {
    "structured": _structured, "prose": _prose, "terse": _terse, "commands": _commands, "list": _list,
}


def write_scene(
    task: str,
    num_objects: int,
    object_set: str,
    environment: str,
    seed: int,
    catalog: Catalog,
    bounds: SceneBounds | None = None,
    style: str | None = None,
    annotate: bool = False,
) -> WrittenScene:
    """A description and basic instruction for one scene of the design; with ``annotate``, also the
    description in the reader's markup (the same text once the markup is taken out)."""
    global _ANNOTATE
    if annotate:
        plain = write_scene(task, num_objects, object_set, environment, seed, catalog, bounds, style)
        _ANNOTATE = True
        try:
            marked = write_scene(task, num_objects, object_set, environment, seed, catalog, bounds, style)
        finally:
            _ANNOTATE = False
        return WrittenScene(plain.description, plain.instruction, plain.style, marked.description)
    bounds = bounds or SceneBounds()
    rng = np.random.default_rng(seed)
    spec = sample_scene(
        task, num_objects, as_object_set(object_set), rng, catalog, bounds,
        environment=environment, seed=seed, min_gap_m=_WRITER_GAP_M,
    )
    style = style or str(STYLES[int(rng.integers(len(STYLES)))])
    items: list[_Item] = []
    pinned: list[tuple[float, float, float]] = []
    for p in spec.objects:
        obj = catalog.get(p.id)
        named = p.role != "distractor" or rng.random() < 0.6
        where = _where(p, style, rng, bounds) if named else None
        if where is not None and "(" in where:
            # The compiler draws a new yaw: coordinates are safe only if the objects'
            # covering circles keep the gap whatever the yaws.
            r = obj.footprint_radius_m + _WRITER_GAP_M / 2
            if any(math.hypot(p.x - x, p.y - y) < r + rr for x, y, rr in pinned):
                where = None
            else:
                pinned.append((p.x, p.y, r))
        items.append(_Item(obj, p, _name(obj, rng), named, where))
    # Task objects first, as people tend to write them.
    items.sort(key=lambda i: {"source": 0, "target": 1}.get(i.placement.role, 2))
    randoms = sum(1 for i in items if not i.named)
    env: list[str] = []
    light = lighting_phrase(spec.lighting.intensity_delta, style, rng)
    if light:
        env.append(_m(light, "LIGHT"))
    env += [_m(c, "CAM") for c in camera_phrases(spec.camera, style, bounds)]
    set_word = ""
    if object_set == "ycb" and rng.random() < 0.7:
        set_word = "YCB "
    elif object_set == "simpler" and rng.random() < 0.2:
        set_word = "SimplerEnv "
    if style == "commands":
        set_word = set_word.strip() + " " if set_word else ""
    description = _WRITERS[style](items, randoms, env, set_word, rng)
    src = spec.source
    tgt = spec.target
    instruction = basic_instruction(
        task, catalog.get(src.id).display_name, catalog.get(tgt.id).display_name if tgt else None
    )
    return WrittenScene(description=description, instruction=instruction, style=style)

