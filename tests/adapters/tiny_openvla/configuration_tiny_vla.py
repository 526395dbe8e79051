"""Config of the tiny OpenVLA stand-in (remote code written into the test checkpoint)."""

from __future__ import annotations

from typing import Any

from transformers import PretrainedConfig


class TinyVLAConfig(PretrainedConfig):
    model_type = "ladev_tiny_vla"

    def __init__(
        self,
        text_config: dict[str, Any] | None = None,
        image_size: int = 224,
        patch_size: int = 32,
        n_action_bins: int = 256,
        pad_to_multiple_of: int = 64,
        norm_stats: dict[str, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        self.text_config = text_config or {}
        self.image_size = image_size
        self.patch_size = patch_size
        self.n_action_bins = n_action_bins
        self.pad_to_multiple_of = pad_to_multiple_of
        self.norm_stats = norm_stats or {}
        super().__init__(**kwargs)
