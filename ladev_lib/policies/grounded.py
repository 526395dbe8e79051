"""``grounded``: a language-grounded scripted baseline.

It reads the instruction, and from the simulator only the objects on the
table (their instance names, catalog entries and poses) — never the scene's
task or the objects' roles. It reads the instruction with the language
reader (:func:`ladev_lib.language.frames.read_instruction`) into a frame,
grounds the object and destination phrases against the objects on the table
(:mod:`ladev_lib.language.grounding`), checks the task is one the scene
affords (a put_in target must be a container the source fits in), and
executes it with the oracle itself (``OraclePolicy`` on the motion skills of
``ladev_lib.policies.skills``), shown the understood task instead of the
scene's: where it understands, it does exactly what the oracle does.

Where it does not understand — no task of the four, a negation, an extra
step, a phrase that names nothing (or more than one thing) on the table, a
task the scene does not afford — it holds still and stops: a control
instruction ("do nothing", "sing a song") fails, as it should. Why is kept
in :attr:`GroundedPolicy.reading`.

``mode: retrieval`` keeps the earlier behaviour: the afforded task whose
short form's sentence embedding is nearest the instruction's (fooled like a
retriever is: a look-alike distractor, a role swap the embedding cannot see).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.catalog import Catalog, CatalogObject, load_catalog
from ladev_lib.language.embeddings import (
    DEFAULT_MODEL,
    SIMILARITY_DECIMALS,
    Embedder,
    load_embedder,
)
from ladev_lib.language.frames import Frame
from ladev_lib.language.grounding import Grounder
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.language.parser import default_parser
from ladev_lib.language.tasks import TASKS, needs_destination
from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.policies.motion import ArmMotion
from ladev_lib.policies.oracle import ORACLE_MAX_EPISODE_STEPS, OraclePolicy
from ladev_lib.scenes.feasibility import task_feasibility
from ladev_lib.scenes.spec import SceneBounds, SceneSpec, TaskSpec
from ladev_lib.vocabulary import TaskType


@dataclass(frozen=True)
class CandidateTask:
    """A task the scene affords, by object instance names, with its short-form text."""

    task: TaskType
    source: str
    target: str | None
    text: str


@dataclass(frozen=True)
class TaskChoice:
    """The retrieved task, its cosine similarity, and the runners-up (best first)."""

    chosen: CandidateTask
    score: float
    ranking: tuple[tuple[CandidateTask, float], ...]


def afforded_tasks(objects: Sequence[tuple[str, CatalogObject]]) -> list[CandidateTask]:
    """Every task the objects afford: (instance name, catalog entry) pairs in scene order."""
    out: list[CandidateTask] = []
    for task in TASKS:
        for s_name, s in objects:
            if not s.graspable:
                continue
            if task == "pick_up":
                out.append(CandidateTask(task, s_name, None, basic_instruction(task, s.display_name)))
                continue
            for t_name, t in objects:
                if t_name == s_name or task_feasibility(task, s, t) is not None:
                    continue
                text = basic_instruction(task, s.display_name, t.display_name)
                out.append(CandidateTask(task, s_name, t_name, text))
    return out


class TaskRetriever:
    """Nearest afforded task to an instruction by sentence-embedding cosine similarity."""

    def __init__(self, embedder: Embedder) -> None:
        self.embedder = embedder
        self._cache: dict[str, Array] = {}

    def _vectors(self, texts: Sequence[str]) -> Array:
        missing = sorted({t for t in texts if t not in self._cache})
        if missing:
            for text, vec in zip(missing, self.embedder.encode(missing), strict=True):
                self._cache[text] = vec
        return np.stack([self._cache[t] for t in texts])

    def choose(self, instruction: str, candidates: Sequence[CandidateTask], top: int = 5) -> TaskChoice:
        if not candidates:
            raise ValueError("the scene affords no task (no graspable object)")
        query = self.embedder.encode([instruction])[0]
        # rounded as every decision reads similarities, so that the choice is the same on any CPU
        scores = np.round((self._vectors([c.text for c in candidates]) @ query).astype(np.float64), SIMILARITY_DECIMALS)
        order = np.argsort(-scores, kind="stable")  # ties: the first in scene order
        ranking = tuple((candidates[int(i)], float(scores[int(i)])) for i in order[:top])
        best = int(order[0])
        return TaskChoice(candidates[best], float(scores[best]), ranking)


@dataclass(frozen=True)
class Reading:
    """What the reader made of an instruction on this table: a task, or why none."""

    frame: Frame
    task: CandidateTask | None
    reason: str | None
    groundings: tuple[str, ...] = ()


class TaskReader:
    """Reads an instruction into one afforded task over the objects on the table, or says why not."""

    def __init__(self, catalog: Catalog, grounder: Grounder) -> None:
        self.catalog = catalog
        self.grounder = grounder
        self.parser = default_parser(catalog)

    def read(self, instruction: str, objects: Sequence[tuple[str, CatalogObject]]) -> Reading:
        ids = [o.id for _, o in objects]
        frame = self.parser.read(instruction, ids)
        if not frame.ok or frame.task not in TASKS or frame.object is None:
            return Reading(frame, None, frame.reason or f"not one of the tasks: {frame.task}")
        scene = self.grounder.scene(dict.fromkeys(ids))
        roles: list[str | None] = []
        notes: list[str] = []
        phrases = [frame.object, frame.destination if needs_destination(frame.task) else None]
        for phrase in phrases:
            if phrase is None:
                roles.append(None)
                continue
            g = self.grounder.ground(phrase, scene)
            notes.append(g.describe())
            if g.object_id is None:
                return Reading(frame, None, g.reason or f"'{phrase.text}' names nothing on the table", tuple(notes))
            instance = next((name for name, o in objects if o.id == g.object_id), None)
            roles.append(instance)
        if needs_destination(frame.task) and roles[1] is None:
            return Reading(frame, None, "no destination on the table", tuple(notes))
        source, target = roles
        for candidate in afforded_tasks(objects):
            if (candidate.task, candidate.source, candidate.target) == (frame.task, source, target):
                return Reading(frame, candidate, None, tuple(notes))
        return Reading(frame, None, f"{frame.task}({source}, {target}) is not afforded by the scene", tuple(notes))


def scene_objects(spec: Any, catalog: Catalog) -> list[tuple[str, CatalogObject]]:
    """The objects on the table, by instance name. Reads names and ids only, never roles or task."""
    return [(o.name, catalog.get(o.id)) for o in spec.objects]


def spec_with_task(spec: SceneSpec, task: CandidateTask) -> SceneSpec:
    """The scene as the grounded policy understood it: its chosen task, roles to match."""

    def role(name: str) -> str:
        return "source" if name == task.source else "target" if name == task.target else "distractor"

    objects = tuple(o.model_copy(update={"role": role(o.name)}) for o in spec.objects)
    chosen = TaskSpec(type=task.task, source=task.source, target=task.target)
    return spec.model_copy(update={"task": chosen, "objects": objects})


class GroundedPolicy(Policy):
    """Retrieve the task from the instruction; execute it exactly as the oracle would."""

    def __init__(
        self,
        embedding_model: str = DEFAULT_MODEL,
        max_attempts: int = 3,
        bounds: SceneBounds | dict[str, object] | None = None,
        mode: str = "reader",
    ) -> None:
        if mode not in ("reader", "retrieval"):
            raise ValueError(f"grounded mode must be reader or retrieval, got {mode!r}")
        self.mode = mode
        self.info = PolicyInfo(
            name="grounded",
            robots=("panda",),
            control_mode="pd_joint_pos",
            image_size=None,
            privileged=True,
            max_episode_steps=ORACLE_MAX_EPISODE_STEPS,  # the oracle's time budget: a fair comparison
        )
        self.embedding_model = embedding_model
        self.catalog = load_catalog()
        embedder = load_embedder(embedding_model)
        self.retriever = TaskRetriever(embedder)
        self.reader = TaskReader(self.catalog, Grounder(self.catalog, embedder))
        self.reading: Reading | None = None
        self._holding = False
        # The executor: the oracle, shown the task this policy understood instead of the scene's.
        self.executor = OraclePolicy(max_attempts=max_attempts, bounds=bounds)
        self.instruction = ""
        self.choice: TaskChoice | None = None
        self._understood: SceneSpec | None = None

    def explain(self) -> str:
        """What it understood: the task read (or why none), or the retrieval's ranking."""
        if self.reading is not None:
            if self.reading.task is None:
                return f"holds still: {self.reading.reason}"
            return f"read {self.reading.task.text!r} ({'; '.join(self.reading.groundings)})"
        if self.choice is None:
            return "no task chosen yet"
        lines = [f"chose {self.choice.chosen.text!r} (similarity {self.choice.score:.3f})"]
        lines += [f"  {score:.3f}  {c.text}" for c, score in self.choice.ranking[1:]]
        return "\n".join(lines)

    def reset(self, instruction: str) -> None:
        self.instruction = instruction
        self.choice = None
        self.reading = None
        self._understood = None
        self._holding = False
        self.executor.reset(instruction)

    def step(self, obs: Observation) -> PolicyStep:
        priv = obs.privileged
        if priv is None or priv.scene is None:
            raise ValueError("grounded is privileged: it needs the object list and the scene's view")
        if self._holding:
            return PolicyStep(action=ArmMotion(priv.scene).hold_action(), terminate=True)
        if self._understood is None:
            objects = scene_objects(priv.spec, self.catalog)
            if self.mode == "retrieval":
                self.choice = self.retriever.choose(self.instruction, afforded_tasks(objects))
                chosen = self.choice.chosen
            else:
                self.reading = self.reader.read(self.instruction, objects)
                if self.reading.task is None:
                    self._holding = True  # not understood: no-op action, and stop
                    return PolicyStep(action=ArmMotion(priv.scene).hold_action(), terminate=True)
                chosen = self.reading.task
            self._understood = spec_with_task(priv.spec, chosen)
        view = dataclasses.replace(priv, spec=self._understood)
        return self.executor.step(dataclasses.replace(obs, privileged=view))
