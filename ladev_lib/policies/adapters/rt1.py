"""RT-1 and RT-1-X: TensorFlow SavedModel policies (tf-agents), as SimplerEnv runs them.

    policy = make_policy("rt1", checkpoint="checkpoints/rt_1_x_tf_trained_for_002272480_step",
                         sentence_encoder="checkpoints/universal-sentence-encoder-large-5",
                         robot="google_robot")

A released RT-1 checkpoint is a tf-agents SavedModel policy (it carries its
own network; no RT-1 source code is needed): it is loaded with tf-agents'
``SavedModelPyTFEagerPolicy`` from the specs stored beside it. The
instruction is embedded with the Universal Sentence Encoder (a TF-Hub
SavedModel; a local directory, or a tfhub.dev URL for users with internet and
``tensorflow-hub``).

Per embodiment (SimplerEnv's ``rt1_model.py``):

- image: resized *with padding* to 320x256 (``tf.image.resize_with_pad``);
- Google robot: rotation delta already axis-angle; gripper command relative
  as predicted, with values under 0.01 zeroed;
- WidowX (RT-1-X): translation rescaled from [-1.75, 1.75] to [-0.05, 0.05] and
  rotation from [-1.4, 1.4] to [-0.25, 0.25] (clipped); rotation as roll-pitch-yaw,
  converted to axis-angle; gripper inverted (RT-1: 1 = close) and binarised;
- the model's ``terminate_episode`` (index 0 of the one-hot) is the stop flag.

Requires the ``rt1`` extra: tensorflow 2.15 and tf-agents 0.19 (see
``mk/adapters/rt1.txt``; ``make test-rt1`` builds that environment).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

# An ImportError here reaches the user through the policy registry, which
# names the extra to install.
import tensorflow as tf
from tf_agents.policies import py_tf_eager_policy
from tf_agents.specs import tensor_spec
from tf_agents.trajectories import time_step as ts

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError, MissingExtraError
from ladev_lib.policies.adapters.common import (
    embodiment,
    policy_info,
    postprocess_rt1,
    require_image,
)
from ladev_lib.policies.base import Observation, Policy, PolicyStep

EMBEDDING_DIM = 512


def _checkpoint_dir(path: str) -> str:
    p = Path(os.path.expanduser(path))
    if not (p / "saved_model.pb").exists():
        raise ConfigError(
            f"RT-1 checkpoint {path!r} is not a SavedModel directory (no saved_model.pb); "
            "download e.g. rt_1_x_tf_trained_for_002272480_step and set its path "
            "(LADEV_CHECKPOINTS in conf/policy/rt1_*.yaml)"
        )
    return str(p)


def load_sentence_encoder(path: str) -> Any:
    """The Universal Sentence Encoder: a local SavedModel dir, or a TF-Hub URL."""
    if path.startswith(("http://", "https://")):
        try:
            import tensorflow_hub as hub
        except ImportError as exc:
            raise MissingExtraError("loading the sentence encoder from a URL", "rt1", exc) from exc
        return hub.load(path)
    local = Path(os.path.expanduser(path))
    if not (local / "saved_model.pb").exists():
        raise ConfigError(
            f"sentence encoder {path!r} is not a SavedModel directory; set sentence_encoder to "
            "the Universal Sentence Encoder (large, v5) downloaded from TF-Hub/Kaggle"
        )
    return tf.saved_model.load(str(local))


class RT1Policy(Policy):
    """RT-1 / RT-1-X through tf-agents, with SimplerEnv's pre- and post-processing."""

    def __init__(
        self,
        checkpoint: str,
        sentence_encoder: str = "https://tfhub.dev/google/universal-sentence-encoder-large/5",
        robot: str = "google_robot",
        image_width: int = 320,
        image_height: int = 256,
        action_scale: float = 1.0,
        device: str | None = None,
        embodiments: dict[str, dict[str, Any]] | None = None,
        name: str = "rt1",
    ) -> None:
        # embodiments: per-robot overrides of SimplerEnv's settings (conf/policy/*.yaml).
        self.emb = embodiment(robot, embodiments)
        self.info = policy_info(name, self.emb)
        self.image_width, self.image_height = image_width, image_height
        self.action_scale = action_scale
        # TensorFlow device string ("/GPU:0", "/CPU:0"); None lets TF place ops.
        self.device = device
        with self._on_device():
            self.encoder = load_sentence_encoder(sentence_encoder)
            self.tfa_policy = py_tf_eager_policy.SavedModelPyTFEagerPolicy(
                model_path=_checkpoint_dir(checkpoint),
                load_specs_from_pbtxt=True,
                use_tf_function=True,
            )
        self._observation: dict[str, Any] = {}
        self._policy_state: Any = None
        self._embedding: Any = None
        self._instruction: str | None = None
        self.last_raw_action: dict[str, Array] = {}
        self._new_episode_state()
        # Trace the graph once now rather than inside the first episode step.
        self._run(self._observation)

    def _on_device(self) -> Any:
        import contextlib

        return tf.device(self.device) if self.device else contextlib.nullcontext()

    def _new_episode_state(self) -> None:
        spec = self.tfa_policy.time_step_spec.observation
        self._observation = tensor_spec.zero_spec_nest(tensor_spec.from_spec(spec))
        self._policy_state = self.tfa_policy.get_initial_state(batch_size=1)

    def _run(self, observation: dict[str, Any]) -> Any:
        time_step = ts.transition(observation, reward=np.zeros((), dtype=np.float32))
        with self._on_device():
            return self.tfa_policy.action(time_step, self._policy_state)

    def preprocess(self, image: Array) -> Array:
        """The camera image as the model sees it: 320x256 (default), resized with padding."""
        resized = tf.image.resize_with_pad(
            image, target_height=self.image_height, target_width=self.image_width
        )
        return np.asarray(tf.cast(resized, tf.uint8))

    def reset(self, instruction: str) -> None:
        self._new_episode_state()
        self._instruction = instruction
        with self._on_device():
            self._embedding = self.encoder([instruction])[0]

    def step(self, obs: Observation) -> PolicyStep:
        if self._instruction is None:
            raise RuntimeError("call reset(instruction) before step()")
        image = require_image(obs.image, "RT-1")
        self._observation["image"] = self.preprocess(image)
        self._observation["natural_language_embedding"] = self._embedding
        policy_step = self._run(self._observation)
        self._policy_state = policy_step.state
        raw = {k: np.asarray(v) for k, v in policy_step.action.items()}
        self.last_raw_action = raw  # the model's own output, for logs and plots
        terminate = bool(raw["terminate_episode"][0] > 0)  # one-hot, index 0 = stop
        return PolicyStep(action=self.postprocess(raw), terminate=terminate)

    def postprocess(self, raw: dict[str, Array]) -> Array:
        """RT-1's action dict -> the controller's 7-vector, per embodiment."""
        return postprocess_rt1(raw, self.emb, self.action_scale)
