"""The words the instruction parser knows: verbs by role, relations, frames.

Only words that decide a task's structure are listed. Everything else in an
instruction (politeness, hedges, adverbs, "robot", "real quick") is noise to
the parser, so a new filler word never breaks a parse; a new *verb* does (an
unknown verb reads as no task, which rejects a candidate rather than
accepting a wrong one).
"""

from __future__ import annotations

from collections.abc import Iterable

# -- verbs ---------------------------------------------------------------------
# Classes:
#   pick      grasp and lift ("pick up", "grab"); with a directional relation
#             to an object they place instead ("take the apple to the sponge").
#   place     move the object somewhere; need a destination ("put", "slide").
#   other     a task outside the four ("knock over", "hand me", "peel").
#   preamble  perception / approach before the task ("find", "reach for").
#   release   let go after placing ("release").
# Verbs that are harmless when negated ("don't drop it", "don't squeeze it")
# are in MANNER_VERBS: a negated manner verb without a destination is a
# constraint on how to do the task, not a negation of the task.

_PICK = "pick lift grab grasp take get raise hoist seize snatch collect pluck scoop hold fetch retrieve snag nab grip clutch obtain acquire elevate clasp"
_PLACE = (
    "put place set lay rest drop lower position move bring slide push shove nudge shift drag carry "
    "transfer relocate reposition stack stick pop toss throw chuck insert deposit tuck stash load "
    "dump sit stand park leave roll go end belong plop slip return transport"
)
_OTHER = (
    "knock tip topple open close shake squeeze eat peel point touch tap poke hit kick spin rotate "
    "turn flip wipe clean wash wrap cover hand give pass show write cut pour fill empty crush break "
    "smash remove unstack unload tilt stir bite lick smell juggle balance bounce play cap"
)
_PREAMBLE = "find locate look spot identify see notice reach approach head use watch check steer guide clamp tighten"
_RELEASE = "release"

MANNER_VERBS: frozenset[str] = frozenset(
    ["drop", "spill", "squeeze", "crush", "break", "damage", "knock", "bump", "hit", "touch", "hurt", "rush", "tip", "topple", "shake", "bang", "dent", "scratch", "lose", "smash", "disturb", "move"]
)

# Irregular forms (base -> extra forms). "left" is deliberately not a form of
# "leave": in instructions it is nearly always a direction.
_IRREGULAR: dict[str, tuple[str, ...]] = {
    "take": ("took", "taken"),
    "hold": ("held",),
    "lay": ("laid",),
    "bring": ("brought",),
    "slide": ("slid",),
    "stick": ("stuck",),
    "throw": ("threw", "thrown"),
    "sit": ("sat",),
    "stand": ("stood",),
    "go": ("went", "gone", "goes"),
    "get": ("got", "gotten"),
    "seize": (),
    "give": ("gave", "given"),
    "eat": ("ate", "eaten"),
    "break": ("broke", "broken"),
    "see": ("saw", "seen"),
    "find": ("found",),
    "spin": ("spun",),
    "write": ("wrote", "written"),
    "shake": ("shook", "shaken"),
    "bite": ("bit", "bitten"),
    "lose": ("lost",),
    "hit": (),
    "cut": (),
    "put": (),
    "set": (),
}
# One-syllable verbs whose final consonant doubles before -ing / -ed.
_DOUBLING = frozenset(
    ["grab", "drop", "pop", "set", "put", "get", "sit", "snag", "nab", "drag", "slip", "tap", "stop", "plop", "flip", "hit", "stir", "grip", "cut", "spin", "tip", "dump", "nab", "chop", "knock"]
) - {"knock", "dump"}


def _forms(base: str) -> set[str]:
    forms = {base}
    if base.endswith(("s", "sh", "ch", "x", "z")):
        forms.add(base + "es")
    elif base.endswith("y") and base[-2] not in "aeiou":
        forms.add(base[:-1] + "ies")
    else:
        forms.add(base + "s")
    if base in _DOUBLING:
        stem = base + base[-1]
    elif base.endswith("e") and not base.endswith("ee"):
        stem = base[:-1]
    else:
        stem = base
    forms.add(stem + "ing")
    if base.endswith("y") and base[-2] not in "aeiou":
        forms.add(base[:-1] + "ied")
    elif base.endswith("e"):
        forms.add(base + "d")
    else:
        forms.add(stem + "ed")
    forms.update(_IRREGULAR.get(base, ()))
    return forms


def _verb_table(classes: Iterable[tuple[str, str]]) -> dict[str, tuple[str, str]]:
    table: dict[str, tuple[str, str]] = {}
    for cls, words in classes:
        for base in words.split():
            for form in _forms(base):
                table.setdefault(form, (cls, base))
    return table


VERBS: dict[str, tuple[str, str]] = _verb_table(
    [("pick", _PICK), ("place", _PLACE), ("release", _RELEASE), ("other", _OTHER), ("preamble", _PREAMBLE)]
)
"""Inflected form -> (class, lemma). A word in two classes keeps the first listed."""

# Pick verbs that still pick up with a "from" / "off" phrase ("lift the hammer off the bench");
# "take the carrot off the plate" takes it away instead.
LIFT_VERBS = frozenset({"pick", "lift", "grab", "grasp", "raise", "hoist", "seize", "snatch", "pluck", "scoop", "grip"})
# Verbs of the pick class that place when given any relation to an object
# ("get the carrot on the plate"), not only a directional one.
PICK_PLACES_WITH_STATIVE = frozenset({"get"})
# Verbs that move the *robot*, not an object, when the clause has no object.
SELF_MOTION = frozenset({"go", "head", "reach", "approach", "move", "come"})

# Multi-word verbs, matched on any inflection of their first word ("taking hold
# of" too): the words after the verb are dropped, and the verb is replaced by
# the given word, or kept (None).
PHRASAL_VERBS: dict[tuple[str, ...], str | None] = {
    ("take", "hold", "of"): None,
    ("get", "hold", "of"): None,
    ("grab", "hold", "of"): None,
    ("catch", "hold", "of"): "grasp",
    ("lay", "hold", "of"): "grasp",
    ("let", "go", "of"): "release",
    ("let", "go"): "release",
    ("let", "it", "go"): "release",
    ("knock", "over"): None,
    ("look", "at"): None,
    ("look", "for"): None,
    ("reach", "for"): None,
    ("end", "up"): None,
    ("hand", "over"): None,
}

# -- relations -----------------------------------------------------------------
# kind: near | on | in (the tasks' relations), other:<word> (a relation that is
# none of them: "behind", "under"), reverse:<word> (taking away: "off", "out of").
RELATIONS: dict[tuple[str, ...], str] = {}


def _add_relations(kind: str, phrases: str) -> None:
    for phrase in phrases.split(","):
        RELATIONS[tuple(phrase.split())] = kind


_add_relations(
    "near",
    "near,nearby,near to,nearer to,next to,right next to,close to,closer to,close by,beside,besides,"
    "by,by the side of,alongside,adjacent to,up to,over to,over by,right by,toward,towards,to,"
    "in the vicinity of,in proximity to,in the proximity of,at the side of,next door to,"
    "in the direction of,in close proximity to,in the immediate vicinity of,close beside,right beside",
)
_add_relations("on", "on,onto,on to,on top of,on the top of,upon,atop,over onto")
_add_relations("in", "in,into,in to,inside,inside of,within,down into")
_add_relations(
    "other",
    "in front of,to the left of,to the right of,left of,right of,on the left of,on the right of,"
    "on the left side of,on the right side of,behind,under,underneath,beneath,below,above,over,"
    "around,between,across,against,at,through,with,of,for,opposite,in back of,along",
)
_add_relations("reverse", "away from,far from,far away from,out of,off of,off,from,out,away")
RELATION_MAX_LEN = max(len(k) for k in RELATIONS)

DIRECTIONAL = frozenset(
    {("onto",), ("on", "to"), ("into",), ("in", "to"), ("to",), ("toward",), ("towards",),
     ("over", "to"), ("up", "to"), ("over", "onto"), ("down", "into")}
)

# -- "to" and "above" as placements ------------------------------------------------
# "to" is "near" ("shift the lamp over to the monitor"), except after a verb that
# carries the object there when what it is carried to is a receptacle or a surface:
# "move the mug to the tray" puts it on the tray, "bring the apple to the basket"
# puts it in the basket. Other nouns keep "near" ("move the stapler to the laptop").
CARRY_VERBS = frozenset({"move", "bring", "carry", "take", "transfer", "transport", "relocate", "go", "belong", "end", "land"})
"""Verbs (lemmas) that carry an object to where "to" points ("the cup goes to the tray": it is carried there)."""
CARRY_TO = frozenset({("to",)})
"""Relation phrases that, after a carrying verb, end at a receptacle ("move it over to the pot" stays near)."""
CARRY_ALL_THE_WAY = frozenset({"carry", "transfer", "transport", "haul", "lug", "ferry"})
"""Verbs whose object is carried all the way, "over to" a receptacle too: "carry the banana over to the plate"."""
SURFACE_HEADS = frozenset(
    ["plate", "dish", "platter", "saucer", "tray", "rack", "shelf", "stove", "stovetop", "burner", "board", "mat", "placemat", "coaster"]
)
"""Head nouns of things an object is put on: carried "to" one, it ends on it."""
CONTAINER_HEADS = frozenset(
    ["basket", "bin", "bowl", "drawer", "caddy", "compartment", "slot", "section", "cubby", "sink", "pot", "bucket", "crate", "tub", "jar", "mug", "cup", "holder", "organizer", "fridge", "refrigerator", "microwave", "oven", "dishwasher",
     "cupboard", "cabinet", "closet", "locker", "wardrobe"]
)
"""Head nouns of things an object is put in: carried "to" one, it ends inside it (storage furniture
too: "put the jam to the cupboard", learner English for "in")."""
PUT_VERBS = frozenset({"put", "place", "set", "lay", "rest", "position", "stack", "sit", "stand", "park", "deposit", "plop"})
"""Verbs (lemmas) of putting down: "put X above Y" puts X on Y."""
ABOVE_AS_ON = frozenset({("above",)})
"""Relation phrases that mean "on" after a putting verb."""

# Words for the same position or part of a thing, compared as one word when two
# phrases name a destination or a landmark ("rear compartment" is "back compartment").
POSITION_SYNONYMS: dict[str, str] = {
    "rear": "back",
    "hind": "back",
    "middle": "center",
    "centre": "center",
    "central": "center",
    "mid": "center",
    "upper": "top",
    "uppermost": "top",
    "topmost": "top",
    "lower": "bottom",
    "lowest": "bottom",
    "bottommost": "bottom",
    "slot": "compartment",
    "section": "compartment",
    "cubby": "compartment",
    "cubbyhole": "compartment",
    "pocket": "compartment",
    # a surface named with its "top" is the furniture itself
    "countertop": "counter",
    "worktop": "counter",
    "tabletop": "table",
    "stovetop": "stove",
    "benchtop": "bench",
    "workbench": "bench",
}


def position_word(word: str) -> str:
    """The one word for a position or part ("rear" -> "back", "slot" -> "compartment")."""
    return POSITION_SYNONYMS.get(word, word)


SIDE_WORDS = frozenset({"left", "right"})
"""Sides, which describe the noun after them ("the right slot") even where "right" is an adverb,
and name a place after a determiner ("the bowl on the right")."""

OPPOSITE_POSITIONS: dict[str, str] = {
    "left": "right", "right": "left", "front": "back", "back": "front", "top": "bottom", "bottom": "top",
}
"""Positions that exclude each other: "the left notebook" is not "the notebook on the right"."""

SIZE_CLASSES: dict[str, str] = {
    "small": "small", "little": "small", "mini": "small", "tiny": "small",
    "large": "large", "big": "large", "huge": "large",
}
"""Size words by the size they state: "the large pot" is not "the small pot"."""

POSITION_NOUNS = frozenset({"end", "side", "corner", "edge", "middle", "center", "centre"})
"""Parts of a place ("the right end of the shelf"): nouns there, never verbs."""

PARTICLES = frozenset({"up", "down", "over", "back", "away", "out", "off", "around", "aside"})
"""Verb particles: a particle followed by no object is not a relation ("put it down")."""
REVERSE_PARTICLES = frozenset({"away", "out", "off", "aside"})

# -- function words ------------------------------------------------------------
DETERMINERS = frozenset(["the", "a", "an", "that", "this", "these", "those", "your", "my", "our", "his", "her", "their", "its", "some", "any"])
PRONOUNS = frozenset({"it", "that", "this", "them"})
"""Words that stand for an object already mentioned ("pick it up")."""
PLURAL_PRONOUNS = frozenset({"them", "these", "those"})
DEFINITE_DETERMINERS = frozenset(["the", "these", "those", "your", "my", "our", "his", "her", "their", "its"])
"""Determiners of a definite noun phrase: "the bananas" are a given group, one object to act on."""


def looks_plural(word: str) -> bool:
    """A regular plural noun form ("bananas", "boxes", "keys"; not "glass", "bus", "asparagus")."""
    return len(word) > 3 and word.isalpha() and word.endswith("s") and not word.endswith(("ss", "us", "is"))


INFINITIVE_AFTER = frozenset(
    ["supposed", "ought", "need", "needs", "needed", "want", "wants", "wanted", "like", "love", "has", "have", "had", "able", "used"]
)
"""Words after which "to" marks an infinitive, whatever follows ("it's supposed *to* rain")."""
TIME_WORDS = frozenset(
    ["tomorrow", "today", "tonight", "yesterday", "noon", "midnight", "morning", "afternoon", "evening", "night",
     "oclock", "pm", "am", "seconds", "minute", "minutes", "hour", "hours", "day", "days", "week", "weeks",
     "while", "bit"]
)
"""Nouns of time: a relation completed by one ("for an hour", "in a minute", "at noon") says when, not where."""
TIME_BOUNDARIES = frozenset(["end", "beginning", "start"])
"""Nouns that say when after "by" / "in" / "until" ("by the end"); after "at" they may be places."""
TIME_RELATIONS = frozenset(["at", "by", "in", "for", "within", "until", "till", "after", "before", "around", "during"])
NUMBER_WORDS = frozenset(
    ["one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
     "fifteen", "twenty", "thirty", "forty", "fifty", "half", "quarter", "few", "couple", "of", "a", "an", "the"]
)
"""Words that count or measure a time ("a couple of minutes", "at three")."""
DISCOURSE_TAGS = frozenset(
    ["k", "kk", "ok", "okay", "yeah", "yes", "yep", "yup", "right", "alright", "eh", "huh", "no", "thanks", "cheers", "cool", "mate", "buddy", "pal"]
)
"""Words that, alone after a comma at the end of a sentence, ask for assent ("..., k?", "..., ok?")."""
INTERJECTIONS = frozenset(
    ["ugh", "sigh", "phew", "whew", "oops", "argh", "meh", "yikes", "wow", "jeez", "geez", "gosh", "alas", "ah", "oh",
     "aw", "ow", "ouch", "whoa", "welp", "yay", "hooray"]
)
"""Words that only voice a feeling: set off by a comma from the rest of a sentence ("..., sigh.",
"ugh, ...") they are no noun."""
POSTURE_PARTICIPLES = frozenset(["sitting", "resting", "lying", "laying", "standing"])
"""Posture participles: before a relation they say how a thing lies ("should end up *lying* on the bench")."""
RELATIVE_PRONOUNS = frozenset({"that", "which", "who"})
CONTAINER_NOUNS = frozenset(
    {"can", "tin", "bottle", "box", "jar", "carton", "pack", "packet", "bag", "piece", "slice", "pair", "tube",
     "sack", "pouch", "tub", "jug", "crate", "canister", "sachet"}
)
"""Nouns in "a can of X": X names the object."""
MEASURE_NOUNS = frozenset({"piece", "slice", "stick", "bar", "roll", "sheet", "bunch", "loaf", "head", "clove", "lump", "chunk"})
"""Nouns in "a stick of chalk": the thing is X itself (a free phrase's head is X)."""
PAST_FORMS = frozenset(
    ["went", "came", "left", "said", "told", "thought", "knew", "made", "gave", "took", "ran", "sat", "stood", "kept",
     "heard", "began", "became", "forgot", "wrote", "spoke", "woke", "slept", "ate", "drank", "fell", "won", "lost",
     "met", "paid", "sent", "spent", "built", "caught", "taught", "fought", "sold", "bought", "brought", "found", "got",
     "meant", "grew", "drew", "flew", "threw", "blew", "rode", "drove", "chose", "froze", "hid", "shook", "broke",
     "stole", "swam", "sang", "rang", "understood", "forgave", "spilt", "burnt", "learnt", "held", "laid", "slid",
     "stuck", "spun", "bit", "was", "were", "had", "did"]
)
"""Irregular past-tense forms: after a subject they make a statement about what happened ("my son *left*
his shoes in the hall"), never a command."""
UNCHANGED_PARTICIPLES = frozenset(["put", "set", "cut", "hit", "let", "shut", "spread", "cast", "quit", "hurt", "split"])
"""Verbs whose past participle is their base form ("should be *put* on the plate")."""
SUBORDINATORS = frozenset(["if", "unless", "when", "whenever", "while", "because", "since", "although", "though", "whether"])
"""Words that open a subordinate clause ("if it isn't too much trouble"): never a verb."""
CONDITIONALS = frozenset(["if", "unless"])
"""Subordinators of a condition: the clause they open is a clause of its own ("pick up the fork if it
isn't too much trouble": the negation is the condition's)."""
VOCATIVES = frozenset(["robot", "bot", "buddy", "pal", "mate", "friend", "everyone", "folks", "there"])
"""Nouns that address the robot after a greeting ("hello robot, ..."), never a subject."""
APPROXIMATORS = frozenset(["like", "about", "around", "almost", "nearly", "roughly", "maybe", "approximately", "just", "over"])
"""Words that hedge an amount ("for *like* five minutes", "for about an hour")."""
RECIPIENTS = frozenset({"me", "us", "him", "her"})
"""After an action verb these make it a hand-over ("bring me the can")."""
QUANTIFIERS = frozenset(
    ["all", "every", "each", "both", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "several", "many", "multiple"]
)
NEGATIONS = frozenset(
    {"not", "never", "avoid", "avoiding", "refrain", "refraining", "no", "without", "nor", "nobody",
     "neither", "forget", "stop", "stopping", "quit", "cease", "except"}
)
COPULAS = frozenset(["is", "are", "be", "being", "been", "was", "were", "am"])
AUXILIARIES = frozenset(["do", "does", "did"])
REPETITION = frozenset(["twice", "thrice", "repeatedly", "times"])
"""Words that ask for the task more than once."""
MODALS = frozenset(["can", "could", "would", "will", "shall", "should", "must", "might", "may"])
DESIRE = frozenset(
    ["should", "must", "need", "needs", "want", "wants", "like", "ought", "supposed", "has", "have", "needed", "wanted", "would"]
)
"""Words that turn a state ("the carrot is on the plate") into a goal ("... should be ...")."""

CONJUNCTIONS = frozenset({"and", "or", "but", "plus", "either"})
SEQUENCE = (
    ("and", "then"), ("and", "afterwards"), ("and", "after", "that"), ("after", "that"),
    ("then",), ("afterwards",), ("afterward",), ("finally",), ("before",),
    ("after",), ("once",), ("later",), ("subsequently",),
)
RESULT = (
    ("so", "that"), ("such", "that"), ("so",), ("until",), ("till",), ("in", "order", "that"),
    ("in", "such", "a", "way", "that"), ("in", "such", "a", "manner", "that"), ("in", "a", "way", "that"),
    ("making", "sure", "that"), ("making", "sure"), ("ensuring", "that"), ("ensuring",),
)
SKIPPABLE = frozenset(
    ["please", "kindly", "just", "also", "now", "then", "carefully", "gently", "slowly", "quickly", "first", "simply", "immediately", "really", "try", "to", "so", "anyway"]
)
"""Words that may stand between a conjunction and the verb that starts a clause."""

# Word sequences that look like negation but are not ("why don't you ...").
NEGATION_NEUTRALIZERS: tuple[tuple[str, ...], ...] = (
    ("why", "do", "not", "you"),
    ("why", "not"),
    ("can", "not", "you"),
    ("could", "not", "you"),
    ("will", "not", "you"),
    ("would", "not", "you"),
    ("do", "not", "forget", "to"),
    ("never", "forget", "to"),
    ("do", "not", "hesitate", "to"),
    ("not", "only"),
    ("no", "problem"),
    ("if", "not"),
)

LOCATION_NOUNS = frozenset(
    ["table", "tabletop", "counter", "countertop", "desk", "surface", "floor", "ground", "shelf", "workspace", "left", "right", "side", "front", "back", "middle", "center", "centre", "corner", "edge", "top", "bottom", "spot", "area", "place", "there", "here", "gripper", "hand", "hands", "arm", "claw", "fingers", "finger", "robot", "camera", "view", "you", "me", "us", "somewhere", "anywhere", "elsewhere", "down", "way"]
)
"""Nouns that name a place or the robot, never a task object."""

GENERIC_HEADS = frozenset({"object", "thing", "item", "one", "stuff"})
"""Head nouns that can stand for any object."""

HYPERNYMS: dict[str, tuple[str, ...]] = {
    "fruit": ("category:fruit",),
    "fruits": ("category:fruit",),
    "vegetable": ("category:vegetable",),
    "veggie": ("category:vegetable",),
    "veg": ("category:vegetable",),
    "soda": ("set:simpler&category:can",),
    "drink": ("set:simpler&category:can",),
    "beverage": ("set:simpler&category:can",),
    "container": ("category:container",),
    "vessel": ("category:container",),
    "receptacle": ("category:container",),
    "utensil": ("category:utensil",),
    "block": ("category:block",),
    "ball": ("category:ball",),
    "cup": ("category:cup",),
    "toy": ("category:toy",),
    "tool": ("category:tool",),
}
"""Generic nouns and the catalog groups they can stand for."""

PLAIN_HYPERNYMS: dict[str, frozenset[str]] = {
    "container": CONTAINER_HEADS, "vessel": CONTAINER_HEADS, "receptacle": CONTAINER_HEADS,
    "surface": SURFACE_HEADS,
}
"""The same for objects named in plain words (not catalog ids): the head nouns a generic noun covers."""

PART_NOUNS = frozenset(
    ["slice", "slices", "piece", "pieces", "peel", "juice", "seed", "seeds", "stem", "leaf", "label", "cap", "handle", "half", "bag", "bunch", "pile", "stack", "wrapper", "box", "bottle", "can", "cans"]
)
"""Nouns after an object name that make the name a modifier ("the coke label")."""

COLOR_WORDS = frozenset(
    ["red", "green", "blue", "yellow", "orange", "purple", "pink", "white", "black", "brown", "grey", "gray", "violet", "light", "dark"]
)
SIZE_WORDS = frozenset(["small", "large", "big", "little", "mini", "tiny", "huge", "extra"])

PERSONS = frozenset(["you", "i", "we", "me", "us", "he", "she", "they", "him", "yourself"])
"""Personal pronouns: never objects ("could you", "for me")."""
ADVERBS = frozenset(
    ["again", "too", "also", "well", "please", "thanks", "thank", "kindly", "just", "now", "then", "here", "there", "right", "quick", "fast", "asap", "soon", "ok", "okay", "hey", "yo", "hi", "hello", "sure", "maybe", "perhaps", "first", "next", "finally", "already", "still", "very", "real", "really", "gonna", "up", "down", "away", "anyway", "anyways", "yeah", "yep", "yup", "tomorrow", "today", "tonight", "yesterday"]
)
"""Words that never belong to a noun phrase (besides any word ending in -ly)."""
NOISE_PHRASES: tuple[tuple[str, ...], ...] = (
    ("go", "ahead", "and"),
    ("go", "ahead"),
    ("as", "well"),
    ("thank", "you"),
    ("thanks", "a", "lot"), ("thanks", "a", "bunch"), ("thanks", "a", "ton"), ("thanks", "a", "million"),
    ("if", "you", "can"),
    ("if", "you", "could"),
    ("if", "possible"),
    ("when", "you", "are", "ready"),
    ("right", "away"),
    ("right", "now"),
    ("in", "one", "go"),
    ("in", "a", "moment"),
    ("for", "me"),
    ("for", "us"),
    ("be", "so", "kind", "as", "to"),
    ("do", "me", "a", "favor", "and"),
    ("do", "me", "a", "favour", "and"),
    ("in", "front", "of", "you"),
    ("uh",), ("um",), ("umm",), ("erm",), ("er",), ("hmm",), ("uhh",),
)
"""Fixed phrases removed before tagging (they would otherwise look like verbs or relations)."""
