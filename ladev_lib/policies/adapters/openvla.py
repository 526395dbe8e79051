"""OpenVLA (openvla-7b): a Hugging Face checkpoint whose model code ships with it.

    policy = make_policy("openvla", checkpoint="checkpoints/openvla-7b", robot="widowx",
                         device="cuda:0", dtype="bfloat16", attn_implementation="flash_attention_2")

Loaded with ``AutoProcessor`` / ``AutoModelForVision2Seq`` and
``trust_remote_code`` from a local directory (or a hub id, for users with a
hub); the checkpoint's own ``predict_action`` decodes the action tokens and
unnormalises them with the statistics stored under ``unnorm_key``
(``fractal20220817_data`` for the Google robot, ``bridge_orig`` for WidowX).

Per step: the image is resized to 224x224 (area interpolation, as SimplerEnv),
the prompt is OpenVLA's "In: What action should the robot take to
{instruction}?\\nOut:", rotation roll-pitch-yaw becomes axis-angle, the
gripper openness becomes a relative command held for 15 steps (Google robot)
or a binary target (WidowX). OpenVLA has no stop signal.

SimplerEnv passes the bare instruction as the prompt; we use the prompt
OpenVLA was trained with (``prompt_template`` to change it).

Requires the ``openvla`` extra: transformers 4.40.1 and timm 0.9.x, which
the core install's transformers cannot replace (``make test-openvla``
builds that environment).
"""

from __future__ import annotations

from typing import Any

import numpy as np

# An ImportError here reaches the user through the policy registry, which
# names the extra to install.
import torch  # noqa: E402  (after the pure imports on purpose: the heavy one last)
import transformers  # noqa: E402

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.common import (
    EulerOpenGripperPostprocessor,
    embodiment,
    policy_info,
    require_image,
)
from ladev_lib.policies.base import Observation, Policy, PolicyStep

PROMPT_TEMPLATE = "In: What action should the robot take to {instruction}?\nOut:"
UNNORM_KEYS = {"google_robot": "fractal20220817_data", "widowx": "bridge_orig"}
DTYPES = {"bfloat16": torch.bfloat16, "float16": torch.float16, "float32": torch.float32}


def _vision2seq_class() -> Any:
    # transformers 5 renamed AutoModelForVision2Seq; support both for remote-code models.
    cls = getattr(transformers, "AutoModelForVision2Seq", None)
    return cls if cls is not None else transformers.AutoModelForImageTextToText


def resize_area(image: Array, size: tuple[int, int]) -> Array:
    """Area-interpolated resize to (width, height), as SimplerEnv does for OpenVLA."""
    try:
        import cv2
    except ImportError:
        from PIL import Image

        return np.asarray(Image.fromarray(image).resize(size, Image.Resampling.BOX))
    return np.asarray(cv2.resize(image, size, interpolation=cv2.INTER_AREA))


class OpenVLAPolicy(Policy):
    """OpenVLA through its remote code, with SimplerEnv's post-processing."""

    def __init__(
        self,
        checkpoint: str = "openvla/openvla-7b",
        robot: str = "widowx",
        unnorm_key: str | None = None,
        device: str | None = None,
        dtype: str = "bfloat16",
        attn_implementation: str | None = None,
        prompt_template: str = PROMPT_TEMPLATE,
        image_size: tuple[int, int] = (224, 224),
        action_scale: float = 1.0,
        local_files_only: bool | None = None,
        embodiments: dict[str, dict[str, Any]] | None = None,
        name: str = "openvla",
    ) -> None:
        # embodiments: per-robot overrides of SimplerEnv's settings (conf/policy/*.yaml).
        self.emb = embodiment(robot, embodiments)
        self.info = policy_info(name, self.emb)
        if dtype not in DTYPES:
            raise ConfigError(f"openvla dtype must be one of {sorted(DTYPES)}, got {dtype!r}")
        if "{instruction}" not in prompt_template:
            raise ConfigError("openvla prompt_template must contain '{instruction}'")
        self.device = torch.device(device or ("cuda:0" if torch.cuda.is_available() else "cpu"))
        self.dtype = DTYPES[dtype]
        self.prompt_template = prompt_template
        self.image_size = (int(image_size[0]), int(image_size[1]))
        load_kwargs: dict[str, Any] = {"trust_remote_code": True}
        if local_files_only is not None:
            load_kwargs["local_files_only"] = local_files_only
        self.processor = transformers.AutoProcessor.from_pretrained(checkpoint, **load_kwargs)
        model_kwargs: dict[str, Any] = {
            **load_kwargs,
            "torch_dtype": self.dtype,
            "low_cpu_mem_usage": True,
        }
        if attn_implementation:
            # "flash_attention_2" (needs flash-attn and a GPU), "sdpa" or "eager".
            model_kwargs["attn_implementation"] = attn_implementation
        self.model = _vision2seq_class().from_pretrained(checkpoint, **model_kwargs)
        self.model.to(self.device)
        self.model.eval()
        self.unnorm_key = unnorm_key or UNNORM_KEYS[self.emb.robot]
        known = sorted(getattr(self.model, "norm_stats", None) or {})
        if self.unnorm_key not in known:
            raise ConfigError(
                f"OpenVLA checkpoint has no action statistics {self.unnorm_key!r}; "
                f"it has: {', '.join(known) or 'none'} (set unnorm_key)"
            )
        self.post = EulerOpenGripperPostprocessor(self.emb, action_scale)
        self._instruction: str | None = None
        self.last_raw_action = np.zeros(7)

    def prompt(self, instruction: str) -> str:
        return self.prompt_template.format(instruction=instruction.strip().lower())

    def reset(self, instruction: str) -> None:
        self._instruction = instruction
        self.post.reset()

    def predict_raw(self, image: Array) -> Array:
        """The model's unnormalised 7-vector [xyz, roll-pitch-yaw, openness] for one image."""
        from PIL import Image

        assert self._instruction is not None
        resized = resize_area(require_image(image, "OpenVLA"), self.image_size)
        inputs = self.processor(self.prompt(self._instruction), Image.fromarray(resized))
        inputs = inputs.to(self.device, dtype=self.dtype)
        with torch.inference_mode():
            action = self.model.predict_action(**inputs, unnorm_key=self.unnorm_key, do_sample=False)
        return np.asarray(action, dtype=np.float64).reshape(-1)

    def step(self, obs: Observation) -> PolicyStep:
        if self._instruction is None:
            raise RuntimeError("call reset(instruction) before step()")
        raw = self.predict_raw(require_image(obs.image, "OpenVLA"))
        self.last_raw_action = raw  # [xyz, roll-pitch-yaw, openness], for logs and plots
        return PolicyStep(action=self.post(raw), terminate=False)
