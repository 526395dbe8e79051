"""Lighting and camera requests read from the words that state them (and only those).

The tagged reader hands these functions the words of the lighting or camera
request that still hold after the writer's corrections ("camera: pan left" +
"4 degrees"). Each motion is a direction or axis with an amount:

- camera, in the camera's own frame as people say it: right / left,
  forward (closer, dolly in) / back (pull back), up (raise) / down (lower);
  pan or yaw right / left, tilt or pitch up / down, roll clockwise /
  counter-clockwise; axis keys with signed values (``x: -1``, ``yaw: +3``,
  ``z_cm: 1.5``, ``dz -4cm``); millimetres, centimetres, metres, degrees;
- lighting: a relative change (direction and amount: "20% darker", "down a
  fifth", "-0.2", "by a third") or a level ("at 70% of normal", "x0.8",
  "1.25x", "half as bright", "twice as bright").

They return operations in the scene spec's frame (x forward, y left, z up;
yaw + pans left, pitch + tilts down, roll + is counter-clockwise seen from
behind), or None when the words state no amount the parser can read (the
caller then asks the rule reader, which knows the worded defaults).
"""

from __future__ import annotations

import re
from typing import Any

_NUMBER_WORDS = {
    "zero": 0, "half": 0.5, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
    "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "fifteen": 15, "twenty": 20, "thirty": 30, "forty": 40,
    "fifty": 50, "sixty": 60, "seventy": 70, "eighty": 80, "ninety": 90, "hundred": 100,
}
_FRACTIONS = {
    "a half": 0.5, "half": 0.5, "a third": 1 / 3, "one third": 1 / 3, "a quarter": 0.25, "one quarter": 0.25,
    "quarter": 0.25, "a fifth": 0.2, "one fifth": 0.2, "fifth": 0.2, "a tenth": 0.1, "one tenth": 0.1, "tenth": 0.1,
    "third": 1 / 3, "two thirds": 2 / 3, "three quarters": 0.75,
}
_NUM = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"


def _clean(text: str) -> str:
    t = text.lower()
    for a, b in (("−", "-"), ("–", "-"), ("—", " - "), ("°", " deg "), ("º", " deg "), ("×", " x "), ("’", "'")):
        t = t.replace(a, b)
    t = re.sub(r"[\"{}\[\]()]", " ", t)
    t = re.sub(r"\bpercents?\b|\bper cent\b|\bpct\b", "%", t)
    t = re.sub(r"\b(twenty|thirty|forty|fifty|sixty|seventy|eighty|ninety)[\s-]+(one|two|three|four|five|six|seven|eight|nine)\b",
               lambda m: str(_NUMBER_WORDS[m.group(1)] + _NUMBER_WORDS[m.group(2)]), t)
    t = re.sub(r"\bhalf an? (?=cm|centimet|mm|millimet|deg|inch)", "0.5 ", t)
    t = re.sub(r"\b(?:a|an|one)\s+(?=(?:cm|centimet\w*|mm|millimet\w*|degree|deg|inch)\b)", "1 ", t)  # "by a centimeter"
    t = re.sub(r"\ba couple(?: of)?\s+(?=(?:cm|centimet\w*|mm|millimet\w*|degrees?|deg)\b)", "2 ", t)  # "a couple of degrees"
    t = re.sub(r"\b(" + "|".join(sorted(_NUMBER_WORDS, key=len, reverse=True)) + r")\b(?!\s+(?:of|as)\b)",
               lambda m: str(_NUMBER_WORDS[m.group(1)]), t)
    t = re.sub(r"(\d),(\d)", r"\1.\2", t)  # "1,5 cm"
    return re.sub(r"[ \t]+", " ", t).strip()


# -- camera --------------------------------------------------------------------------

_TRANSLATE = [  # (pattern, axis, sign) in the description frame: x right, y forward, z up
    (r"\b(?:to the right|rightwards?|right)\b", 0, 1),
    (r"\b(?:to the left|leftwards?|left)\b", 0, -1),
    (r"\b(?:forwards?|ahead|closer|nearer|close to (?:the )?table|toward(?:s)? (?:the )?table|towards? (?:the )?scene|in(?:wards?)?|push(?:ed)? in|dolly(?:ing|ied)? in|zoom(?:ed)? in)\b", 1, 1),
    (r"\b(?:backwards?|backs? off|backs|backing off|back|further|farther|away from (?:the )?table|away|out(?:wards?)?|pull(?:ed|s)? back|dolly(?:ing|ied)? out|zoom(?:ed)? out|retreat)\b", 1, -1),
    (r"\b(?:up(?:wards?)?|higher|raise[ds]?|rais(?:ing)|lift(?:ed|s)?|elevate[ds]?|above|boom up|crane up)\b", 2, 1),
    (r"\b(?:down(?:wards?)?|lower(?:ed|s)?|drop(?:ped|s)?|descend(?:ed|s)?|below|sink|sunk)\b", 2, -1),
]
_AXIS_KEYS = {"x": 0, "dx": 0, "y": 1, "dy": 1, "z": 2, "dz": 2}
_ROTATION_VERBS = r"pan(?:ned|s|ning)?|yaw(?:ed|s|ing)?|tilt(?:ed|s|ing)?|pitch(?:ed|es|ing)?|roll(?:ed|s|ing)?|rotat\w*|turn(?:ed|s|ing)?|swing|swung|swivel\w*|spin|spun|twist\w*"


def _rotation_axis(part: str) -> tuple[int, int] | None:
    """(axis, sign) of a rotation in the description frame: 0 yaw (+ right), 1 pitch (+ up), 2 roll (+ clockwise)."""
    cw = re.search(r"\b(?:counter[\s-]?clockwise|anti[\s-]?clockwise|ccw)\b", part)
    if re.search(r"\broll", part) or cw or re.search(r"\bclockwise|\bcw\b", part):
        if cw:
            return 2, -1
        if re.search(r"\bclockwise|\bcw\b|\bright\b", part):
            return 2, 1
        if re.search(r"\bleft\b", part):
            return 2, -1
        return 2, 1
    if re.search(r"\b(?:tilt|pitch)", part):
        if re.search(r"\b(?:down(?:wards?)?|lower)\b", part):
            return 1, -1
        return 1, 1
    if re.search(r"\b(?:pan|yaw)", part) or re.search(rf"\b(?:{_ROTATION_VERBS})\b", part):
        if re.search(r"\b(?:down(?:wards?)?)\b", part):
            return 1, -1
        if re.search(r"\b(?:up(?:wards?)?)\b", part) and not re.search(r"\b(?:pan|yaw)", part):
            return 1, 1
        if re.search(r"\bleft\b", part):
            return 0, -1
        return 0, 1
    return None


def _amount(part: str) -> tuple[float, str | None] | None:
    """The first signed amount of a motion and its unit (cm, deg or None)."""
    m = re.search(rf"({_NUM})\s*(mm|millimet(?:er|re)s?|cm|centimet(?:er|re)s?|m\b|met(?:er|re)s?|inch(?:es)?|\"|deg(?:rees?)?|d\b)?", part)
    if m is None:
        return None
    value = float(m.group(1))
    unit = m.group(2) or ""
    if unit.startswith(("mm", "milli")):
        return value / 10, "cm"
    if unit.startswith(("cm", "centi")):
        return value, "cm"
    if unit == "m" or unit.startswith("met"):
        return value * 100, "cm"
    if unit.startswith("inch") or unit == '"':
        return value * 2.54, "cm"
    if unit.startswith("d"):
        return value, "deg"
    return value, None


def _has_cue(part: str) -> bool:
    """Whether a piece of a request says a direction or an axis (not only an amount)."""
    return bool(
        re.search(r"\b[xyz]\b", part) or _rotation_axis(part) is not None
        or any(re.search(pattern, part) for pattern, _, _ in _TRANSLATE)
    )


def _motions(text: str) -> list[str]:
    text = re.sub(r"\s+(?=(?:dx|dy|dz|x|y|z|yaw|pitch|roll|pan|tilt)\s*[:=]?\s*[-+]?\d)", ", ", text)
    parts = [p for p in re.split(r"\s*(?:,|;|\band\b|\bthen\b|\bwhile\b|\bplus\b|\s\+\s|\n|\.\s)\s*", text) if p.strip()]
    out: list[str] = []
    for p in parts:
        has_number = re.search(r"\d", p) is not None
        has_cue = _has_cue(p)
        if out and has_number and not has_cue:
            out[-1] += f" {p}"  # "pan left, 4 degrees": the amount of the motion before
        elif out and not has_number and not re.search(r"\d", out[-1]) and not re.search(rf"\b(?:{_ROTATION_VERBS})\b", p):
            out[-1] += f" {p}"  # "pull back, further": still one motion without its amount
        else:
            out.append(p)
    return out


def read_camera_request(text: str) -> dict[str, Any] | None:
    """A move_camera operation (spec frame) from the words of a camera request; None without amounts."""
    t = re.sub(r"\b(?:camera|cam)_", " ", _clean(text))
    t = re.sub(r"\bl\b(?!\s*[:=])", "left", re.sub(r"\br\b(?!\s*[:=])", "right", t))  # "pan L 3 deg"
    t = re.sub(r"\b(?:camera|cam|view|viewpoint|the|it|by|about|around|roughly|approximately|of|move|moved|moves|shift|shifted|"
               r"shifts|translate[ds]?|translation|position|rotation|rotate|nudge[ds]?|slightly|a bit|a little|please)\b",
               lambda m: " rotate " if m.group(0).startswith("rotat") else " ", t)
    t = re.sub(r"[ \t]+", " ", t)
    translate = [0.0, 0.0, 0.0]
    rotate = [0.0, 0.0, 0.0]
    read_any = False
    # "translate_cm = 0, -3, 0", "translate_cm": [0, 0, 5]: [x right, y forward, z up]
    vector = re.search(rf"\btranslat\w*?(?:_(cm|mm|m))?\s*[:=]\s*\[?\s*({_NUM})\s*[,;]\s*({_NUM})\s*[,;]\s*({_NUM})", t)
    if vector is not None:
        scale = {"mm": 0.1, "m": 100.0}.get(vector.group(1) or "", 1.0)
        for k in range(3):
            translate[k] += float(vector.group(k + 2)) * scale
        read_any = True
        t = t[: vector.start()] + " " + t[vector.end():]
    # axis keys with signed values: "x: -1", "dz -4cm", "yaw: +3", "z_cm: 1.5", "pitch_deg = 2", "yaw;-4"
    keyed = re.compile(rf"\b(dx|dy|dz|x|y|z|d?yaw|d?pitch|d?roll|pan|tilt|up|down|left|right|forward|back)(?:_(cm|mm|deg))?\s*[:=;]\s*({_NUM})\s*(cm|mm|deg(?:rees?)?)?")
    for m in keyed.finditer(t):
        key, unit = m.group(1), m.group(2) or m.group(4) or ""
        key = key[1:] if key in ("dyaw", "dpitch", "droll") else key
        value = float(m.group(3))
        if unit == "mm":
            value /= 10
        if key in _AXIS_KEYS:
            translate[_AXIS_KEYS[key]] += value
        elif key in ("yaw", "pan"):
            rotate[0] += value
        elif key in ("pitch", "tilt"):
            rotate[1] += value
        elif key == "roll":
            rotate[2] += value
        else:
            axis, sign = next((a, s) for pat, a, s in _TRANSLATE if re.fullmatch(pat, key))
            translate[axis] += sign * value
        read_any = True
    t = keyed.sub(" ", t)
    for part in _motions(t):
        amount = _amount(part)
        if amount is None:
            continue
        value, unit = amount
        # "-3cm x", "+2 cm z", "x -3": a signed value along a named axis
        axis_after = re.search(rf"{_NUM}\s*(?:cm|mm|m)?\s*(?:in |along |on )?(?:the )?\b([xyz])\b(?:[\s-]*axis)?", part)
        axis_before = re.search(rf"\b([xyz])\b(?:[\s-]*axis)?\s*{_NUM}", part)
        if axis_after or axis_before:
            key = (axis_after or axis_before).group(1)  # type: ignore[union-attr]
            translate[_AXIS_KEYS[key]] += value
            read_any = True
            continue
        rot = _rotation_axis(part)
        if rot is not None and unit != "cm":
            axis, sign = rot
            worded = re.search(r"\b(?:left|right|up|down|upwards?|downwards?|clockwise|counter[\s-]?clockwise|anti[\s-]?clockwise|ccw|cw)\b", part)
            # "roll -3 degrees (counter-clockwise)": the word and the sign say one thing; "pan -2": the sign
            rotate[axis] += sign * abs(value) if worded else sign * value
            read_any = True
            continue
        if unit == "deg":
            continue
        found = False
        for pattern, axis, sign in _TRANSLATE:
            if re.search(pattern, part):
                translate[axis] += sign * value
                found = read_any = True
                break
        del found
    if not read_any:
        return None
    if not any(abs(v) > 1e-9 for v in (*translate, *rotate)):
        return {"op": "move_camera", "translation_m": [0.0, 0.0, 0.0], "rotation_deg": [0.0, 0.0, 0.0]}
    x, y, z = translate
    yaw, pitch, roll = rotate
    return {
        "op": "move_camera",
        "translation_m": [round(y / 100, 6), round(-x / 100, 6), round(z / 100, 6)],
        "rotation_deg": [round(-roll, 6) + 0.0, round(-pitch, 6) + 0.0, round(-yaw, 6) + 0.0],
    }


# -- lighting ------------------------------------------------------------------------

_BRIGHTER = re.compile(
    r"\b(?:bright(?!ness)\w*|up|increase[ds]?|increas\w+|rais\w+|boost\w*|more light|stronger|strengthen\w*|higher|"
    r"crank\w*|bump\w*|intensif\w*|plus|more|lighter|turn(?:ed)? up)\b|^\s*\+"
)
_DARKER = re.compile(
    r"\b(?:dark\w*|dim\w*|down|decrease[ds]?|decreas\w+|reduc\w+|lower\w*|less|weaker|cut|drop\w*|minus|"
    r"fainter|gloom\w*|below|under|turn(?:ed)? down|tone(?:d)? down|darken\w*|shad\w*)\b|^\s*-"
)


def read_lighting_request(text: str) -> dict[str, Any] | None:
    """A set_lighting operation from the words of a lighting request; None without an amount."""
    t = _clean(text)
    # levels: "at 70% of normal", "to 40%", "85% brightness", "150 percent of normal"
    level = re.search(
        rf"({_NUM})\s*%\s*(?:of\s+(?:the\s+)?(?:default|normal|usual|full|original|standard|regular|current|nominal|baseline|today|now)\b|"
        rf"(?:brightness|intensity|power)\b)|\b(?:at|to)\s+({_NUM})\s*%",
        t,
    )
    if level is not None:
        value = float(level.group(1) or level.group(2))
        return {"op": "set_lighting", "intensity_delta": round(value / 100 - 1.0, 4)}
    # "down to a quarter of normal brightness", "two thirds of the default"
    part = re.search(
        r"\b(a quarter|one quarter|a third|one third|a fifth|a tenth|half|two thirds|three quarters|(\d+) (?:thirds|quarters|fifths))"
        r"\s+of\s+(?:the\s+)?(?:its\s+)?(?:normal|default|usual|full|original|standard|current|regular|nominal)\b", t
    )
    if part is not None:
        share = _FRACTIONS.get(part.group(1))
        if share is None and part.group(2):
            share = int(part.group(2)) / {"third": 3, "quarter": 4, "fifth": 5}[part.group(1).split()[1].rstrip("s")]
        if share is not None:
            return {"op": "set_lighting", "intensity_delta": round(share - 1.0, 4)}
    factor = re.search(
        rf"(?:\bx\s*|\btimes\s+)({_NUM})\b|({_NUM})\s*(?:x\b|times\b)|\b(?:factor|scale|multiplier|gain)\s*(?:of|to|[:=])?\s*({_NUM})", t
    )
    if factor is not None:
        value = float(factor.group(1) or factor.group(2) or factor.group(3))
        return {"op": "set_lighting", "intensity_delta": round(value - 1.0, 4)}
    if re.search(r"\bhalf as (?:bright|light|strong|intense)\b|\bhalve[ds]?\b|\bhalf (?:the )?(?:brightness|light)\b", t):
        return {"op": "set_lighting", "intensity_delta": -0.5}
    if re.search(r"\b(?:twice|double[ds]?) (?:as )?(?:bright|the (?:brightness|light|lighting))?|\bdoubl(?:e|ed|ing)\b", t):
        return {"op": "set_lighting", "intensity_delta": 1.0}
    amount: float | None = None
    signed = 0
    t = re.sub(r"\b(\d) (third|quarter|fifth|tenth)s?\b",
               lambda m: f"{100 * int(m.group(1)) / {'third': 3, 'quarter': 4, 'fifth': 5, 'tenth': 10}[m.group(2)]:g}%", t)
    pct = re.search(rf"({_NUM})\s*%", t)
    if pct is not None:
        amount = float(pct.group(1)) / 100
        signed = -1 if pct.group(1).startswith("-") else (1 if pct.group(1).startswith("+") else 0)
    else:
        for words, value in sorted(_FRACTIONS.items(), key=lambda kv: -len(kv[0])):
            if re.search(rf"\b{words}\b", t):
                amount = value
                break
        if amount is None:
            dec = re.search(rf"(?<![\w.])({_NUM})(?![\w.%])", t)
            if dec is not None and abs(float(dec.group(1))) <= 100.0:
                value = float(dec.group(1))
                amount = value if abs(value) <= 1.0 else value / 100  # "lights up 70": a percentage
                signed = -1 if dec.group(1).startswith("-") else (1 if dec.group(1).startswith("+") else 0)
    if amount is None:
        return None
    words = re.sub(rf"{_NUM}\s*%?", " ", t)
    dark, bright = _DARKER.search(words), _BRIGHTER.search(words)
    if dark and bright:
        sign = -1 if dark.start() > bright.start() else 1  # "up - no, down": the later word
        if re.search(r"\b(?:more|less)\b", words) and re.search(r"\b(?:dark|dim)\w*|\bbright\w*", words):
            sign = -1 if re.search(r"\bmore (?:dark|dim)|\bless bright", words) else 1
    elif dark:
        sign = -1
    elif bright:
        sign = 1
    elif signed:
        sign = signed
    else:
        return None
    if signed and signed != sign and not (dark and bright):
        sign = signed  # "brightness -10%", "lights: -0.2": the sign said with the number
    return {"op": "set_lighting", "intensity_delta": round(sign * abs(amount), 4)}


__all__ = ["read_camera_request", "read_lighting_request"]
