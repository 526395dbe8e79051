"""An in-memory stand-in with the OctoModel interface the adapter uses (test fixture, not Octo).

Octo's model code (octo-models/octo) is not on PyPI, so no real OctoModel can
be built here. This tiny Flax module takes what OctoModel.sample_actions takes
(an image history with its timestep pad mask, a task from create_tasks, an
RNG key) and returns a chunk of normalised actions of shape (1, horizon, 7),
with noise drawn from the key like Octo's diffusion head. It records each
call so tests can check what the adapter sends.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import flax.linen as nn
import jax
import jax.numpy as jnp
import numpy as np

STATS = {
    "bridge_dataset": {"action": {
        "mean": [0.0002, 0.0001, -0.0002, -0.0002, -0.0002, 0.0003, 0.5],
        "std": [0.0096, 0.0135, 0.0125, 0.0281, 0.0302, 0.0763, 0.5],
        "mask": [True, True, True, True, True, True, False],
    }},
    "fractal20220817_data": {"action": {
        "mean": [0.0070, 0.0063, -0.0126, 0.0433, -0.0057, 0.0009, 0.5],
        "std": [0.0693, 0.0602, 0.0735, 0.1561, 0.1316, 0.1459, 0.5],
        "mask": [True, True, True, True, True, True, False],
    }},
}


class TinyChunkHead(nn.Module):
    horizon: int = 4
    action_dim: int = 7

    @nn.compact
    def __call__(self, images: jnp.ndarray, pad_mask: jnp.ndarray, task: jnp.ndarray) -> jnp.ndarray:
        x = images.astype(jnp.float32) / 255.0  # (B, T, H, W, 3)
        x = nn.avg_pool(x.reshape((-1, *x.shape[2:])), (16, 16), strides=(16, 16))
        x = nn.relu(nn.Conv(8, (3, 3), strides=(2, 2))(x))
        x = x.mean(axis=(1, 2)).reshape((images.shape[0], images.shape[1], -1))
        x = (x * pad_mask[..., None]).sum(axis=1) / pad_mask.sum(axis=1, keepdims=True)
        x = jnp.concatenate([x, task], axis=-1)
        out = nn.Dense(self.horizon * self.action_dim)(x)
        return jnp.tanh(out).reshape((-1, self.horizon, self.action_dim))


@dataclass
class TinyOctoModel:
    horizon: int = 4
    seed: int = 0
    dataset_statistics: dict[str, Any] = field(default_factory=lambda: STATS)
    calls: list[dict[str, Any]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.module = TinyChunkHead(horizon=self.horizon)
        images = jnp.zeros((1, 2, 256, 256, 3), jnp.uint8)
        self.params = self.module.init(jax.random.PRNGKey(self.seed), images, jnp.ones((1, 2)), jnp.zeros((1, 8)))

    def replace(self, **changes: Any) -> TinyOctoModel:
        for key, value in changes.items():
            setattr(self, key, value)
        return self

    def create_tasks(self, texts: list[str]) -> dict[str, Any]:
        codes = np.array([[(hash(t) >> (4 * i)) % 16 / 16.0 for i in range(8)] for t in texts])
        return {"language_instruction": jnp.asarray(codes, jnp.float32), "texts": list(texts)}

    def sample_actions(self, observations: dict[str, Any], tasks: dict[str, Any], rng: Any) -> jnp.ndarray:
        images = observations["image_primary"]
        pad_mask = jnp.asarray(observations["timestep_pad_mask"], jnp.float32)
        self.calls.append({"images": np.asarray(images), "pad_mask": np.asarray(pad_mask), "rng": np.asarray(rng)})
        mean = self.module.apply(self.params, images, pad_mask, tasks["language_instruction"])
        return mean + 0.1 * jax.random.normal(rng, mean.shape)
