"""LeRobot policies (SmolVLA, pi0, pi0.5, ACT, diffusion, ...) through LeRobot's own classes.

    policy = make_policy("lerobot", checkpoint="checkpoints/smolvla_libero", robot="panda",
                         device="cuda", state_layout="tcp_euler", gripper_convention="signed_close")

Loading is LeRobot's for a pretrained checkpoint (a local directory written
by ``save_pretrained``, or a hub id for users with a hub):
``PreTrainedConfig.from_pretrained`` reads ``config.json`` (its ``type`` picks
the class), ``get_policy_class(type).from_pretrained`` the weights, and
``make_pre_post_processors(cfg, pretrained_path=...)`` the processor
pipelines saved beside them (normalisation statistics, tokenizer, device).

Per step the LADEV observation becomes the checkpoint's declared inputs:
the camera image resized to each fed ``observation.images.*`` feature's
(H, W), ``observation.state`` from the proprioception in ``state_layout``,
and the instruction as ``task``; LeRobot's ``preprocess_observation``
turns them into tensors, the preprocessor normalises (and tokenises), the
policy's ``select_action`` returns one action from its queue (a new chunk
is predicted every ``n_action_steps`` steps, as in LeRobot's own eval), the
postprocessor unnormalises it, and :class:`.lerobot_maps.ActionMapper` turns
it into the robot's controller action. An input the checkpoint needs and
LADEV cannot give (a second camera, an environment state) is a ConfigError
naming it.

Runs in its own environment (``make adapter-env-lerobot``: LeRobot 0.4.4
pins torch < 2.11 and transformers < 5) and reaches the rollout through
``ladev serve-policy``.
"""

from __future__ import annotations

import importlib.util
import zlib
from pathlib import Path
from typing import Any

import numpy as np

# An ImportError here reaches the user through the policy registry, which
# names the extra to install.
import torch  # noqa: E402
from lerobot.configs.policies import PreTrainedConfig  # noqa: E402
from lerobot.configs.types import FeatureType  # noqa: E402
from lerobot.envs.utils import preprocess_observation  # noqa: E402
from lerobot.policies.factory import get_policy_class, make_pre_post_processors  # noqa: E402
from lerobot.utils.constants import OBS_IMAGE, OBS_IMAGES, OBS_STATE  # noqa: E402

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.common import embodiment, policy_info, require_image
from ladev_lib.policies.adapters.lerobot_maps import (
    LEROBOT_EMBODIMENTS,
    STATE_LAYOUTS,
    ActionMapper,
    describe_features,
    fit_image,
    state_vector,
)
from ladev_lib.policies.base import EpisodeContext, Observation, Policy, PolicyStep

# Policies whose model fills a declared camera missing from the batch with an
# empty, masked image (their prepare_images); for the others every image is needed.
PADS_MISSING_CAMERAS = frozenset({"smolvla", "pi0", "pi05", "pi0_fast"})
# LeRobot's PaliGemma policies refuse to build without its patched transformers
# (a git branch, LeRobot's `pi` extra), which PyPI's transformers is not.
NEEDS_PATCHED_TRANSFORMERS = frozenset({"pi0", "pi05", "pi0_fast"})
PALIGEMMA_TOKENIZER = "google/paligemma-3b-pt-224"


def hub_files(cfg: Any) -> list[str]:
    """What a checkpoint of this type loads by hub name besides itself (for error messages)."""
    if cfg.type == "smolvla":
        return [f"{cfg.vlm_model_name} (the VLM's config, tokenizer and processor: "
                "config_overrides.vlm_model_name and tokenizer)"]
    if cfg.type in NEEDS_PATCHED_TRANSFORMERS:
        return [f"{PALIGEMMA_TOKENIZER} (the tokenizer: set tokenizer)"]
    return []


def pick_device(device: str | None) -> str:
    """``device`` as given, else cuda when there is one, else cpu (never assumed)."""
    if device:
        return device
    return "cuda" if torch.cuda.is_available() else "cpu"


class LeRobotPolicy(Policy):
    """A LeRobot ``PreTrainedPolicy`` with its processors, driving a LADEV robot."""

    def __init__(
        self,
        checkpoint: str,
        robot: str = "panda",
        device: str | None = None,
        policy_type: str | None = None,
        image_features: list[str] | None = None,
        rotate_image_180: bool = False,
        state_layout: str = "proprio",
        action_layout: str = "ee_delta_euler",
        gripper_convention: str = "open_is_1",
        action_scale: float = 1.0,
        rotation_scale: float | None = None,
        n_action_steps: int | None = None,
        task_template: str = "{instruction}",
        config_overrides: dict[str, Any] | None = None,
        tokenizer: str | None = None,
        seed: int = 0,
        local_files_only: bool = False,
        embodiments: dict[str, dict[str, Any]] | None = None,
        name: str = "lerobot",
    ) -> None:
        # embodiments: per-robot overrides of the robot's settings (conf/policy/*.yaml).
        self.emb = embodiment(robot, embodiments, table=LEROBOT_EMBODIMENTS)
        self.info = policy_info(name, self.emb)
        if "{instruction}" not in task_template:
            raise ConfigError("lerobot task_template must contain '{instruction}'")
        if state_layout not in STATE_LAYOUTS:
            raise ConfigError(f"lerobot state_layout must be one of {list(STATE_LAYOUTS)}, got {state_layout!r}")
        self.task_template = task_template
        # For checkpoints trained on upside-down renders (raw LIBERO frames); LeRobot's
        # own LIBERO env rotates them upright, as LADEV renders them.
        self.rotate_image_180 = bool(rotate_image_180)
        self.state_layout = state_layout
        self.mapper = ActionMapper(
            self.emb, action_layout, gripper_convention, action_scale, rotation_scale
        )
        self.device = pick_device(device)
        self.checkpoint = checkpoint

        # LeRobot's own loading path for a pretrained checkpoint.
        cfg = PreTrainedConfig.from_pretrained(checkpoint, local_files_only=local_files_only)
        if policy_type is not None and cfg.type != policy_type:
            raise ConfigError(
                f"{checkpoint}: a LeRobot {cfg.type!r} checkpoint, but the config says policy_type "
                f"{policy_type!r}"
            )
        for key, value in (config_overrides or {}).items():
            # e.g. vlm_model_name: a local copy of SmolVLA's backbone (config, processor)
            if not hasattr(cfg, key):
                raise ConfigError(f"config_overrides: a {cfg.type} config has no field {key!r}")
            setattr(cfg, key, value)
        if cfg.type in NEEDS_PATCHED_TRANSFORMERS and importlib.util.find_spec(
            "transformers.models.siglip.check"
        ) is None:
            import transformers

            raise ConfigError(
                f"LeRobot's {cfg.type} needs its patched transformers (install LeRobot's `pi` extra "
                f"from a LeRobot checkout: pip install -e '.[pi]'); this environment has PyPI's "
                f"transformers {transformers.__version__}"
            )
        cfg.device = self.device
        cfg.pretrained_path = Path(checkpoint) if Path(checkpoint).is_dir() else checkpoint
        if n_action_steps is not None:
            chunk = getattr(cfg, "chunk_size", None)
            if n_action_steps < 1 or (chunk is not None and n_action_steps > chunk):
                raise ConfigError(f"lerobot n_action_steps must be in [1, {chunk}] (the chunk size), "
                                  f"got {n_action_steps}")
            cfg.n_action_steps = n_action_steps
        self.cfg = cfg
        # Checked before any weights load: a missing input fails in seconds, not after GBs.
        self.image_features, self.state_feature = self._map_inputs(image_features)
        pre_overrides: dict[str, Any] = {"device_processor": {"device": self.device}}
        if tokenizer is not None:  # a local tokenizer instead of the hub name saved with it
            pre_overrides["tokenizer_processor"] = {"tokenizer_name": tokenizer}
        try:
            self.model = get_policy_class(cfg.type).from_pretrained(
                checkpoint, config=cfg, local_files_only=local_files_only
            )
            self.model.eval()
            self.preprocessor, self.postprocessor = make_pre_post_processors(
                cfg, pretrained_path=checkpoint, preprocessor_overrides=pre_overrides
            )
        except OSError as exc:  # transformers' "couldn't connect ... cached files"
            needed = hub_files(cfg)
            if not needed:
                raise
            raise ConfigError(
                f"{checkpoint}: the {cfg.type} policy loads files by hub name that are not here: "
                f"{'; '.join(needed)}. Point those settings at local copies. ({exc})"
            ) from exc
        self._instruction: str | None = None
        self.seed = int(seed)
        self._episode_seed: int | None = None
        self.last_raw_action = np.zeros(0)

    # ------------------------------------------------------------------ features

    def _map_inputs(self, image_features: list[str] | None) -> tuple[dict[str, tuple[int, ...]], tuple[str, int] | None]:
        """Which declared inputs LADEV fills; a ConfigError naming any it cannot."""
        declared = {k: (f.type.value, tuple(f.shape)) for k, f in self.cfg.input_features.items()}
        visual = {k: s for k, (t, s) in declared.items() if t == FeatureType.VISUAL.value}
        if image_features is None:
            if len(visual) > 1 and self.cfg.type not in PADS_MISSING_CAMERAS:
                raise ConfigError(
                    f"the {self.cfg.type} checkpoint expects {len(visual)} cameras "
                    f"({', '.join(sorted(visual))}); LADEV renders one policy camera: "
                    "set image_features to the feature(s) it feeds"
                )
            # The first declared camera: LeRobot's main view by convention.
            image_features = list(visual)[:1]
        unknown = [k for k in image_features if k not in visual]
        if unknown:
            raise ConfigError(
                f"image_features {unknown} are not visual inputs of this checkpoint; it declares: "
                f"{describe_features(declared)}"
            )
        if not image_features and visual:
            raise ConfigError(f"image_features is empty; the checkpoint needs one of {sorted(visual)}")
        fed = {k: visual[k] for k in image_features}
        for k in image_features:
            if k != OBS_IMAGE and not k.startswith(OBS_IMAGES + "."):
                raise ConfigError(f"visual feature {k!r} is not named observation.images.<camera>")
        unfed = sorted(set(visual) - set(fed))
        if unfed and self.cfg.type not in PADS_MISSING_CAMERAS:
            raise ConfigError(
                f"the {self.cfg.type} checkpoint needs camera(s) {unfed}, which LADEV cannot provide "
                f"(it renders one policy camera, fed to {sorted(fed)})"
            )
        state: tuple[str, int] | None = None
        for key, (ftype, shape) in declared.items():
            if ftype == FeatureType.VISUAL.value:
                continue
            if key == OBS_STATE and ftype == FeatureType.STATE.value:
                state = (key, int(np.prod(shape)))
                continue
            raise ConfigError(
                f"the checkpoint expects input {key!r} ({ftype}, {shape}), which LADEV cannot provide "
                "(it gives observation.images.*, observation.state and the task)"
            )
        return fed, state

    # ------------------------------------------------------------------ episode

    def begin_episode(self, ctx: EpisodeContext) -> None:
        self._episode_seed = ctx.seed

    def reset(self, instruction: str) -> None:
        """Start an episode: an empty action queue and seeded sampling noise.

        Diffusion and flow-matching policies sample noise. In process the episode
        seed (begin_episode) decides it; served, where the protocol carries no
        seed, ``seed`` and the instruction do, so a rerun gives the same actions.
        """
        self._instruction = instruction
        if self._episode_seed is not None:
            episode_seed, self._episode_seed = self._episode_seed, None
        else:
            episode_seed = zlib.crc32(f"{self.seed}:{instruction}".encode())
        torch.manual_seed(episode_seed)
        self.model.reset()  # empties select_action's queue
        self.preprocessor.reset()
        self.postprocessor.reset()
        self.mapper.reset()

    def task(self, instruction: str) -> str:
        return self.task_template.format(instruction=instruction.strip())

    def batch(self, obs: Observation) -> dict[str, Any]:
        """The checkpoint's inputs for one observation, before its preprocessor."""
        assert self._instruction is not None
        raw: dict[str, Any] = {}
        if self.image_features:
            image = require_image(obs.image, f"LeRobot {self.cfg.type}")
            if self.rotate_image_180:
                image = np.ascontiguousarray(image[::-1, ::-1])
            pixels = {k: fit_image(image, shape) for k, shape in self.image_features.items()}
            if list(pixels) == [OBS_IMAGE]:
                raw["pixels"] = pixels[OBS_IMAGE]
            else:
                raw["pixels"] = {k.removeprefix(OBS_IMAGES + "."): v for k, v in pixels.items()}
        if self.state_feature is not None:
            key, dim = self.state_feature
            raw["agent_pos"] = state_vector(obs.proprio, self.state_layout, dim, key)
        batch: dict[str, Any] = preprocess_observation(raw)
        batch["task"] = [self.task(self._instruction)]
        return batch

    def predict_raw(self, obs: Observation) -> Array:
        """The checkpoint's unnormalised action for this step (from its action queue)."""
        batch = self.preprocessor(self.batch(obs))
        with torch.inference_mode():
            action = self.model.select_action(batch)
        action = self.postprocessor(action)
        return np.asarray(action.detach().float().cpu().numpy(), dtype=np.float64).reshape(-1)

    def step(self, obs: Observation) -> PolicyStep:
        if self._instruction is None:
            raise RuntimeError("call reset(instruction) before step()")
        raw = self.predict_raw(obs)
        self.last_raw_action = raw
        return PolicyStep(action=self.mapper(raw), terminate=False)
