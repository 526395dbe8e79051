"""The simulation core: a ManiSkill3 environment that builds, renders and judges a SceneSpec.

    from ladev_lib.sim import make_env
    env = make_env(spec, sim_config)                  # gym.make("LADEV-Scene-v1", ...)
    obs, info = env.reset(seed=spec.seed)
    obs, info = env.reset(seed=other.seed, options={"spec": other.model_dump(mode="json")})
    u = env.unwrapped
    u.spec               # the SceneSpec simulated (robot override applied)
    u.objects            # instance name -> ManiSkill Actor
    u.object_sources     # instance name -> "mesh" | "standin"
    u.built              # instance name -> BuiltObject (collision box in the actor frame)
    u.evaluate()         # task predicates and "success" (torch bool, shape (1,)); u.predicates(): bools
    u.policy_image()     # (H, W, 3) uint8 from the policy camera (real background when active)
    u.overview_image()   # a wider render-only view
    u.object_poses()     # name -> [x, y, z, qw, qx, qy, qz], world frame
    u.workspace_to_world(x, y)  # SceneSpec's workspace frame -> world (table top at z = 0)
    u.profile            # the RobotProfile: base pose, camera, reach, control modes, episode steps
    u.agent              # the ManiSkill agent
    u.spawn_report       # spawn overlaps, spawn and settled poses (ladev_lib.sim.validity reads it)

Modules: ``env`` (the environment), ``robots`` (embodiments), ``agents`` (ManiSkill agents
for the asset-pack robots), ``objects`` (meshes and stand-ins), ``tasks`` (predicates),
``validity`` (physical-validity verdicts), ``view`` (the read-only scene view privileged policies get), ``render`` (pictures), ``config`` (SimConfig,
RobotConfig). Importing this package is cheap; ManiSkill loads when an env is made.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ladev_lib.sim.config import RobotConfig, SimConfig

if TYPE_CHECKING:
    import gymnasium as gym

    from ladev_lib.scenes.spec import SceneSpec

__all__ = ["RobotConfig", "SimConfig", "make_env"]

_FROM_CONFIG = "config"


def make_env(
    spec: SceneSpec | dict[str, Any],
    sim_config: SimConfig | dict[str, Any] | None = None,
    control_mode: str | None = "pd_joint_pos",
    robot: str | None = None,
    image_size: tuple[int, int] | None | str = _FROM_CONFIG,
    **kwargs: Any,
) -> gym.Env[Any, Any]:
    """Make a ``LADEV-Scene-v1`` env for ``spec``.

    Args:
        spec: the scene (a ``SceneSpec`` or its JSON dict).
        sim_config: simulator settings (``SimConfig`` or its dict); defaults when None.
        control_mode: ManiSkill controller; ``None`` takes the robot's default
            (``pd_joint_pos`` exists on every robot).
        robot: simulate this robot instead of ``spec.robot`` (for this and later specs).
        image_size: ``(width, height)`` of the policy camera; ``None`` for no camera
            (state only, fastest); by default the config's ``image_size``.
        kwargs: passed to ``gym.make`` (e.g. ``obs_mode``, ``render_mode``).
    """
    import gymnasium as gym

    import ladev_lib.sim.env  # noqa: F401 - registers LADEV-Scene-v1
    from ladev_lib.scenes.spec import SceneSpec

    cfg = sim_config if isinstance(sim_config, SimConfig) else SimConfig.model_validate(sim_config or {})
    spec_json = spec.model_dump(mode="json") if isinstance(spec, SceneSpec) else dict(spec)
    size = cfg.image_size if image_size == _FROM_CONFIG else image_size
    return gym.make(
        "LADEV-Scene-v1",
        spec=spec_json,
        sim_cfg=cfg.model_dump(mode="json"),
        robot=robot,
        image_size=list(size) if size is not None else None,
        control_mode=control_mode,
        **kwargs,
    )
