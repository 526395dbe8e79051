"""Is a scene solvable? Run the privileged oracle on it and report what happened.

    result = check_solvable(spec)                      # builds a state-only env
    result.solved, result.reason, result.predicates

    for result in check_scenes(specs):                 # one env reused for all
        ...

LADEV proves generated scenes solvable this way: a scene the oracle solves is
known to be physically possible for the Panda; one it fails is reported with
the reason (no grasp fits, nothing reachable, the object slipped, the final
predicates that are false), never dropped silently.
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.policies.base import Observation, PrivilegedState
from ladev_lib.policies.oracle import OraclePolicy
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.sim.config import SimConfig

SOLVABILITY_VERSION: Literal[1] = 1


class SolvabilityResult(BaseModel):
    """The oracle's verdict on one scene."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    schema_version: Literal[1] = SOLVABILITY_VERSION
    scene_id: str | None = None
    task: str
    status: Literal["solved", "failed", "error"]
    """solved: the task's success predicate holds at the end; failed: it does not;
    error: the check itself crashed (a bug; ``reason`` has the exception)."""
    reason: str = Field(default="", description="Why it failed; empty when solved.")
    predicates: dict[str, bool] = Field(default_factory=dict, description="Final task predicates.")
    steps: int = 0
    seconds: float = 0.0
    attempts: int = Field(default=0, description="Grasp attempts the oracle made.")
    object_sources: dict[str, str] = Field(
        default_factory=dict, description="Object name -> 'mesh' or 'standin', as built."
    )

    @property
    def solved(self) -> bool:
        return self.status == "solved"


def make_check_env(
    spec: SceneSpec, sim_config: SimConfig | None = None, *, prefer_meshes: bool = True
) -> Any:
    """A state-only Panda env for the oracle (no camera: nothing is rendered).

    ``prefer_meshes=False`` builds stand-ins even where ``MS_ASSET_DIR`` has meshes.
    """
    from ladev_lib.sim import make_env

    return make_env(
        spec,
        sim_config,
        control_mode=OraclePolicy.info.control_mode,
        image_size=None,
        obs_mode="none",
        prefer_meshes=prefer_meshes,
    )


def check_solvable(
    spec: SceneSpec,
    sim_config: SimConfig | None = None,
    *,
    env: Any = None,
    max_steps: int | None = None,
    policy: OraclePolicy | None = None,
) -> SolvabilityResult:
    """Run the oracle on ``spec`` and judge the final state with the task's predicates.

    ``env`` (a ``LADEV-Scene-v1`` env made with ``pd_joint_pos``) is reused when given:
    it is reset to ``spec``. Otherwise a state-only env is made and closed here.
    """
    own_env = env is None
    if env is None:
        env = make_check_env(spec, sim_config)
    try:
        return _run(env, spec, policy or OraclePolicy(), max_steps)
    finally:
        if own_env:
            env.close()


def _run(env: Any, spec: SceneSpec, policy: OraclePolicy, max_steps: int | None) -> SolvabilityResult:
    start = time.perf_counter()
    env.reset(seed=spec.seed, options={"spec": spec.model_dump(mode="json")})
    u = env.unwrapped
    limit = max_steps or policy.info.max_episode_steps or 400
    policy.reset("")
    steps = 0
    while steps < limit:
        obs = Observation(
            image=None,
            privileged=PrivilegedState(spec=u.spec, object_poses=u.object_poses(), env=u),
            step=steps,
        )
        out = policy.step(obs)
        if out.terminate:
            break
        env.step(out.action)
        steps += 1
    predicates = {k: bool(v.reshape(-1)[0]) for k, v in u.evaluate().items()}
    success = predicates.pop("success", False)
    outcome = policy.outcome
    if success:
        reason = ""
    else:
        false = [k for k, v in predicates.items() if not v]
        why = outcome.reason if outcome is not None and outcome.reason else ""
        if not why and steps >= limit:
            why = f"ran out of steps ({limit})"
        reason = "; ".join(part for part in (why, f"false: {', '.join(false)}" if false else "") if part)
    return SolvabilityResult(
        scene_id=spec.scene_id,
        task=spec.task.type,
        status="solved" if success else "failed",
        reason=reason,
        predicates=predicates,
        steps=steps,
        seconds=round(time.perf_counter() - start, 3),
        attempts=outcome.attempts if outcome is not None else 0,
        object_sources={n: str(s) for n, s in getattr(u, "object_sources", {}).items()},
    )


def check_scenes(
    specs: Iterable[SceneSpec],
    sim_config: SimConfig | None = None,
    *,
    max_steps: int | None = None,
    prefer_meshes: bool = True,
) -> Iterator[SolvabilityResult]:
    """Check many scenes with one env; a scene whose check crashes becomes an ``error`` row."""
    env = None
    try:
        for spec in specs:
            try:
                if env is None:
                    env = make_check_env(spec, sim_config, prefer_meshes=prefer_meshes)
                yield check_solvable(spec, sim_config, env=env, max_steps=max_steps)
            except Exception as exc:  # a crash is data here: report it, keep checking the rest
                yield SolvabilityResult(
                    scene_id=spec.scene_id,
                    task=spec.task.type,
                    status="error",
                    reason=f"{type(exc).__name__}: {exc}",
                )
    finally:
        if env is not None:
            env.close()
