"""Descriptions written as data: keyed lines, YAML blocks and shorthand, as one key per line.

People paste scene descriptions from configs and notes: ``task:`` blocks with
``type / object / target`` under them, ``obj: carrot@front; lgt=-0.3;
cam=(dz -4cm)``, ``goal | sugar box next to pudding box``. This module rewrites
such text into the plain form the reader reads — one ``objects:`` / ``task:`` /
``lighting:`` / ``camera:`` line each — and leaves prose as it is.
"""

from __future__ import annotations

import re
from typing import Any

import yaml

KEYS: dict[str, tuple[str, ...]] = {
    "objects": ("objects", "object", "objs", "obj", "items", "item", "props", "things", "table", "scene", "spawn"),
    "task": ("task", "goal", "instruction", "command", "job", "todo"),
    "lighting": ("lighting", "lights", "light", "lgt", "lite", "illumination", "brightness", "light level", "lux"),
    "camera": ("camera", "cam", "view", "viewpoint", "pov"),
}
"""Each field's key and the other names people give it."""
_ALIAS = {alias: key for key, aliases in KEYS.items() for alias in aliases}
_KEY = "|".join(re.escape(a) for a in sorted(_ALIAS, key=len, reverse=True))
_KEYED = re.compile(rf"(?:^|(?<=[;\n|]))\s*(?:[-*\u2022]\s*)?(?P<key>{_KEY})\s*(?:[:=]|\|(?!\|))\s*", re.IGNORECASE)
"""A key at the start of a line or after a separator: "obj: ...", "; lgt=-0.3", "goal | ..."."""
_TASK_FIELDS = {"type": "type", "task": "type", "action": "type", "object": "object", "source": "object",
                "obj": "object", "target": "target", "destination": "target", "container": "target", "dest": "target"}
_ABBREVIATIONS = (
    (r"\bdn\b", "down"), (r"\bfwd\b", "forward"), (r"\bbwd\b|\bbk\b", "back"), (r"\bccw\b", "counterclockwise"),
    (r"\bcw\b", "clockwise"), (r"\bdeg\.", "degrees"),
)
_SIDE = re.compile(r"\b(pan|yaw|turn|shift|move|slide|truck|rotate|nudge)\s+(?:the\s+camera\s+)?([rl])\b", re.IGNORECASE)


def _inline(value: Any) -> str:
    if isinstance(value, dict):
        return ", ".join(f"{k} {_inline(v)}" for k, v in value.items() if v is not None)
    if isinstance(value, list):
        return ", ".join(_inline(v) for v in value)
    return "none" if value is None else str(value)


def _task_text(value: Any) -> str:
    if not isinstance(value, dict):
        return _inline(value)
    fields = {_TASK_FIELDS.get(str(k).lower()): v for k, v in value.items()}
    kind, obj, target = fields.get("type"), fields.get("object"), fields.get("target")
    if kind is None or obj is None:
        return _inline(value)
    return f"{kind}({obj}{', ' + str(target) if target not in (None, '', 'null', 'none') else ''})"


def _from_yaml(text: str) -> str | None:
    """A YAML / JSON mapping with the fields' keys as one line per field; None if it is not one."""
    if "\n" not in text.strip() and not text.strip().startswith("{"):
        return None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        return None
    if not isinstance(data, dict):
        return None
    keyed = {_ALIAS.get(str(k).lower().replace("_", " ")): v for k, v in data.items()}
    if len([k for k in keyed if k is not None]) < 2 or None in keyed:
        return None  # not a scene mapping, or keys this reader would lose
    lines = []
    for key, value in keyed.items():
        lines.append(f"{key}: {_task_text(value) if key == 'task' else _inline(value)}")
    return "\n".join(lines)


_BRACKET_KEY = re.compile(rf"[\[<]\s*({_KEY})\s*[\]>]\s*[:=]?\s*", re.IGNORECASE)
"""A key in brackets: "[objs] pear, cup [task] put_in pear cup"."""


def as_fields(text: str) -> str:
    """Data-like descriptions rewritten as plain keyed lines; prose unchanged."""
    text = _BRACKET_KEY.sub(lambda m: f"\n{_ALIAS[m.group(1).lower()]}: ", text)
    mapped = _from_yaml(text)
    if mapped is not None:
        text = mapped
    else:
        text = _KEYED.sub(lambda m: f"\n{_ALIAS[m.group('key').lower()]}: ", text)
    # "carrot@front": an object and its place
    text = re.sub(r"(?<=[a-z])\s*@\s*(left|right|front|back|center|centre|middle|rear)\b", r" at the \1", text,
                  flags=re.IGNORECASE)
    for pattern, word in _ABBREVIATIONS:
        text = re.sub(pattern, word, text, flags=re.IGNORECASE)
    text = _SIDE.sub(lambda m: f"{m.group(1)} {'right' if m.group(2).lower() == 'r' else 'left'}", text)
    # "cam=(dx 0, dy 0, dz -4cm)": the brackets of a value
    return re.sub(r"(?m)^(\w+): \((.*)\)\s*$", r"\1: \2", text)
