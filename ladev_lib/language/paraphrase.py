"""The offline paraphraser: compositional, seeded, k distinct sentences.

A paraphrase is a *verb phrase* for the task (verb synonyms, relation
synonyms, "pick up X and put it on Y", "move X so that it is next to Y"),
wrapped in a *frame* (plain, polite, question, casual, with added context),
with each object named by its display name or a catalog synonym. Some tasks
also have whole-sentence forms that reorder the roles ("on top of the plate,
place the carrot", "the carrot should go on the plate").

    offline_paraphrases("put_on", "carrot", "plate", k=3, seed=0)
    -> ["Could you lay the orange carrot on top of the dish?", ...]

The generator draws verb phrases and frames in a shuffled round-robin, so k
candidates differ in structure, not only in one word. It never returns the
basic instruction itself, and never the same sentence twice (compared
case- and punctuation-insensitively).
"""

from __future__ import annotations

import random
import re
from collections.abc import Sequence

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.language.instructions import basic_instruction

# (imperative, gerund) verb phrases per task; {S} source, {T} target.
_GERUND = {
    "move": "moving", "bring": "bringing", "slide": "sliding", "push": "pushing",
    "place": "placing", "put": "putting", "set": "setting", "shift": "shifting",
    "position": "positioning", "nudge": "nudging", "lay": "laying", "rest": "resting",
    "drop": "dropping", "insert": "inserting", "lower": "lowering", "stand": "standing",
}
_NEAR = ("near", "next to", "beside", "close to", "right next to")
_ON = ("on", "onto", "on top of")
_IN = ("in", "into", "inside")


def _relation_phrases(verbs: Sequence[str], relations: Sequence[str]) -> list[tuple[str, str]]:
    return [(f"{v} {{S}} {r} {{T}}", f"{_GERUND[v]} {{S}} {r} {{T}}") for v in verbs for r in relations]


VERB_PHRASES: dict[str, list[tuple[str, str]]] = {
    "pick_up": [
        ("pick up {S}", "picking up {S}"),
        ("pick {S} up", "picking {S} up"),
        ("lift {S}", "lifting {S}"),
        ("lift up {S}", "lifting up {S}"),
        ("grab {S}", "grabbing {S}"),
        ("grasp {S}", "grasping {S}"),
        ("take hold of {S}", "taking hold of {S}"),
        ("pick {S} up off the table", "picking {S} up off the table"),
        ("lift {S} off the table", "lifting {S} off the table"),
        ("pick up {S} from the table", "picking up {S} from the table"),
        ("grab {S} and lift it", "grabbing {S} and lifting it"),
        ("raise {S}", "raising {S}"),
    ],
    "move_near": [
        *_relation_phrases(("move", "bring", "slide", "push", "place", "put", "set", "shift", "position", "nudge"), _NEAR),
        ("move {S} so that it is next to {T}", "moving {S} so that it is next to {T}"),
        ("bring {S} over to {T}", "bringing {S} over to {T}"),
        ("slide {S} until it is close to {T}", "sliding {S} until it is close to {T}"),
        ("pick up {S} and set it down next to {T}", "picking up {S} and setting it down next to {T}"),
        ("grab {S} and put it near {T}", "grabbing {S} and putting it near {T}"),
    ],
    "put_on": [
        *_relation_phrases(("put", "place", "set", "lay", "rest", "lower"), _ON),
        ("pick up {S} and put it on {T}", "picking up {S} and putting it on {T}"),
        ("grab {S} and place it on top of {T}", "grabbing {S} and placing it on top of {T}"),
        ("lift {S} and set it down on {T}", "lifting {S} and setting it down on {T}"),
    ],
    "put_in": [
        *_relation_phrases(("put", "place", "drop", "insert", "lower"), _IN),
        ("pick up {S} and drop it into {T}", "picking up {S} and dropping it into {T}"),
        ("grab {S} and put it inside {T}", "grabbing {S} and putting it inside {T}"),
    ],
}

# Whole sentences that reorder the roles; no frame goes around them.
STANDALONE: dict[str, list[str]] = {
    "pick_up": ["{S} needs to be picked up", "{S}, pick it up"],
    "move_near": ["{S} should end up next to {T}", "next to {T}, put {S}", "{S} goes beside {T}"],
    "put_on": ["on top of {T}, place {S}", "{S} should go on {T}", "onto {T} with {S}, please"],
    "put_in": ["into {T}, put {S}", "{S} should go in {T}", "{S} belongs inside {T}"],
}

# Frames: {VP} an imperative verb phrase, {VPG} its gerund form.
FRAMES: tuple[str, ...] = (
    "{VP}",
    "please {VP}",
    "{VP}, please",
    "could you {VP}?",
    "can you {VP}?",
    "would you {VP}?",
    "could you please {VP}?",
    "would you mind {VPG}?",
    "how about {VPG}?",
    "i'd like you to {VP}",
    "i need you to {VP}",
    "i want you to {VP}",
    "let's {VP}",
    "go ahead and {VP}",
    "your task is to {VP}",
    "try to {VP}",
    "now {VP}",
    "{VP} for me",
    "it would be great if you could {VP}",
    "{VP}, thanks",
    "carefully {VP}",
    "gently {VP}",
    "{VP} with your gripper",
    "using your gripper, {VP}",
    "okay robot, {VP}",
    "hey robot, {VP}",
    "time to {VP}",
    "make sure to {VP}",
    "robot, please {VP}",
    "whenever you're ready, {VP}",
)

# Catalog synonyms that help matching but nobody says ("ycb apple", "bridge plate").
_UNSPOKEN = re.compile(r"\b(ycb|bridge)\b")
STANDALONE_SHARE = 0.15


def spoken_names(catalog: Catalog, object_id: str) -> list[str]:
    """Names a person would use for the object: the display name, then synonyms."""
    obj = catalog.get(object_id)
    return [n for n in obj.names if not _UNSPOKEN.search(n.lower())]


def sentence_key(text: str) -> str:
    """Case-, punctuation- and spacing-insensitive form, for duplicate checks."""
    return " ".join(re.sub(r"[^a-z0-9' ]", " ", text.lower().replace("'", "")).split())


def offline_paraphrases(
    task: str,
    source: str,
    target: str | None,
    k: int,
    seed: int = 0,
    catalog: Catalog | None = None,
) -> list[str]:
    """Up to ``k`` distinct paraphrases of the basic instruction for (task, source, target)."""
    if task not in VERB_PHRASES:
        raise ValueError(f"unknown task {task!r}; known: {', '.join(VERB_PHRASES)}")
    if k < 0:
        raise ValueError(f"k must be >= 0, got {k}")
    cat = catalog or load_catalog()
    source_names = spoken_names(cat, source)
    target_names = spoken_names(cat, target) if target else [""]
    original = basic_instruction(task, cat.get(source).display_name, cat.get(target).display_name if target else None)
    rng = random.Random(f"ladev-paraphrase:{seed}:{task}:{source}:{target}")
    phrases = list(VERB_PHRASES[task])
    frames = list(FRAMES)
    standalone = list(STANDALONE[task])
    rng.shuffle(phrases)
    rng.shuffle(frames)
    rng.shuffle(standalone)

    seen = {sentence_key(original)}
    out: list[str] = []
    attempt = 0
    while len(out) < k and attempt < 40 * max(k, 1):
        if standalone and rng.random() < STANDALONE_SHARE:
            template = standalone[attempt % len(standalone)]
        else:
            imperative, gerund = phrases[attempt % len(phrases)]
            frame = frames[(attempt * 7) % len(frames)]
            template = frame.replace("{VP}", imperative).replace("{VPG}", gerund)
        attempt += 1
        sentence = _fill(template, rng, source_names, target_names)
        key = sentence_key(sentence)
        if key not in seen:
            seen.add(key)
            out.append(sentence)
    return out


def _fill(template: str, rng: random.Random, source_names: list[str], target_names: list[str]) -> str:
    def noun(names: list[str]) -> str:
        # The display name half of the time, a synonym otherwise.
        name = names[0] if len(names) == 1 or rng.random() < 0.5 else rng.choice(names[1:])
        return f"the {name}"

    text = template.replace("{S}", noun(source_names)).replace("{T}", noun(target_names))
    return text[0].upper() + text[1:]
