"""The paraphrase stage's logic: basic instructions in, validated instructions out.

For every scene that generated and compiled ``ok``:

- the basic instruction (``scenes.parquet``'s ``base_instruction``) becomes a
  ``basic`` row, always valid and selected;
- the LLM layer is asked for k paraphrases (one cached call per distinct
  instruction), each validated against the scene's task (similarity and
  structural round-trip, resolving names against the scene's objects) and
  written as a ``paraphrase`` row with its scores, its reading and, when
  rejected, the reason;
- for scenes of the ``instruction`` factor, one valid paraphrase is drawn
  (seeded by the study seed and the scene id) and marked ``selected``, as the
  paper "randomly chose one from ten paraphrased task instructions".
"""

from __future__ import annotations

import random
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.language.llm_jobs import ParaphraseAnswer, paraphrase_request
from ladev_lib.language.paraphrase import sentence_key
from ladev_lib.language.parser import InstructionParse
from ladev_lib.language.validator import ParaphraseValidator, Verdict
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.tables import CompiledSceneRow, InstructionRow, SceneDesignRow

Progress = Callable[[Iterable[Any], int, str], Iterable[Any]]
VALIDATION_CHUNK = 512
"""Candidates validated per batch (one progress step)."""


def _no_progress(items: Iterable[Any], total: int, desc: str) -> Iterable[Any]:
    return items


@dataclass(frozen=True)
class SceneTask:
    """What one scene asks for, from its compiled spec."""

    scene_id: str
    factor: str
    instruction: str
    expected: InstructionParse
    objects: frozenset[str]


@dataclass
class ParaphraseOutcome:
    rows: list[InstructionRow]
    summary: dict[str, Any] = field(default_factory=dict)


def scene_tasks(
    scenes: Sequence[SceneDesignRow], compiled: Sequence[CompiledSceneRow]
) -> tuple[list[SceneTask], dict[str, int]]:
    """The scenes to paraphrase, and counts of those skipped (by why)."""
    by_id = {c.scene_id: c for c in compiled}
    tasks: list[SceneTask] = []
    skipped: Counter[str] = Counter()
    for s in scenes:
        comp = by_id.get(s.scene_id)
        if s.status != "ok" or not s.base_instruction:
            skipped["generation failed"] += 1
            continue
        if comp is None or comp.status != "ok" or not comp.spec_json:
            skipped["not compiled"] += 1
            continue
        spec = SceneSpec.from_json(comp.spec_json)
        target = spec.target.id if spec.target is not None else None
        expected = InstructionParse(s.base_instruction, spec.task.type, spec.source.id, target)
        objects = frozenset(o.id for o in spec.objects)
        tasks.append(SceneTask(s.scene_id, s.factor, s.base_instruction, expected, objects))
    return tasks, dict(skipped)


def paraphrase_scenes(
    tasks: Sequence[SceneTask],
    *,
    client: LLMClient,
    prompt: PromptTemplate,
    llm: LLMConfig,
    validator: ParaphraseValidator,
    k: int,
    seed: int,
    progress: Progress = _no_progress,
) -> ParaphraseOutcome:
    """Rows of ``instructions.parquet`` for the given scenes."""
    answers = _ask(tasks, client, prompt, llm, k, progress)
    pairs: list[tuple[str, str]] = []
    owners: list[tuple[SceneTask, int]] = []
    for t in tasks:
        for i, cand in enumerate(answers[t.instruction].candidates, start=1):
            pairs.append((t.instruction, cand))
            owners.append((t, i))
    verdicts: list[Verdict] = []
    chunks = range(0, len(pairs), VALIDATION_CHUNK)
    for start in progress(chunks, len(chunks), "validate"):
        part = owners[start : start + VALIDATION_CHUNK]
        verdicts += validator.validate_pairs(
            pairs[start : start + VALIDATION_CHUNK], [t.objects for t, _ in part], [t.expected for t, _ in part]
        )
    by_scene: dict[str, list[tuple[int, Verdict]]] = {}
    for (t, i), v in zip(owners, verdicts, strict=True):
        by_scene.setdefault(t.scene_id, []).append((i, v))
    basics = validator.reader.read([t.instruction for t in tasks], [t.objects for t in tasks])

    rows: list[InstructionRow] = []
    missing_selection: list[str] = []
    for t, basic_parse in zip(tasks, basics, strict=True):
        answer = answers[t.instruction]
        rows.append(_basic_row(t, basic_parse, answer.call_ids))
        scene_rows = [_candidate_row(t, i, v, answer.call_ids) for i, v in by_scene.get(t.scene_id, [])]
        if answer.problem is not None and not scene_rows:
            scene_rows.append(_error_row(t, answer.problem, answer.call_ids))
        if t.factor == "instruction":
            valid = [r for r in scene_rows if r.valid]
            if valid:
                chosen = random.Random(f"ladev-select:{seed}:{t.scene_id}").choice(valid)
                chosen.selected = True
            else:
                missing_selection.append(t.scene_id)
        rows.extend(scene_rows)
    summary = _summary(rows, tasks, missing_selection, client)
    return ParaphraseOutcome(rows, summary)


@dataclass
class _Answer:
    candidates: list[str]
    call_ids: list[str]
    problem: str | None


def _ask(
    tasks: Sequence[SceneTask],
    client: LLMClient,
    prompt: PromptTemplate,
    llm: LLMConfig,
    k: int,
    progress: Progress,
) -> dict[str, _Answer]:
    """One (cached) call per distinct basic instruction; candidates de-duplicated, at most k."""
    instructions = list(dict.fromkeys(t.instruction for t in tasks))
    answers: dict[str, _Answer] = {}
    for text in progress(instructions, len(instructions), "paraphrase"):
        result = client.complete_json(paraphrase_request(prompt, llm, text, k), ParaphraseAnswer)
        if result.value is None:
            answers[text] = _Answer([], result.call_ids, f"LLM gave no usable answer: {result.reason}")
            continue
        seen = {sentence_key(text)}
        kept: list[str] = []
        for cand in result.value.paraphrases:
            key = sentence_key(cand)
            if cand.strip() and key not in seen:
                seen.add(key)
                kept.append(cand.strip())
        problem = result.value.problem
        if len(kept) < k and problem is None:
            problem = f"{len(kept)} distinct paraphrases of {k} asked"
        answers[text] = _Answer(kept[:k], result.call_ids, problem)
    return answers


def _basic_row(t: SceneTask, parse: InstructionParse, call_ids: list[str]) -> InstructionRow:
    # The basic instruction is the reference; its own reading is recorded as a check.
    disagrees = parse.roles != t.expected.roles or not parse.ok
    reason = None
    if disagrees:
        reason = f"basic instruction reads as {parse.roles} ({parse.reason or 'parsed'}), spec says {t.expected.roles}"
    return InstructionRow(
        instruction_id=f"{t.scene_id}/basic",
        scene_id=t.scene_id,
        kind="basic",
        text=t.instruction,
        parsed_task=parse.task,
        parsed_source=parse.source,
        parsed_target=parse.target,
        valid=True,
        reason=reason,
        selected=True,
        llm_call_ids=[],
    )


def _candidate_row(t: SceneTask, i: int, v: Verdict, call_ids: list[str]) -> InstructionRow:
    return InstructionRow(
        instruction_id=f"{t.scene_id}/para-{i}",
        scene_id=t.scene_id,
        kind="paraphrase",
        text=v.candidate,
        similarity=round(v.similarity, 4),
        canonical_similarity=round(v.canonical_similarity, 4) if v.canonical_similarity is not None else None,
        parsed_task=v.parse.task,
        parsed_source=v.parse.source,
        parsed_target=v.parse.target,
        valid=v.valid,
        reason=v.reason,
        selected=False,
        llm_call_ids=list(call_ids),
    )


def _error_row(t: SceneTask, problem: str, call_ids: list[str]) -> InstructionRow:
    return InstructionRow(
        instruction_id=f"{t.scene_id}/para-error",
        scene_id=t.scene_id,
        kind="paraphrase",
        text="",
        valid=False,
        reason=problem,
        selected=False,
        llm_call_ids=list(call_ids),
    )


def _summary(
    rows: list[InstructionRow], tasks: Sequence[SceneTask], missing: list[str], client: LLMClient
) -> dict[str, Any]:
    candidates = [r for r in rows if r.kind == "paraphrase" and r.text]
    valid = [r for r in candidates if r.valid]
    reasons: Counter[str] = Counter()
    for r in candidates:
        if not r.valid and r.reason:
            reasons[r.reason.split(":")[0]] += 1
    return {
        "scenes": len(tasks),
        "candidates": len(candidates),
        "valid": len(valid),
        "valid_rate": round(len(valid) / len(candidates), 4) if candidates else None,
        "instruction_scenes": sum(t.factor == "instruction" for t in tasks),
        "selected_paraphrases": sum(r.selected and r.kind == "paraphrase" for r in rows),
        "instruction_scenes_without_valid_paraphrase": missing,
        "rejections": dict(reasons.most_common()),
        "llm_calls": client.calls,
        "llm_cache_hits": client.cache_hits,
    }
