"""Lighting and camera requests read from the words that state them (and only those).

The tagged reader hands these functions the words of the lighting or camera
request that still hold after the writer's corrections ("camera: pan left" +
"4 degrees"). Each motion is a direction or axis with an amount:

- camera, in the camera's own frame as people say it: right / left,
  forward (closer, dolly in, to the front) / back (pull back, backed off),
  up (raise, higher, ↑) / down (lower, ↓); pan or yaw right / left, tilt or
  pitch up / down, roll clockwise / counter-clockwise (or about the optical
  axis); a degree amount with only up / down or left / right is a tilt or a
  pan ("2° down"); axis keys, flags and columns with signed values (``x: -1``,
  ``yaw: +3``, ``z_cm: 1.5``, ``dz -4cm``, ``Δy = −25 mm``, ``--cam-dx -0.5``,
  ``height -1 cm``, ``lift_cm: 0.5``), value-first axes (``-1 cm x``) and
  translation tuples (``translate (0, -2, 1.5)``); millimetres, centimetres,
  metres, degrees; amounts in digits, words ("one point five", "a centimetre
  and a half", "a quarter degree") and fractions;
- lighting: a relative change (direction and amount: "20% darker", "down a
  fifth", "-0.2", "by a third", "↓ 10%", "1/4 brighter", "kill a tenth") or a
  level or factor, which is a change of level - 1 ("at 70% of normal",
  "brightness 110%", "light 80%", "to three quarters", "0.9 of before", "x0.8",
  "1.25x", "x½", "light = 0.9", "half as bright", "three quarters as bright",
  "one and a half times as bright").

A later word that only restates the direction of a motion said before
("pan right 4°, sorry, left"; "4 cm higher — I mean lower") corrects it.

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
_NUMERATORS = {
    "a": 1, "an": 1, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
    "nine": 9, "ten": 10,
}
_DENOMINATORS = {
    "half": 2, "halve": 2, "third": 3, "quarter": 4, "fourth": 4, "fifth": 5, "sixth": 6, "seventh": 7, "eighth": 8,
    "ninth": 9, "tenth": 10, "twelfth": 12, "twentieth": 20, "hundredth": 100,
}
_VULGAR = {
    "½": 1 / 2, "⅓": 1 / 3, "⅔": 2 / 3, "¼": 1 / 4, "¾": 3 / 4, "⅕": 1 / 5, "⅖": 2 / 5, "⅗": 3 / 5, "⅘": 4 / 5,
    "⅙": 1 / 6, "⅚": 5 / 6, "⅛": 1 / 8, "⅜": 3 / 8, "⅝": 5 / 8, "⅞": 7 / 8, "⅒": 1 / 10,
}
_NUM = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"
_UNIT_WORD = r"cm|centimet(?:er|re)s?|mm|millimet(?:er|re)s?|degrees?|deg|inch(?:es)?"


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def _count(word: str) -> float:
    return float(_NUMERATORS.get(word, _NUMBER_WORDS.get(word, 0))) if not word[0].isdigit() else float(word)


def _latest_statement(text: str) -> str:
    """ "roll -2. Change of plan: yaw -3" -> "Change of plan: yaw -3": a key label never spans a sentence, and
    what stands before its sentence is another request (or a cancelled one) when the labelled words have an amount."""
    colon = re.search(r":\s", text)
    if colon is None or colon.start() > 48:
        return text
    ends = list(re.finditer(r"[.!?]\s+", text[: colon.start()]))
    if ends and not re.search(r"\d", text[ends[-1].end(): colon.start()]):
        rest = text[ends[-1].end():]
        if re.search(r"\d", _clean(rest)):
            return rest
    return text


def _clean(text: str) -> str:
    t = text.lower()
    for a, b in (("−", "-"), ("–", "-"), ("—", " - "), ("°", " deg "), ("º", " deg "), ("×", " x "), ("’", "'"),
                 ("↑", " up "), ("⬆", " up "), ("↓", " down "), ("⬇", " down "), ("@", " at ")):
        t = t.replace(a, b)
    t = re.sub(r"[δ∆]\s*(?=[a-z])", "d", t)  # "Δy = -25 mm"
    # "--cam-dx -0.5", "--light 1.35": a flag names the value after it
    t = re.sub(r"(?<![\w-])--([a-z][a-z0-9]*(?:[-_][a-z0-9]+)*)\s*=?\s*", lambda m: f" {m.group(1).replace('-', '_')}: ", t)
    t = re.sub(r"\*{2,}", " ", t)  # markdown bold
    t = re.sub(r"\*\s*=?\s*(?=[\d.])", " x ", t)  # "light *= 0.85"
    t = re.sub(r"[\"{}\[\]()]", " ", t)
    t = re.sub(r"\bpercents?\b|\bper cent\b|\bpct\b", "%", t)
    t = re.sub(r"\b(?:a|one) hundred(?: and)?(?:\s+(twenty|thirty|forty|fifty|sixty|seventy|eighty|ninety|ten|five))?\b",
               lambda m: str(100 + ({"ten": 10, "five": 5}.get(m.group(1) or "", 0) or _NUMBER_WORDS.get(m.group(1) or "", 0))), t)
    t = re.sub(r"\b(twenty|thirty|forty|fifty|sixty|seventy|eighty|ninety)[\s-]+(one|two|three|four|five|six|seven|eight|nine)\b",
               lambda m: str(_NUMBER_WORDS[m.group(1)] + _NUMBER_WORDS[m.group(2)]), t)
    t = re.sub(r"\b(this|that|which|each|every|another|other|no) one\b(?!\s+(?:point|and)\b)", r"\1 item", t)
    counts = r"(?:" + "|".join(sorted(set(_NUMERATORS) | set(_NUMBER_WORDS) - {"half"}, key=len, reverse=True)) + r"|\d+(?:\.\d+)?)"
    # "a centimetre and a half", "three and a half centimetres", "one and a half times"
    t = re.sub(rf"\b({counts})\s+({_UNIT_WORD})\s+and\s+a\s+half\b", lambda m: f"{_fmt(_count(m.group(1)) + 0.5)} {m.group(2)}", t)
    t = re.sub(rf"\b({counts})\s+and\s+a\s+half\b", lambda m: _fmt(_count(m.group(1)) + 0.5), t)
    # "a quarter", "two-thirds", "eight-tenths", "a twentieth", "three quarter": a fraction as a number
    t = re.sub(
        r"(?<![\d.])\b(" + "|".join(sorted(_NUMERATORS, key=len, reverse=True)) + r"|\d+)[\s-]+(" + "|".join(_DENOMINATORS)
        + r")s?\b",
        lambda m: _fmt(_count(m.group(1)) / _DENOMINATORS[m.group(2)]), t,
    )
    t = re.sub(r"(\d*)([" + "".join(_VULGAR) + r"])", lambda m: f" {_fmt(float(m.group(1) or 0) + _VULGAR[m.group(2)])} ", t)
    t = re.sub(r"(?<![\w.])(\d+)\s*/\s*(\d+)(?![\w.])",
               lambda m: _fmt(int(m.group(1)) / int(m.group(2))) if 2 <= int(m.group(2)) <= 100 else m.group(0), t)
    t = re.sub(rf"(\d*\.\d+)\s+of\s+(?:a|an|one)\s+(?=(?:{_UNIT_WORD})\b)", r"\1 ", t)  # "three quarters of a degree"
    t = re.sub(r"\bhalf an? (?=cm|centimet|mm|millimet|deg|inch)", "0.5 ", t)
    t = re.sub(r"\b(?:a|an|one)\s+(?:full\s+|whole\s+|single\s+)?(?=(?:cm|centimet\w*|mm|millimet\w*|degree|deg|inch)\b)", "1 ",
               t)  # "by a centimeter", "a full centimetre"
    t = re.sub(r"\ba couple(?: of)?\s+(?=(?:cm|centimet\w*|mm|millimet\w*|degrees?|deg)\b)", "2 ", t)  # "a couple of degrees"
    t = re.sub(r"\b(" + "|".join(sorted(_NUMBER_WORDS, key=len, reverse=True)) + r")\b(?!\s+(?:of|as)\b)",
               lambda m: _fmt(_NUMBER_WORDS[m.group(1)]), t)
    t = re.sub(r"(?<![\d.])(\d+)\s+point\s+(\d+)\b", r"\1.\2", t)  # "one point five"
    t = re.sub(r"(?<![\d.])(?<!\d\s)\bpoint\s+(\d+)\b", r"0.\1", t)  # "point five"
    t = re.sub(r"\b(?:minus|negative)\s*(?=\d|\.\d)", "-", t)
    # "1,5 cm" (a decimal comma), not a list of numbers ("translate 0,3,-1 cm", "(0,0,4)")
    t = re.sub(r"(?<![\d.,])(\d),(\d)(?![\d.]*\s*,\s*[-+]?\d)", r"\1.\2", t)
    t = re.sub(r"\b(?:dn|dwn|dwon)\b", "down", t)
    t = re.sub(r"\bout[\s-]+of[\s-]+(?:range|spec|bounds)\b", " ", t)  # "out-of-range test": not a direction
    return re.sub(r"[ \t]+", " ", t).strip()


# -- camera --------------------------------------------------------------------------

_TRANSLATE = [  # (pattern, axis, sign) in the description frame: x right, y forward, z up
    (r"\b(?:to the right|rightwards?|right|rigth|rite|rihgt)\b", 0, 1),
    (r"\b(?:to the left|leftwards?|left|lft)\b", 0, -1),
    (r"\b(?:forwards?|fwd|ahead|(?:to (?:the )?)?front|closer|nearer|near(?= to)|close to (?:the )?table|toward(?:s)? (?:the )?table|"
     r"towards? (?:the )?scene|approach\w*|advanc\w*|in(?:wards?)?|push(?:ed)? in|dolly(?:ing|ied)? in|zoom(?:ed)? in)\b", 1, 1),
    (r"\b(?:backwards?|bwd|back(?:s|ed|ing)? (?:off|away|up)|backs|backed|back|further|farther|away from (?:the )?table|away|"
     r"out(?:wards?)?|pull(?:ed|s)? back|dolly(?:ing|ied)? out|zoom(?:ed)? out|retreat\w*)\b", 1, -1),
    (r"\b(?:up(?:wards?)?|higher|high|raise[ds]?|rais(?:ing)|lift(?:ed|s)?|elevate[ds]?|above|boom up|crane up|climb\w*|"
     r"ascend\w*|rise[sn]?|rose)\b", 2, 1),
    (r"\b(?:down(?:wards?)?|lower(?:ed|s)?|drop(?:ped|s)?|descend(?:ed|s)?|below|sink|sunk)\b", 2, -1),
]
_SENSES = [  # rotation senses said without a translation word
    (r"\b(?:counter[\s-]?clockwise|anti[\s-]?clockwise|ccw)\b", -1),
    (r"\b(?:clockwise|cw)\b", 1),
]
_DIRECTION = re.compile("|".join(f"(?:{p})" for p, _ in _SENSES) + "|" + "|".join(f"(?:{p})" for p, _, _ in _TRANSLATE))
_AXIS_KEYS = {"x": 0, "dx": 0, "tx": 0, "y": 1, "dy": 1, "ty": 1, "z": 2, "dz": 2, "tz": 2, "height": 2, "elevation": 2}
_ROTATION_VERBS = (
    r"pan(?:ned|s|ning)?|yaw(?:ed|s|ing)?|tilt(?:ed|s|ing)?|pitch(?:ed|es|ing)?|roll(?:ed|s|ing)?|rotat\w*|turn(?:ed|s|ing)?|"
    r"swing|swung|swivel\w*|spin|spun|twist\w*|tip(?:ped|s|ping)?|angle[ds]?|angling"
)
_UNIT = r"mm|millimet(?:er|re)s?|cm|centimet(?:er|re)s?|m\b|met(?:er|re)s?|inch(?:es)?|\"|deg(?:rees?)?|d\b"
_AMOUNT = re.compile(rf"({_NUM})(?:\s*|-)({_UNIT})?")
_LINES = {(0, "t"): "lr", (1, "t"): "fb", (2, "t"): "ud", (0, "r"): "lr", (1, "r"): "ud", (2, "r"): "cw"}


def _rotation_axis(part: str) -> tuple[int, int] | None:
    """(axis, sign) of a rotation in the description frame: 0 yaw (+ right), 1 pitch (+ up), 2 roll (+ clockwise)."""
    cw = re.search(r"\b(?:counter[\s-]?clockwise|anti[\s-]?clockwise|ccw)\b", part)
    optical = re.search(r"\b(?:optical|view(?:ing)?|lens|boresight)[\s-]+axis\b|\bline of sight\b", part)
    if re.search(r"\broll", part) or cw or re.search(r"\bclockwise|\bcw\b", part) or optical:
        if cw:
            return 2, -1
        if re.search(r"\bclockwise|\bcw\b|\bright\b", part):
            return 2, 1
        if re.search(r"\bleft\b", part):
            return 2, -1
        return 2, 1
    if re.search(r"\b(?:tilt|pitch|tip(?:ped|s|ping)?\b)", part):
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
    """The signed amount of a motion (the first with a unit, else the first) and its unit (cm, deg or None)."""
    found = list(_AMOUNT.finditer(part))
    if not found:
        return None
    m = next((f for f in found if f.group(2)), found[0])
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


def _direction(part: str) -> tuple[str, int] | None:
    """The line ("lr", "ud", "fb", "cw") and sense of the last direction word of a piece."""
    last: tuple[str, int] | None = None
    for m in _DIRECTION.finditer(part):
        word = m.group(0)
        for pattern, sign in _SENSES:
            if re.fullmatch(pattern, word):
                last = ("cw", sign)
                break
        else:
            for pattern, axis, sign in _TRANSLATE:
                if re.fullmatch(pattern, word):
                    last = (_LINES[(axis, "t")], sign)
                    break
    return last


def _has_cue(part: str) -> bool:
    """Whether a piece of a request says a direction or an axis (not only an amount)."""
    return bool(
        re.search(r"\b[xyz]\b", part) or _rotation_axis(part) is not None
        or any(re.search(pattern, part) for pattern, _, _ in _TRANSLATE)
    )


def _split_motion(part: str) -> list[str]:
    """ "up 2 cm 1 cm backward", "pitched 1 deg down yawed right 3 deg": one piece, several motions."""
    tokens: list[tuple[int, str, str]] = [(m.start(), "amount", m.group(0)) for m in _AMOUNT.finditer(part)]
    tokens += [(m.start(), "verb", m.group(0)) for m in re.finditer(rf"\b(?:{_ROTATION_VERBS})\b", part)]
    tokens += [(m.start(), "dir", m.group(0)) for m in _DIRECTION.finditer(part)]
    tokens.sort()
    cuts: list[int] = []
    seen = {"amount": False, "verb": False, "dir": False, "sense": False}
    for k, (at, kind, word) in enumerate(tokens):
        if kind == "amount":
            new = seen["amount"] and (seen["dir"] or seen["verb"])
        elif kind == "dir":
            new = seen["dir"] and seen["amount"]
        else:  # "0.25 deg counter-clockwise roll", "a 2-degree downward tilt": a verb after its motion, nothing after it
            new = seen["verb"] or (seen["amount"] and seen["dir"] and not (word.startswith("roll") and seen["sense"])
                                   and any(kind_ != "verb" for _, kind_, _ in tokens[k + 1:]))
        if new and at > 0:
            cuts.append(at)
            seen = dict.fromkeys(seen, False)
        seen[kind] = True
        if kind == "dir" and re.search(r"clockwise|\bc?cw\b", word):
            seen["sense"] = True
    bounds = [0, *cuts, len(part)]
    return [part[a:b].strip() for a, b in zip(bounds, bounds[1:], strict=False) if part[a:b].strip()]


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
    return [piece for p in out for piece in _split_motion(p)]


def _read_motion(part: str) -> tuple[str, int, float] | None:
    """("t" or "r", axis, signed value in cm or degrees) of one motion with its amount, description frame."""
    amount = _amount(part)
    if amount is None:
        return None
    value, unit = amount
    rot = _rotation_axis(part)
    if rot is not None and unit != "cm":
        axis, sign = rot
        worded = re.search(r"\b(?:left|right|up|down|upwards?|downwards?|clockwise|counter[\s-]?clockwise|anti[\s-]?clockwise|ccw|cw)\b", part)
        # "roll -3 degrees (counter-clockwise)": the word and the sign say one thing; "pan -2": the sign
        return "r", axis, sign * abs(value) if worded else sign * value
    if unit == "deg":
        # "2 deg down", "2 degrees to the left": an angle with a direction is a tilt or a pan
        said = _direction(part)
        if said is None or said[0] == "fb":
            return None
        return "r", {"lr": 0, "ud": 1, "cw": 2}[said[0]], said[1] * abs(value)
    for pattern, axis, sign in _TRANSLATE:
        if re.search(pattern, part):
            return "t", axis, sign * value
    return None


def _read_vector(t: str, translate: list[float]) -> tuple[str, bool]:
    """ "translate (0, -2, 1.5)", "translation (x, y, z) = (-10 mm, 0, +25 mm)", "xyz 0, 0, -2 cm", "translate_cm = 0, -3, 0"."""
    unit = r"(mm|cm|m(?![a-z]))"
    vector = re.search(
        rf"\b(?:translat\w*?|xyz|offset|move|moved|shift|delta|displacement)(?:[_\s]*(?<![a-z])(mm|cm|m)\b)?\s*"
        rf"(?:x\s*,\s*y\s*,\s*z\s*)?(?:in\s+{unit}\s*)?[:=]?\s*"
        rf"({_NUM})\s*{unit}?(?:\s*[,;]\s*|\s+)({_NUM})\s*{unit}?(?:\s*[,;]\s*|\s+)({_NUM})\s*{unit}?(?:\s*{unit})?",
        t,
    )
    if vector is None:
        return t, False
    g = vector.groups()
    shared = g[8] or g[1] or g[0] or "cm"
    for k in range(3):
        scale = {"mm": 0.1, "cm": 1.0, "m": 100.0}[g[3 + 2 * k] or shared]
        translate[k] += float(g[2 + 2 * k]) * scale
    return t[: vector.start()] + " " + t[vector.end():], True


def _read_axes_after(t: str, translate: list[float]) -> tuple[str, bool]:
    """ "-1 cm x, +1 cm z", "+0.5 cm in x", "+1 cm camera height": values written before their axes."""
    after = re.compile(
        rf"(?<![\w.])({_NUM})\s*(mm|cm|m\b|millimet\w*|centimet\w*)?\s*(in |along |on )?(?:the )?\b(x|y|z|height|elevation)\b([\s-]*axis)?"
    )

    def said(m: re.Match[str]) -> bool:  # "-1 cm x", "+0.5 in x", "+1 cm height" (not "pitch +4 z -1")
        return bool((m.group(2) or m.group(3) or m.group(5)) and (m.group(4) in "xyz" or m.group(1)[0] in "+-"))

    before = re.search(rf"\bd?[xyz]\b(?:[\s-]*axis)?\s*[:=]?\s*{_NUM}", t)
    found = [m for m in after.finditer(t) if said(m)]
    if not found or (before is not None and before.start() < found[0].start()):
        return t, False
    for m in found:
        unit = m.group(2) or ""
        scale = 0.1 if unit.startswith(("mm", "milli")) else 100.0 if unit == "m" else 1.0
        translate[_AXIS_KEYS[m.group(4)]] += float(m.group(1)) * scale
    return after.sub(lambda m: " " if said(m) else m.group(0), t), True


def read_camera_request(text: str) -> dict[str, Any] | None:
    """A move_camera operation (spec frame) from the words of a camera request; None without amounts."""
    t = re.sub(r"\b(?:camera|cam)[_.-](?=[a-z])", " ", _clean(_latest_statement(text)))
    t = re.sub(r"\bl\b(?!\s*[:=])", "left", re.sub(r"\br\b(?!\s*[:=])", "right", t))  # "pan L 3 deg"
    t = re.sub(r"\b(tilt\w*|pitch\w*|tip\w*)\s+([du])\b(?!\s*[:=])", lambda m: f"{m.group(1)} {'down' if m.group(2) == 'd' else 'up'}", t)
    t = re.sub(r"\b(?:in|to)\s+(?:the\s+|a\s+)?(?=(?:counter[\s-]?|anti[\s-]?)?clockwise|c?cw\b)", " ", t)  # "3 deg in clockwise"
    # "1 cm further left", "3 degrees further down": an intensifier before a direction, not "back"
    t = re.sub(r"\b(?:further|farther|more)\s+(?=(?:to\s+the\s+)?(?:left|right|up|down|in|out|back|forward|away|closer|lower|higher|high)\b)", " ", t)
    translate = [0.0, 0.0, 0.0]
    rotate = [0.0, 0.0, 0.0]
    t, read_any = _read_vector(t, translate)
    t = re.sub(r"\b(?:camera|cam|view|viewpoint|the|it|by|about|around|roughly|approximately|of|move|moved|moves|shift|shifted|"
               r"shifts|translate[ds]?|translation|position|rotation|rotate|nudge[ds]?|slightly|a bit|a little|please)\b",
               lambda m: " rotate " if m.group(0).startswith("rotat") else " ", t)
    t = re.sub(r"\b(d?[xyz]|d?yaw|d?pitch|d?roll|pan|tilt|height)\s+(?:should|must|shall|will|would)?\s*(?:be|is|becomes|to)\s+(?=[-+]?\d)",
               r"\1: ", t)  # "z should be +2"
    t = re.sub(r"\b(height|elevation)\s+(?=[-+]\d)", r"\1: ", t)  # "height -1 cm"
    t = re.sub(r"\b(d[xyz]|t[xyz]|[xyz]_(?:cm|mm|m))\s+(?=[-+]?\d)", r"\1: ", t)  # "dy -1.5 dz +1", "x_cm  -2": a key and its column
    t = re.sub(r"[ \t]+", " ", t)
    t, read_vals = _read_axes_after(t, translate)
    read_any = read_any or read_vals
    # axis keys with signed values: "x: -1", "dz -4cm", "yaw: +3", "z_cm: 1.5", "pitch_deg = 2", "yaw;-4", "lift_cm: 0.5"
    keyed = re.compile(
        r"\b(dx|dy|dz|tx|ty|tz|x|y|z|height|elevation|d?yaw|d?pitch|d?roll|pan|tilt|up|down|left|right|forward|fwd|back|lift|"
        r"raise|lower|drop)"
        rf"(?:_(cm|mm|m|deg))?\s*[:=;]\s*({_NUM})\s*(cm|mm|deg(?:rees?)?)?"
    )
    for m in keyed.finditer(t):
        key, unit = m.group(1), m.group(2) or m.group(4) or ""
        key = key[1:] if key in ("dyaw", "dpitch", "droll") else key
        value = float(m.group(3))
        if unit == "mm":
            value /= 10
        elif unit == "m":
            value *= 100
        worded = re.match(r"\s*(?:to\s+the\s+)?(down|up|left|right|counter[\s-]?clockwise|anti[\s-]?clockwise|clockwise)\b",
                          t[m.end():])
        if worded is not None and key in ("yaw", "pan", "pitch", "tilt", "roll"):
            # "tilt to 5 degrees down": the direction said after the value gives its sign
            word = worded.group(1)
            value = abs(value) * (-1 if word in ("down", "left") or word.startswith(("counter", "anti")) else 1)
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
    done: list[tuple[str, int, float]] = []  # motions read so far: kind, axis, value
    waiting: str | None = None  # "4 cm" before its direction ("Camera 4 cm higher - sorry, lower")
    for part in _motions(t):
        if _amount(part) is None:
            said = _direction(part)
            if said is None:
                continue
            if waiting is not None:
                part, waiting = f"{waiting} {part}", None
            else:  # "pan right 4 deg, sorry, left": the direction of the last motion on that line (or axis)
                rot = _rotation_axis(part) if re.search(rf"\b(?:{_ROTATION_VERBS})\b", part) else None
                for k in range(len(done) - 1, -1, -1):
                    kind, axis, value = done[k]
                    if rot is not None and kind == "r" and axis == rot[0]:
                        done[k] = (kind, axis, rot[1] * abs(value))
                        break
                    if rot is None and _LINES[(axis, kind)] == said[0]:
                        done[k] = (kind, axis, said[1] * abs(value))
                        break
                continue
        # "-3cm x", "+2 cm z", "x -3": a signed value along a named axis
        amount = _amount(part)
        axis_after = re.search(rf"{_NUM}\s*(?:cm|mm|m)?\s*(?:in |along |on )?(?:the )?\b([xyz])\b(?:[\s-]*axis)?", part)
        axis_before = re.search(rf"\b([xyz])\b(?:[\s-]*axis)?\s*{_NUM}", part)
        if amount is not None and (axis_after or axis_before):
            key = (axis_after or axis_before).group(1)  # type: ignore[union-attr]
            translate[_AXIS_KEYS[key]] += amount[0]
            read_any = True
            continue
        motion = _read_motion(part)
        if motion is None:
            if amount is not None and not _has_cue(part):
                waiting = part
            continue
        done.append(motion)
    for kind, axis, value in done:
        (rotate if kind == "r" else translate)[axis] += value
        read_any = True
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
    r"crank\w*|bump\w*|intensif\w*|plus|more|lighter|turn(?:ed)? up|add(?:ed|s)?|above)\b|^\s*\+"
)
_DARKER = re.compile(
    r"\b(?:dark\w*|dim\w*|down|decrease[ds]?|decreas\w+|reduc\w+|lower\w*|less|lesser|weaker|cut|drop\w*|minus|"
    r"fainter|gloom\w*|below|under|turn(?:ed)? down|tone(?:d)? down|darken\w*|shad\w*|kill\w*|remov\w*|subtract\w*|"
    r"take (?:away|off)|took (?:away|off)|lose|losing|off|soft\w*|low|mute[ds]?|subdue[ds]?)\b|^\s*-"
)
_BASELINE = (
    r"(?:the\s+|its\s+|their\s+|what it is\s+)?(?:(?:default|normal|usual|full|original|standard|regular|current|nominal|"
    r"baseline|reference|initial|stock|existing|present|previous)\b(?:\s+(?:brightness|intensity|level|light\w*|value))?"
    r"|before|now|today|what it is)\b"
)
_COMPARATIVE = r"(?:brighter|darker|dimmer|lighter|more|less|higher|lower|up|down)\b"
_LEVEL_WORDS = r"(?:brightness|intensity|power|level|illumination|output)"


def _change(value: float) -> dict[str, Any]:
    return {"op": "set_lighting", "intensity_delta": round(value, 4)}


def _level(t: str, undirected: bool) -> float | None:
    """The level a request sets, as a fraction of normal ("at 70% of normal", "brightness 110%", "to 0.8")."""
    pct = re.search(
        rf"({_NUM})\s*%\s*(?:of|from)\s+{_BASELINE}|(?<![-+])(?<![-+]\s)\b(\d+(?:\.\d+)?)\s*%\s*{_LEVEL_WORDS}\b|\b(?:at|to)\s+(?:about\s+|around\s+|roughly\s+)?({_NUM})\s*%(?!\s*(?:{_COMPARATIVE}|below|above|under|beneath))",
        t,
    )
    if pct is not None:
        return float(pct.group(1) or pct.group(2) or pct.group(3)) / 100
    # "0.6 of normal", "two thirds of the usual brightness", "three quarters as bright", "to 0.8", "level 0.85"
    share = re.search(
        rf"(?<![\w.+-])(\d*\.\d+|[12])\s*(?:of|from)\s+{_BASELINE}|(?<![\w.+-])(\d*\.\d+)\s+(?:as\s+(?:bright|light|strong|intense|much)|the\s+(?:brightness|light\w*|intensity))\b"
        rf"|\b(?:at|to)\s+(?:about\s+|around\s+|roughly\s+|the\s+)?(\d*\.\d+)(?![\d%]|\s*(?:x\b|times\b|{_COMPARATIVE}))|\blevel\s*[:=]?\s*(\d*\.\d+)(?![\d%])",
        t,
    )
    if share is not None and not re.search(r"\bby\s+[\d.]", t):
        value = float(next(g for g in share.groups() if g))
        if value <= 2.0:
            return value
    if not undirected:
        return None
    # "light 80%", "Brightness: 125%", "lights ninety percent": a bare percentage said with no direction is a level
    bare = re.search(r"(?<![-+\d.])(\d+(?:\.\d+)?)\s*%", t)
    if bare is not None and float(bare.group(1)) >= 50:
        return float(bare.group(1)) / 100
    return None


def read_lighting_request(text: str) -> dict[str, Any] | None:
    """A set_lighting operation from the words of a lighting request; None without an amount."""
    t = _clean(_latest_statement(text))
    keyed_delta = re.search(r"(?:\b|_)(?:delta|change|offset|diff|adjust(?:ment)?)\s*[:=]", t) is not None
    words = re.sub(rf"{_NUM}\s*%?", " ", t)
    undirected = _DARKER.search(words) is None and _BRIGHTER.search(words) is None
    if not keyed_delta:
        level = _level(t, undirected)
        if level is not None:
            return _change(level - 1.0)
        factor = re.search(
            rf"(?:\bx\s*|\btimes\s+)({_NUM})(?![\d.])|({_NUM})\s*(?:x\b|times\b)|\b(?:factor|scale|multiplier|gain)\w*\s*(?:of|to|[:=])?\s*x?\s*({_NUM})", t
        )
        if factor is not None:
            value = float(factor.group(1) or factor.group(2) or factor.group(3))
            return _change(value - 1.0)
        if not re.search(r"\d", t):
            if re.search(r"\bhalf as (?:bright|light|strong|intense)\b|\bhalve[ds]?\b|\bhalf (?:the )?(?:brightness|light)\b|"
                         r"\b(?:to|at) (?:the )?half\b", t):
                return _change(-0.5)
            if re.search(r"\b(?:twice|double[ds]?) (?:as )?(?:bright|the (?:brightness|light|lighting))?|\bdoubl(?:e|ed|ing)\b", t):
                return _change(1.0)
        if undirected:  # "light = 0.9", "--light 1.35": a bare unsigned number past a plausible change is a factor
            bare = re.search(r"(?<![\w.+-])(\d*\.\d+)(?![\w.%])", t)
            if bare is not None and 0.5 < float(bare.group(1)) < 2:  # "LIGHT 0.3" stays a change of +0.3
                return _change(float(bare.group(1)) - 1.0)
    amount: float | None = None
    signed = 0
    pct = re.search(rf"({_NUM})\s*%", t)
    if pct is not None:
        amount = float(pct.group(1)) / 100
        signed = -1 if pct.group(1).startswith("-") else (1 if pct.group(1).startswith("+") else 0)
    else:
        for words_, value in sorted(_FRACTIONS.items(), key=lambda kv: -len(kv[0])):
            if re.search(rf"\b{words_}\b", t):
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
    elif keyed_delta:
        sign = 1  # "delta: 0.3"
    else:
        return None
    if signed and signed != sign and not (dark and bright):
        sign = signed  # "brightness -10%", "lights: -0.2": the sign said with the number
    return _change(sign * abs(amount))


__all__ = ["read_camera_request", "read_lighting_request"]
