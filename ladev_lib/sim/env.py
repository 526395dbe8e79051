"""``LADEV-Scene-v1``: a ManiSkill3 environment that builds and judges a ``SceneSpec``.

    env = gym.make("LADEV-Scene-v1", spec=spec.model_dump(mode="json"))
    obs, info = env.reset(seed=spec.seed, options={"spec": other.model_dump(mode="json")})

One env serves many scenes: ``reset(options={"spec": ...})`` rebuilds the scene
(ManiSkill's ``reconfigure``) only when the set of objects changes; a scene with
the same objects (other poses, lighting, camera, task) is re-posed in place. The
first rendered frame of a process is the expensive one on software Vulkan, so
keep one env per worker.

Each reset spawns the objects upright at their workspace poses, 2 mm above the
table, records contacts that interpenetrate at spawn, lets physics settle for
``SimConfig.settle_s`` with the robot held at its initial joint positions, and
records where everything came to rest: the predicates of ``ladev_lib.sim.tasks``
and the checks of ``ladev_lib.sim.validity`` start from there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import sapien
import torch
from mani_skill.envs.sapien_env import BaseEnv
from mani_skill.sensors.camera import CameraConfig
from mani_skill.utils import sapien_utils
from mani_skill.utils.building.ground import build_ground
from mani_skill.utils.registration import register_env
from mani_skill.utils.scene_builder.table import scene_builder as table_module
from mani_skill.utils.structs.pose import Pose
from mani_skill.utils.structs.types import SimConfig as ManiSkillSimConfig
from transforms3d.euler import euler2quat

from ladev_lib.arrays import Array
from ladev_lib.assets import asset_dir
from ladev_lib.catalog import load_catalog
from ladev_lib.errors import ConfigError
from ladev_lib.scenes.spec import SceneSpec, parse_scene_spec
from ladev_lib.sim import agents as _agents  # noqa: F401 - registers the pack robots
from ladev_lib.sim.config import SimConfig
from ladev_lib.sim.geometry import quat_to_matrix, yaw_quat
from ladev_lib.sim.objects import BuiltObject, ObjectSource, build_object
from ladev_lib.sim.robots import RobotProfile, get_robot
from ladev_lib.sim.tasks import get_task

ENV_ID = "LADEV-Scene-v1"
POLICY_CAMERA = "policy"
OVERVIEW_CAMERA = "overview"
SPAWN_GAP_M = 0.002
PENETRATION_M = 0.003
"""Contact separation below -3 mm at spawn counts as interpenetration."""
_TABLE_HEIGHT = 0.9196429  # ManiSkill's table model, scaled as TableSceneBuilder does
_TABLE_HALF = (2.418 / 2, 1.209 / 2, _TABLE_HEIGHT / 2)


@dataclass
class SpawnReport:
    """What happened between spawning and settling, for the validity check."""

    penetrations: list[tuple[str, str, float]] = field(default_factory=list)
    """(body, body, depth in m) for pairs of objects or object and robot that overlap at spawn."""
    spawn_poses: dict[str, Array] = field(default_factory=dict)
    settled_poses: dict[str, Array] = field(default_factory=dict)
    settled_speeds: dict[str, tuple[float, float]] = field(default_factory=dict)
    """name -> (linear m/s, angular rad/s) after settling."""
    settle_steps: int = 0


class SimulatedSpec(SceneSpec):
    """The ``SceneSpec`` an env simulates, as ``env.unwrapped.spec`` returns it.

    Gymnasium also keeps its registration record in ``env.unwrapped.spec`` and reads
    ``additional_wrappers`` from it while making the env; this subclass answers that
    one question (no extra wrappers) so that ``spec`` can stay the scene. The
    gymnasium record is kept in ``env.unwrapped.gym_spec``.
    """

    @property
    def additional_wrappers(self) -> tuple[Any, ...]:
        return ()


def resolve_render_backend(name: str) -> str:
    if name != "auto":
        return name
    return "gpu" if torch.cuda.is_available() else "cpu"


@register_env(ENV_ID, max_episode_steps=None)
class LadevSceneEnv(BaseEnv):
    """**Description:** one LADEV test scene: a robot at a table with catalog objects,
    lighting and a policy camera as a ``SceneSpec`` describes, judged by the spec's task.

    **Randomizations:** none; everything comes from the spec (its ``seed`` seeds the
    episode RNG for policies that want one).

    **Success Conditions:** those of the spec's task, see ``ladev_lib.sim.tasks``.
    """

    SUPPORTED_OBS_MODES = ("state_dict", "state", "none", "sensor_data", "rgb", "rgb+segmentation")
    SUPPORTED_REWARD_MODES = ("none", "sparse")

    profile: RobotProfile
    objects: dict[str, Any]
    object_sources: dict[str, ObjectSource]
    built: dict[str, BuiltObject]

    def __init__(
        self,
        *args: Any,
        spec: dict[str, Any] | str,
        sim_cfg: dict[str, Any] | None = None,
        robot: str | None = None,
        image_size: list[int] | tuple[int, int] | None = (256, 256),
        prefer_meshes: bool = True,
        **kwargs: Any,
    ) -> None:
        self.sim_cfg = SimConfig.model_validate(sim_cfg or {})
        self._robot_override = robot
        self.catalog = load_catalog()
        self.gym_spec: Any = None
        self.spec = self._adopt(spec)
        self.profile = get_robot(self.spec.robot)
        if self.profile.needs_assets:
            _agents.robot_urdf(self.profile.name)  # clear error before ManiSkill tries
        self.image_size = tuple(int(v) for v in image_size) if image_size is not None else None
        self.prefer_meshes = prefer_meshes
        control_mode = kwargs.pop("control_mode", None) or self.profile.default_control_mode
        if control_mode not in self.profile.control_modes:
            raise ConfigError(
                f"control_mode {control_mode!r} is not available on {self.profile.name}; "
                f"choose one of {', '.join(self.profile.control_modes)}"
            )
        self.objects, self.object_sources, self.built = {}, {}, {}
        self.spawn_report = SpawnReport()
        self._lights: list[tuple[Any, float]] = []
        self._overlay: torch.Tensor | None = None
        kwargs.setdefault("sim_backend", self.sim_cfg.sim_backend)
        kwargs["render_backend"] = resolve_render_backend(
            kwargs.get("render_backend", self.sim_cfg.render_backend)
        )
        kwargs.setdefault("obs_mode", "state_dict")
        kwargs.setdefault("reward_mode", "none")
        super().__init__(*args, robot_uids=self.profile.agent_uid, control_mode=control_mode, **kwargs)

    # -- spec handling --------------------------------------------------------------
    @property
    def spec(self) -> SimulatedSpec:
        """The scene being simulated (the robot override applied)."""
        return self._scene_spec

    @spec.setter
    def spec(self, value: Any) -> None:
        if isinstance(value, SimulatedSpec):
            self._scene_spec = value
        else:  # gymnasium's EnvSpec, set by gym.make
            self.gym_spec = value

    def _adopt(self, spec: dict[str, Any] | str | SceneSpec) -> SimulatedSpec:
        parsed = spec if isinstance(spec, SceneSpec) else parse_scene_spec(spec, catalog=self.catalog)
        data = parsed.model_dump()
        if self._robot_override:
            data["robot"] = self._robot_override
        return SimulatedSpec.model_validate(data)

    def _layout_key(self, spec: SceneSpec) -> tuple[tuple[str, str], ...]:
        return tuple((o.name, o.id) for o in spec.objects)

    def reset(self, seed: Any = None, options: dict[str, Any] | None = None) -> Any:
        options = dict(options or {})
        if "spec" in options:
            new = self._adopt(options.pop("spec"))
            if new.robot != self.profile.name:
                raise ConfigError(
                    f"this env simulates {self.profile.name}; the new spec asks for {new.robot}. "
                    "Make one env per robot (or pass robot=... to make_env to override specs)."
                )
            if self._layout_key(new) != self._layout_key(self.spec):
                options["reconfigure"] = True
            self.spec = new
        return super().reset(seed=seed, options=options)

    # -- simulation setup ------------------------------------------------------------
    @property
    def _default_sim_config(self) -> ManiSkillSimConfig:
        return ManiSkillSimConfig(
            sim_freq=self.sim_cfg.sim_freq_hz or self.profile.sim_freq_hz,
            control_freq=self.sim_cfg.control_freq_hz or self.profile.control_freq_hz,
        )

    def policy_camera_pose(self) -> sapien.Pose:
        """World pose of the policy camera: the robot's default moved by the spec's offset."""
        cam, off = self.profile.policy_camera, self.spec.camera
        p = np.asarray(cam.p) + self.profile.workspace_vector_to_world(off.translation_m)
        roll, pitch, yaw = (math.radians(a) for a in off.rotation_deg)
        base = sapien.Pose(q=list(cam.q))
        q = (base * sapien.Pose(q=euler2quat(roll, pitch, yaw))).q
        return sapien.Pose(p=p.tolist(), q=q)

    @property
    def _default_sensor_configs(self) -> list[CameraConfig]:
        if self.image_size is None:
            return []
        w, h = self.image_size
        cam = self.profile.policy_camera
        return [
            CameraConfig(
                POLICY_CAMERA,
                pose=self.policy_camera_pose(),
                width=w,
                height=h,
                intrinsic=cam.intrinsic((w, h)),
                near=cam.near,
                far=cam.far,
            )
        ]

    @property
    def _default_human_render_camera_configs(self) -> list[CameraConfig]:
        w, h = self.sim_cfg.overview_size
        eye = self.profile.workspace_to_world(0.6, -0.65, 0.65)
        target = self.profile.workspace_to_world(-0.18, 0.0, 0.12)
        pose = sapien_utils.look_at(eye.tolist(), target.tolist())
        return [CameraConfig(OVERVIEW_CAMERA, pose=pose, width=w, height=h, fov=0.9, near=0.01, far=20)]

    def _load_agent(self, options: dict[str, Any]) -> None:
        pose = sapien.Pose(p=list(self.profile.base_xyz), q=yaw_quat(self.profile.base_yaw).tolist())
        super()._load_agent(options, pose)

    def _load_scene(self, options: dict[str, Any]) -> None:
        self._build_table()
        if self.profile.needs_assets:
            for art in self.agent.robot._objs:  # SimplerEnv's robot look (glossy)
                sapien_utils.set_articulation_render_material(art, specular=0.9, roughness=0.3)
        self.objects, self.object_sources, self.built = {}, {}, {}
        root = asset_dir()
        for i, placement in enumerate(self.spec.objects):
            obj = self.catalog.get(placement.id)
            # Park each object far apart until _initialize_episode places it.
            parking = sapien.Pose(p=[10.0 + i, 10.0, 1.0])
            actor, built = build_object(
                self.scene, obj, f"obj_{placement.name}", root, parking, prefer_mesh=self.prefer_meshes
            )
            self.objects[placement.name] = actor
            self.object_sources[placement.name] = built.source
            self.built[placement.name] = built
        self._load_overlay()

    def _build_table(self) -> None:
        """ManiSkill's table (TableSceneBuilder's model and box) with its top at the workspace."""
        builder = self.scene.create_actor_builder()
        model = str(Path(table_module.__file__).parent / "assets" / "table.glb")
        builder.add_box_collision(pose=sapien.Pose(p=[0, 0, _TABLE_HEIGHT / 2]), half_size=_TABLE_HALF)
        builder.add_visual_from_file(
            filename=model, scale=[1.75] * 3, pose=sapien.Pose(q=euler2quat(0, 0, math.pi / 2))
        )
        tx, ty = self.profile.table_xy
        builder.initial_pose = sapien.Pose(
            p=[tx, ty, self.profile.table_top_z - _TABLE_HEIGHT], q=euler2quat(0, 0, math.pi / 2)
        )
        self.table = builder.build_kinematic(name="table")
        floor_z = 0.0 if self.profile.table_top_z > 0.5 else -_TABLE_HEIGHT
        self.ground = build_ground(self.scene, altitude=floor_z)

    def _load_overlay(self) -> None:
        self._overlay = None
        rel, root = self.profile.overlay_image, asset_dir()
        if not (self.sim_cfg.overlay and rel and root and self.image_size):
            return
        path = root / rel
        if not path.exists():
            return
        from PIL import Image

        with Image.open(path) as img:
            size = (self.image_size[0], self.image_size[1])
            pixels = np.array(img.convert("RGB").resize(size, Image.Resampling.BILINEAR))
            self._overlay = torch.from_numpy(pixels)

    def _load_lighting(self, options: dict[str, Any]) -> None:
        light = self.profile.lighting
        self.scene.set_ambient_light([light.ambient] * 3)
        for direction, intensity in light.directional:
            self.scene.add_directional_light(list(direction), [intensity] * 3, shadow=self.enable_shadow)
        # Keep each light with its default intensity, to rescale in place per episode.
        self._lights = []
        for entity in self.scene.sub_scenes[0].entities:
            for comp in entity.components:
                if isinstance(comp, sapien.render.RenderDirectionalLightComponent):
                    self._lights.append((comp, float(comp.color[0])))
        self._apply_lighting()

    def _apply_lighting(self) -> None:
        scale = 1.0 + self.spec.lighting.intensity_delta
        self.scene.set_ambient_light([self.profile.lighting.ambient * scale] * 3)
        for comp, base in self._lights:
            comp.color = [base * scale] * 3

    # -- episode initialisation -----------------------------------------------------------
    def _initialize_episode(self, env_idx: torch.Tensor, options: dict[str, Any]) -> None:
        self._apply_lighting()
        if POLICY_CAMERA in self.scene.sensors:
            self.scene.sensors[POLICY_CAMERA].camera.set_local_pose(self.policy_camera_pose())
        self._reset_robot()
        report = SpawnReport()
        for placement in self.spec.objects:
            built, actor = self.built[placement.name], self.objects[placement.name]
            p = self.profile.workspace_to_world(placement.x, placement.y, built.bottom_z + SPAWN_GAP_M)
            q = yaw_quat(self.profile.workspace_yaw + math.radians(placement.yaw_deg))
            actor.set_pose(Pose.create_from_pq(p=torch.tensor(p, dtype=torch.float32)[None], q=torch.tensor(q, dtype=torch.float32)[None]))
            actor.set_linear_velocity(torch.zeros(1, 3))
            actor.set_angular_velocity(torch.zeros(1, 3))
            report.spawn_poses[placement.name] = np.concatenate([p, q])
        self._physics_step()
        report.penetrations = self._spawn_penetrations()
        steps = 1 + self._settle(self.sim_cfg.settle_s)
        # Slow settlers (rolling fruit, wobbling meshes) get more time, as in SimplerEnv.
        while steps < self.sim_cfg.settle_max_s * self.sim_freq and self._anything_moving():
            steps += self._settle(0.25)
        report.settle_steps = steps
        report.settled_poses = {n: self._pose_np(a) for n, a in self.objects.items()}
        report.settled_speeds = {n: self._speed(n) for n in self.objects}
        self.spawn_report = report

    def _reset_robot(self) -> None:
        robot = self.agent.robot
        names = [j.name for j in robot.active_joints]
        missing = [n for n in names if n not in self.profile.init_qpos]
        if missing:
            raise ConfigError(f"robot {self.profile.name}: no initial position for joints {missing}")
        qpos = torch.tensor([[self.profile.init_qpos[n] for n in names]], dtype=torch.float32)
        robot.set_pose(
            sapien.Pose(p=list(self.profile.base_xyz), q=yaw_quat(self.profile.base_yaw).tolist())
        )
        self.agent.reset(qpos)
        # Hold the robot where it starts while the objects settle (drive targets persist
        # from the previous episode otherwise).
        robot.set_joint_drive_targets(qpos, joints=robot.active_joints)

    def _physics_step(self, n: int = 1) -> None:
        """``n`` physics steps with no control, keeping GPU buffers in sync with poses set here."""
        if self.gpu_sim_enabled:
            self.scene._gpu_apply_all()
        for _ in range(n):
            self.scene.px.step()
        if self.gpu_sim_enabled:
            self.scene._gpu_fetch_all()

    def _settle(self, seconds: float) -> int:
        n = int(round(seconds * self.sim_freq))
        self._physics_step(n)
        return n

    def _anything_moving(self) -> bool:
        return any(v > 1e-3 or w > 1e-2 for v, w in (self._speed(n) for n in self.objects))

    def __str__(self) -> str:  # gymnasium's would print spec.id
        return f"<LadevSceneEnv<{ENV_ID}> {self.profile.name}: {len(self.objects)} objects>"

    def _spawn_penetrations(self) -> list[tuple[str, str, float]]:
        if self.gpu_sim_enabled:
            return []  # contact lists are CPU-only; GPU runs skip this check
        names: dict[Any, str] = {a._objs[0]: n for n, a in self.objects.items()}
        for link in self.agent.robot.links:
            names[link._objs[0].entity] = f"robot:{link.name}"
        found: dict[tuple[str, str], float] = {}
        for contact in self.scene.px.get_contacts():
            a = names.get(contact.bodies[0].entity)
            b = names.get(contact.bodies[1].entity)
            if a is None or b is None or (a.startswith("robot:") and b.startswith("robot:")):
                continue
            depth = -min((pt.separation for pt in contact.points), default=0.0)
            if depth > PENETRATION_M:
                key = (min(a, b), max(a, b))
                found[key] = max(found.get(key, 0.0), depth)
        return [(a, b, d) for (a, b), d in sorted(found.items())]

    # -- state queries (used by tasks, validity, planners) ---------------------------------
    @staticmethod
    def _pose_np(actor: Any) -> Array:
        out: Array = actor.pose.raw_pose[0].detach().cpu().numpy().astype(float)
        return out

    def _speed(self, name: str) -> tuple[float, float]:
        a = self.objects[name]
        return (
            float(torch.linalg.norm(a.linear_velocity[0])),
            float(torch.linalg.norm(a.angular_velocity[0])),
        )

    def object_poses(self) -> dict[str, Array]:
        """Instance name -> world pose [x, y, z, qw, qx, qy, qz] of each object's actor."""
        return {n: self._pose_np(a) for n, a in self.objects.items()}

    def workspace_to_world(self, x: float, y: float, z: float = 0.0) -> Array:
        """A workspace-frame point (on the table top when z = 0) in world coordinates."""
        return self.profile.workspace_to_world(x, y, z)

    def world_to_workspace(self, p: Array) -> Array:
        return self.profile.world_to_workspace(p)

    def _box_center(self, pose: Array, name: str) -> Array:
        out: Array = pose[:3] + quat_to_matrix(pose[3:]) @ self.built[name].box_center
        return out

    def box_center_world(self, name: str) -> Array:
        """World position of the centre of ``name``'s collision box."""
        return self._box_center(self._pose_np(self.objects[name]), name)

    def settled_center(self, name: str) -> Array:
        return self._box_center(self.spawn_report.settled_poses[name], name)

    def xy_displacement(self, name: str) -> float:
        d = self.box_center_world(name) - self.settled_center(name)
        return float(np.hypot(d[0], d[1]))

    def z_displacement(self, name: str) -> float:
        return float(self.box_center_world(name)[2] - self.settled_center(name)[2])

    def point_in_object_frame(self, name: str, p_world: Array) -> Array:
        pose = self._pose_np(self.objects[name])
        out: Array = quat_to_matrix(pose[3:]).T @ (np.asarray(p_world) - pose[:3])
        return out

    def contact_force(self, a: Any, b: Any) -> float:
        """Magnitude of the net contact force between two actors or links (N)."""
        return float(torch.linalg.norm(self.scene.get_pairwise_contact_forces(a, b)[0]))

    def is_grasped(self, name: str) -> torch.Tensor:
        out: torch.Tensor = self.agent.is_grasping(self.objects[name]).reshape(1).cpu()
        return out

    def teleport(self, name: str, p_world: Array, q: Array | None = None) -> None:
        """Place object ``name`` at a world position (and orientation), at rest."""
        actor = self.objects[name]
        q = self._pose_np(actor)[3:] if q is None else np.asarray(q, dtype=float)
        actor.set_pose(
            Pose.create_from_pq(
                p=torch.tensor(np.asarray(p_world), dtype=torch.float32)[None],
                q=torch.tensor(q, dtype=torch.float32)[None],
            )
        )
        actor.set_linear_velocity(torch.zeros(1, 3))
        actor.set_angular_velocity(torch.zeros(1, 3))

    # -- task ----------------------------------------------------------------------------
    def evaluate(self) -> dict[str, torch.Tensor]:
        if not self.spawn_report.settled_poses:
            return {"success": torch.zeros(1, dtype=torch.bool)}
        return get_task(self.spec.task.type).evaluate(self)

    def predicates(self) -> dict[str, bool]:
        """``evaluate()`` as plain booleans (for episode rows and printing)."""
        return {k: bool(v.reshape(-1)[0]) for k, v in self.evaluate().items()}

    def _get_obs_extra(self, info: dict[str, Any]) -> dict[str, Any]:
        tcp = self.agent.robot.links_map.get(self.profile.tcp_link)
        return {"tcp_pose": tcp.pose.raw_pose} if tcp is not None else {}

    # -- images ----------------------------------------------------------------------------
    @property
    def overlay_active(self) -> bool:
        return self._overlay is not None

    def _keep_ids(self) -> torch.Tensor:
        ids = [link.per_scene_id for link in self.agent.robot.links]
        ids += [a.per_scene_id for a in self.objects.values()]
        kept: torch.Tensor = torch.unique(torch.cat([i.cpu() for i in ids]))
        return kept

    def _with_overlay(self, rgb: torch.Tensor, seg: torch.Tensor) -> torch.Tensor:
        """Replace background pixels (not robot, not objects) of (1, H, W, 3) rgb by the real image."""
        assert self._overlay is not None
        background = ~torch.isin(seg[..., 0].cpu(), self._keep_ids())
        out = rgb.cpu().clone()
        out[background] = self._overlay[background[0]].to(out.dtype)
        return out.to(rgb.device)

    def _get_obs_sensor_data(self, apply_texture_transforms: bool = True) -> dict[str, Any]:
        # Image observation modes see what policy_image() returns: overlay included.
        obs: dict[str, Any] = super()._get_obs_sensor_data(apply_texture_transforms)
        cam = obs.get(POLICY_CAMERA)
        if self.overlay_active and cam is not None and "rgb" in cam:
            seg = self.scene.sensors[POLICY_CAMERA].get_obs(
                rgb=False, depth=False, position=False, segmentation=True
            )["segmentation"]
            cam["rgb"] = self._with_overlay(cam["rgb"], seg)
        return obs

    def policy_image(self, overlay: bool | None = None) -> Array:
        """(H, W, 3) uint8 RGB from the policy camera, with the real background when active."""
        if POLICY_CAMERA not in self.scene.sensors:
            raise ConfigError("this env has no policy camera (made with image_size=None)")
        use_overlay = self.overlay_active if overlay is None else (overlay and self.overlay_active)
        self.scene.update_render(update_sensors=True, update_human_render_cameras=False)
        cam = self.scene.sensors[POLICY_CAMERA]
        cam.capture()
        obs = cam.get_obs(rgb=True, depth=False, position=False, segmentation=use_overlay)
        rgb = self._with_overlay(obs["rgb"], obs["segmentation"]) if use_overlay else obs["rgb"]
        out: Array = rgb[0].cpu().numpy()
        return out

    def policy_segmentation(self) -> Array:
        """(H, W) int per-scene ids seen by the policy camera (for visibility checks)."""
        self.scene.update_render(update_sensors=True, update_human_render_cameras=False)
        cam = self.scene.sensors[POLICY_CAMERA]
        cam.capture()
        seg: Array = cam.get_obs(rgb=False, depth=False, position=False, segmentation=True)[
            "segmentation"
        ][0, ..., 0].cpu().numpy()
        return seg

    def overview_image(self) -> Array:
        """(H, W, 3) uint8 RGB from the overview camera (renders only, never the policy's input)."""
        self.scene.update_render(update_sensors=False, update_human_render_cameras=True)
        cam = self.scene.human_render_cameras[OVERVIEW_CAMERA]
        cam.capture()
        out: Array = cam.get_obs(rgb=True, depth=False, position=False, segmentation=False)["rgb"][0].cpu().numpy()
        return out
