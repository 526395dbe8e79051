"""``grounded``: a language-grounded scripted baseline.

It reads the instruction, and from the simulator only the objects on the
table (their instance names, catalog entries and poses) — never the scene's
task or the objects' roles. It lists the tasks the scene affords, each in the
standard short form ("pick up the apple", "put the apple on the plate"), over
the objects' display names and respecting what they can do (a put_in target
must be a container the source fits in), then picks the one whose sentence
embedding is nearest the instruction's (all-MiniLM-L6-v2 by default, loaded
once per process; one batch per episode, candidate embeddings cached), and
executes it with the oracle's motion skills (``ladev_lib.policies.skills``).

So its success moves with language the way a VLA's should not: a paraphrase
far from the short form, a distractor whose name is close to the source's, a
role swap the embedding cannot see, each can make it solve the wrong task.
What it chose is kept in :attr:`GroundedPolicy.choice` for inspection.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ladev_lib.catalog import Catalog, CatalogObject, load_catalog
from ladev_lib.language.embeddings import DEFAULT_MODEL, Embedder, load_embedder
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.policies.base import EpisodeContext, Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.scenes.feasibility import task_feasibility

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


class GroundedPolicy(Policy):
    """Retrieve the task from the instruction, execute it with the Panda motion skills."""

    def __init__(self, embedding_model: str = DEFAULT_MODEL, max_attempts: int = 3) -> None:
        self.info = PolicyInfo(
            name="grounded",
            robots=("panda",),
            control_mode="pd_joint_pos",
            image_size=None,
            privileged=True,
        )
        self.embedding_model = embedding_model
        self.max_attempts = max_attempts
        self.catalog = load_catalog()
        self.retriever = TaskRetriever(load_embedder(embedding_model))
        self.instruction = ""
        self.choice: TaskChoice | None = None
        self._actions: Iterator[np.ndarray] | None = None
        self._last: np.ndarray | None = None
        self._ctx: EpisodeContext | None = None

    def begin_episode(self, ctx: EpisodeContext) -> None:
        self._ctx = ctx

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
        self._actions = None
        self._last = None

    def _start(self, obs: Observation) -> Iterator[np.ndarray]:
        from ladev_lib.policies.skills import TaskSkill

        if obs.privileged is None or obs.privileged.env is None:
            raise RuntimeError("grounded is privileged: it needs the object list and the env")
        objects = scene_objects(obs.privileged.spec, self.catalog)
        self.choice = self.retriever.choose(self.instruction, afforded_tasks(objects))
        c = self.choice.chosen
        return iter(TaskSkill(obs.privileged.env, c.task, c.source, c.target, max_attempts=self.max_attempts))

    def _hold(self, obs: Observation) -> np.ndarray:
        """Stay where the arm is, gripper as it was (used only if the skill ends at once)."""
        if self._last is not None:
            return self._last
        if self._ctx is None or obs.proprio is None:
            raise RuntimeError("begin_episode() must be called before step()")
        n = self._ctx.action_low.shape[0]
        hold = np.concatenate([obs.proprio[: n - 1], [self._ctx.action_high[-1]]])
        return hold.astype(np.float32)

    def step(self, obs: Observation) -> PolicyStep:
        if self._actions is None:
            self._actions = self._start(obs)
        try:
            self._last = np.asarray(next(self._actions), dtype=np.float32)
        except StopIteration:
            return PolicyStep(action=self._hold(obs), terminate=True)
        return PolicyStep(action=self._last)
