"""A tiny vision-language-action model with OpenVLA's *interface* (test fixture, not OpenVLA).

OpenVLA's real modeling code (Prismatic: DINOv2 + SigLIP backbones, an MLP
projector, Llama-2) ships inside its checkpoint and is not obtainable here.
This stand-in keeps what the adapter relies on: it loads with
``AutoModelForVision2Seq.from_pretrained(..., trust_remote_code=True)``, its
language model is a (tiny, random) ``LlamaForCausalLM`` whose input is the
projected image patches after the BOS token, and ``predict_action`` decodes
seven greedily generated tokens the way OpenVLA does: the last 256 ids of the
vocabulary are bins over [-1, 1], mapped onto [q01, q99] of ``norm_stats
[unnorm_key]["action"]`` where its mask is true.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import torch
from torch import nn
from transformers import LlamaConfig, LlamaForCausalLM, PreTrainedModel

from .configuration_tiny_vla import TinyVLAConfig

ACTION_DIM = 7


class TinyVLAForActionPrediction(PreTrainedModel):
    config_class = TinyVLAConfig
    _supports_sdpa = True

    def __init__(self, config: TinyVLAConfig) -> None:
        super().__init__(config)
        text = LlamaConfig(**config.text_config)
        text._attn_implementation = config._attn_implementation
        self.language_model = LlamaForCausalLM(text)
        hidden = text.hidden_size
        self.patch_embed = nn.Conv2d(3, hidden, kernel_size=config.patch_size, stride=config.patch_size)
        self.projector = nn.Sequential(nn.Linear(hidden, hidden), nn.GELU(), nn.Linear(hidden, hidden))
        self.norm_stats = config.norm_stats
        self.vocab_size = text.vocab_size - config.pad_to_multiple_of
        edges = np.linspace(-1, 1, config.n_action_bins)
        self.bin_centers = (edges[:-1] + edges[1:]) / 2.0
        self.last_input_ids: torch.Tensor | None = None
        self.post_init()

    def _init_weights(self, module: nn.Module) -> None:
        if isinstance(module, nn.Linear | nn.Conv2d | nn.Embedding):
            nn.init.normal_(module.weight, std=0.5)
        if isinstance(module, nn.Linear | nn.Conv2d) and module.bias is not None:
            nn.init.zeros_(module.bias)

    def forward(self, input_ids: torch.Tensor, pixel_values: torch.Tensor, **_: Any) -> torch.Tensor:
        patches = self.patch_embed(pixel_values).flatten(2).transpose(1, 2)
        text = self.language_model.get_input_embeddings()(input_ids)
        embeds = torch.cat([text[:, :1], self.projector(patches), text[:, 1:]], dim=1)
        logits: torch.Tensor = self.language_model(inputs_embeds=embeds).logits
        return logits

    @torch.no_grad()
    def predict_action(
        self,
        input_ids: torch.Tensor,
        pixel_values: torch.Tensor,
        unnorm_key: str,
        attention_mask: torch.Tensor | None = None,
        do_sample: bool = False,
        **_: Any,
    ) -> np.ndarray:
        assert not do_sample, "the stand-in decodes greedily"
        self.last_input_ids = input_ids
        ids = input_ids
        for _step in range(ACTION_DIM):
            next_id = self.forward(ids, pixel_values)[:, -1].argmax(dim=-1, keepdim=True)
            ids = torch.cat([ids, next_id], dim=1)
        tokens = ids[0, -ACTION_DIM:].cpu().numpy()
        bins = np.clip(self.vocab_size - tokens - 1, 0, len(self.bin_centers) - 1)
        normalized = self.bin_centers[bins]
        stats = self.norm_stats[unnorm_key]["action"]
        low, high = np.asarray(stats["q01"]), np.asarray(stats["q99"])
        mask = np.asarray(stats.get("mask", np.ones_like(low, dtype=bool)))
        return np.where(mask, 0.5 * (normalized + 1) * (high - low) + low, normalized)
