"""The basic instruction's task: "put the carrot on the plate" -> put_on(carrot, plate)."""

from __future__ import annotations

import re
from typing import Any

_TASK_PATTERNS: list[tuple[str, re.Pattern[str]]] = [
    (
        "move_near",
        re.compile(
            r"^(?:please\s+)?(?:move|bring|push|slide|place|put|set|take|carry|shift|get)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:so that it is\s+)?(?:near|next to|close to|closer to|towards?|beside|by|near to|alongside)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "put_in",
        re.compile(
            r"^(?:please\s+)?(?:put|place|drop|insert|stick|set|move|store|toss|throw)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:into|inside of|inside|in|within)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "put_on",
        re.compile(
            r"^(?:please\s+)?(?:put|place|set|stack|lay|move|rest)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:on top of|onto|on to|on|upon|atop)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "pick_up",
        re.compile(
            r"^(?:please\s+)?(?:pick up|pick|lift up|lift|grab|grasp|take|get|raise)\s+(?:up\s+)?(?:the\s+|a\s+|an\s+)?"
            r"(?P<src>.+?)(?:\s+up)?(?:\s+(?:from|off) the table)?$"
        ),
    ),
]


def parse_instruction(instruction: str) -> dict[str, Any] | None:
    """The task of an instruction in one of the four forms, objects as written; None if none fits."""
    text = instruction.strip().lower().rstrip(".!").replace("_", " ")
    text = re.sub(r"\s+", " ", text)
    for task, pattern in _TASK_PATTERNS:
        m = pattern.match(text)
        if m:
            groups = m.groupdict()
            return {"type": task, "source": groups["src"].strip(), "target": (groups.get("tgt") or None)}
    return None
