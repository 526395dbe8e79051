"""Tiny, randomly initialised LeRobot checkpoints, written with LeRobot's own save methods.

    python -m tests.adapters.tiny_lerobot act|diffusion|smolvla OUT_DIR [--state-dim 16] [--image 64x64] [--std 0.0]

A checkpoint directory as LeRobot's training writes it: ``config.json`` and
``model.safetensors`` (``policy.save_pretrained``) beside the pre- and
post-processor pipelines with their normalisation statistics
(``make_pre_post_processors(...).save_pretrained``). The adapter loads it
through the same path it takes for a downloaded checkpoint.

Needs the LeRobot environment (torch, lerobot): the core-install test of an
episode runs this module with .venv-lerobot's Python.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np
import torch
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.policies.factory import make_pre_post_processors

ACTION_DIM = 7
# The action statistics the unnormaliser applies: mean + std * (network output).
# Hand-picked: [2 cm, -1 cm, 0.5 cm, roll 0, pitch 0, yaw -0.2 rad, gripper 0.9].
ACTION_MEAN = np.array([0.02, -0.01, 0.005, 0.0, 0.0, -0.2, 0.9])


def _stats(dim: int, mean: np.ndarray | float, std: np.ndarray | float) -> dict[str, torch.Tensor]:
    m = np.broadcast_to(np.asarray(mean, dtype=np.float32), (dim,))
    s = np.broadcast_to(np.asarray(std, dtype=np.float32), (dim,))
    return {
        "mean": torch.tensor(m),
        "std": torch.tensor(s),
        "min": torch.tensor(m - 1.0),
        "max": torch.tensor(m + 1.0),
    }


def state_stats(state_dim: int) -> dict[str, np.ndarray]:
    """Hand-picked state statistics (the tests recompute the normalised state from them)."""
    return {"mean": np.linspace(-0.5, 0.5, state_dim), "std": np.full(state_dim, 2.0)}


def tiny_features(
    state_dim: int,
    image_hw: tuple[int, int],
    cameras: tuple[str, ...] = ("image",),
    env_state_dim: int = 0,
) -> tuple[dict[str, PolicyFeature], dict[str, PolicyFeature]]:
    h, w = image_hw
    inputs = {f"observation.images.{c}": PolicyFeature(FeatureType.VISUAL, (3, h, w)) for c in cameras}
    if state_dim:
        inputs["observation.state"] = PolicyFeature(FeatureType.STATE, (state_dim,))
    if env_state_dim:
        inputs["observation.environment_state"] = PolicyFeature(FeatureType.ENV, (env_state_dim,))
    return inputs, {"action": PolicyFeature(FeatureType.ACTION, (ACTION_DIM,))}


def dataset_stats(
    inputs: dict[str, PolicyFeature], action_std: float
) -> dict[str, dict[str, torch.Tensor]]:
    stats: dict[str, dict[str, torch.Tensor]] = {}
    for key, feat in inputs.items():
        if feat.type is FeatureType.VISUAL:  # per channel, as LeRobot's dataset stats are
            stats[key] = {k: v.reshape(3, 1, 1) for k, v in _stats(3, 0.5, 0.25).items()}
        else:
            st = state_stats(feat.shape[0])
            stats[key] = _stats(feat.shape[0], st["mean"], st["std"])
    stats["action"] = _stats(ACTION_DIM, ACTION_MEAN, action_std)
    return stats


def save_checkpoint(policy: Any, cfg: Any, stats: dict[str, dict[str, torch.Tensor]], out: Path) -> Path:
    """LeRobot's own save: the policy, then its processors with the statistics."""
    out.mkdir(parents=True, exist_ok=True)
    policy.save_pretrained(out)
    pre, post = make_pre_post_processors(cfg, dataset_stats=stats)
    pre.save_pretrained(out)
    post.save_pretrained(out)
    return out


def build_tiny_act(
    out: Path,
    state_dim: int = 16,
    image_hw: tuple[int, int] = (64, 64),
    action_std: float = 0.0,
    chunk_size: int = 4,
    cameras: tuple[str, ...] = ("image",),
    env_state_dim: int = 0,
    seed: int = 0,
) -> Path:
    """An ACT policy (ResNet-18 backbone without pretrained weights, 1+1 layers, d=32).

    ``action_std=0`` makes every unnormalised action exactly ACTION_MEAN, whatever
    the random network outputs: the mapping tests compare against hand-computed values.
    """
    from lerobot.policies.act.configuration_act import ACTConfig
    from lerobot.policies.act.modeling_act import ACTPolicy

    torch.manual_seed(seed)
    inputs, outputs = tiny_features(state_dim, image_hw, cameras, env_state_dim)
    cfg = ACTConfig(
        input_features=inputs,
        output_features=outputs,
        chunk_size=chunk_size,
        n_action_steps=chunk_size,
        pretrained_backbone_weights=None,
        dim_model=32,
        n_heads=2,
        dim_feedforward=64,
        n_encoder_layers=1,
        n_decoder_layers=1,
        use_vae=False,
        device="cpu",
    )
    policy = ACTPolicy(cfg)
    return save_checkpoint(policy, cfg, dataset_stats(inputs, action_std), out)


# Words of the tiny backbone's tokenizer (WordLevel: anything else is <unk>).
TINY_VOCAB = [
    "<unk>", "<pad>", "<|im_start|>", "<end_of_utterance>", "<fake_token_around_image>", "<image>",
    "<global-img>", "pick", "up", "put", "the", "a", "red", "green", "can", "mug", "apple", "on", "in",
    "plate", "bowl", "drawer", "stapler", "next", "to", ".", "\n",
]


def build_tiny_smolvlm(out: Path) -> Path:
    """A stand-in for SmolVLM2-500M-Video-Instruct's hub files: a tiny SmolVLM config
    (2-layer Llama text model, 1-layer SigLIP on 32x32 images) and a processor whose
    tokenizer carries SmolVLM's image tokens. SmolVLA builds its backbone from these
    (``vlm_model_name``) with random weights, as it does with ``load_vlm_weights=False``.
    """
    from tokenizers import Tokenizer, models, pre_tokenizers
    from transformers import (
        PreTrainedTokenizerFast,
        SmolVLMConfig,
        SmolVLMImageProcessor,
        SmolVLMProcessor,
        SmolVLMVideoProcessor,
    )

    out.mkdir(parents=True, exist_ok=True)
    words = Tokenizer(models.WordLevel(vocab={w: i for i, w in enumerate(TINY_VOCAB)}, unk_token="<unk>"))
    words.pre_tokenizer = pre_tokenizers.WhitespaceSplit()
    special = {
        "fake_image_token": "<fake_token_around_image>",
        "image_token": "<image>",
        "global_image_token": "<global-img>",
        "end_of_utterance_token": "<end_of_utterance>",
    }
    tokenizer = PreTrainedTokenizerFast(
        tokenizer_object=words, unk_token="<unk>", pad_token="<pad>", bos_token="<|im_start|>",
        eos_token="<end_of_utterance>", additional_special_tokens=list(special.values()),
        extra_special_tokens=special,
    )
    images = SmolVLMImageProcessor(do_resize=False, do_image_splitting=False, size={"longest_edge": 32},
                                   max_image_size={"longest_edge": 32})
    SmolVLMProcessor(image_processor=images, tokenizer=tokenizer, video_processor=SmolVLMVideoProcessor(),
                     image_seq_len=4).save_pretrained(out)
    SmolVLMConfig(
        text_config={"model_type": "llama", "vocab_size": len(TINY_VOCAB), "hidden_size": 32,
                     "intermediate_size": 64, "num_hidden_layers": 2, "num_attention_heads": 2,
                     "num_key_value_heads": 1, "head_dim": 16, "max_position_embeddings": 256,
                     "pad_token_id": 1},
        vision_config={"hidden_size": 32, "intermediate_size": 64, "num_hidden_layers": 1,
                       "num_attention_heads": 2, "image_size": 32, "patch_size": 8},
        scale_factor=2, image_token_id=TINY_VOCAB.index("<image>"), vocab_size=len(TINY_VOCAB),
    ).save_pretrained(out)
    return out


def build_tiny_smolvla(
    out: Path,
    backbone: Path,
    state_dim: int = 8,
    image_hw: tuple[int, int] = (64, 64),
    action_std: float = 0.05,
    cameras: tuple[str, ...] = ("image", "image2"),
    seed: int = 0,
) -> Path:
    """A SmolVLA policy on the tiny backbone at ``backbone`` (LIBERO-like: two cameras,
    8-value state, 7-value action), chunks of 4 actions, 2 flow-matching steps."""
    from lerobot.policies.smolvla.configuration_smolvla import SmolVLAConfig
    from lerobot.policies.smolvla.modeling_smolvla import SmolVLAPolicy

    torch.manual_seed(seed)
    inputs, outputs = tiny_features(state_dim, image_hw, cameras)
    cfg = SmolVLAConfig(
        input_features=inputs,
        output_features=outputs,
        chunk_size=4,
        n_action_steps=4,
        vlm_model_name=str(backbone),
        load_vlm_weights=False,
        num_vlm_layers=2,
        expert_width_multiplier=0.5,
        resize_imgs_with_padding=(32, 32),
        tokenizer_max_length=16,
        num_steps=2,
        max_state_dim=16,
        max_action_dim=16,
        device="cpu",
    )
    policy = SmolVLAPolicy(cfg)
    return save_checkpoint(policy, cfg, dataset_stats(inputs, action_std), out)


def build_tiny_diffusion(
    out: Path,
    state_dim: int = 16,
    image_hw: tuple[int, int] = (64, 64),
    action_std: float = 0.05,
    seed: int = 0,
) -> Path:
    """A diffusion policy: 2 observations of history, a horizon of 8 of which 4 run,
    a small U-Net and ResNet-18 (no pretrained weights), 3 DDIM denoising steps."""
    from lerobot.policies.diffusion.configuration_diffusion import DiffusionConfig
    from lerobot.policies.diffusion.modeling_diffusion import DiffusionPolicy

    torch.manual_seed(seed)
    inputs, outputs = tiny_features(state_dim, image_hw)
    cfg = DiffusionConfig(
        input_features=inputs,
        output_features=outputs,
        n_obs_steps=2,
        horizon=8,
        n_action_steps=4,
        drop_n_last_frames=3,
        crop_shape=None,
        down_dims=(16, 32),
        kernel_size=3,
        n_groups=4,
        diffusion_step_embed_dim=16,
        spatial_softmax_num_keypoints=8,
        noise_scheduler_type="DDIM",
        num_train_timesteps=10,
        num_inference_steps=3,
        device="cpu",
    )
    policy = DiffusionPolicy(cfg)
    return save_checkpoint(policy, cfg, dataset_stats(inputs, action_std), out)


def build_tiny_smolvla_with_backbone(out: Path, state_dim: int = 8, image_hw: tuple[int, int] = (64, 64),
                                     action_std: float = 0.05) -> Path:
    """SmolVLA with its tiny backbone written beside it (``<out>-smolvlm``)."""
    backbone = build_tiny_smolvlm(out.parent / f"{out.name}-smolvlm")
    return build_tiny_smolvla(out, backbone, state_dim=state_dim, image_hw=image_hw, action_std=action_std)


BUILDERS = {
    "act": build_tiny_act,
    "diffusion": build_tiny_diffusion,
    "smolvla": build_tiny_smolvla_with_backbone,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=sorted(BUILDERS))
    parser.add_argument("out", type=Path)
    parser.add_argument("--state-dim", type=int, default=16)
    parser.add_argument("--image", default="64x64", help="HxW of the checkpoint's camera input")
    parser.add_argument("--std", type=float, default=0.0, help="action std of the statistics")
    args = parser.parse_args()
    h, w = (int(v) for v in args.image.split("x"))
    path = BUILDERS[args.kind](args.out, state_dim=args.state_dim, image_hw=(h, w), action_std=args.std)
    print(path)


if __name__ == "__main__":
    main()
