"""Processor of the tiny OpenVLA stand-in: a word-level tokenizer and an image transform."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import torch
from PIL import Image
from transformers import BatchFeature, PreTrainedTokenizerFast


class TinyVLAProcessor:
    def __init__(self, tokenizer: PreTrainedTokenizerFast, image_size: int) -> None:
        self.tokenizer = tokenizer
        self.image_size = image_size
        self.last_prompt: str | None = None
        self.last_image_size: tuple[int, int] | None = None

    @classmethod
    def register_for_auto_class(cls, auto_class: str = "AutoProcessor") -> None:
        """AutoProcessor calls this on remote-code processors; nothing to register."""

    @classmethod
    def from_pretrained(cls, path: str, **_: Any) -> TinyVLAProcessor:
        with open(Path(path) / "processor_config.json", encoding="utf-8") as f:
            config = json.load(f)
        return cls(PreTrainedTokenizerFast.from_pretrained(path), int(config["image_size"]))

    def __call__(self, text: str, images: Image.Image, return_tensors: str = "pt") -> BatchFeature:
        self.last_prompt, self.last_image_size = text, images.size
        enc = self.tokenizer(text, return_tensors="pt")
        image = images.convert("RGB").resize((self.image_size, self.image_size), Image.Resampling.BICUBIC)
        pixels = (np.asarray(image, dtype=np.float32) / 255.0 - 0.5) / 0.5
        pixel_values = torch.from_numpy(pixels).permute(2, 0, 1)[None]
        return BatchFeature(
            {"input_ids": enc["input_ids"], "attention_mask": enc["attention_mask"], "pixel_values": pixel_values}
        )
