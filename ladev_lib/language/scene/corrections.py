"""Self-corrections and take-backs in a scene description, read as the writer means them.

    text, dropped, replaced = apply_corrections(text, vocab)

- "a bowl - no, make that a basket", "pan right 3 degrees - sorry, left: pan
  left 3 degrees", "5 cm to the right - hmm, not enough, make it 8 cm": what
  comes before the correction, back to the start of its clause, is taken back
  (a camera or lighting word it held is kept, so "make it 8 cm" stays a camera
  move);
- "not a bowl, a mug", "no bowl", "without a sponge": the negated object is
  not in the scene;
- "a on the left and b on the right - actually, swap them": the two objects
  trade places (the reader swaps them at ``@swap@``);
- "drop the pepsi can", "scratch the softball", "remove the mug", "leave out
  the lemon": an object described earlier is taken out (``dropped`` lists the
  names, in order; the reader removes the last such object it read); one
  replaced at once ("scratch the pear, make it a peach") is also in
  ``replaced``: the count of objects stays.

The text is normalised (lower case, digits) when this runs.
"""

from __future__ import annotations

import re

from ladev_lib.language.scene.objects import canonical_name
from ladev_lib.language.scene.words import Vocabulary

_MARKER_WORDS = (
    r"(?:(?:no+(?=\s*[,!—–-]|\s+wait\b|\s+make\b|\s+sorry\b|\s+i mean\b)|nope|wait|sorry|oops|actually|correction|typo|never ?mind|"
    r"hmm+|scratch that|i mean|or rather|on second thought|not quite|my bad|err?|um+)\b[\s,.:;!-]*)"
)
_RESTATE = (
    r"(?:(?:not enough|too much|too little|make (?:that|it)|change (?:that|it) to|instead(?: of that)?|just|only|"
    r"i meant?|lets (?:say|do|make it|go with)|go with|it should be|should be|"
    r"thats too (?:much|little|bright|dark|far)(?:[\s,]+(?:go with|make it|use|lets say))?)\b[\s,:]*)"
)
_MARKER = re.compile(
    r"\s*(?:-+|—|–|,|;|\(|\.\.\.)\s*(?:then\s+)?"
    rf"(?:{_MARKER_WORDS}+{_RESTATE}*|(?:(?<=\.\.\.)|(?<=[-—–]))\s*(?:make (?:that|it)|change (?:that|it) to)\b[\s,:]*)"
)
"""A self-correction: "- no, make that", ", sorry,", "... actually", "... make that"."""
_DIRECTIONS = (
    "counterclockwise", "anticlockwise", "clockwise", "left", "right", "up", "down", "forward", "backward", "back",
    "closer", "farther", "higher", "lower", "brighter", "darker", "dimmer",
)
_SWAP = re.compile(r"\s*(?:swap|switch|exchange)\s+(?:them|those|these|the two|their (?:places|positions|spots))\b[\s:,]*")
_CLAUSE_START = re.compile(r"[:;.!?\n]|—|\s-+\s|\bthen\b")
_KEEP = re.compile(r"\b(?:camera|cam|view|light|lights|lighting|brightness)\b")
_REMOVE_VERB = (
    r"(?:drop|scratch|remove|delete|skip|forget|lose|ditch|leave out|take out|take away|get rid of|no need for|"
    r"cross out|cut)"
)


_REPLACED_BY = re.compile(
    r"\s*[,;:]?\s*(?:and\s+)?(?:make (?:it|that)|replace (?:it|that)? ?with|use|put|swap (?:it|that)? ?for|instead)\b"
    r"(?:\s+(?:a|an|the)\s+)?"
)


_RELATION = (
    r"(?:right next to|next to|close to|near|beside|on top of|onto|into|inside|in front of|behind|"
    r"(?:to the )?(?:left|right) of|on|in)"
)


def correct_relations(text: str) -> str:
    """ "move the golf ball next to the tennis ball - no, next to the cup": the corrected relation
    replaces the one said before it (the rest of the statement stays). Case is kept; runs before
    the task is looked for."""
    # "... on the towel. Hmm, no, on the sponge.": a correction that starts a sentence
    out = re.sub(
        rf"(\.+|…|[!?])\s+((?:hmm+|no+|nope|wait|sorry|actually|oops)\b[,!.]?\s*(?:(?:no+|wait|sorry|actually)\b[,!.]?\s*)*"
        rf"{_RELATION}\s+(?:the|a|an)\s)",
        r" - \2", text, flags=re.IGNORECASE,
    )
    for _ in range(4):
        low = out.lower()
        for m in _MARKER.finditer(low):
            new = re.match(rf"\s*({_RELATION})\s+(?:the|a|an|that|this)\s", low[m.end():])
            if new is None:
                swapped = _corrected_noun_phrase(out, low, m)
                if swapped is not None:
                    out = swapped
                    break
                continue
            starts = [c.end() for c in _CLAUSE_START.finditer(low, 0, m.start())]
            start = starts[-1] if starts else 0
            said = [r for r in re.finditer(rf"\b{_RELATION}\s+(?:the|a|an|that|this)\s", low[start : m.start()])]
            if not said:
                continue
            cut = start + said[-1].start()
            out = out[:cut] + out[m.end() :].lstrip()
            break
        else:
            return out
    return out


_NP = r"(?:the|a|an)\s+(?:(?!(?:and|or)\b)[a-z0-9']+\s+){0,3}?(?!(?:and|or)\b)[a-z0-9']+"
"""One noun phrase ("the red plate"; "a pear and a basket" is two)."""


def _corrected_noun_phrase(out: str, low: str, m: re.Match[str]) -> str | None:
    """ "the robot picks up the spoon - sorry, the banana", "... the lemon - actually, use the golf
    ball, not the lemon": the corrected noun phrase replaces the one it names (or the last one)."""
    new = re.match(rf"\s*(?:use\s+|take\s+|it should be\s+)?(?P<np>{_NP})\s*(?:,\s*not\s+(?P<old>{_NP}))?\s*(?=$|[.;!?\n]|instead\b)", low[m.end():])
    if new is None:
        return None
    starts = [c.end() for c in _CLAUSE_START.finditer(low, 0, m.start())]
    start = starts[-1] if starts else 0
    clause = low[start : m.start()]
    if not re.search(r"\b(?:pick|put|place|move|set|lift|grab|drop|bring|stack|picks|puts|places|moves|sets|lifts|grabs)\b", clause):
        return None  # only inside a task statement; object lists are apply_corrections' business
    said = list(re.finditer(rf"\b{_NP}", clause))
    if new.group("old"):
        said = [s for s in said if s.group(0) == new.group("old")]
    if not said:
        return None
    old = said[-1]
    np = new.group("np")
    one = re.fullmatch(r"(the|a|an)\s+((?:[a-z0-9']+\s+)+)one", np)
    if one is not None:
        # "... the purple brick next to the board - hmm, no, the green one": the phrase with a modifier
        # of its own, said again with the new one ("the green brick")
        stop = r"(?!(?:next|to|near|on|onto|in|into|inside|with|and|or|beside|by|from|of|at)\b)"
        whole = rf"\b(?:the|a|an)\s+{stop}[a-z0-9']+(?:\s+{stop}[a-z0-9']+){{1,3}}"
        modified = [p for p in re.finditer(whole, clause)]
        if not modified:
            return None
        old = modified[-1]
        for p in modified:
            if p.end() <= m.start() - start:
                old = p
                break  # the first such phrase: the object, before the destination
        np = f"{one.group(1)} {one.group(2)}{old.group(0).split()[-1]}"
    rest = out[m.end() + new.end():]
    rest = re.sub(r"^\s*instead\b", "", rest)
    return out[: start + old.start()] + np + out[start + old.end() : m.start()] + rest


def apply_corrections(text: str, vocab: Vocabulary) -> tuple[str, list[str], list[str]]:
    """The text with taken-back statements removed, the objects taken out by name, and those of
    them that another object replaces."""
    # "... 3 cm forward. Hmm, make it 4.": a new amount said as the next sentence corrects the last one
    out = re.sub(
        r"(?<![.])[.!?]\s+((?:hmm+|no+|wait|sorry|actually|oops)\b[,!.]?\s*(?:(?:no+|sorry)\b[,!.]?\s*)?"
        # "hmm, that's too much, make it 50%": a few words of the same sentence before the new amount
        r"(?:(?:[a-z']+,?\s+){0,4}?(?:make (?:it|that)|change (?:it|that) to|i meant?|just|go with|by)\s+"
        r"(?:-?\d|a (?:quarter|third|fifth|tenth)|half)"
        r"|-?\d+(?:\.\d+)?\s*(?:%|cm|mm|degrees?|deg)\b"  # "3 cm forward. Hmm, no, 6 cm forward."
        r"|(?:" + "|".join(_DIRECTIONS) + r")\b\s*(?=$|[.;!\n])))",
        r" - \1", text,
    )
    # "dim it by a third? Let's just say 30%.": a new amount offered in the next sentence
    out = re.sub(r"(?<![.])[.!?]\s+(?:ok(?:ay)?,?\s+)?lets (?:just )?(?:say|make it|call it|go with)\s+(-?\d+(?:\.\d+)?\s*%?)",
                 r" - actually, make it \1", out)
    # "... 30% darker. And 30% is too much, say 20%.": the amount restated in the next sentence
    out = re.sub(
        r"(?<![.])[.!?]\s+(?:and\s+)?(?:-?\d+(?:\.\d+)?\s*%?\s+)?(?:is|was|seems|thats|that is|its)\s+(?:way\s+)?too\s+"
        r"(?:much|little|bright|dark|strong|weak|far)\s*,?\s*(?:say|make it|go with|use|lets say|try)\s+(-?\d+(?:\.\d+)?\s*%?)",
        r" - actually, make it \1", out,
    )
    # 1. "X - no, make that Y": drop X (from its clause start) and the marker.
    for _ in range(8):
        m = _MARKER.search(out)
        if m is None or not _has_content_after(out, m.end()):
            break
        swap = _SWAP.match(out, m.end())
        if swap is not None:
            # "a on the left and b on the right - actually, swap them": nothing is taken back
            out = out[: m.start()] + " . @swap@ . " + out[swap.end():]
            continue
        starts = [c.end() for c in _CLAUSE_START.finditer(out, 0, m.start())]
        start = starts[-1] if starts else 0
        taken = out[start:m.start()]
        same = _same_object_again(out, start, m, vocab)
        if same is not None:
            out = same  # "one apple with a mug and a knife... actually make it two apples"
            continue
        # keep an object list's head ("a lemon, a bowl - no, a mug": only the last item goes)
        # unless the correction is itself a list ("a pear and a bowl - no, make that a pear and a basket")
        items = [c.end() for c in re.finditer(r",|\band\b", taken)]
        restated = re.match(r"[^.;!?\n\u2014\u2013]*?(?=$|[.;!?\n\u2014\u2013]|\s-)", out[m.end():])
        again = {n.group(0) for n in vocab.name_pattern.finditer(restated.group(0))} if restated is not None else set()
        relisted = len(again) >= 2 and bool(again & {n.group(0) for n in vocab.name_pattern.finditer(taken)})
        if items and vocab.name_pattern.search(taken[: items[-1]]) and not relisted:
            start += items[-1]
            taken = out[start:m.start()]
        keep = " ".join(sorted({k.group(0) for k in _KEEP.finditer(taken)}))
        after = out[m.end():]
        fraction = r"a (?:quarter|third|fifth|tenth)|(?:a )?half"
        amount = re.match(
            rf"\s*(?:by\s+)?(-?\d+(?:\.\d+)?\s*(?:%|percent|cm|mm|degrees?|deg|x)?|{fraction})\s*(?=$|[.;,!?\n])", after
        )
        said_amounts = list(re.finditer(rf"-?\d+(?:\.\d+)?\s*(?:%|percent|cm|mm|degrees?|deg|x\b)?|\b(?:{fraction})\b", taken))
        if amount is not None and said_amounts:
            # "lights 20% darker, actually make it 25%": only the amount changes
            old = said_amounts[-1]
            new_amount = amount.group(1).strip()
            unit = re.search(r"[a-z%]+\s*$", old.group(0))
            if unit is not None and re.fullmatch(r"-?\d+(?:\.\d+)?", new_amount):
                new_amount += f" {unit.group(0).strip()}"  # "3 cm forward. hmm, make it 4": 4 cm
            fixed = taken[: old.start()] + new_amount + " " + taken[old.end():]
            out = out[:start] + fixed + after[amount.end():]
            continue
        short = re.match(r"\s*(?:to (?:the )?)?([a-z]+(?: [a-z]+)?)\s*(?=$|[.;!\n]|\s-)", after)
        if short is not None and short.group(1).split()[0] in _DIRECTIONS:
            # "roll 3 degrees clockwise - no, counterclockwise": only the direction changes
            word = short.group(1).split()[0]
            olds = [w for w in _DIRECTIONS if re.search(rf"\b{w}\b", taken)]
            if olds:
                fixed = re.sub(rf"\b{olds[0]}\b", word, taken, count=1)
                out = out[:start] + fixed + after[short.end():]
                continue
        named = vocab.name_pattern.search(taken)
        if named is not None:
            # "a strawberry near the plate - no wait, put it on the right": 'it' is the strawberry
            after = re.sub(r"^\s*(?:(?:put|place|set|move|make)\s+)?(?:it|that)\b", f" the {named.group(0)}", after, count=1)
        out = out[:start] + f" {keep} " + after
    # 2. "not a bowl, a mug" / "no bowl" / "without a sponge": the negated object is not there.
    names = vocab.name_pattern.pattern
    swapped: list[str] = []

    out = _swap_objects(out, names, swapped)
    negation = r"\b(?:not|no|without|never|dont (?:add|include|put|want|need)|do not (?:add|include|put))\s+"
    dropped: list[str] = []

    def instead(m: re.Match[str]) -> str:
        # "not a bowl, a mug": a bowl said before is replaced; else the mug is said again, not added again
        said = re.search(rf"(?<![a-z]){re.escape(m.group(1))}(?![a-z])", out[: m.start()])
        if said is not None:
            dropped.append(m.group(1))
            return " a "
        return " the "

    def taken_back(m: re.Match[str]) -> str:
        # "a fork, a spoon and a knife, but not the knife after all": said before, taken back
        said = re.search(rf"(?<![a-z]){re.escape(m.group(1))}(?![a-z])", out[: m.start()])
        if said is not None:
            dropped.append(m.group(1))
        return " "

    out = re.sub(
        rf"\b(?:but\s+)?(?:not|no|dont (?:include|add|put|use|want|need)|do not (?:include|add|put|use|want|need))\s+"
        rf"(?:a|an|the|that)?\s*({names})\s+(?:after all|anymore|any more|on second thought|now|either)\b",
        taken_back, out,
    )
    out = re.sub(rf"{negation}(?:a|an|the|any)?\s*({names})\s*,\s*(?:but\s+)?(?:a|an)\s+", instead, out)
    out = re.sub(rf"{negation}(?:a|an|the|any)?\s*{names}\s*,?", " ", out)
    out = re.sub(rf"\bnot\s+(?:near|next to|beside|by|on|in|behind|left of|right of)\s+(?:the|a|an)\s+{names}", " ", out)
    # 3. "drop the pepsi can": an object described before is taken out.

    replaced: list[str] = []

    def take_out(m: re.Match[str]) -> str:
        dropped.append(m.group("name"))
        follow = _REPLACED_BY.match(out, m.end())
        if follow is not None and vocab.name_pattern.match(out, follow.end()):
            replaced.append(m.group("name"))
        return " "

    out = re.sub(
        rf"\b{_REMOVE_VERB}\s+(?:the|that|this|my)\s+(?P<name>{names})(?=\s*(?:$|[,;.!]|\band\b|\breplace))",
        take_out, out,
    )

    def take_out_by_word(m: re.Match[str]) -> str:
        # "remove the windex": the one object named before whose name has that word
        word = m.group("word")
        said = {n.group(0) for n in vocab.name_pattern.finditer(out[: m.start()]) if word in n.group(0).split()}
        if len(said) != 1:
            return m.group(0)
        dropped.append(said.pop())
        return " "

    out = re.sub(
        rf"\b{_REMOVE_VERB}\s+(?:the|that|this|my)\s+(?P<word>[a-z0-9]+)(?=\s*(?:$|[,;.!]|\band\b))",
        take_out_by_word, out,
    )
    for name in swapped:
        dropped.append(name)
        replaced.append(name)
    return out, dropped, replaced


def _swap_objects(text: str, names: str, swapped: list[str]) -> str:
    """ "instead of the bowl use the basket", "swap the pepsi can for a sprite can": the new object
    is said (as a new one) and the old one is taken back (listed in ``swapped``)."""
    forms = (
        rf"\binstead of (?:the|a|an) (?P<old>{names}),? (?:use|take|put|go with|make it) (?:the|a|an) (?P<new>{names})",
        rf"\b(?:use|take|put|go with|make (?:it|that)|i want|add) (?:the|a|an) (?P<new>{names}) instead of (?:the|a|an) (?P<old>{names})",
        rf"\bnot (?:the|a|an) (?:[a-z]+ )?(?P<old>{names}),? (?:but |use |take |go with |make it |i want )(?:the|a|an) (?P<new>{names})",
        rf"\b(?:swap|replace|switch|exchange|trade) (?:the|a|an|that|this) (?P<old>{names}) (?:for|with) (?:the|a|an) (?P<new>{names})",
    )
    for form in forms:
        def use(m: re.Match[str], text: str = text) -> str:
            if re.search(rf"(?<![a-z]){re.escape(m.group('old'))}(?![a-z])", text[: m.start()]) is None:
                return m.group(0)
            swapped.append(m.group("old"))
            return f" a {m.group('new')} "

        text = re.sub(form, use, text)
    return text


def _same_object_again(text: str, start: int, marker: re.Match[str], vocab: Vocabulary) -> str | None:
    """The text with one object of the clause said again, when the correction names an object with
    its head noun ("1 apple, a mug and a knife - actually, make it 2 apples": the mug and knife
    stay; "a banana on a plate... make that the red plate": the banana stays)."""
    after = text[marker.end():]
    phrase = re.match(r"\s*(?:(?:a|an|the|\d+)\s+)?([^.,;!?\n]+?)\s*(?=$|[.,;!?\n])", after)
    if phrase is None:
        return None
    named = vocab.name_pattern.fullmatch(phrase.group(1).strip())
    if named is None:
        return None
    head = canonical_name(vocab, named.group(0)).split()[-1]
    for m in vocab.name_pattern.finditer(text, start, marker.start()):
        if canonical_name(vocab, m.group(0)).split()[-1] == head:  # "a plate ... make that the red plate"
            counted = re.search(r"(?:\b(?:a|an|\d+)\s+)$", text[start : m.start()])
            begin = start + counted.start() if counted is not None else m.start()
            return text[:begin] + phrase.group(0).strip() + text[m.end() : marker.start()] + after[phrase.end():]
    return None


def _has_content_after(text: str, pos: int) -> bool:
    return bool(re.match(r"\s*[a-z0-9+-]", text[pos:]))
