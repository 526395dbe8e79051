"""Tokenise an instruction and tag each token with its role for the parser.

    tag_tokens("Could you put the can of coke onto the dish?", index)
    -> MODAL PERSON VERB(place:put) DET OBJ(coke_can) REL(on:onto) DET OBJ(plate) PUNCT

Catalog names are matched first (longest first, on the same normalisation as
the catalog's), so a name that contains a function word ("cup with a
handle", "seven up can") stays one object.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ladev_lib.language import lexicon as lx
from ladev_lib.language.mentions import NameIndex

Kind = str
# OBJ PRON RELPRON DET QUANT REL VERB NEG BE AUX MODAL PART CONJ SEQ RESULT PUNCT PERSON ADV REPEAT WORD


@dataclass(frozen=True)
class Token:
    kind: Kind
    text: str
    object_id: str | None = None
    relation: str | None = None
    """near | on | in | other | reverse (REL tokens)."""
    directional: bool = False
    verb_class: str | None = None
    lemma: str | None = None


_CONTRACTIONS: tuple[tuple[str, str], ...] = (
    (r"\bwon't\b", "will not"),
    (r"\bcan't\b", "can not"),
    (r"\bcannot\b", "can not"),
    (r"\bshan't\b", "shall not"),
    (r"\b(\w+)n't\b", r"\1 not"),
    (r"\bdont\b", "do not"),
    (r"\blet's\b", "let us"),
    (r"\b(it|that|there|here|what|who|where)'s\b", r"\1 is"),
    # "the teddy bear's been on the floor": a noun's "'s" before a participle or a place is "has" / "is", no plural
    (r"\b([a-z]+)'s\s+(?=(?:been|got|gotten|gone|fallen|rolled|ended)\b)", r"\1 has "),
    (r"\b([a-z]+)'s\s+(?=(?:being|sitting|lying|standing|still|already|now|on|in|at|under|over|next|near|here|there)\b)",
     r"\1 is "),
    (r"'re\b", " are"),
    (r"'m\b", " am"),
    (r"'ll\b", " will"),
    (r"'d\b", " would"),
    (r"'ve\b", " have"),
    (r"\bgimme\b", "give me"),
    (r"\bwanna\b", "want to"),
    (r"\bgotta\b", "got to"),
    (r"\bpl[sz]\b", "please"),
    (r"\bthx\b", "thanks"),
)
_PUNCT = frozenset(",.;:!?")
_SENTENCE_END = frozenset(".;:!?")


def words_of(text: str) -> list[str]:
    """Lower-case words and punctuation, contractions expanded, names normalised like the catalog's."""
    t = text.lower().replace("\u2019", "'").replace("\u2018", "'").replace("`", "'")
    t = re.sub(r"\s+[-\u2013\u2014]+\s+|[\u2013\u2014]", " , ", t)  # a dash between words is a pause
    for pattern, repl in _CONTRACTIONS:
        t = re.sub(pattern, repl, t)
    t = t.replace("'", "")
    t = re.sub(r"[-_/]", " ", t)
    t = re.sub(r"([,.;:!?])", r" \1 ", t)
    t = re.sub(r"[^a-z0-9,.;:!? ]", " ", t)
    return t.split()


def _rewrite_phrasal(words: list[str]) -> list[str]:
    out: list[str] = []
    i = 0
    while i < len(words):
        w = words[i]
        lemma = lx.VERBS[w][1] if w in lx.VERBS else w
        for phrase, replacement in lx.PHRASAL_VERBS.items():
            if phrase[0] == lemma and tuple(words[i + 1 : i + len(phrase)]) == phrase[1:]:
                out.append(replacement or w)
                i += len(phrase)
                break
        else:
            out.append(w)
            i += 1
    return out


def _rewrite(words: list[str], table: dict[tuple[str, ...], tuple[str, ...]]) -> list[str]:
    out: list[str] = []
    i = 0
    longest = max(len(k) for k in table)
    while i < len(words):
        for n in range(min(longest, len(words) - i), 0, -1):
            repl = table.get(tuple(words[i : i + n]))
            if repl is not None:
                out.extend(repl)
                i += n
                break
        else:
            out.append(words[i])
            i += 1
    return out


_DROP: dict[tuple[str, ...], tuple[str, ...]] = {
    **{k: () for k in lx.NEGATION_NEUTRALIZERS},
    **{k: () for k in lx.NOISE_PHRASES},
}


def is_adverb(word: str) -> bool:
    return word in lx.ADVERBS or (word.endswith("ly") and len(word) > 4)


def _starts_phrase(words: list[str], i: int, index: NameIndex) -> bool:
    """Whether a noun phrase starts at ``words[i]`` (to tell a preposition from a particle)."""
    if i >= len(words):
        return False
    w = words[i]
    if w in _PUNCT or w in lx.CONJUNCTIONS or is_adverb(w) and index.match_at(words, i) is None:
        return False
    if w in lx.DETERMINERS or w in lx.PRONOUNS or w in lx.QUANTIFIERS or index.match_at(words, i):
        return True
    if w in lx.VERBS or w in lx.COPULAS or w in lx.MODALS or w in lx.NEGATIONS:
        return False
    return not any(tuple(words[i : i + n]) in lx.RELATIONS for n in range(1, lx.RELATION_MAX_LEN + 1))


def _match_phrase(
    words: list[str], i: int, table: tuple[tuple[str, ...], ...]
) -> tuple[str, ...] | None:
    for phrase in sorted(table, key=len, reverse=True):
        if tuple(words[i : i + len(phrase)]) == phrase:
            return phrase
    return None


_BE_WORDS = frozenset({"is", "s", "was", "will", "would", "be"})


def _unfold_where(words: list[str]) -> list[str]:
    """Pseudo-clefts in the plain order: "next to the notebook is where the glue stick goes"
    -> "the glue stick goes next to the notebook"; "the plate is where the carrot should go"
    -> "... go to the plate"; "where the apple belongs is the basket" likewise. One sentence
    at a time; anything else is left as written."""
    out: list[str] = []
    start = 0
    for end in [*(k for k, w in enumerate(words) if w in _SENTENCE_END), len(words)]:
        out.extend(_unfold_sentence(words[start:end]))
        out.extend(words[end : end + 1])
        start = end + 1
    return out


_WISH = (("would", "like"), ("want",), ("need",), ("wish",), ("would", "love"))
_STRANDED = frozenset({"on", "onto", "in", "into", "inside", "near", "beside", "by", "to"})


def _unfold_sentence(s: list[str]) -> list[str]:
    # "what i would like is for the glass to end up on the plate" -> "i would like the glass to ..."
    if len(s) > 5 and s[0] == "what" and s[1] in ("i", "we"):
        for wish in _WISH:
            n = len(wish)
            if tuple(s[2 : 2 + n]) == wish and s[2 + n : 4 + n] == ["is", "for"]:
                return [s[1], *wish, *s[4 + n :]]
    # "it is the drawer that the bowl should go into" -> "the bowl should go into the drawer"
    trailing = len(s) - (1 if s and s[-1] in _PUNCT else 0)
    fronted = _fronted_relation(s, trailing)
    if fronted is not None:
        return fronted
    if len(s) > 5 and s[0] in ("it", "that") and s[1] in _BE_WORDS and trailing > 0 and s[trailing - 1] in _STRANDED:
        rel = next((k for k in range(3, trailing - 1) if s[k] in ("that", "which")), None)
        if rel is not None and rel < trailing - 2:
            return [*s[rel + 1 : trailing], *s[2:rel], *s[trailing:]]
    if "where" not in s:
        return s
    w = s.index("where")
    if w > 0 and s[w - 1] in _BE_WORDS and w + 1 < len(s):  # "A is where B"
        place, rest = s[: w - 1], s[w + 1 :]
    elif w == 0 and any(x in _BE_WORDS for x in s[2:]):  # "where B is A"
        k = max(i for i, x in enumerate(s) if x in _BE_WORDS and i > 1)
        place, rest = s[k + 1 :], s[1:k]
    else:
        return s
    if not place or not rest or place[-1] == ",":
        return s
    related = any(tuple(place[:n]) in lx.RELATIONS for n in range(1, lx.RELATION_MAX_LEN + 1))
    return [*rest, *(place if related else ["to", *place])]


def _fronted_relation(s: list[str], trailing: int) -> list[str] | None:
    """A cleft on a relation phrase: "it is near the bike that the kite should be moved" -> "the
    kite should be moved near the bike". The clause after "that" must open with its subject."""
    if len(s) < 7 or s[0] not in ("it", "that") or s[1] not in _BE_WORDS:
        return None
    n = next((n for n in range(lx.RELATION_MAX_LEN, 0, -1) if tuple(s[2 : 2 + n]) in lx.RELATIONS), 0)
    if n == 0 or lx.RELATIONS[tuple(s[2 : 2 + n])] not in ("near", "on", "in"):
        return None
    rel = next((k for k in range(3 + n, trailing - 2) if s[k] in ("that", "which")), None)
    if rel is None or s[rel + 1] not in lx.DETERMINERS and s[rel + 1] not in lx.PRONOUNS:
        return None
    if any(w in _PUNCT for w in s[2:rel]):
        return None
    return [*s[rel + 1 : trailing], *s[2:rel], *s[trailing:]]


def tag_tokens(text: str, index: NameIndex) -> list[Token]:
    """The tagged tokens of an instruction."""
    words = _rewrite_phrasal(_rewrite(_unfold_where(words_of(text)), _DROP))
    tokens: list[Token] = []
    i = 0
    while i < len(words):
        w = words[i]
        prev = tokens[-1] if tokens else None
        after_det = prev is not None and prev.kind in ("DET", "QUANT")
        match = index.match_at(words, i)
        if match is not None:
            name = " ".join(words[i : i + match.length])
            tokens.append(Token("OBJ", name, object_id=match.object_id))
            i += match.length
            continue
        seq = _match_phrase(words, i, lx.SEQUENCE)
        if seq is not None:
            tokens.append(Token("SEQ", " ".join(seq)))
            i += len(seq)
            continue
        res = _match_phrase(words, i, lx.RESULT)
        if res is not None and (res != ("so",) or _starts_phrase(words, i + 1, index)):
            tokens.append(Token("RESULT", " ".join(res)))
            i += len(res)
            continue
        if w in lx.TIME_RELATIONS and i + 1 < len(words) and words[i + 1] in _TIME_ADVERBS:
            tokens.append(Token("ADV", w))  # "by tomorrow", "until tonight": when, not where
            i += 1
            continue
        rel = _relation_at(words, i, index)
        if rel is not None:
            phrase, kind = rel
            tokens.append(
                Token("REL", " ".join(phrase), relation=kind, directional=phrase in lx.DIRECTIONAL)
            )
            i += len(phrase)
            continue
        compound = prev is not None and prev.kind == "WORD" and len(tokens) > 1 and tokens[-2].kind in ("DET", "QUANT")
        tokens.append(_tag_word(w, prev, after_det or _noun_head(w, compound, words, i, index), words, i, index))
        i += 1
    return tokens


def _relation_at(words: list[str], i: int, index: NameIndex) -> tuple[tuple[str, ...], str] | None:
    for n in range(min(lx.RELATION_MAX_LEN, len(words) - i), 0, -1):
        phrase = tuple(words[i : i + n])
        kind = lx.RELATIONS.get(phrase)
        if kind is None:
            continue
        nxt = i + n
        if phrase == ("of",) and i > 0 and (words[i - 1] in lx.CONTAINER_NOUNS or words[i - 1] in lx.MEASURE_NOUNS):
            return None  # "a can of coca-cola": one noun phrase, not a relation
        if phrase == ("to",) and (not _starts_phrase(words, nxt, index) or (i > 0 and words[i - 1] in lx.INFINITIVE_AFTER)):
            return None  # "to" before a verb marks an infinitive ("try to pick", "it's supposed to rain")
        if n == 1 and phrase[0] in lx.PARTICLES and not _starts_phrase(words, nxt, index):
            return None  # a particle: "put it down", "take it out"
        return phrase, kind
    return None


def _noun_head(w: str, compound: bool, words: list[str], i: int, index: NameIndex) -> bool:
    """A verb's base form inside a determined noun phrase is a noun: its head when it ends the
    phrase ("the glue *stick* should go ...", "the cake *stand*"), or the first noun of a
    compound when one more noun ends the phrase ("the little *hand* shovel near ..."); not when
    an object follows: "the kid, stack the cups", "the kid hand me the cup")."""
    if not compound or w not in lx.VERBS or lx.VERBS[w][1] != w:
        return False
    nxt = words[i + 1] if i + 1 < len(words) else ""
    if nxt not in lx.PRONOUNS and nxt not in lx.DETERMINERS and not _starts_phrase(words, i + 1, index):
        return True
    return (
        nxt.isalpha()
        and nxt not in lx.PRONOUNS and nxt not in lx.DETERMINERS and nxt not in lx.QUANTIFIERS
        and nxt not in lx.PERSONS and nxt not in lx.VERBS and not is_adverb(nxt)
        and _starts_phrase(words, i + 1, index)
        and not _starts_phrase(words, i + 2, index)
        and (words[i + 2] if i + 2 < len(words) else "") not in lx.PERSONS
    )


def _tag_word(
    w: str, prev: Token | None, after_det: bool, words: list[str], i: int, index: NameIndex
) -> Token:
    if w in _PUNCT:
        return Token("PUNCT", w)
    if w in lx.CONJUNCTIONS:
        return Token("CONJ", w)
    if w in _STATIVE_PARTICIPLES and prev is not None and prev.kind in ("OBJ", "WORD"):
        return Token("ADV", w)  # "the bowl sitting on the cabinet": describes where it is
    posture = w in lx.POSTURE_PARTICIPLES and (prev is None or prev.kind != "DET")
    if posture and (_relation_follows(words, i + 1, index) or (prev is not None and prev.kind == "BE")):
        return Token("ADV", w)  # "should end up lying on the bench", "has been sitting out all day": how it lies
    if w in lx.DISCOURSE_TAGS and prev is not None and prev.text == "," and _ends_sentence(words, i + 1):
        return Token("ADV", w)  # a tag asking for assent: "..., k?", "..., ok?"
    set_off = (prev is not None and prev.text == "," and _ends_sentence(words, i + 1)) or (
        (prev is None or prev.text in _SENTENCE_END) and i + 1 < len(words) and words[i + 1] in _PUNCT
    )
    if w in lx.INTERJECTIONS and set_off:
        return Token("ADV", w)  # "..., sigh.", "ugh, ...": a feeling voiced, no noun
    if w == "like" and _hedges_amount(prev, words, i):
        return Token("ADV", w)  # "for like five minutes": a hedge on an amount, no wish
    describes = (after_det or (prev is not None and prev.kind == "REL")) and _starts_phrase(words, i + 1, index)
    if w in lx.PARTICLES and not describes and not (after_det and w in lx.OPPOSITE_POSITIONS):
        return Token("PART", w)  # after a determiner or a relation word it describes the noun: "(the) back slot"
    if w in lx.SIDE_WORDS and (describes or after_det):
        return Token("WORD", w)  # "the right slot", "on the right": a side, not "right now"
    if w in lx.POSITION_NOUNS and prev is not None and prev.kind == "WORD" and prev.text in lx.SIDE_WORDS:
        return Token("WORD", w)  # "the right end (of the shelf)": a part of a place, not a verb
    if is_adverb(w) and w not in lx.VERBS:
        return Token("ADV", w)
    if w in lx.NEGATIONS and not (w == "no" and after_det):
        return Token("NEG", w)
    if w in lx.PERSONS:
        return Token("PERSON", w)
    nxt = words[i + 1] if i + 1 < len(words) else ""
    after_noun = prev is not None and prev.kind in ("OBJ", "WORD")
    if w in lx.RELATIVE_PRONOUNS and after_noun and (nxt in lx.COPULAS or nxt in lx.MODALS or nxt in lx.VERBS):
        return Token("RELPRON", w)  # "the can that is on the table": what follows describes it
    if w in ("that", "this") and nxt not in lx.PRONOUNS and (
        _starts_phrase(words, i + 1, index)
        or (nxt == "can" and (words[i + 2] if i + 2 < len(words) else "") not in lx.PERSONS)
    ):
        return Token("DET", w)
    if w in lx.PRONOUNS:
        return Token("PRON", w)
    if w in lx.DETERMINERS:
        return Token("DET", w)
    if w in lx.QUANTIFIERS:
        return Token("QUANT", w)
    if w in lx.COPULAS:
        return Token("BE", w)
    if w in lx.AUXILIARIES:
        return Token("AUX", w)
    if w in lx.REPETITION:
        return Token("REPEAT", w)
    noun_position = after_det or (prev is not None and prev.kind in ("WORD", "OBJ"))
    if w in lx.MODALS and not (w == "can" and noun_position):
        return Token("MODAL", w)
    if w in lx.VERBS and not after_det:
        cls, lemma = lx.VERBS[w]
        if cls == "other" and w == lemma and w not in lx.UNCHANGED_PARTICIPLES and _after_copula(words, i):
            return Token("WORD", w)  # "the door is open", "the jar is still empty": an adjective, not a verb
        if w == lemma and (prev is None or prev.kind == "PUNCT") and _compound_subject(words, i, index):
            return Token("WORD", w)  # "shift change is at noon": the first noun of the subject, no command
        return Token("VERB", w, verb_class=cls, lemma=lemma)
    return Token("WORD", w)


def _hedges_amount(prev: Token | None, words: list[str], i: int) -> bool:
    """ "like" before a number, not after a subject or a modal: "it took *like* ten minutes"."""
    nxt = words[i + 1] if i + 1 < len(words) else ""
    counts = nxt.isdigit() or nxt in lx.NUMBER_WORDS - {"a", "an", "the", "of"} or nxt in lx.QUANTIFIERS
    return counts and prev is not None and prev.kind not in ("MODAL", "PERSON", "AUX", "NEG")


def _after_copula(words: list[str], i: int) -> bool:
    """Right after a form of "be", an adverb between at most: "is open", "is still open"."""
    if i >= 1 and words[i - 1] in lx.COPULAS:
        return True
    return i >= 2 and words[i - 2] in lx.COPULAS and is_adverb(words[i - 1])


def _compound_subject(words: list[str], i: int, index: NameIndex) -> bool:
    """A verb's base form opening a sentence before a bare noun and a finite "be", a modal or
    "has": the two nouns are the subject ("shift change is in ten minutes", "play time should
    ..."), not a command and its object."""
    if i + 2 >= len(words):
        return False
    nxt, after = words[i + 1], words[i + 2]
    noun = (
        nxt.isalpha()
        and not any(nxt in table for table in _NOT_SUBJECT_NOUNS)
        and not is_adverb(nxt)
        and index.match_at(words, i + 1) is None
        and _relation_at(words, i + 1, index) is None
    )
    return noun and (after in lx.COPULAS or after in _FINITE_AFTER_SUBJECT)


_NOT_SUBJECT_NOUNS = (
    lx.DETERMINERS, lx.PRONOUNS, lx.QUANTIFIERS, lx.PERSONS, lx.VERBS, lx.PARTICLES, lx.COPULAS, lx.MODALS,
    lx.CONJUNCTIONS, lx.NEGATIONS, lx.AUXILIARIES,
)
_FINITE_AFTER_SUBJECT = frozenset({"will", "would", "should", "must", "might", "may", "has", "had"})


_TIME_ADVERBS = frozenset({"tomorrow", "today", "tonight", "yesterday", "now", "then", "later", "soon"})


def _relation_follows(words: list[str], i: int, index: NameIndex) -> bool:
    """A relation word at ``words[i]``, after at most one particle ("sitting *out for* an hour")."""
    for k in (i, i + 1):
        if _relation_at(words, k, index) is not None:
            return True
        if k >= len(words) or words[k] not in lx.PARTICLES:
            return False
    return False


def _ends_sentence(words: list[str], i: int) -> bool:
    return i >= len(words) or words[i] in _SENTENCE_END


_STATIVE_PARTICIPLES = frozenset(
    ["sitting", "resting", "lying", "standing", "placed", "located", "positioned", "kept", "situated", "lying", "sat", "laid", "stored"]
)
"""Participles that, right after a noun phrase, say where it is rather than ask for an action."""


def is_sentence_end(token: Token) -> bool:
    return token.kind == "PUNCT" and token.text in _SENTENCE_END
