"""Lighting and camera clauses -> set_lighting / move_camera operations.

Lighting: words ("slightly darker", "much brighter", "dim"), signed deltas
("-0.2"), percentages ("20% dimmer", "lights at 120%"), factors ("x1.3"),
"by half". Camera: moves and rotations in numbers ("3 cm left", "rotate 4
degrees down", "yaw +3 deg", "+2 cm in y", tuples) or words ("slightly
higher"); "random"/"altered" asks for a random change; silence or "default"
keeps the default.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from ladev_lib.language.scene.words import NUM, length_scale

LIGHT_WORDS = re.compile(
    r"\b(?:light|lights|lighting|lit|illumination|illuminated|brightness|lamp|lamps|exposure|"
    r"brighter|darker|dimmer|dimmed|dim|dimly|darken|darkened|brighten|brightened|luminosity|as bright|"
    r"set lighting|set_lighting)\b"
)
CAMERA_WORDS = re.compile(
    r"\b(?:camera|cam|view|viewpoint|viewing angle|perspective|pov|lens|move_camera|"
    r"dolly|dollied|dollies|truck|trucked|crane|craned|zoom|zoomed)\b"
)
"""Words that name the camera, and motions only a camera makes ("dolly in 2 cm")."""
MOTION = re.compile(
    rf"(?:{NUM}\s*(?:cm|mm|m|centimet(?:er|re)s?|millimet(?:er|re)s?|met(?:er|re)s?|inch(?:es)?|deg|degrees?)\b)|"
    r"\b(?:tilt(?:ed|s)?|pan(?:ned|s)?|rotat(?:e|ed|es|ion)|roll(?:ed|s)?|yaw(?:ed)?|pitch(?:ed)?|"
    r"turn(?:ed|s)?|shift(?:ed|s)?|mov(?:e|ed|es)|rais(?:e|ed)|lower(?:ed)?|translat\w*|dolly|dollied)\b|"
    rf"\b(?:dx|dy|dz|x|y|z)\s*[:=]?\s*{NUM}"
)
DEFAULT_WORDS = re.compile(
    r"\b(?:default|normal|unchanged|standard|regular|usual|no change|no changes|as is|original|untouched|nominal)\b"
)
RANDOM_WORDS = re.compile(r"\b(?:random|randomly|randomized|arbitrary|perturbed|altered|different|varied|changed|jittered)\b")

DARKER = re.compile(
    r"\b(?:darker|dimmer|dim|dimmed|dimly|dark|darken|darkened|lower|lowered|reduce|reduced|decrease|"
    r"decreased|less|weaker|fainter|gloomy|gloomier|low|shadowy|minus|down|cut|lessen|below|under|drop|dropped)\b|-\s*$"
)
BRIGHTER = re.compile(
    r"\b(?:brighter|bright|brightly|brighten|brightened|increase|increased|raise|raised|more|stronger|"
    r"intense|higher|boost|boosted|well lit|harsh|harsher|vivid|plus|up|stronger|high)\b"
)
SLIGHT = re.compile(
    r"\b(?:slightly|slight|a bit|a little|a tad|somewhat|marginally|mildly|a touch|subtly|little|"
    r"small|bit|touch|barely|gently|faintly)\b"
)
STRONG = re.compile(
    r"\b(?:much|a lot|significantly|considerably|far|very|strongly|greatly|way|substantially|heavily|"
    r"really|extremely|dramatically|noticeably much|lot|large|big|drastically|very much)\b"
)
MAXIMAL = re.compile(r"\b(?:maximum|maximally|max|as (?:bright|dark|dim) as possible|fully)\b")


def read_lighting(clause: str) -> dict[str, Any] | None:
    """A set_lighting operation from a lighting clause; None for default lighting."""
    text = f" {clause} "
    factor = re.search(rf"(?:\bx|×|\btimes)\s*({NUM})|({NUM})\s*(?:x\b|×|times\b)", text)
    if factor is not None:
        value = float(factor.group(1) or factor.group(2))
        return {"op": "set_lighting", "intensity_delta": round(value - 1.0, 4)}
    text = re.sub(rf"({NUM})\s*(?:percent|per cent|pct)\b", r"\1%", text)
    # "3/10 dimmer": a fraction is a share
    text = re.sub(r"(?<![\d.])(\d+)\s*/\s*(\d+)(?![\d.])", lambda m: f" {100 * int(m.group(1)) / max(int(m.group(2)), 1):g}% ", text)
    text = re.sub(r"\b(\d) quarters\b", lambda m: f" {int(m.group(1)) * 25}% ", text)
    text = re.sub(r"\b(\d) tenths?\b", lambda m: f" {int(m.group(1)) * 10}% ", text)
    text = re.sub(r"\b(\d) fifths?\b", lambda m: f" {int(m.group(1)) * 20}% ", text)
    # "three quarters of what it is now": a level of the current lighting
    text = re.sub(r"\bof (?:what it is now|what it is|the current(?: level| lighting| light)?|current|now)\b", " of normal ", text)
    text = re.sub(r"\b(\d) thirds\b", lambda m: f" {round(int(m.group(1)) * 100 / 3)}% ", text)
    text = re.sub(r"\b(?:a )?tenth\b", " 10% ", text)
    # "at 60% of default", "dim to 40% of normal", "85% brightness": a level, not a change
    level = re.search(
        rf"({NUM})\s*%\s*(?:of\s+(?:the\s+)?(?:default|normal|usual|full|original|standard|regular)|brightness|intensity)"
        rf"|\b(?:at|to)\s+(?:about\s+|around\s+)?({NUM})\s*%",
        text,
    )
    if level is not None:
        value = float(level.group(1) or level.group(2))
        return {"op": "set_lighting", "intensity_delta": round(value / 100 - 1.0, 4)}
    text = re.sub(r"\b(?:a )?quarter\b", " 25% ", text)
    text = re.sub(r"\b(?:a )?fifth\b", " 20% ", text)
    text = re.sub(r"\b(?:a )?third\b", " 33% ", text)
    if re.search(r"\bhalf as (?:bright|light|strong|intense)\b|\bhalve(?:d)?\s+(?:the\s+)?(?:brightness|light|lights|lighting|it)\b", text):
        return {"op": "set_lighting", "intensity_delta": -0.5}
    if re.search(r"\b(?:twice|double) as (?:bright|light|strong|intense)\b|\bdoubled?\b", text):
        return {"op": "set_lighting", "intensity_delta": 1.0}
    text = re.sub(r"\b(?:by )?half\b|\bhalved\b", " 50% ", text)
    nums = [m for m in re.finditer(rf"(?<![\w.@]){NUM}(?:\s*(%))?", text)]
    darker, brighter = DARKER.search(text), BRIGHTER.search(text)
    sign = -1.0 if darker and not brighter else 1.0 if brighter and not darker else 0.0
    if darker and brighter:
        sign = -1.0 if darker.start() < brighter.start() else 1.0
    if nums:
        m = nums[0]
        raw = m.group(0)
        number = re.match(NUM, raw.strip())
        if number is None:  # the pattern that found ``raw`` starts with a number; kept for the type
            raise ValueError(f"no number at the start of {raw!r}")
        value = float(number.group(0))
        suffix = m.group(1)
        explicit_sign = raw.strip()[0] in "+-"
        if suffix == "%":
            if sign == 0.0 and re.search(r"\b(?:at|of|to)\s*$", text[: m.start()]):
                delta = value / 100 - 1.0
            else:
                delta = (sign or 1.0) * abs(value) / 100 if not explicit_sign else value / 100
        elif explicit_sign:
            delta = value
        elif sign != 0.0:
            delta = sign * abs(value)
        elif 0.5 <= value <= 2.0:
            delta = value - 1.0  # an absolute intensity factor: "intensity 0.8"
        else:
            delta = value
        return {"op": "set_lighting", "intensity_delta": round(delta, 4)}
    if sign == 0.0:
        if RANDOM_WORDS.search(text):
            return {"op": "set_lighting", "random": True}
        return None  # "default lighting" and the like: no operation
    if MAXIMAL.search(text):
        magnitude = 0.5
    elif STRONG.search(text):
        magnitude = 0.4
    elif SLIGHT.search(text):
        magnitude = 0.15
    else:
        magnitude = 0.25
    return {"op": "set_lighting", "intensity_delta": sign * magnitude}


def read_camera(clause: str, slots: Mapping[str, tuple[float, ...]]) -> dict[str, Any] | None:
    """A move_camera operation from a camera clause; None for the default camera."""
    text = f" {clause} "
    translation = [0.0, 0.0, 0.0]
    rotation = [0.0, 0.0, 0.0]
    moved = False
    for key in re.findall(r"@v\d+@", text):
        values = slots[key]
        is_rotation = bool(re.search(r"\b(?:rotat\w*|deg\w*|orientation|angles?)\b", text))
        if is_rotation:
            rotation = [a + b for a, b in zip(rotation, values, strict=True)]
        else:
            scale = 0.01 if re.search(r"\bcm\b", text) or any(abs(v) > 0.5 for v in values) else 1.0
            # "translate_cm = [0, 2, 0]": [x right, y forward, z up] in the camera's own frame, as the
            # axis keys are read; the spec's frame is x forward, y left, z up
            x, y, z = values
            translation = [a + b * scale for a, b in zip(translation, (y, -x, z), strict=True)]
        moved = True
        text = text.replace(key, " ")
    parts: list[str] = []
    for part in re.split(r"\band\b|,|\bthen\b|\bbut\b|\bwhile\b|\bwhilst\b|\s\+\s", text):
        if parts and re.fullmatch(rf"\s*(?:by\s+|about\s+)?{NUM}\s*(?:cm|mm|m|deg|degrees?)\s*", part):
            parts[-1] += f" {part}"  # "tilt it slightly downward, 2 degrees": the amount of the motion before
        else:
            parts.append(part)
    valued = re.search(rf"\b(?:yaw|pitch|roll|dx|dy|dz|x|y|z)\s*[:=]?\s*{NUM}", text) is not None
    for part in parts:
        if valued and not re.search(r"\d", part):
            continue  # "rotate the camera: pitch +5, yaw -5": the verb only introduces the values
        if re.search(r"\b(?:dont|do not|not|never|without|no)\s+(?:\w+\s+)?(?:rotat|tilt|pan|roll|yaw|pitch|turn|mov|shift|translat)", part):
            continue  # "don't rotate it"
        if re.search(r"[:=]\s*(?:none|null|no|0|false|unchanged|default)\s*$", part.strip()):
            continue  # "camera.rotate = none"
        t, r, ok = camera_motion(part)
        if ok:
            translation = [a + b for a, b in zip(translation, t, strict=True)]
            rotation = [a + b for a, b in zip(rotation, r, strict=True)]
            moved = True
    if moved:
        return {
            "op": "move_camera",
            "translation_m": [round(v, 4) for v in translation],
            "rotation_deg": [round(v, 2) for v in rotation],
        }
    if RANDOM_WORDS.search(text) and not DEFAULT_WORDS.search(text):
        return {"op": "move_camera", "random": True}
    return None

def camera_motion(part: str) -> tuple[list[float], list[float], bool]:
    translation = [0.0, 0.0, 0.0]
    rotation = [0.0, 0.0, 0.0]
    strength = 2.0 if SLIGHT.search(part) else 5.0 if STRONG.search(part) else 3.0
    found = False
    # Signed axis values: "x+0.02", "dy = -3 cm", "yaw -2", "pitch: 3 deg".
    # Signed axis values are in the camera's own frame, as camera operators write them:
    # x right, y forward (toward the table), z up; yaw + pans right, pitch + tilts up,
    # roll + turns clockwise seen from behind. The spec's frame is the workspace's
    # (x away from the robot, y to its left; yaw + pans left, pitch + tilts down).
    cm_default = re.search(r"\(\s*cm\s*\)|\bin cm\b|\bcm\b", part) is not None
    worded = re.search(
        r"\b(?:left|right|up|upward|down|downward|clockwise|counterclockwise|counter clockwise|anticlockwise)\b", part
    )
    axis_first = list(re.finditer(
        rf"\b(dx|dy|dz|x|y|z|roll|pitch|yaw)\s*[:=]?\s*({NUM})\s*(cm|mm|m|deg|degrees?)?(?![\w.])", part
    ))
    rest = part
    for m in reversed(axis_first):
        rest = rest[: m.start()] + " " * (m.end() - m.start()) + rest[m.end():]
    # "+2cm z", "-5 deg yaw": the value before its axis
    value_first = re.finditer(
        rf"({NUM})\s*(cm|mm|m|deg|degrees?)?\s+(dx|dy|dz|x|y|z|roll|pitch|yaw)\b(?!\s*[:=]?\s*[-+]?\d)", rest
    )
    said = [(m.group(1), m.group(2), m.group(3)) for m in axis_first]
    said += [(m.group(3), m.group(1), m.group(2)) for m in value_first]
    for axis, value_text, unit in said:
        value = float(value_text)
        if axis in ("roll", "pitch", "yaw") and worded is not None and value >= 0:
            continue  # "roll 3 degrees counterclockwise": the words give the sense
        if axis in ("roll", "pitch", "yaw"):
            rotation[("roll", "pitch", "yaw").index(axis)] -= value
        else:
            scale = length_scale(unit) if unit else 0.01 if cm_default or abs(value) > 0.5 else 1.0
            frame_axis, sign = {"x": (1, -1.0), "y": (0, 1.0), "z": (2, 1.0)}[axis[-1]]
            translation[frame_axis] += sign * value * scale
        found = True
    for m in re.finditer(
        rf"({NUM})\s*(cm|mm|m)?\s*(?:in|along|on)\s+(?:the\s+)?(x|y|z)(?:\s*(?:axis|direction))?\b", part
    ):
        value, unit, axis = float(m.group(1)), m.group(2), m.group(3)
        scale = length_scale(unit) if unit else (0.01 if abs(value) > 0.5 else 1.0)
        frame_axis, sign = {"x": (1, -1.0), "y": (0, 1.0), "z": (2, 1.0)}[axis]
        translation[frame_axis] += sign * value * scale
        found = True
    if found:
        return translation, rotation, True
    dist = re.search(
        rf"({NUM})\s*(cm|mm|m|centimet(?:er|re)s?|millimet(?:er|re)s?|met(?:er|re)s?|inch(?:es)?)\b", part
    )
    angle = re.search(rf"({NUM})\s*(?:deg|degrees?)\b", part)
    rotate_verb = re.search(r"\b(tilt\w*|pan\w*|rotat\w*|roll\w*|yaw\w*|pitch\w*|turn\w*|angled)\b", part)
    direction = re.search(
        r"\b(left|right|up|upward|upwards|down|downward|downwards|forward|forwards|closer|nearer|toward|towards|"
        r"backward|backwards|back|away|farther|further|higher|lower|raised|lowered|in|out|"
        r"clockwise|counterclockwise|counter clockwise|anticlockwise|anti clockwise)\b",
        part,
    )
    dir_word = direction.group(1) if direction else None
    if angle is not None or (rotate_verb is not None and dist is None):
        value = float(angle.group(1)) if angle is not None else strength
        verb = rotate_verb.group(1) if rotate_verb is not None else ""
        if angle is None and dir_word is None and not verb:
            return translation, rotation, False
        if verb.startswith("roll") or dir_word in (
            "clockwise", "counterclockwise", "counter clockwise", "anticlockwise", "anti clockwise"
        ):
            sign = -1.0 if dir_word == "clockwise" or dir_word == "right" else 1.0
            rotation[0] += sign * value
        elif dir_word in ("up", "upward", "upwards", "higher", "raised") or (
            verb.startswith(("tilt", "pitch")) and dir_word not in ("down", "downward", "downwards", "lower", "lowered")
            and dir_word is not None
        ):
            rotation[1] -= value
        elif dir_word in ("down", "downward", "downwards", "lower", "lowered") or verb.startswith(("tilt", "pitch")):
            rotation[1] += value
        elif dir_word == "right":
            rotation[2] -= value
        else:  # left, or a pan / yaw / turn without a direction
            rotation[2] += value
        return translation, rotation, True
    move_verb = re.search(
        r"\b(mov\w*|shift\w*|translat\w*|slid\w*|displac\w*|rais\w*|lower\w*|offset|push\w*|pull\w*|nudg\w*|"
        r"lift\w*|elevat\w*|dolly|dollie\w*|crane\w*|boom\w*|truck\w*)\b",
        part,
    )
    if move_verb is not None and dir_word is None:
        # verbs that carry their direction: "lifted 5 cm", "dolly 2 cm" (in, toward the table)
        verb = move_verb.group(1)
        dir_word = "up" if verb.startswith(("lift", "elevat", "rais")) else "forward" if verb.startswith("dolly") else None
    comparative = dir_word in ("higher", "lower", "closer", "nearer", "farther", "further", "raised", "lowered")
    if dist is None and ((move_verb is None and not comparative) or dir_word is None):
        return translation, rotation, False
    value = float(dist.group(1)) * length_scale(dist.group(2)) if dist is not None else strength / 100
    if dir_word is None:
        dir_word = "left"  # a move without a direction: sideways, as the most common case
    axis, sign = {
        "left": (1, 1.0), "right": (1, -1.0), "up": (2, 1.0), "upward": (2, 1.0), "upwards": (2, 1.0),
        "higher": (2, 1.0), "raised": (2, 1.0), "down": (2, -1.0), "downward": (2, -1.0),
        "downwards": (2, -1.0), "lower": (2, -1.0), "lowered": (2, -1.0), "forward": (0, 1.0),
        "forwards": (0, 1.0), "closer": (0, 1.0), "nearer": (0, 1.0), "in": (0, 1.0), "toward": (0, 1.0), "towards": (0, 1.0), "backward": (0, -1.0),
        "backwards": (0, -1.0), "back": (0, -1.0), "away": (0, -1.0), "farther": (0, -1.0),
        "further": (0, -1.0), "out": (0, -1.0),
    }.get(dir_word, (1, 1.0))
    if move_verb is not None and move_verb.group(1).startswith("rais"):
        axis, sign = 2, 1.0
    elif move_verb is not None and move_verb.group(1).startswith("lower") and dir_word in (None, "left"):
        axis, sign = 2, -1.0
    translation[axis] += sign * abs(value)
    return translation, rotation, True


def merge_camera(moves: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """All camera moves of a description as one operation (a random one stays apart)."""
    if not moves:
        return []
    if any(m.get("random") for m in moves):
        return [{"op": "move_camera", "random": True}]
    t = [round(sum(m["translation_m"][k] for m in moves), 4) for k in range(3)]
    r = [round(sum(m["rotation_deg"][k] for m in moves), 2) for k in range(3)]
    return [{"op": "move_camera", "translation_m": t, "rotation_deg": r}]
