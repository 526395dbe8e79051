"""Descriptions written as data: keyed lines, YAML blocks and shorthand, as one key per line.

People paste scene descriptions from configs and notes: ``task:`` blocks with
``type / object / target`` under them, ``obj: carrot@front; lgt=-0.3;
cam=(dz -4cm)``, ``goal | sugar box next to pudding box``. This module rewrites
such text into the plain form the reader reads — one ``objects:`` / ``task:`` /
``lighting:`` / ``camera:`` line each — and leaves prose as it is.
"""

from __future__ import annotations

import ast
import configparser
import csv
import re
from typing import Any

import yaml

KEYS: dict[str, tuple[str, ...]] = {
    "objects": ("objects", "object", "objs", "obj", "items", "item", "props", "things", "table", "scene", "spawn"),
    "task": ("task", "goal", "instruction", "command", "job", "todo", "action"),
    "lighting": ("lighting", "lights", "light", "lgt", "lite", "illumination", "brightness", "light level", "lux"),
    "camera": ("camera", "cam", "view", "viewpoint", "pov"),
}
"""Each field's key and the other names people give it."""
_ALIAS = {alias: key for key, aliases in KEYS.items() for alias in aliases}
_KEY = "|".join(re.escape(a) for a in sorted(_ALIAS, key=len, reverse=True))
_KEYED = re.compile(rf"(?:^|(?<=[;\n|]))\s*(?:[-*\u2022]\s*)?(?P<key>{_KEY})\s*(?:[:=]|\|(?!\|))\s*", re.IGNORECASE)
"""A key at the start of a line or after a separator: "obj: ...", "; lgt=-0.3", "goal | ..."."""
_TASK_FIELDS = {"type": "type", "task": "type", "action": "type", "kind": "type", "object": "object",
                "source": "object", "obj": "object", "target": "target", "destination": "target",
                "container": "target", "dest": "target", "receptacle": "target"}
_META = re.compile(
    r"\s*(?:id|case|case id|tc|test|test id|name|title|note|notes|comment|comments|expected|result|status|owner|"
    r"author|date|version|run|seed|priority)\s*$",
    re.IGNORECASE,
)
"""Keys that label a row rather than describe the scene ("id", "expected")."""
_AXES = frozenset({"x", "y", "z", "dx", "dy", "dz", "yaw", "pitch", "roll"})
_UNITS = {"cm": "cm", "mm": "mm", "m": "m", "deg": "deg", "degrees": "deg", "degree": "deg"}
_ABBREVIATIONS = (
    (r"\bdn\b", "down"), (r"\bfwd\b", "forward"), (r"\bbwd\b|\bbk\b", "back"), (r"\bccw\b", "counterclockwise"),
    (r"\bcw\b", "clockwise"), (r"\bdeg\.", "degrees"),
)
_SIDE = re.compile(r"\b(pan|yaw|turn|shift|move|slide|truck|rotate|nudge)\s+(?:the\s+camera\s+)?([rl])\b", re.IGNORECASE)


def _words(key: Any) -> list[str]:
    return re.split(r"[\s_.-]+", str(key).strip().lower())


def _field(key: Any) -> tuple[str | None, list[str]]:
    """A key's field and the words after its name ("camera_x_cm" -> camera, [x, cm])."""
    words = _words(key)
    for n in (2, 1):
        name = " ".join(words[:n])
        if name in _ALIAS:
            return _ALIAS[name], words[n:]
    return None, words


def _inline(value: Any) -> str:
    if isinstance(value, dict):
        return ", ".join(f"{k} {_inline(v)}" for k, v in value.items() if v is not None)
    if isinstance(value, (list, tuple)):
        return ", ".join(_inline(v) for v in value)
    return "none" if value is None else str(value)


def _task_text(value: Any) -> str:
    if isinstance(value, (list, tuple)) and 2 <= len(value) <= 3 and all(isinstance(v, (str, type(None))) for v in value):
        value = dict(zip(("type", "object", "target"), value, strict=False))  # ("put_on", "pear", "plate")
    if not isinstance(value, dict):
        return _inline(value)
    fields = {_TASK_FIELDS.get(str(k).lower()): v for k, v in value.items()}
    kind, obj, target = fields.get("type"), fields.get("object"), fields.get("target")
    if kind is None or obj is None:
        return _inline(value)
    return f"{kind}({obj}{', ' + str(target) if target not in (None, '', 'null', 'none') else ''})"


def _camera_text(items: list[tuple[list[str], Any]]) -> str:
    """Camera values keyed by axis and unit ("yaw_deg: -3", "x_cm = -5", "z: 10mm") as one phrase each."""
    said = []
    for words, value in items:
        if isinstance(value, dict):
            said.append(_camera_text([(words + _words(k), v) for k, v in value.items()]))
            continue
        axis = next((w for w in words if w in _AXES), None)
        unit = next((_UNITS[w] for w in words if w in _UNITS), None)
        if axis is None:
            said.append(" ".join(words + [_inline(value)]).strip())
        else:
            numeric = isinstance(value, (int, float)) or re.fullmatch(r"\s*[-+]?\d+(?:\.\d+)?\s*", str(value))
            said.append(f"{axis} {_inline(value)}{' ' + unit if unit and numeric else ''}")
    return ", ".join(p for p in said if p)


def _fields(data: dict[Any, Any]) -> dict[str, list[tuple[list[str], Any]]]:
    out: dict[str, list[tuple[list[str], Any]]] = {}
    for key, value in data.items():
        field, rest = _field(key)
        if isinstance(value, dict) and field not in ("task", "camera"):
            nested = _fields(value)  # "[env] light = -0.5", "scene: {objects: ...}": a section of fields
            for k, items in nested.items():
                out.setdefault(k, []).extend(items)
            if nested:
                continue
        if field is not None:
            out.setdefault(field, []).append((rest, value))
        elif isinstance(value, (str, int, float)) and not isinstance(value, bool) and not _META.match(str(key)):
            out.setdefault(f"other:{key}", []).append(([], value))  # "Setup: brighten the lights ...": kept as said
    return out


def _mapping_text(data: dict[Any, Any]) -> str | None:
    """A mapping of the fields as one "key: value" line each; None when it names fewer than two."""
    fields = _fields(data)
    if len([f for f in fields if not f.startswith("other:")]) < 2:
        return None
    lines = []
    for field, items in fields.items():
        if field.startswith("other:"):
            lines.append(f"{field[len('other:'):]}: {_inline(items[0][1])}")
            continue
        if field == "camera":
            text = _camera_text(items)
        elif field == "task":
            task = {" ".join(w): v for w, v in items if w} or None
            text = _task_text(task) if task and len(items) > 1 else _task_text(items[0][1])
        elif field == "objects":
            text = ", ".join(_inline(v).replace("|", ",") for _, v in items)
        else:
            text = ", ".join(_inline(v) for _, v in items)
        lines.append(f"{field}: {text}")
    return "\n".join(lines)


def _parse(text: str) -> dict[Any, Any] | None:
    """Text that is data: YAML / JSON, a Python literal, INI sections or a CSV header and row."""
    stripped = text.strip()
    literal = re.sub(r"^[A-Za-z_]\w*\s*=\s*(?=[{\[])", "", stripped)
    if literal.startswith("{"):
        try:
            value = ast.literal_eval(literal)
            if isinstance(value, dict):
                return value
        except (ValueError, SyntaxError, MemoryError, RecursionError):
            pass
    if re.search(r"(?m)^\s*\[[\w .-]+\]\s*$", stripped):
        parser = configparser.ConfigParser(strict=False, interpolation=None)
        try:
            parser.read_string(stripped)
            return {name: dict(parser[name]) for name in parser.sections()}
        except configparser.Error:
            pass
    lines = stripped.splitlines()
    if len(lines) == 2 and lines[0].count(",") >= 2:
        header, row = next(csv.reader([lines[0]])), next(csv.reader([lines[1]]))
        if len(header) == len(row):
            return dict(zip(header, row, strict=True))
    if "\n" not in stripped and not stripped.startswith("{"):
        return None
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return None
    return value if isinstance(value, dict) else None


_BRACKET_KEY = re.compile(rf"[\[<]\s*({_KEY})\s*[\]>]\s*[:=]?\s*", re.IGNORECASE)
"""A key in brackets: "[objs] pear, cup [task] put_in pear cup"."""


def as_fields(text: str) -> str:
    """Data-like descriptions rewritten as plain keyed lines; prose unchanged."""
    # "pick_up: knife", "put_in = pear, bowl": a task key word as the key
    text = re.sub(r"(?im)^\s*(pick_up|move_near|put_on|put_in)\s*[:=]\s*(.+?)\s*$", r"task: \1(\2)", text)
    # "tennis ball L, softball R": a side as one capital letter after an object in a list
    text = re.sub(r"(?<=[a-z])\s+([LR])(?=\s*(?:[,;.|]|$))", lambda m: f" on the {'left' if m.group(1) == 'L' else 'right'}",
                  text, flags=re.MULTILINE)
    data = _parse(text)
    mapped = _mapping_text(data) if data is not None else None
    if mapped is not None:
        text = mapped
    else:
        text = _BRACKET_KEY.sub(lambda m: f"\n{_ALIAS[m.group(1).lower()]}: ", text)
        text = _KEYED.sub(lambda m: f"\n{_ALIAS[m.group('key').lower()]}: ", text)
    # "put_in(strawberry; large orange cup)": the call's arguments
    text = re.sub(r"\b((?:pick_up|move_near|put_on|put_in)\s*\([^;()]*);", r"\1,", text, flags=re.IGNORECASE)
    # "carrot@front": an object and its place
    text = re.sub(r"(?<=[a-z])\s*@\s*(left|right|front|back|center|centre|middle|rear)\b", r" at the \1", text,
                  flags=re.IGNORECASE)
    for pattern, word in _ABBREVIATIONS:
        text = re.sub(pattern, word, text, flags=re.IGNORECASE)
    text = _SIDE.sub(lambda m: f"{m.group(1)} {'right' if m.group(2).lower() == 'r' else 'left'}", text)
    # "cam=(dx 0, dy 0, dz -4cm)": the brackets of a value
    return re.sub(r"(?m)^(\w+): \((.*)\)\s*$", r"\1: \2", text)
