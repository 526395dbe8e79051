"""The basic instruction: the standard short form VLA models are trained on.

    basic_instruction("put_on", "carrot", "plate") == "put the carrot on the plate"
"""

from __future__ import annotations

BASIC_TEMPLATES: dict[str, str] = {
    "pick_up": "pick up the {source}",
    "move_near": "move the {source} near the {target}",
    "put_on": "put the {source} on the {target}",
    "put_in": "put the {source} in the {target}",
}


def basic_instruction(task: str, source: str, target: str | None = None) -> str:
    """The basic instruction for a task, with objects named by their display names."""
    try:
        template = BASIC_TEMPLATES[task]
    except KeyError:
        raise ValueError(f"unknown task {task!r}; known: {', '.join(BASIC_TEMPLATES)}") from None
    if "{target}" in template and not target:
        raise ValueError(f"{task} needs a target object")
    return template.format(source=source, target=target)
