"""Octo (octo-small, octo-base): JAX models loaded with Octo's own ``OctoModel``.

    policy = make_policy("octo", checkpoint="checkpoints/octo-base", robot="widowx",
                         text_encoder="checkpoints/t5-base")

Octo's model code is not on PyPI (PyPI's ``octo`` is an unrelated plugin
framework): install it from a checkout of octo-models/octo into the ``octo``
environment (``OCTO_SPEC=/path/to/octo make adapter-env-octo``). A checkpoint
is a local directory (or ``hf://rail-berkeley/octo-base`` with a hub).

The checkpoint names its text encoder and tokenizer by hub id ("t5-base").
Offline, ``text_encoder`` points at a local directory holding that model's
config and tokenizer; the adapter then loads the checkpoint through a view
of it whose ``config.json`` names that directory instead.

Per step (SimplerEnv's ``octo_model.py``): the image is resized to 256x256
(Lanczos, antialiased), kept in a two-frame history, and the model samples
a chunk of 4 normalised actions; the chunks are temporally ensembled, then
unnormalised with the mean/std of ``fractal20220817_data`` (Google robot)
or ``bridge_dataset`` (WidowX), every dimension as SimplerEnv does
(``use_action_mask=True``: Octo's own convention, skipping masked dims). Rotation roll-pitch-yaw becomes axis-angle;
the gripper openness becomes a relative command held for 15 steps (Google
robot) or a binary open/close target (WidowX). Octo has no stop signal.

Deviation from SimplerEnv, on purpose: the sampling key restarts from
``seed`` at every ``reset`` so that an episode is reproducible on its own
(LADEV caches episodes by seed); SimplerEnv carries it across episodes.
"""

from __future__ import annotations

import copy
import json
import os
import tempfile
from collections import deque
from pathlib import Path
from typing import Any

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError, MissingExtraError
from ladev_lib.policies.adapters.common import (
    ActionEnsembler,
    EulerOpenGripperPostprocessor,
    embodiment,
    policy_info,
    require_image,
    unnormalize_gaussian,
)
from ladev_lib.policies.base import Observation, Policy, PolicyStep

TEXT_ENCODER_KEYS = ("tokenizer_name", "encoder")
"""Config keys under which Octo names hub models for its text processing."""


def override_text_encoder(config: dict[str, Any], path: str) -> tuple[dict[str, Any], int]:
    """A copy of an Octo config naming ``path`` wherever it named a text encoder/tokenizer."""
    replaced = 0

    def walk(node: Any) -> Any:
        nonlocal replaced
        if isinstance(node, dict):
            out = {}
            for key, value in node.items():
                if key in TEXT_ENCODER_KEYS and isinstance(value, str):
                    out[key] = path
                    replaced += 1
                else:
                    out[key] = walk(value)
            return out
        if isinstance(node, list):
            return [walk(v) for v in node]
        return node

    return walk(copy.deepcopy(config)), replaced


def checkpoint_view(checkpoint: str, text_encoder: str, workdir: str) -> str:
    """A directory that mirrors ``checkpoint`` (symlinks) with the text encoder overridden."""
    src = Path(os.path.expanduser(checkpoint)).resolve()
    config_path = src / "config.json"
    if not config_path.exists():
        raise ConfigError(f"Octo checkpoint {checkpoint!r} has no config.json")
    with open(config_path, encoding="utf-8") as f:
        config = json.load(f)
    patched, replaced = override_text_encoder(config, str(Path(text_encoder).expanduser().resolve()))
    if replaced == 0:
        raise ConfigError(
            f"Octo checkpoint {checkpoint!r} names no text encoder/tokenizer "
            f"({'/'.join(TEXT_ENCODER_KEYS)}); drop text_encoder from the config"
        )
    view = Path(workdir) / src.name
    view.mkdir(parents=True, exist_ok=True)
    for entry in src.iterdir():
        if entry.name != "config.json":
            (view / entry.name).symlink_to(entry)
    with open(view / "config.json", "w", encoding="utf-8") as f:
        json.dump(patched, f)
    return str(view)


def load_octo_model(checkpoint: str, text_encoder: str | None, workdir: str) -> Any:
    """``OctoModel.load_pretrained`` on the checkpoint (or its text-encoder view)."""
    try:
        from octo.model.octo_model import OctoModel
    except ImportError as exc:
        raise MissingExtraError(
            "policy 'octo' (Octo's model code from github.com/octo-models/octo; PyPI's "
            "'octo' is an unrelated package: OCTO_SPEC=<checkout> make adapter-env-octo)",
            "octo",
            exc,
        ) from exc
    path = checkpoint
    if not checkpoint.startswith("hf://"):
        local = Path(os.path.expanduser(checkpoint))
        if not (local / "config.json").exists():
            raise ConfigError(
                f"Octo checkpoint {checkpoint!r} not found (a directory with config.json, "
                "dataset_statistics.json and the step folders); set its path "
                "(LADEV_CHECKPOINTS in conf/policy/octo_*.yaml)"
            )
        if text_encoder:
            path = checkpoint_view(checkpoint, text_encoder, workdir)
    elif text_encoder:
        raise ConfigError("text_encoder needs a local checkpoint directory, not an hf:// id")
    return OctoModel.load_pretrained(path)


def resize_lanczos(image: Array, size: int) -> Array:
    """Square Lanczos resize as SimplerEnv does for Octo (TensorFlow's, when available)."""
    try:
        import tensorflow as tf
    except ImportError:
        from PIL import Image

        resized = Image.fromarray(image).resize((size, size), Image.Resampling.LANCZOS)
        return np.asarray(resized, dtype=np.uint8)
    out = tf.image.resize(image, size=(size, size), method="lanczos3", antialias=True)
    return np.asarray(tf.cast(tf.clip_by_value(tf.round(out), 0, 255), tf.uint8))


class OctoPolicy(Policy):
    """Octo with SimplerEnv's history, ensembling and gripper handling."""

    def __init__(
        self,
        checkpoint: str = "hf://rail-berkeley/octo-base",
        robot: str = "widowx",
        dataset_key: str | None = None,
        text_encoder: str | None = None,
        window: int = 2,
        action_horizon: int = 4,
        ensemble: bool = True,
        ensemble_temperature: float = 0.0,
        image_size: int = 256,
        seed: int = 0,
        use_action_mask: bool = False,
        action_scale: float = 1.0,
        device: str | None = None,
        embodiments: dict[str, dict[str, Any]] | None = None,
        name: str = "octo",
        model: Any = None,
    ) -> None:
        try:
            import jax
        except ImportError as exc:
            raise MissingExtraError("policy 'octo'", "octo", exc) from exc

        self._jax = jax
        # embodiments: per-robot overrides of SimplerEnv's settings (conf/policy/*.yaml).
        self.emb = embodiment(robot, embodiments)
        self.info = policy_info(name, self.emb)
        self.window = window
        self.action_horizon = action_horizon
        self.image_size = image_size
        self.seed = seed
        self._workdir = tempfile.TemporaryDirectory(prefix="ladev-octo-")
        # ``model``: an OctoModel already in memory (then ``checkpoint`` is unused).
        self.model = model if model is not None else load_octo_model(
            checkpoint, text_encoder, self._workdir.name
        )
        if device is not None:
            target = jax.devices(device)[0]
            self.model = self.model.replace(params=jax.device_put(self.model.params, target))
        self.dataset_key = dataset_key or self.emb.dataset_key
        stats = self.model.dataset_statistics or {}
        if self.dataset_key not in stats:
            raise ConfigError(
                f"Octo checkpoint has no action statistics for {self.dataset_key!r}; "
                f"it has: {', '.join(sorted(stats)) or 'none'} (set dataset_key)"
            )
        self.action_stats = stats[self.dataset_key]["action"]
        # False: SimplerEnv's choice (every dim unnormalised, the gripper too);
        # True: Octo's own (dims whose statistics mask is false left as predicted).
        self.use_action_mask = use_action_mask
        self.ensembler = ActionEnsembler(action_horizon, ensemble_temperature) if ensemble else None
        self.post = EulerOpenGripperPostprocessor(self.emb, action_scale)
        self._history: deque[Array] = deque(maxlen=window)
        self._task: Any = None
        self.last_raw_action = np.zeros(7)
        self._rng: Any = None

    def _fresh_rng(self) -> Any:
        rng = self._jax.random.PRNGKey(self.seed)
        # SimplerEnv splits five times first, to match Octo's server-side seeds.
        for _ in range(5):
            rng, _ = self._jax.random.split(rng)
        return rng

    def reset(self, instruction: str) -> None:
        self._task = self.model.create_tasks(texts=[instruction])
        self._history.clear()
        if self.ensembler is not None:
            self.ensembler.reset()
        self.post.reset()
        self._rng = self._fresh_rng()

    def step(self, obs: Observation) -> PolicyStep:
        if self._task is None:
            raise RuntimeError("call reset(instruction) before step()")
        image = resize_lanczos(require_image(obs.image, "Octo"), self.image_size)
        self._history.append(image)
        images = np.stack(self._history)[None]
        # Every frame in the (not yet full) window is real: no padding entries.
        pad_mask = np.ones((1, len(self._history)), dtype=np.float64)
        self._rng, key = self._jax.random.split(self._rng)
        observation = {"image_primary": images, "timestep_pad_mask": pad_mask}
        chunk = np.asarray(self.model.sample_actions(observation, self._task, rng=key))[0]
        if chunk.ndim != 2 or chunk.shape[0] < self.action_horizon or chunk.shape[1] < 7:
            raise ValueError(
                f"Octo returned actions of shape {chunk.shape}, expected "
                f"({self.action_horizon}, >=7); check action_horizon"
            )
        chunk = chunk[: self.action_horizon, :7]
        normalized = self.ensembler(chunk) if self.ensembler is not None else chunk[0]
        raw = unnormalize_gaussian(normalized, self.action_stats, self.use_action_mask)
        self.last_raw_action = raw  # [xyz, roll-pitch-yaw, openness], for logs and plots
        return PolicyStep(action=self.post(raw), terminate=False)

    def close(self) -> None:
        self._workdir.cleanup()
