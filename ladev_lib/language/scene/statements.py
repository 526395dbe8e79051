"""Where a scene description states its task, and what that task is.

    found = find_task(text)
    found.task       # {"type": "put_on", "source": "orange", "target": "plate"} or None
    found.rest       # the text without the task statement(s), for the scene reader
    found.statement  # the words the task was read from

A description may state the task anywhere: a labelled line or clause
("Task: ...", "TASK ...", "task(...)", "the goal is to ...", "instruction =
..."), a sentence about the robot ("the robot should ...", "I want the arm to
...", "let's see whether it can ...", "... — that's the robot's whole job"),
or a bare command over definite or bare nouns ("put the peach on the red
plate", "move fanta near green cup"). Placement commands that set the scene
("put a carrot near the front", "place the bowl on the left side") are not
tasks: their object is introduced with "a"/"an"/a number, or their
destination is a part of the table.

A labelled or robot statement wins over a bare command; among statements of
the same strength, the last one wins ("task: a — no, b"). Each statement is
read with :func:`ladev_lib.language.frames.read_instruction`, so the scene
reader and the instruction reader share one grammar of the four tasks.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.language.frames import Frame, NounPhrase, read_instruction
from ladev_lib.language.tasks import TASKS

_VERB = (
    r"(?:pick(?:s|ing)?\s+up|pick|grab|grasp|lift|take|put|place|set|move|bring|stack|drop|insert|push|slide|"
    r"carry|lay|rest|get|pop|stick|deposit|transfer|relocate|nudge|shift|stand|position|load)"
)
_AGENT = r"(?:the\s+)?(?:robot|arm|agent|gripper|policy|system|manipulator|model|it|they|you|we)"
_MODAL = (
    r"(?:should|must(?:\s+to)?|will|would|shall|can|could|may|might|needs?\s+to|has\s+to|have\s+to|is\s+to|are\s+to|"
    r"is\s+supposed\s+to|is\s+expected\s+to|is\s+meant\s+to|is\s+going\s+to|ought\s+to|'ll|is\s+asked\s+to|"
    r"gets?\s+to|tries\s+to|try\s+to|attempts?\s+to|is\s+able\s+to|manages?\s+to)"
)
LABEL = re.compile(
    r"(?:^|(?<=[\s(\[{|;,.:•*-]))(?:the\s+)?(?:main\s+|actual\s+|robot(?:'s)?\s+|its\s+)?"
    r"(?:task|instruction|command|goal|objective|job|mission|assignment|challenge|prompt|aim|purpose|robot(?=\s*:))"
    r"(?:\s+(?:here|for\s+the\s+robot|for\s+the\s+arm|of\s+the\s+robot))?"
    r"\s*(?:[:=(]|-+>|\s+is\s+(?:to\s+|that\s+)?|\s+(?:will|should|would|shall|must)\s+be\s+(?:to\s+)?|"
    r"\s+(?=" + _VERB + r"\b)|\s+(?=(?:pick_up|move_near|put_on|put_in)\s*\())|\s*:\s*(?=\{\s*type\b)",
    re.IGNORECASE,
)
AGENT_MODAL = re.compile(
    rf"\b{_AGENT}\s+(?:\w+\s+)?{_MODAL}\s+(?:now\s+|then\s+|first\s+|simply\s+|just\s+|only\s+|also\s+)?(?={_VERB}\b)",
    re.IGNORECASE,
)
AGENT_DOES = re.compile(
    # "the robot is put the eggplant in the basket", "robot to put ...": said without standard grammar
    rf"(?<!for )(?<!for the )\b(?:the\s+)?(?:robot|arm|agent|gripper|policy|manipulator)\s+(?:is|are|do|does|to)\s+(?={_VERB}\b)|"
    r"\b(?:the\s+)?(?:robot|arm|agent|gripper|policy|manipulator)\s+(?:then\s+|just\s+|simply\s+)?"
    r"(?=(?:picks\s+up|picks|grabs|grasps|lifts|takes|puts|places|sets|moves|brings|stacks|drops|inserts|pushes|"
    r"slides|carries|lays|rests|gets|transfers|picking|grabbing|grasping|lifting|taking|putting|placing|setting|"
    r"moving|bringing|stacking|dropping|inserting|pushing|sliding|carrying|laying|resting|getting|transferring)\b)",
    re.IGNORECASE,
)
WANT_TO = re.compile(
    # pseudo-cleft: "what I want the robot to do is (to) move ...", "what the arm should do is put ..."
    rf"\b(?:what|all|the\s+(?:only|one|main)\s+thing)\s+(?:(?:i|we)(?:'d|\s+would)?\s+(?:want|need|like|expect)\s+"
    rf"(?:{_AGENT}\s+)?to\s+do|{_AGENT}\s+(?:should|must|has\s+to|needs\s+to|will)\s+do)\s+is\s+(?:to\s+)?(?={_VERB}\b)|"
    rf"\b(?:want|wants|like|need|needs|ask|asks|have|get|tell|make|let|expect|expects|instruct)\s+{_AGENT}\s+(?:to\s+)?(?={_VERB}\b)"
    rf"|\b(?:see|test|check|find\s+out|verify|evaluate|whether|if)\s+(?:if\s+|whether\s+)?{_AGENT}\s+(?:can|could|will|is\s+able\s+to|manages?\s+to)\s+(?={_VERB}\b)"
    rf"|\b(?:see|watch|let|make|have|help)\s+{_AGENT}\s+(?={_VERB}\b)"
    rf"|\b(?:can|could|will|does|do)\s+(?:the\s+)?(?:robot|arm|agent|gripper|policy|manipulator|it)\s+(?:still\s+|reliably\s+|actually\s+)?(?={_VERB}\b)",  # "can the arm pick up ...?"
    re.IGNORECASE,
)
BACK_LABEL = re.compile(
    r"^\s*(?:that|this|which)(?:'s|\s+is|\s+will\s+be)\s+(?:the\s+)?(?:robot'?s?\s+|arm'?s?\s+|its\s+)?"
    r"(?:whole\s+|only\s+|main\s+|actual\s+|entire\s+)?(?:task|job|goal|objective|mission)",
    re.IGNORECASE,
)
NEED_THE = re.compile(
    r"\b(?:i|we)(?:'d|\s+would)?\s+(?:really\s+|just\s+|also\s+)?(?:need|want|like|wish\s+for|expect)\s+"
    r"(?=the\s+(?!robot|arm|agent|gripper|policy|scene|camera|light)\w)",
    re.IGNORECASE,
)
"""A wish about a named object ("I need the strawberry on the plate"): read as a statement only
when it reads as one of the four tasks ("I need the plate and a knife" lists objects)."""
_SETTING_WORDS = frozenset(
    {"brightness", "light", "lights", "lighting", "illumination", "exposure", "camera", "cam", "view", "viewpoint",
     "angle", "intensity", "dimmer"}
)
_RETRACT = re.compile(
    r"^[\s.…,;:-]*(?:(?:hmm+|no+|nope|wait|sorry|actually|oops|scratch that|on second thought|change of plan)\b[\s,.!:;-]*)+"
    rf"(?={_VERB}\b)",
    re.IGNORECASE,
)
"""A statement that takes the one before back ("no, put it in the cup instead")."""
PASSIVE = re.compile(
    r"\b(?:(?:must|should|has\s+to|have\s+to|needs?\s+to|is\s+to|are\s+to|will|shall|is\s+supposed\s+to)\s+be|"
    r"gets?|got|(?:is|are)\s+(?:being|getting))\s+"  # "the apple gets put on the sponge"
    r"(?:put|placed|moved|set|dropped|stacked|picked\s+up|lifted|carried|brought|laid|inserted|transferred|slid)\b",
    re.IGNORECASE,
)
"""A task said in the passive ("the plum should be placed in the bowl")."""
END_STATE = re.compile(
    r"(?:^|(?<=[\s,;:]))(?:(?:when|once|after)\s+(?:the\s+)?(?:robot|arm|agent|it|policy|manipulator|gripper|episode|"
    r"run|trial|rollout)\s+(?:is|has|'s|has\s+been)\s+(?:done|finished|over|complete|completed|through)|"
    r"at the end(?: of (?:the|this|each) (?:episode|trial|run|rollout))?|by the end(?: of (?:the|this) "
    r"(?:episode|trial|run))?|in the end|success(?:\s+(?:means|is when|is that|is defined as|=|:))|the end state is(?: that)?|"
    r"the (?:desired|target|final) (?:state|outcome|result) is(?: that)?|"
    # "what we want at the end is the golf ball sitting on the plate"
    r"what (?:i|we|you) (?:actually |really |just |ultimately )?(?:want|need|expect|would like|'d like|like) (?:to see )?"
    r"(?:at the end |in the end |afterwards )?is(?: that| for)?|"
    r"(?:the (?:run|episode|trial|rollout|test) )?(?:ends|should end|must end|finishes|should finish) with)"
    r"\s*[,:]?\s*(?=the\s)",
    re.IGNORECASE,
)
"""A stated end state ("success means the marble ends up in the cup"): the task, when it reads as one."""
IMPERATIVE = re.compile(
    rf"^\s*(?:(?:please|now|then|and|just|finally|simply|so|also|next|oh|ok|okay|well|alright|lastly)\s*,?\s+)*(?={_VERB}\b)",
    re.IGNORECASE,
)
_INDEFINITE = re.compile(
    r"^\s*(?:up\s+)?(?:a|an|one|two|three|four|five|six|some|several|\d+|another|any|random)\b", re.IGNORECASE
)
_PLACE_WORDS = frozenset(
    {"left", "right", "front", "back", "center", "centre", "middle", "side", "edge", "corner", "table",
     "tabletop", "table top", "surface", "scene", "somewhere", "anywhere", "spot", "area", "rear", "far side",
     "near side", "workspace", "top", "bottom", "place", "position"}
)
_SEGMENT = re.compile(
    r"\n|\|+|;|•|(?<![\d.])\.(?!\d)|(?<=\d)\.(?=\s|$)|[!?]|\s[—–]\s|\s-\s|—"
    # "..., but new plan: put the pear in the bowl instead": a change of mind starts a new statement
    r"|,\s*but\s+(?=(?:let'?s|new plan|change of plan|on second thought|actually|scratch that|now)\b)",
    re.IGNORECASE,
)


INLINE_LABEL = re.compile(
    r"\s*[(,]?\s*(?:that|this)(?:'s|s|\s+is)\s+(?:the\s+)?(?:robot'?s?\s+|arm'?s?\s+|its\s+)?"
    r"(?:whole\s+|only\s+|main\s+|actual\s+|entire\s+)?(?:task|job|goal|objective|mission)\b\s*\)?"
    # "..., that's what I want the robot to do" / "that is what the arm should do"
    r"|\s*[(,]?\s*(?:that|this)(?:'s|s|\s+is)\s+what\s+(?:(?:i|we)(?:'d|\s+would)?\s+(?:want|need|like|expect)\s+"
    r"(?:the\s+)?(?:robot|arm|it|agent|policy)\s+to\s+do|(?:the\s+)?(?:robot|arm|it|agent|policy)\s+"
    r"(?:should|must|has\s+to|needs\s+to|will)\s+do)\b\s*\)?",
    re.IGNORECASE,
)
_GOES = re.compile(
    r"^\s*(?P<x>.+?)\s+(?:goes|belongs|should\s+go|needs\s+to\s+go|has\s+to\s+go|must\s+go|ends?\s+up)\s+"
    r"(?P<rel>on\s+top\s+of|onto|on|into|inside|in|near|next\s+to|beside)\s+(?P<y>.+)$",
    re.IGNORECASE,
)
_VERBLESS = re.compile(
    r"^\s*(?P<x>(?:the\s+)?[a-z0-9' ]{2,40}?)\s+(?P<rel>into|onto|in|inside|on top of|on|next to|near|beside|close to)\s+"
    r"(?P<y>(?:the\s+)?[a-z0-9' ]{2,40}?)\s*$",
    re.IGNORECASE,
)
"""A task said without its verb: "plum into the cup", "apple in bowl" (a whole segment; not "a towel on the left")."""


_NOT_IN_NOUN_PHRASE = frozenset(
    {"is", "are", "was", "were", "be", "and", "or", "with", "also", "there", "here", "it", "they", "i", "we", "you",
     "has", "have", "sits", "stands", "lies", "rests", "table", "scene", "left", "right", "front", "back", "middle",
     "center", "centre", "side", "corner", "edge"}
)
"""Words that do not occur in the two bare noun phrases of a verbless task ("apple in bowl")."""


def _as_command(clause: str) -> str:
    """'the brick goes on the towel' / 'plum into the cup' -> 'put the brick on the towel' (else as given)."""
    m = _GOES.match(clause) or _VERBLESS.match(clause)
    if m is None:
        return clause
    rel = re.sub(r"\s+", " ", m.group("rel").lower())
    verb = "move" if rel in ("near", "next to", "beside", "close to") else "put"
    return f"{verb} {m.group('x')} {rel} {m.group('y')}"


_INTRODUCES = re.compile(r"\b(?:a|an|some|\d+|one|two|three|four|five|six|seven)\s", re.IGNORECASE)
_CLAUSE_END = re.compile(
    r",\s*|\bthen\s+|\band\s+(?=then\b|have\b|let\b|make\b|get\b|(?:the\s+)?(?:robot|arm|agent|gripper|manipulator)\b)|:\s*",
    re.IGNORECASE,
)
_NEW_CLAUSE = re.compile(
    r",?\s*(?:and\s+|but\s+|while\s+|whereas\s+|when\s+|with\s+|plus\s+)?(?:there|it|they|a|an|the|\d+)\b"
    r"|,\s*[a-z][a-z ]{1,20}:"  # ", light: darker 0.35": the next field of a key-value line
    # dictated text: the setup goes on ("... near the hammer and lights a bit brighter and tilt the camera")
    r"|\s+(?:and\s+|also\s+)*(?:the\s+)?(?:lights?|lighting|brightness|camera|cam)\b"
    r"|,?\s+and\s+(?:tilt|pan|rotate|raise|lower|dim|brighten|darken)\b",
    re.IGNORECASE
)
_RELATIVE = re.compile(r",\s*(?=(?:which|that|who)\s+(?:is|are|sits?|stands?|lies|lying)\b)", re.IGNORECASE)


@dataclass(frozen=True)
class TaskStatement:
    """One statement of the task, where it is in the text and how strongly it is marked."""

    start: int
    end: int
    text: str
    frame: Frame
    strength: int
    """2: labelled or about the robot; 1: a bare command."""
    replacement: str = " . "
    """What the statement leaves in the text (the object, when a relative clause about it follows)."""


@dataclass
class FoundTask:
    task: dict[str, Any] | None
    rest: str
    statement: str | None = None
    statements: list[TaskStatement] = field(default_factory=list)
    candidates: list[str] = field(default_factory=list)
    start: int | None = None
    """Where the chosen statement starts in the text."""
    """Statements marked as the task that need the scene to be read ("the robot moves the green
    brick near the pink one", "plum into the cup"), last first; the reader retries them in its scene."""


def _segments(text: str) -> list[tuple[int, int]]:
    spans: list[tuple[int, int]] = []
    pos = 0
    for m in _SEGMENT.finditer(text):
        if m.start() > pos:
            spans.append((pos, m.start()))
        pos = m.end()
    if pos < len(text):
        spans.append((pos, len(text)))
    return spans


def _is_place(phrase: NounPhrase | None) -> bool:
    if phrase is None:
        return False
    words = phrase.text.lower().split()
    return phrase.head.lower() in _PLACE_WORDS or (bool(words) and words[-1] in _PLACE_WORDS)


def _cuts(candidate: str) -> list[tuple[str, int]]:
    """The candidate, then shorter versions cut at clause boundaries (first boundary last), with their lengths."""
    out = [(candidate, len(candidate))]
    for m in reversed(list(re.finditer(
        r",|\s+(?:and|but|while|whereas|when|so that|so|then|with|because)\s+|\(|\)"
        r"|\s+(?=(?:the\s+)?(?:lights?|lighting|brightness|camera|cam)\s)",  # dictated text without commas
        candidate,
    ))):
        head = candidate[: m.start()]
        if head.strip() and head.strip() not in [c.strip() for c, _ in out]:
            out.append((head, m.start()))
    return out


_ARROW = re.compile(
    r"^\s*(?P<src>[^>]+?)\s*(?:->|→|=>)\s*(?P<tgt>[^(]+?)\s*\(\s*(?P<rel>put\s+in|put\s+on|in|into|inside|on|onto|"
    r"on\s+top(?:\s+of)?|near|next\s+to|beside|move\s+near)\s*\)",
    re.IGNORECASE,
)


_TASK_DICT = re.compile(
    r"^\s*\{?\s*type\s*[:=]\s*(?P<task>pick_up|move_near|put_on|put_in)\s*,\s*(?:object|source)\s*[:=]\s*(?P<src>[^,{}]+?)"
    r"\s*(?:,\s*(?:target|destination|container)\s*[:=]\s*(?P<tgt>[^,{}]+?)\s*)?\}?\s*$",
    re.IGNORECASE,
)
_CALL = re.compile(
    r"^\s*(?P<task>pick_up|move_near|put_on|put_in)\s*\(\s*(?P<src>[^,()]+?)\s*(?:,\s*(?P<tgt>[^()]+?)\s*)?\)", re.IGNORECASE
)


_AS_WORDS = {"move_near": "move {} near {}", "put_on": "put {} on {}", "put_in": "put {} in {}"}
"""A two-object task's key word said as a command."""


def _call(text: str) -> str:
    """'put_on(banana, red plate)' / '{type: put_on, object: banana, target: red plate}' -> 'put banana on red plate'."""
    d = _TASK_DICT.match(text)
    if d is not None:
        text = f"{d.group('task')}({d.group('src')}{', ' + d.group('tgt') if d.group('tgt') else ''})"
    m = _CALL.match(text)
    if m is None:
        return text
    task, src, tgt = m.group("task").lower(), m.group("src"), m.group("tgt")
    if task == "pick_up" or tgt is None:
        return f"pick up {src}"
    return _AS_WORDS[task].format(src, tgt) + text[m.end():]


_BARE_ARROW = re.compile(
    r"^\s*(?P<src>[^>]+?)\s*(?:->|→|=>)\s*(?P<rel>put\s+in|put\s+on|into|onto|in|on|near|next\s+to|beside)\s+(?P<tgt>.+?)\s*$",
    re.IGNORECASE,
)


def _arrow(text: str) -> str:
    """'marker -> mug (put in)' / 'marker -> in mug' -> 'put marker in mug'."""
    m = _ARROW.match(text)
    if m is None:
        bare = _BARE_ARROW.match(text)
        if bare is None:
            return text
        rel = bare.group("rel").lower().split()[-1]
        rel = {"into": "in", "onto": "on", "to": "near", "beside": "near"}.get(rel, rel)
        return f"{'move' if rel == 'near' else 'put'} {bare.group('src')} {rel} {bare.group('tgt')}"
    rel = re.sub(r"\s+", " ", m.group("rel").lower())
    rel = {"into": "in", "inside": "in", "onto": "on", "on top": "on", "on top of": "on", "next to": "near",
           "beside": "near"}.get(rel, rel).split()[-1]
    verb = "move" if rel == "near" else "put"
    return f"{verb} {m.group('src')} {rel} {m.group('tgt')}"


_ING = {"grabb": "grab", "putt": "put", "sett": "set", "dropp": "drop", "gett": "get", "tak": "take",
        "plac": "place", "mov": "move", "slid": "slide"}


_FOR_AGENT = re.compile(
    r"^\s*(?:for\s+(?:the\s+)?(?:robot|arm|manipulator|agent|gripper|policy|it)\s+to\s+|that\s+(?:the\s+)?"
    r"(?:robot|arm|manipulator|agent|gripper|policy|it)\s+)",
    re.IGNORECASE,
)


def _normalise(candidate: str) -> str:
    """A statement as an instruction: 'one of the carrots', arrows, '-ing' and third-person verbs undone."""
    candidate = _FOR_AGENT.sub("", candidate)  # "(the aim is) for the manipulator to deposit the die ..."
    # "one of the carrots" -> "the carrot"
    candidate = re.sub(
        r"\b(?:one|any|either|each)\s+of\s+(?:the|those|these)\s+((?:\w+\s+){0,2}?\w+?)(?:e?s)\b"
        r"(?=\s+(?:near|on|onto|in|into|inside|next|to|by|beside|close|up|should|must|will|would|needs?|has|have|"
        r"goes|go|is|are|ends?|can|gets?|sits?)\b|\s*$)",
        r"the \1", candidate, flags=re.IGNORECASE,
    )
    candidate = re.sub(r"\b(?:one|any|either|each)\s+of\s+(?:the|those|these)\s+", "the ", candidate, flags=re.IGNORECASE)
    candidate = _arrow(_call(candidate))
    candidate = re.sub(
        r"^\s*(pick|grabb|grasp|lift|tak|putt|plac|sett|mov|bring|stack|dropp|insert|push|slid|carry|lay|rest|gett)ing\b",
        lambda m: _ING.get(m.group(1).lower(), m.group(1)), candidate, flags=re.IGNORECASE,
    )
    candidate = re.sub(
        r"^\s*(\w+?)(?<!s)s\b",
        lambda m: m.group(1) if re.fullmatch(_VERB, m.group(1), re.IGNORECASE) else m.group(0), candidate,
    )
    candidate = re.sub(r"^\s*picks\s+up\b", "pick up", candidate, flags=re.IGNORECASE)
    return candidate.strip().strip(")(\"'`*").strip()


_KEYWORD_TASK = re.compile(
    r"^\s*(?P<task>move_near|put_on|put_in)\s+(?P<rest>[a-z0-9' ]+?|[a-z0-9' ]+?\s*(?:->|→|=>|,)\s*[a-z0-9' ]+?)\s*$",
    re.IGNORECASE,
)


def _keyword_frame(text: str, reader: Callable[[str], Frame]) -> Frame | None:
    """'put_in pear basket': the task's key word and its two objects, the split the reader grounds best."""
    m = _KEYWORD_TASK.match(text)
    if m is None:
        return None
    pattern = _AS_WORDS[m.group("task").lower()]
    said = re.split(r"\s*(?:->|→|=>|,)\s*", m.group("rest"))
    if len(said) == 2:  # "put_on carrot->sponge"
        frames = [reader(pattern.format(*said))]
    else:
        words = m.group("rest").split()
        frames = [reader(pattern.format(" ".join(words[:k]), " ".join(words[k:]))) for k in range(1, len(words))]
    frames = [f for f in frames if f.task in TASKS and f.object is not None and f.destination is not None and f.ok]
    grounded = [f for f in frames if f.object and f.object.object_id and f.destination and f.destination.object_id]
    best = grounded or frames
    return best[0] if best else None


def _read_one(candidate: str, reader: Callable[[str], Frame]) -> Frame | None:
    text = _normalise(candidate)
    if not text:
        return None
    frame = _keyword_frame(text, reader) or reader(text)
    if any(p is not None and p.candidates for p in (frame.object, frame.destination)):
        return None  # "the cup" with several cups in the catalog: only the scene can say which
    if frame.object is not None and frame.object.head in _SETTING_WORDS:
        return None  # "drop the brightness to 90 %": a setting, not an object
    if frame.task in TASKS and frame.object is not None and frame.ok:
        if frame.task != "pick_up" and (frame.destination is None or _is_place(frame.destination)):
            return None
        return frame
    return None


def _needs_scene(candidate: str, reader: Callable[[str], Frame]) -> bool:
    """A command of the four tasks whose object or destination several catalog objects fit."""
    frame = reader(_normalise(candidate))
    if frame.task not in TASKS or frame.object is None or not frame.ok:
        return False
    if frame.task != "pick_up" and (frame.destination is None or _is_place(frame.destination)):
        return False
    return any(p is not None and p.candidates for p in (frame.object, frame.destination))


def _read_span(candidate: str, reader: Callable[[str], Frame]) -> tuple[Frame, int] | None:
    """The frame a statement gives, and how much of the candidate it used (None: no task in it)."""
    # an aside in brackets is not part of the statement ("move the pear near the plum (objects: pear,
    # plum and a plate)"): read without it, and leave it in the text when it ends the statement
    blank = candidate
    if not (_ARROW.match(candidate) or _CALL.match(candidate) or _TASK_DICT.match(candidate)):
        blank = re.sub(r"(?<=\s)\([^()]*\)", lambda m: " " * len(m.group(0)), candidate)
    cuts = [(raw, min(used, len(raw.rstrip()))) for raw, used in _cuts(blank)]
    for k, (raw, used) in enumerate(cuts):
        frame = _read_one(raw, reader)
        if frame is None:
            continue
        # the shortest cut that reads the same: what follows it is another clause about the scene
        for shorter, length in cuts[k + 1:]:
            again = _read_one(shorter, reader)
            if again is not None and _same_frame(again, frame):
                used = length
        return frame, used
    return None


def _same_frame(a: Frame, b: Frame) -> bool:
    def key(f: Frame) -> tuple[str | None, str | None, str | None]:
        return (f.task, f.object.text if f.object else None, f.destination.text if f.destination else None)

    return key(a) == key(b)


def _read(candidate: str, reader: Callable[[str], Frame]) -> Frame | None:
    found = _read_span(candidate, reader)
    return found[0] if found is not None else None


def _it_as_named(seg: str, before: str, names: Mapping[str, str] | None) -> str:
    """ "put the banana on it": 'it' after a relation is the object named last before the statement."""
    if not names or not re.search(rf"\b{_RELATION_WORD}\s+it\b", seg, re.IGNORECASE):
        return seg
    pattern = "|".join(re.escape(n) for n in sorted(set(names.values()), key=len, reverse=True))
    said = list(re.finditer(rf"(?<![a-z])(?:{pattern})(?![a-z])", before.lower()))
    if not said:
        return seg
    return re.sub(rf"\b({_RELATION_WORD})\s+it\b", rf"\1 the {said[-1].group(0)}", seg, count=1, flags=re.IGNORECASE)


_RELATION_WORD = r"(?:on top of|onto|on|into|inside|in|next to|near|beside)"


def _statements(text: str, reader: Callable[[str], Frame], names: Mapping[str, str] | None = None) -> list[TaskStatement]:
    found: list[TaskStatement] = []
    spans = _segments(text)
    for i, (s, e) in enumerate(spans):
        seg = text[s:e]
        marked = None
        for pattern in (LABEL, AGENT_MODAL, WANT_TO, AGENT_DOES):
            m = pattern.search(seg)
            if m is not None and (marked is None or m.end() < marked):
                marked = m.end()
        passive = PASSIVE.search(seg)
        if passive is not None and re.search(r"\b(?:camera|cam|view|lights?|lighting|brightness|illumination)\b",
                                             seg[: passive.start()], re.IGNORECASE):
            passive = None  # "the camera should be moved 4 cm closer": a setting, not the task
        if marked is None and passive is not None:
            said = re.sub(r"\s+by\s+(?:the\s+)?(?:robot|arm|manipulator|gripper|agent)\b", "", seg, flags=re.IGNORECASE)
            frame = _read(said, reader)
            if frame is not None:
                # "Strawberry must be put inside the big blue cup by robot": a passive command
                found.append(TaskStatement(s, e, said.strip(), frame, 1))
                continue
            if _needs_scene(said, reader):
                found.append(TaskStatement(s, e, _normalise(said.strip()), reader(""), -2))
                continue
        need = NEED_THE.search(seg)
        if marked is None and need is not None and _read_span(seg[need.start():], reader) is not None:
            marked = need.start()  # "I need the knife near the fork": an end state is the task
        end_state = END_STATE.search(seg)
        if marked is None and end_state is not None and _read_span(seg[end_state.end():], reader) is not None:
            marked = end_state.end()  # "At the end of the episode the carrot should be inside the basket"
        if marked is not None:
            span = _read_span(seg[marked:], reader)
            frame = span[0] if span is not None else None
            if frame is not None and span is not None:
                label = LABEL.search(seg)
                if label is not None:
                    # "Correction: the task is to ...": a one-word heading goes with the statement
                    heading = re.fullmatch(r"\s*[a-z]+\s*[:-]\s*", seg[: label.start()], re.IGNORECASE)
                    start = s if heading is not None else s + label.start()
                else:
                    # from the clause the statement starts in ("A and B at the back, then have the robot ...")
                    bounds = [m.end() for m in _CLAUSE_END.finditer(seg[:marked])]
                    first = min((m.start() for p in (AGENT_MODAL, WANT_TO, AGENT_DOES) if (m := p.search(seg))), default=0)
                    before = [b for b in bounds if b <= first]
                    start = s + (before[-1] if before else 0)
                end, keep = e, " . "
                if span[1] < len(seg) - marked and _NEW_CLAUSE.match(seg, marked + span[1]):
                    end = s + marked + span[1]  # "..., and there is a green cube at the front" stays
                rel = _RELATIVE.search(seg, marked)
                if rel is not None and frame.object is not None:
                    end, keep = s + rel.start(), f" . the {frame.object.text} "
                found.append(TaskStatement(start, end, seg[marked:].strip(), frame, 2, keep))
                continue
            if LABEL.search(seg) and seg[marked:].strip():
                # what a label introduces may be said in any of the ways a statement can be ("Task: at
                # the end, the sponge should be inside the cup"); else it is the unreadable task statement
                inner = [t for t in _statements(seg[marked:], reader, names) if t.strength >= 1]
                if inner:
                    found.append(TaskStatement(s, e, inner[-1].text, inner[-1].frame, 2))
                else:
                    found.append(TaskStatement(s, e, seg[marked:].strip(), reader(seg[marked:].strip()), 0))
                continue
            if seg[marked:].strip():
                # about the robot, but only its scene can say which objects: read again there
                # (from the clause the statement starts in, as above)
                bounds = [m.end() for m in _CLAUSE_END.finditer(seg[:marked])]
                first = min((m.start() for p in (AGENT_MODAL, WANT_TO, AGENT_DOES) if (m := p.search(seg))), default=0)
                before = [b for b in bounds if b <= first]
                start = s + (before[-1] if before else 0)
                found.append(TaskStatement(start, e, _normalise(seg[marked:].strip()), reader(""), -2))
                continue
        inline = INLINE_LABEL.search(seg)
        if inline is not None and seg[: inline.start()].strip():
            # "the small brick goes on the towel (that's the task), not the pink one"
            said = _as_command(seg[: inline.start()])
            frame = _read(said, reader)
            if frame is not None:
                found.append(TaskStatement(s, e, said.strip(), frame, 2))
            else:
                found.append(TaskStatement(s, e, _normalise(said), reader(""), -2))
            continue
        if _ARROW.match(seg) or _BARE_ARROW.match(seg):
            # "foam brick -> near blue cube": a line that maps an object to where it goes
            frame = _read(seg, reader)
            if frame is not None:
                found.append(TaskStatement(s, e, _arrow(seg).strip(), frame, 1))
                continue
        # "I'm testing put-in behaviour: the bottle goes into the basket": the clause after a colon
        tail = seg[seg.rfind(":") + 1:] if ":" in seg else seg
        goes = _GOES.match(tail)
        if (
            goes is not None and IMPERATIVE.match(tail) is None
            # "the carrot goes ...", "one of the balls goes ...", "one plum should go ..."
            and re.match(r"\s*(?:the|that|this|one of the|one)\s", goes.group("x"), re.IGNORECASE)
            and (not re.match(r"(?:near|next|beside)", goes.group("rel"), re.IGNORECASE)
                 or re.search(r"\bend\s+up\b", tail, re.IGNORECASE))  # "goes near" may be a layout; "ends up near" is not
            and not re.search(r",|;|\band\b", goes.group("y"))
        ):
            # "The carrot goes on the red plate.": an end state for an object named before is the task
            said = _as_command(tail)
            frame = _read(said, reader)
            if frame is not None:
                found.append(TaskStatement(s, e, said, frame, 1))
                continue
        # "Plum into the cup.": a task said without its verb, as a whole segment or after the list it
        # ends ("coke can + bowl, coke next to bowl"). With a plain "in" / "on" only a phrase that
        # introduces nothing ("apple in bowl", not "a towel on the plate").
        offsets = [0] + ([seg.rfind(",") + 1] if "," in seg and _RETRACT.match(seg) is None else [])
        said_verbless = None
        for offset in offsets:
            part = seg[offset:]
            verbless = _VERBLESS.match(part)
            if verbless is None or IMPERATIVE.match(part) is not None or re.match(rf"\s*{_VERB}\b", part, re.IGNORECASE):
                continue
            strict = verbless.group("rel").lower() in ("into", "onto")
            words = set(f"{verbless.group('x')} {verbless.group('y')}".lower().split())
            nouns_only = not words & _NOT_IN_NOUN_PHRASE and len(verbless.group("x").split()) <= 4
            if not nouns_only or (not strict and _INDEFINITE.match(verbless.group("x"))):
                continue
            said = _as_command(part)
            frame = _read(said, reader)
            if frame is not None:
                said_verbless = TaskStatement(s + offset, e, said, frame, 1)
            elif strict and offset == 0:
                said_verbless = TaskStatement(s, e, _normalise(said), reader(""), -2)
            if said_verbless is not None:
                break
        if said_verbless is not None:
            found.append(said_verbless)
            continue
        retracted = _RETRACT.match(seg)
        if retracted is not None and found and found[-1].frame.object is not None:
            # "... place the strawberry on the sponge... hmm, no, put it in the cup instead": the new task
            said = re.sub(rf"^\s*({_VERB})\s+it\b", rf"\1 the {found[-1].frame.object.text}", seg[retracted.end():],
                          flags=re.IGNORECASE)
            said = re.sub(r"\s*\binstead\b\s*", " ", said).strip()
            earlier = found[-1].frame.destination
            if earlier is not None:  # "... actually put the strawberry in it instead": 'it' is the destination said before
                said = re.sub(rf"\b({_RELATION_WORD})\s+it\b", rf"\1 the {earlier.text}", said, count=1, flags=re.IGNORECASE)
            frame = _read(said, reader)
            if frame is not None:
                found.append(TaskStatement(s, e, said, frame, 3))
                continue
        m = IMPERATIVE.match(seg)
        colon = seg.rfind(":")
        if m is None and colon > 0 and LABEL.search(seg[: colon + 1]) is None and IMPERATIVE.match(seg[colon + 1:]):
            # "..., but let's change that: move the red apple next to the cup instead": the command after the colon
            s, seg = s + colon + 1, seg[colon + 1:]
            m = IMPERATIVE.match(seg)
        if m is None:
            continue
        seg = _it_as_named(seg, text[:s], names)
        after_verb = re.sub(rf"^\s*{_VERB}\s*(?:up\s+)?", "", seg[m.end():], flags=re.IGNORECASE)
        span = _read_span(seg[m.end():], reader)
        frame = span[0] if span is not None else None
        if span is not None and (
            seg[m.end() + span[1]:].lstrip().startswith("(") or _NEW_CLAUSE.match(seg, m.end() + span[1])
        ):
            # what follows the command stays in the text: "(objects: pear, plum and a plate)", ", and tilt the camera"
            e = s + m.end() + span[1]
        if frame is None:
            if _needs_scene(seg[m.end():], reader):
                # "put the small yellow brick on the sponge": which brick, only the scene says
                found.append(TaskStatement(s, e, _normalise(seg[m.end():].strip()), reader(""), -2))
            continue
        said_before = frame.object is not None and (
            re.search(rf"\b{re.escape(frame.object.head.rstrip('y'))}", text[:s], re.IGNORECASE) is not None
            or (  # "two dice ... pick up a die": the object the catalog grounds it on, by its name
                names is not None and frame.object.object_id is not None and frame.object.object_id in names
                and re.search(rf"\b{re.escape(names[frame.object.object_id])}", text[:s], re.IGNORECASE) is not None
            )
        )
        if _INDEFINITE.match(after_verb) and not said_before:
            continue  # "put a carrot near the plate" sets the scene; "two apples ... put an apple in" is the task
        back = i + 1 < len(spans) and BACK_LABEL.match(text[spans[i + 1][0]:spans[i + 1][1]]) is not None
        # "... move the red apple next to the cup instead": a command that replaces one said before
        replaces = re.search(r"\binstead\s*$", seg, re.IGNORECASE) is not None and bool(found)
        found.append(TaskStatement(s, e, seg[m.end():].strip(), frame, 3 if replaces else 2 if back else 1))
        if back:
            ns, ne = spans[i + 1]
            found.append(TaskStatement(ns, ne, "", frame, -1))  # the tag itself, removed with the statement
    return found


def _mention(phrase: NounPhrase | None, names: Mapping[str, str]) -> str | None:
    """The catalog name a phrase grounds to when its head noun is in that name; else the phrase as written."""
    if phrase is None:
        return None
    if phrase.object_id is not None and phrase.object_id in names:
        name = names[phrase.object_id]
        if phrase.head.lower() in name.split():
            return name
    return phrase.text


def find_task(
    text: str,
    names: Mapping[str, str] | None = None,
    reader: Callable[[str], Frame] | None = None,
) -> FoundTask:
    """The task a description states (or None), and the description without its task statements.

    ``names`` maps catalog ids to the names the scene reader knows them by (the
    prompt's object list), so that the task's objects are the described ones.
    """
    read = reader or read_instruction
    # "put the marble - not the die - on the box", "(not the carrot)": asides that name what is not meant
    text = re.sub(r"\s[—–-]+\s*not\s+(?:the|a|an)\s+[^—–\n.-]+?\s*[—–-]+\s", " ", text, flags=re.IGNORECASE)
    text = re.sub(r"\(\s*not\s+(?:the|a|an)\s+[^)]*\)", " ", text, flags=re.IGNORECASE)
    text = re.sub(r"\b(wait|no|sorry|hmm+|actually|oops)\s*[—–]+\s*", r"\1, ", text, flags=re.IGNORECASE)
    # "make it the tennis ball that goes in the bowl": a cleft correction is the command it clefts
    text = re.sub(
        r"\b(?:make\s+(?:it|that)|it(?:'s|\s+is|\s+should\s+be))\s+(the\s+[\w' ]+?)\s+(?:that|which)\s+"
        r"(?:goes|should\s+go|must\s+go|needs\s+to\s+go|gets\s+put|is\s+put|should\s+be\s+put)\s+"
        r"(into|in|inside|onto|on|on\s+top\s+of|next\s+to|near|beside)\s+",
        lambda m: f"{'move' if m.group(2).lower() in ('next to', 'near', 'beside') else 'put'} {m.group(1)} {m.group(2)} ",
        text, flags=re.IGNORECASE,
    )
    statements = _statements(text, read, names)
    unreadable = [s for s in statements if s.strength == 0]
    maybe = [s for s in statements if s.strength == -2]
    ranked = [(s.strength, k, s) for k, s in enumerate(statements) if s.strength >= 1]
    chosen = max(ranked, key=lambda r: (r[0], r[1]))[2] if ranked else None  # strongest, then last
    # a statement to read in the scene leaves the text unless it introduces objects ("set up a table with a ...")
    maybe_out = [s for s in maybe if not _INTRODUCES.search(s.text)]
    removed = [s for s in statements if s.strength in (3, 2, 0, -1)] + maybe_out + ([chosen] if chosen is not None else [])
    rest = text
    spans = {(s.start, s.end): s.replacement for s in removed}
    for (a, b), keep in sorted(spans.items(), reverse=True):
        rest = rest[:a] + keep + rest[b:]
    candidates = [s.text for s in reversed(maybe)]
    if chosen is None:
        if unreadable:
            return FoundTask(None, rest, unreadable[-1].text, statements, candidates)
        return FoundTask(None, rest, None, statements, candidates)
    names = names or {}
    frame = chosen.frame
    task = {
        "type": frame.task,
        "source": _mention(frame.object, names),
        "target": _mention(frame.destination, names) if frame.task != "pick_up" else None,
    }
    return FoundTask(task, rest, chosen.text, statements, candidates, chosen.start)
