"""The language side's two LLM jobs: ``paraphrase`` and ``parse_instruction``.

Each job has a request builder (template inputs -> rendered request, through
``ladev_lib.llm.prompts``), an answer schema, and an offline handler that
answers the same request deterministically (registered in ``OFFLINE_JOBS``
by :mod:`ladev_lib.language.offline_jobs`). The ``LLMReader`` reads
instructions into (task, source, target) through any backend, resolving the
object names the model gives against the catalog (and the scene).
"""

from __future__ import annotations

import json
from collections.abc import Sequence

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language.lexicon import DETERMINERS
from ladev_lib.language.mentions import ObjectRef, name_index
from ladev_lib.language.paraphrase import offline_paraphrases
from ladev_lib.language.parser import InstructionParse, parse_instruction
from ladev_lib.language.tasks import TaskType
from ladev_lib.llm.base import LLMRequest
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate, build_request
from ladev_lib.vocabulary import as_task

PARAPHRASE_JOB = "paraphrase"
PARSE_JOB = "parse_instruction"

RULE_MODULES: tuple[str, ...] = (
    "ladev_lib.language.paraphrase",
    "ladev_lib.language.parser",
    "ladev_lib.language.clauses",
    "ladev_lib.language.tokens",
    "ladev_lib.language.lexicon",
    "ladev_lib.language.mentions",
    "ladev_lib.language.instructions",
)
"""Modules the offline answers depend on (fingerprinted by the offline backend)."""

TaskName = TaskType


class ParaphraseAnswer(BaseModel):
    """The paraphrase job's answer."""

    model_config = ConfigDict(extra="ignore")

    paraphrases: list[str] = Field(description="Alternative instructions for the same task.")
    problem: str | None = Field(default=None, description="Why fewer (or none) could be written.")


class ParseAnswer(BaseModel):
    """The parse_instruction job's answer: objects as named in the instruction."""

    model_config = ConfigDict(extra="ignore")

    task: TaskName | None = None
    source: str | None = Field(default=None, description="The object to manipulate, as named.")
    target: str | None = Field(default=None, description="The reference object, as named (null for pick_up).")
    problem: str | None = Field(
        default=None, description="Why the instruction does not ask for exactly one task of the four."
    )


# -- requests ------------------------------------------------------------------


def paraphrase_request(
    prompt: PromptTemplate, llm: LLMConfig, instruction: str, k: int, seed: int | None = None
) -> LLMRequest:
    """Ask for ``k`` paraphrases of one instruction."""
    return build_request(
        PARAPHRASE_JOB,
        prompt,
        {"instruction": instruction, "k": k},
        llm,
        json_schema=ParaphraseAnswer.model_json_schema(),
        seed=seed,
    )


def parse_request(
    prompt: PromptTemplate, llm: LLMConfig, instruction: str, object_names: Sequence[str] = ()
) -> LLMRequest:
    """Ask for the (task, source, target) an instruction states; ``object_names`` are the scene's."""
    return build_request(
        PARSE_JOB,
        prompt,
        {"instruction": instruction, "objects": list(object_names)},
        llm,
        json_schema=ParseAnswer.model_json_schema(),
    )


# -- offline handlers ---------------------------------------------------------------


def offline_paraphrase_job(request: LLMRequest) -> str:
    """Read the instruction with the parser, then write k paraphrases compositionally."""
    instruction = str(request.inputs["instruction"])
    k = int(request.inputs["k"])
    parse = parse_instruction(instruction)
    if not parse.ok or parse.task is None or parse.source is None:
        answer = ParaphraseAnswer(paraphrases=[], problem=f"cannot read the instruction: {parse.reason}")
    else:
        sentences = offline_paraphrases(parse.task, parse.source, parse.target, k, seed=request.seed or 0)
        answer = ParaphraseAnswer(paraphrases=sentences)
    return answer.model_dump_json(exclude_none=True)


def offline_parse_job(request: LLMRequest) -> str:
    """Parse with the grammar; answer with display names, as a model would name the objects."""
    catalog = load_catalog()
    index = name_index(catalog)
    scene = {
        index.names[tuple(normalize_name(n).split())]
        for n in request.inputs.get("objects") or []
        if tuple(normalize_name(n).split()) in index.names
    }
    parse = parse_instruction(str(request.inputs["instruction"]), scene or None, catalog)
    if not parse.ok:
        return json.dumps({"task": None, "source": None, "target": None, "problem": parse.reason})
    return ParseAnswer(
        task=as_task(parse.task or ""),
        source=index.display_name(parse.source) if parse.source else None,
        target=index.display_name(parse.target) if parse.target else None,
    ).model_dump_json()


# -- reading through an LLM ---------------------------------------------------------


class LLMReader:
    """Reads instructions with the ``parse_instruction`` job of any backend."""

    name = "llm"

    def __init__(
        self,
        client: LLMClient,
        prompt: PromptTemplate,
        llm: LLMConfig,
        catalog: Catalog | None = None,
    ) -> None:
        self.client = client
        self.prompt = prompt
        self.llm = llm
        self.catalog = catalog or load_catalog()
        self.index = name_index(self.catalog)
        self.call_ids: list[str] = []

    def read(
        self, texts: Sequence[str], scene_objects: Sequence[frozenset[str] | None]
    ) -> list[InstructionParse]:
        return [self.read_one(t, s) for t, s in zip(texts, scene_objects, strict=True)]

    def read_one(self, text: str, scene: frozenset[str] | None) -> InstructionParse:
        names = [self.index.display_name(o) for o in sorted(scene)] if scene else []
        result = self.client.complete_json(parse_request(self.prompt, self.llm, text, names), ParseAnswer)
        self.call_ids.extend(result.call_ids)
        if result.value is None:
            return InstructionParse(text, None, None, None, f"LLM gave no usable reading: {result.reason}")
        answer = result.value
        if answer.problem:
            return InstructionParse(text, answer.task, None, None, f"LLM: {answer.problem}")
        reasons: list[str] = []
        source = self._resolve(answer.source, scene, "source", reasons)
        target = self._resolve(answer.target, scene, "target", reasons)
        if answer.task is None:
            reasons.append("LLM named no task")
        return InstructionParse(text, answer.task, source, target, "; ".join(reasons) or None)

    def _resolve(
        self, name: str | None, scene: frozenset[str] | None, role: str, reasons: list[str]
    ) -> str | None:
        if not name:
            return None
        ref = resolve_name(name, self.catalog, scene)
        if ref.object_id is None:
            reasons.append(f"{role} {ref.problem or repr(name) + ' is not a catalog object'}")
        return ref.object_id


def resolve_name(name: str, catalog: Catalog, scene: frozenset[str] | None = None) -> ObjectRef:
    """A catalog object for a name as a person or a model writes it ("the can of coke")."""
    index = name_index(catalog)
    words = [w for w in normalize_name(name).split() if w not in DETERMINERS]
    if not words:
        return ObjectRef(name, problem=f"'{name}' names no object")
    exact = index.names.get(tuple(words))
    if exact is not None:
        return index.prefer_scene(exact, words, scene, name)
    found = index.resolve_head(words, scene, name)
    return found or ObjectRef(name, problem=f"'{name}' names no known object")
