"""Test doubles for the episode engine: a toy simulator and a scripted policy.

``ToySim`` implements the engine's ``EpisodeSim`` protocol without SAPIEN: a
point moves on the table by the actions, and the task succeeds when it
reaches the source object's position. ``ScriptedToyPolicy`` drives it there,
and misbehaves on request, chosen by words in the instruction, so one run can
hold healthy episodes and each kind of failure:

    "raise"     the policy raises at step 1
    "nan"       the policy returns a NaN action at step 1
    "shape"     the policy returns an action of the wrong shape
    "hang"      the policy blocks every signal and sleeps in C holding the GIL
    "die-once"  the worker process kills itself at step 1, the first time only
    "slow"      the policy sleeps 100 ms per step
    "late"      the misbehaviour above happens at step 5 instead of step 1

A scene whose id contains "sim-crash" makes the simulator raise at step 2;
"bad-scene" makes the validity check fail. Workers import this module by name
(tests.rollout.doubles), so it must stay importable from the repository root.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import random
import signal
import time
from pathlib import Path

import numpy as np

from ladev_lib.policies.base import (
    EpisodeContext,
    Observation,
    Policy,
    PolicyInfo,
    PolicyStep,
    PrivilegedState,
)
from ladev_lib.rollout.simulator import SimSetup
from ladev_lib.scenes import SceneSpec

ACTION_DIM = 2
STEP_SIZE = 0.01
REACH_M = 0.02
MAX_STEPS = 60

# Where "die-once" leaves its marker and every policy reset logs a line (set by tests).
MARKER_DIR_ENV = "LADEV_TEST_MARKERS"
RUN_LOG_ENV = "LADEV_TEST_RUN_LOG"


class ToySim:
    """A point robot on a table: state-only physics, deterministic."""

    def __init__(self, setup: SimSetup) -> None:
        self.setup = setup
        self.spec: SceneSpec | None = None
        self.pos = np.zeros(2)
        self.steps = 0
        self.loads = 0

    def load(self, spec: SceneSpec, seed: int) -> None:
        self.spec = spec
        rng = np.random.default_rng(seed)
        self.pos = rng.uniform(-0.05, 0.05, size=2)
        self.steps = 0
        self.loads += 1

    def _goal(self) -> np.ndarray:
        assert self.spec is not None
        src = self.spec.source
        return np.array([src.x, src.y])

    def action_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return -np.ones(ACTION_DIM), np.ones(ACTION_DIM)

    def invalid_reason(self) -> str | None:
        assert self.spec is not None
        if "bad-scene" in (self.spec.scene_id or ""):
            return "objects interpenetrate at spawn (injected by the test)"
        return None

    def max_steps(self, task: str) -> int:
        return MAX_STEPS

    def observe(self, *, image: bool, privileged: bool) -> Observation:
        assert self.spec is not None
        priv = None
        if privileged:
            poses = {o.name: np.array([o.x, o.y, 0.0, 1.0, 0.0, 0.0, 0.0]) for o in self.spec.objects}
            priv = PrivilegedState(spec=self.spec, object_poses=poses, scene=self)
        return Observation(image=self.frame() if image else None, proprio=self.pos.copy(), privileged=priv)

    def step(self, action: np.ndarray) -> dict[str, bool]:
        assert self.spec is not None
        self.steps += 1
        if "sim-crash" in (self.spec.scene_id or "") and self.steps == 2:
            raise RuntimeError("injected simulator failure")
        self.pos = self.pos + STEP_SIZE * np.clip(action, -1, 1)
        return self.evaluate()

    def evaluate(self) -> dict[str, bool]:
        reached = bool(np.linalg.norm(self.pos - self._goal()) < REACH_M)
        return {"reached": reached, "success": reached}

    def frame(self) -> np.ndarray:
        w, h = self.setup.image_size or (32, 32)
        img = np.zeros((h, w, 3), dtype=np.uint8)
        col = int(np.clip((self.pos[1] + 0.25) / 0.5, 0, 0.999) * w)
        row = int(np.clip((0.15 - self.pos[0]) / 0.3, 0, 0.999) * h)
        img[row, col] = 255
        img[..., 1] = min(255, 10 * self.steps)
        return img

    def close(self) -> None:
        self.spec = None


def make_toy_sim(setup: SimSetup) -> ToySim:
    return ToySim(setup)


def _hang_in_c() -> None:
    """Stuck in C holding the GIL, deaf to every catchable signal: only SIGKILL ends it."""
    catchable = set(signal.Signals) - {signal.SIGKILL, signal.SIGSTOP}
    signal.pthread_sigmask(signal.SIG_BLOCK, catchable)
    ctypes.PyDLL(None).sleep(3600)


class ScriptedToyPolicy(Policy):
    """Privileged: heads for the source object; misbehaves when the instruction says so."""

    def __init__(
        self, image_size: tuple[int, int] | None = None, gain: float = 1.0, robot: str = "panda"
    ) -> None:
        self.info = PolicyInfo(
            name="scripted-toy",
            robots=(robot,),
            control_mode="toy_delta_xy",
            image_size=tuple(image_size) if image_size else None,  # type: ignore[arg-type]
            privileged=True,
        )
        self.gain = gain
        self.instruction = ""
        self.seed = 0

    def begin_episode(self, ctx: EpisodeContext) -> None:
        self.seed = ctx.seed

    def reset(self, instruction: str) -> None:
        self.instruction = instruction
        log = os.environ.get(RUN_LOG_ENV)
        if log:
            with open(log, "a", encoding="utf-8") as f:
                f.write(f"{instruction}\t{os.getpid()}\n")

    def _once(self, what: str) -> bool:
        marker_dir = Path(os.environ.get(MARKER_DIR_ENV, "."))
        key = hashlib.sha256(self.instruction.encode()).hexdigest()[:12]
        marker = marker_dir / f"{what}-{key}-{self.seed}"
        if marker.exists():
            return False
        marker.write_text("x")
        return True

    def step(self, obs: Observation) -> PolicyStep:
        text = self.instruction
        if "slow" in text:
            time.sleep(0.1)
        if obs.step == (5 if "late" in text else 1):
            if "raise" in text:
                raise ValueError("injected policy failure")
            if "nan" in text:
                return PolicyStep(action=np.array([np.nan, 0.0]))
            if "shape" in text:
                return PolicyStep(action=np.zeros(ACTION_DIM + 1))
            if "hang" in text:
                _hang_in_c()
            if "die-once" in text and self._once("die"):
                os.kill(os.getpid(), signal.SIGKILL)
        assert obs.privileged is not None and obs.proprio is not None
        src = obs.privileged.spec.source
        delta = (np.array([src.x, src.y]) - obs.proprio) / STEP_SIZE
        return PolicyStep(action=np.clip(self.gain * delta, -1, 1))


def make_scripted_policy(**config: object) -> ScriptedToyPolicy:
    return ScriptedToyPolicy(**config)  # type: ignore[arg-type]


class NoisyToyPolicy(ScriptedToyPolicy):
    """Heads for the source through noise drawn from Python's ``random``, NumPy's global
    generator and the C library's ``rand()``: its outcomes repeat only if the engine seeds
    all three per episode."""

    def step(self, obs: Observation) -> PolicyStep:
        base = np.asarray(super().step(obs).action, dtype=float)
        libc_draw = (ctypes.CDLL(None).rand() % 1000) / 1000.0 - 0.5
        noise = np.array([random.uniform(-1, 1), np.random.uniform(-1, 1)]) + libc_draw
        return PolicyStep(action=np.clip(0.6 * base + 0.9 * noise, -1, 1))


def make_noisy_policy(**config: object) -> NoisyToyPolicy:
    return NoisyToyPolicy(**config)  # type: ignore[arg-type]
