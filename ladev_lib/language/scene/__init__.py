"""A rule-based reader of scene descriptions: text -> scene operations (as a dict).

It reads the styles people write, not only the offline writer's:

- the paper's structure ("Number and details of objects: 3 objects, one is a
  plastic bottle on the left. Environmental setup: slightly darker lighting,
  camera moved 3 cm left."), free prose, terse lists ("4 objects: coke can
  (left), plate, 2 random; light -0.2"), command lines ("ADD coke can to
  (0.1, 0.2)", "SET LIGHTING -0.2", "MOVE CAMERA 3 cm left");
- counts in digits or words; objects by display name, synonym, catalog id or
  category ("a fruit"); unknown objects where a phrase introduces one ("one of
  them is a purple elephant"), so the compiler can report them;
- positions as coordinates (metres, or cm/mm with units), regions ("front
  left", "in the middle") or relations ("near the bowl", "left of the plate");
- lighting in words ("slightly darker", "much brighter", "dim"), signed deltas,
  percentages or factors; camera moves and rotations in words and numbers
  ("camera moved 3 cm left", "rotate the camera 4 degrees down");
- silence means defaults; text with nothing recognisable is an error.

The task comes from the basic instruction ("put the carrot on the plate"),
or a "task:" / "instruction:" line in the description, or the task type alone.
"""

from ladev_lib.language.scene.instruction import parse_instruction
from ladev_lib.language.scene.reader import read_description
from ladev_lib.language.scene.words import Vocabulary, normalize_text

RULE_MODULES = (
    "ladev_lib.language.scene",
    "ladev_lib.language.scene.words",
    "ladev_lib.language.scene.corrections",
    "ladev_lib.language.scene.statements",
    "ladev_lib.language.scene.objects",
    "ladev_lib.language.scene.environment",
    "ladev_lib.language.scene.instruction",
    "ladev_lib.language.scene.reader",
)
"""The modules the grammar's rules live in (fingerprinted by the offline backend)."""

__all__ = ["RULE_MODULES", "Vocabulary", "normalize_text", "parse_instruction", "read_description"]
