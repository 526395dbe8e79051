"""Training the span tagger on annotated rows, and scoring it span by span.

Rows are JSON lines with an ``annotated`` description in the markup of
:mod:`ladev_lib.language.tagging.markup` (and, optionally, the ``expected``
scene of ``../shared/dev/README.md``'s format, which the reader's own
evaluation uses). A share of the rows, chosen by a hash of their ids, is held
out for validation; the weights of the last epoch are saved.

    examples = load_examples([Path("data/reader/train_a.jsonl"), ...])
    report = train(examples, out=Path("reader.safetensors"), epochs=8)
"""

from __future__ import annotations

import hashlib
import json
import random
import time
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ladev_lib.language.tagging.markup import LABELS, TAGS, MarkupError, Span, parse_markup
from ladev_lib.language.tagging.model import (
    MAX_TOKENS,
    _token_spans,
    decode,
    encoder_digest,
    new_model,
    resolve_encoder,
    save_weights,
)

_LABEL_ID = {name: i for i, name in enumerate(LABELS)}


@dataclass(frozen=True)
class Example:
    id: str
    text: str
    spans: tuple[Span, ...]
    source: str = ""


def load_examples(paths: Iterable[Path]) -> tuple[list[Example], list[str]]:
    """The annotated rows of JSONL files, and one problem line per row that could not be read."""
    out: list[Example] = []
    problems: list[str] = []
    for path in paths:
        for n, line in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), 1):
            if not line.strip():
                continue
            try:
                row = json.loads(line)
                text, spans = parse_markup(str(row["annotated"]))
            except (json.JSONDecodeError, KeyError, MarkupError) as exc:
                problems.append(f"{path}:{n}: {exc}")
                continue
            out.append(Example(str(row.get("id") or f"{Path(path).stem}:{n}"), text, tuple(spans), Path(path).name))
    return out, problems


def token_labels(offsets: Sequence[tuple[int, int]], spans: Sequence[Span]) -> list[int]:
    """One label id per token (-100 for special tokens): B on a phrase's first token, I on the rest."""
    labels: list[int] = []
    started: set[int] = set()
    for s, e in offsets:
        if s == e:
            labels.append(-100)
            continue
        hit = next((k for k, sp in enumerate(spans) if sp.start < e and s < sp.end), None)
        if hit is None:
            labels.append(_LABEL_ID["O"])
        else:
            prefix = "I" if hit in started else "B"
            started.add(hit)
            labels.append(_LABEL_ID[f"{prefix}-{spans[hit].tag}"])
    return labels


def is_validation(example_id: str, fraction: float) -> bool:
    digest = int(hashlib.sha256(example_id.encode()).hexdigest()[:8], 16)
    return (digest % 10_000) < fraction * 10_000


@dataclass
class SpanScore:
    """Exact-span precision / recall per tag."""

    tp: Counter[str] = field(default_factory=Counter)
    fp: Counter[str] = field(default_factory=Counter)
    fn: Counter[str] = field(default_factory=Counter)

    def add(self, gold: Sequence[Span], pred: Sequence[Span]) -> None:
        g = Counter((s.tag, s.start, s.end) for s in gold)
        p = Counter((s.tag, s.start, s.end) for s in pred)
        for key in g | p:
            hit = min(g[key], p[key])
            self.tp[key[0]] += hit
            self.fp[key[0]] += p[key] - hit
            self.fn[key[0]] += g[key] - hit

    def table(self) -> dict[str, dict[str, float]]:
        out: dict[str, dict[str, float]] = {}
        for tag in (*TAGS, "all"):
            tp = sum(self.tp.values()) if tag == "all" else self.tp[tag]
            fp = sum(self.fp.values()) if tag == "all" else self.fp[tag]
            fn = sum(self.fn.values()) if tag == "all" else self.fn[tag]
            if tp + fp + fn == 0:
                continue
            p = tp / (tp + fp) if tp + fp else 0.0
            r = tp / (tp + fn) if tp + fn else 0.0
            out[tag] = {"precision": round(p, 3), "recall": round(r, 3),
                        "f1": round(2 * p * r / (p + r), 3) if p + r else 0.0, "n": tp + fn}
        return out


def train(
    examples: Sequence[Example],
    out: Path,
    encoder: str | None = None,
    epochs: int = 8,
    batch_size: int = 16,
    lr: float = 1e-3,
    rank: int = 16,
    alpha: float = 32.0,
    seed: int = 0,
    val_fraction: float = 0.1,
    log: Callable[[str], None] = print,
) -> dict[str, Any]:
    """Train on ``examples`` (minus the validation share), save to ``out``; the validation scores."""
    import torch

    random.seed(seed)
    torch.manual_seed(seed)
    encoder_path = resolve_encoder(encoder)
    module, tokenizer = new_model(encoder_path, rank=rank, alpha=alpha)
    train_set = [e for e in examples if not is_validation(e.id, val_fraction)]
    val_set = [e for e in examples if is_validation(e.id, val_fraction)]

    def encode(e: Example) -> tuple[list[int], list[int]]:
        enc = tokenizer(e.text, return_offsets_mapping=True, truncation=True, max_length=MAX_TOKENS)
        return list(enc["input_ids"]), token_labels([tuple(x) for x in enc["offset_mapping"]], e.spans)

    encoded = [encode(e) for e in train_set]
    params = [p for p in module.parameters() if p.requires_grad]
    optim = torch.optim.AdamW(params, lr=lr, weight_decay=0.01)
    steps_per_epoch = (len(encoded) + batch_size - 1) // batch_size
    total = max(steps_per_epoch * epochs, 1)
    warm = max(total // 20, 1)
    sched = torch.optim.lr_scheduler.LambdaLR(
        optim, lambda s: min((s + 1) / warm, max(0.0, (total - s) / max(total - warm, 1)))
    )
    loss_fn = torch.nn.CrossEntropyLoss(ignore_index=-100)
    log(f"train: {len(train_set)} rows, validation: {len(val_set)}; {sum(p.numel() for p in params):,} trained parameters")
    started = time.perf_counter()
    for epoch in range(epochs):
        module.train()
        order = sorted(range(len(encoded)), key=lambda i: (len(encoded[i][0]) + random.random() * 8))
        batches = [order[i : i + batch_size] for i in range(0, len(order), batch_size)]
        random.shuffle(batches)
        running = 0.0
        for batch in batches:
            width = max(len(encoded[i][0]) for i in batch)
            ids = torch.zeros((len(batch), width), dtype=torch.long)
            mask = torch.zeros((len(batch), width), dtype=torch.long)
            labels = torch.full((len(batch), width), -100, dtype=torch.long)
            for row, i in enumerate(batch):
                x, y = encoded[i]
                ids[row, : len(x)] = torch.tensor(x)
                mask[row, : len(x)] = 1
                labels[row, : len(y)] = torch.tensor(y)
            logits = module(ids, mask)
            loss = loss_fn(logits.reshape(-1, logits.shape[-1]), labels.reshape(-1))
            optim.zero_grad()
            loss.backward()
            torch.nn.utils.clip_grad_norm_(params, 1.0)
            optim.step()
            sched.step()
            running += loss.item()
        log(f"epoch {epoch + 1}/{epochs}: loss {running / max(len(batches), 1):.4f} "
            f"({time.perf_counter() - started:.0f} s)")
    module.eval()
    score = score_spans(module, tokenizer, val_set)
    meta = {
        "encoder": "all-MiniLM-L6-v2" if encoder in (None, "", "default", "minilm", "all-MiniLM-L6-v2") else encoder_path,
        "encoder_digest": encoder_digest(encoder_path), "rank": rank, "alpha": alpha, "epochs": epochs,
        "lr": lr, "batch_size": batch_size, "seed": seed, "rows": len(train_set), "validation_rows": len(val_set),
        "validation": score.table().get("all", {}),
    }
    save_weights(module, out, meta)
    log(f"saved {out} ({out.stat().st_size / 1e6:.1f} MB) in {time.perf_counter() - started:.0f} s")
    return {"meta": meta, "validation": score.table()}


def score_spans(module: Any, tokenizer: Any, examples: Sequence[Example]) -> SpanScore:
    """Exact-span scores of ``module`` on ``examples``."""
    import torch

    score = SpanScore()
    with torch.inference_mode():
        for e in examples:
            enc = tokenizer(e.text, return_offsets_mapping=True, truncation=True, max_length=MAX_TOKENS, return_tensors="pt")
            logp = torch.log_softmax(module(enc["input_ids"], enc["attention_mask"]), -1)[0].numpy()
            offsets = [tuple(x) for x in enc["offset_mapping"][0].tolist()]
            tokens = tokenizer.convert_ids_to_tokens(enc["input_ids"][0].tolist())
            score.add(e.spans, _token_spans(e.text, offsets, decode(logp, tokens, offsets), tokens, logp))
    return score
