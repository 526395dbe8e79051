"""``grounded``: a language-grounded scripted baseline.

It reads the instruction, and from the simulator only the objects on the
table (their instance names, catalog entries and poses) — never the scene's
task or the objects' roles. It lists the tasks the scene affords, each in the
standard short form ("pick up the apple", "put the apple on the plate"), over
the objects' display names and respecting what they can do (a put_in target
must be a container the source fits in), then picks the one whose sentence
embedding is nearest the instruction's (all-MiniLM-L6-v2 by default, loaded
once per process; candidate embeddings cached), and executes it with the
oracle itself (``OraclePolicy`` on the motion skills of
``ladev_lib.policies.skills``), shown the understood task instead of the
scene's: where it understands, it does exactly what the oracle does.

So its success moves with language the way a VLA's should not: a paraphrase
far from the short form, a distractor whose name is close to the source's, a
role swap the embedding cannot see, each can make it solve the wrong task.
What it chose is kept in :attr:`GroundedPolicy.choice` for inspection.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ladev_lib.catalog import Catalog, CatalogObject, load_catalog
from ladev_lib.language.embeddings import DEFAULT_MODEL, Embedder, load_embedder
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.policies.oracle import ORACLE_MAX_EPISODE_STEPS, OraclePolicy
from ladev_lib.scenes.feasibility import task_feasibility
from ladev_lib.scenes.spec import SceneBounds, SceneSpec, TaskSpec

TASK_ORDER: tuple[str, ...] = ("pick_up", "move_near", "put_on", "put_in")


@dataclass(frozen=True)
class CandidateTask:
    """A task the scene affords, by object instance names, with its short-form text."""

    task: str
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
    for task in TASK_ORDER:
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
        self._cache: dict[str, np.ndarray] = {}

    def _vectors(self, texts: Sequence[str]) -> np.ndarray:
        missing = sorted({t for t in texts if t not in self._cache})
        if missing:
            for text, vec in zip(missing, self.embedder.encode(missing), strict=True):
                self._cache[text] = vec
        return np.stack([self._cache[t] for t in texts])

    def choose(self, instruction: str, candidates: Sequence[CandidateTask], top: int = 5) -> TaskChoice:
        if not candidates:
            raise ValueError("the scene affords no task (no graspable object)")
        query = self.embedder.encode([instruction])[0]
        scores = self._vectors([c.text for c in candidates]) @ query
        order = np.argsort(-scores, kind="stable")  # ties: the first in scene order
        ranking = tuple((candidates[int(i)], float(scores[int(i)])) for i in order[:top])
        best = int(order[0])
        return TaskChoice(candidates[best], float(scores[best]), ranking)


def scene_objects(spec: Any, catalog: Catalog) -> list[tuple[str, CatalogObject]]:
    """The objects on the table, by instance name. Reads names and ids only, never roles or task."""
    return [(o.name, catalog.get(o.id)) for o in spec.objects]


def spec_with_task(spec: SceneSpec, task: CandidateTask) -> SceneSpec:
    """The scene as the grounded policy understood it: its chosen task, roles to match."""

    def role(name: str) -> str:
        return "source" if name == task.source else "target" if name == task.target else "distractor"

    objects = tuple(o.model_copy(update={"role": role(o.name)}) for o in spec.objects)
    chosen = TaskSpec(type=task.task, source=task.source, target=task.target)  # type: ignore[arg-type]
    return spec.model_copy(update={"task": chosen, "objects": objects})


class GroundedPolicy(Policy):
    """Retrieve the task from the instruction; execute it exactly as the oracle would."""

    def __init__(
        self,
        embedding_model: str = DEFAULT_MODEL,
        max_attempts: int = 3,
        bounds: SceneBounds | dict[str, object] | None = None,
    ) -> None:
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
        self.retriever = TaskRetriever(load_embedder(embedding_model))
        # The executor: the oracle, shown the task this policy understood instead of the scene's.
        self.executor = OraclePolicy(max_attempts=max_attempts, bounds=bounds)
        self.instruction = ""
        self.choice: TaskChoice | None = None
        self._understood: SceneSpec | None = None

    def explain(self) -> str:
        """What it understood: the chosen task and the runners-up, with similarities."""
        if self.choice is None:
            return "no task chosen yet"
        lines = [f"chose {self.choice.chosen.text!r} (similarity {self.choice.score:.3f})"]
        lines += [f"  {score:.3f}  {c.text}" for c, score in self.choice.ranking[1:]]
        return "\n".join(lines)

    def reset(self, instruction: str) -> None:
        self.instruction = instruction
        self.choice = None
        self._understood = None
        self.executor.reset(instruction)

    def step(self, obs: Observation) -> PolicyStep:
        priv = obs.privileged
        if priv is None or priv.scene is None:
            raise ValueError("grounded is privileged: it needs the object list and the scene's view")
        if self._understood is None:
            objects = scene_objects(priv.spec, self.catalog)
            self.choice = self.retriever.choose(self.instruction, afforded_tasks(objects))
            self._understood = spec_with_task(priv.spec, self.choice.chosen)
        view = dataclasses.replace(priv, spec=self._understood)
        return self.executor.step(dataclasses.replace(obs, privileged=view))
