"""A tiny, randomly initialised RT-1-format checkpoint and sentence encoder (test fixtures).

What is real: the checkpoint *format*. A released RT-1 checkpoint is a
tf-agents policy written by ``PolicySaver`` (``saved_model.pb`` +
``policy_specs.pbtxt``) with RT-1's observation, policy-state and action
specs; this one is written the same way, so the adapter loads it through the
same code path (``SavedModelPyTFEagerPolicy(load_specs_from_pbtxt=True)``).

What is not: the network inside. RT-1's (EfficientNet-B3 + FiLM +
TokenLearner + Transformer, google-research/robotics_transformer) is not
installable from PyPI; this is a small FiLM-conditioned conv net of our own
that, like RT-1, predicts each action dimension as one of 256 bins. It stops
(``terminate_episode`` = [1, 0, 0]) from its third step on, and echoes the
first two entries of the language embedding in ``base_displacement_vector``,
so tests can see that the policy state and the instruction reach the model.

The sentence encoder stands in for the Universal Sentence Encoder: a
SavedModel mapping strings to 512-d unit vectors by hashing.

Writing needs tf-agents' own typing-extensions pin (4.5.0; TF 2.15 cannot
trace PolicySaver's tracked dicts with newer ones, which pydantic 2 needs), so
the tests run this module as a subprocess with ``$VENV/writer-site`` first on
its path (``mk/adapters/rt1.writer.txt``):

    python -m tests.adapters.tiny_rt1 OUT_DIR   # writes OUT_DIR/rt_1_tiny, OUT_DIR/use_tiny
"""

from __future__ import annotations

import math
from pathlib import Path

import tensorflow as tf
from tf_agents.policies import policy_saver, tf_policy
from tf_agents.specs import tensor_spec
from tf_agents.trajectories import policy_step
from tf_agents.trajectories import time_step as ts

BINS = 256
IMAGE_SHAPE = (256, 320, 3)

OBSERVATION_SPEC = {
    "image": tf.TensorSpec(IMAGE_SHAPE, tf.uint8, name="image"),
    "natural_language_embedding": tf.TensorSpec((512,), tf.float32, name="natural_language_embedding"),
    "natural_language_instruction": tf.TensorSpec((), tf.string, name="natural_language_instruction"),
}
# RT-1's action space (robotics_transformer's Fractal action spec).
ACTION_SPEC = {
    "world_vector": tensor_spec.BoundedTensorSpec((3,), tf.float32, -1.0, 1.0, name="world_vector"),
    "rotation_delta": tensor_spec.BoundedTensorSpec(
        (3,), tf.float32, -math.pi / 2, math.pi / 2, name="rotation_delta"
    ),
    "gripper_closedness_action": tensor_spec.BoundedTensorSpec(
        (1,), tf.float32, -1.0, 1.0, name="gripper_closedness_action"
    ),
    "terminate_episode": tensor_spec.BoundedTensorSpec((3,), tf.int32, 0, 1, name="terminate_episode"),
    "base_displacement_vertical_rotation": tensor_spec.BoundedTensorSpec(
        (1,), tf.float32, -math.pi, math.pi, name="base_displacement_vertical_rotation"
    ),
    "base_displacement_vector": tensor_spec.BoundedTensorSpec(
        (2,), tf.float32, -1.0, 1.0, name="base_displacement_vector"
    ),
}
CONTINUOUS = ["world_vector", "rotation_delta", "gripper_closedness_action", "base_displacement_vertical_rotation"]
STATE_SPEC = {
    "step_num": tf.TensorSpec((), tf.int32, name="step_num"),
    "memory": tf.TensorSpec((16,), tf.float32, name="memory"),
}
STOP_AT_STEP = 3


class TinyFilmNet(tf.keras.Model):
    """Downsampled image -> conv -> FiLM(language) -> pooled features -> per-dimension bin logits."""

    def __init__(self, n_dims: int, seed: int) -> None:
        super().__init__()
        init = tf.keras.initializers.GlorotUniform(seed=seed)
        self.conv = tf.keras.layers.Conv2D(16, 3, strides=2, activation="relu", kernel_initializer=init)
        self.film = tf.keras.layers.Dense(32, kernel_initializer=init)
        self.head = tf.keras.layers.Dense(n_dims * BINS, kernel_initializer=init)
        self.memory = tf.keras.layers.Dense(16, activation="tanh", kernel_initializer=init)
        self.n_dims = n_dims

    def call(self, image: tf.Tensor, embedding: tf.Tensor, memory: tf.Tensor) -> tuple[tf.Tensor, tf.Tensor]:
        x = tf.nn.avg_pool2d(tf.cast(image, tf.float32) / 255.0, ksize=8, strides=8, padding="VALID")
        x = self.conv(x)
        gamma, beta = tf.split(self.film(embedding), 2, axis=-1)
        x = x * (1.0 + gamma[:, None, None, :]) + beta[:, None, None, :]
        features = tf.concat([tf.reduce_mean(x, axis=[1, 2]), memory], axis=-1)
        logits = tf.reshape(self.head(features), [-1, self.n_dims, BINS])
        return logits, self.memory(features)


class TinyRT1Policy(tf_policy.TFPolicy):
    def __init__(self, seed: int = 0) -> None:
        super().__init__(
            ts.time_step_spec(OBSERVATION_SPEC), ACTION_SPEC, policy_state_spec=STATE_SPEC
        )
        self._dims = [(k, ACTION_SPEC[k].shape[0]) for k in CONTINUOUS]
        self._net = TinyFilmNet(sum(n for _, n in self._dims), seed)

    def _distribution(self, time_step, policy_state):  # type: ignore[no-untyped-def]
        raise NotImplementedError("deterministic policy: use action()")

    def _action(self, time_step, policy_state, seed=None):  # type: ignore[no-untyped-def]
        obs = time_step.observation
        embedding = obs["natural_language_embedding"]
        logits, memory = self._net(obs["image"], embedding, policy_state["memory"])
        # Like RT-1: one of 256 bins per dimension, mapped back onto the spec's bounds.
        fraction = tf.cast(tf.argmax(logits, axis=-1), tf.float32) / (BINS - 1)
        action, start = {}, 0
        for key, n in self._dims:
            spec = ACTION_SPEC[key]
            low, high = float(spec.minimum), float(spec.maximum)
            action[key] = low + fraction[:, start : start + n] * (high - low)
            start += n
        action["base_displacement_vector"] = tf.tanh(embedding[:, :2])
        step_num = policy_state["step_num"] + 1
        stop = step_num >= STOP_AT_STEP
        action["terminate_episode"] = tf.where(
            stop[:, None], tf.constant([[1, 0, 0]], tf.int32), tf.constant([[0, 1, 0]], tf.int32)
        )
        state = {"step_num": step_num, "memory": memory}
        return policy_step.PolicyStep(action, state, ())


def save_tiny_rt1(path: Path, seed: int = 0) -> Path:
    policy = TinyRT1Policy(seed)
    # Build the variables with one call before saving.
    zero_obs = tensor_spec.zero_spec_nest(OBSERVATION_SPEC, outer_dims=(1,))
    policy.action(ts.restart(zero_obs, batch_size=1), policy.get_initial_state(1))
    policy_saver.PolicySaver(policy, batch_size=None).save(str(path))
    return path


class HashSentenceEncoder(tf.Module):
    @tf.function(input_signature=[tf.TensorSpec([None], tf.string)])
    def __call__(self, texts: tf.Tensor) -> tf.Tensor:
        rows = []
        for salt in range(8):
            buckets = tf.strings.to_hash_bucket_fast(tf.strings.join([texts, str(salt)], "#"), 2**20)
            phases = tf.cast(buckets, tf.float32)[:, None] * tf.range(1.0, 65.0)[None, :] * 1e-3
            rows.append(tf.sin(phases))
        vec = tf.concat(rows, axis=-1)
        return vec / tf.norm(vec, axis=-1, keepdims=True)


def save_sentence_encoder(path: Path) -> Path:
    tf.saved_model.save(HashSentenceEncoder(), str(path))
    return path


if __name__ == "__main__":
    import sys

    out = Path(sys.argv[1])
    save_tiny_rt1(out / "rt_1_tiny")
    save_sentence_encoder(out / "use_tiny")
