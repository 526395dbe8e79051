"""Write a tiny OpenVLA stand-in checkpoint directory (see ``modeling_tiny_vla``).

The directory has what an OpenVLA checkpoint has: ``config.json`` with an
``auto_map``, remote-code modules, weights (safetensors), a tokenizer and a
processor config, plus OpenVLA's ``norm_stats`` for the two datasets LADEV
uses (values: OpenVLA-7b's published Bridge and Fractal q01/q99 ranges are
not reproduced; these are round illustrative bounds).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import torch
from tokenizers import Tokenizer, models, normalizers, pre_tokenizers, processors
from transformers import PreTrainedTokenizerFast

from tests.adapters.tiny_openvla.configuration_tiny_vla import TinyVLAConfig
from tests.adapters.tiny_openvla.modeling_tiny_vla import TinyVLAForActionPrediction

HERE = Path(__file__).resolve().parent
REMOTE_CODE = ("configuration_tiny_vla.py", "modeling_tiny_vla.py", "processing_tiny_vla.py")
WORDS = ["in", ":", "what", "action", "should", "the", "robot", "take", "to", "?", "out", "pick", "up", "move", "near", "put", "on", "into", "the", "a", "coke", "can", "apple", "sponge", "carrot", "plate", "spoon", "towel", "eggplant", "basket", "yellow", "green", "block"]
NORM_STATS = {
    "bridge_orig": {"action": {
        "q01": [-0.03, -0.04, -0.03, -0.1, -0.1, -0.2, 0.0],
        "q99": [0.03, 0.04, 0.03, 0.1, 0.1, 0.2, 1.0],
        "mask": [True, True, True, True, True, True, False],
    }},
    "fractal20220817_data": {"action": {
        "q01": [-0.2, -0.2, -0.2, -0.4, -0.4, -0.4, 0.0],
        "q99": [0.2, 0.2, 0.2, 0.4, 0.4, 0.4, 1.0],
        "mask": [True, True, True, True, True, True, False],
    }},
}


def _tokenizer() -> PreTrainedTokenizerFast:
    vocab = {"<unk>": 0, "<s>": 1, "</s>": 2, "<pad>": 3}
    for word in WORDS:
        vocab.setdefault(word, len(vocab))
    tok = Tokenizer(models.WordLevel(vocab, unk_token="<unk>"))
    tok.normalizer = normalizers.Lowercase()
    tok.pre_tokenizer = pre_tokenizers.Sequence(
        [pre_tokenizers.Whitespace(), pre_tokenizers.Punctuation()]
    )
    tok.post_processor = processors.TemplateProcessing(single="<s> $A", special_tokens=[("<s>", 1)])
    return PreTrainedTokenizerFast(
        tokenizer_object=tok, unk_token="<unk>", bos_token="<s>", eos_token="</s>", pad_token="<pad>"
    )


def build_tiny_openvla(out: Path, seed: int = 0) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    torch.manual_seed(seed)
    config = TinyVLAConfig(
        text_config={
            "vocab_size": 512 + 64, "hidden_size": 32, "intermediate_size": 64,
            "num_hidden_layers": 2, "num_attention_heads": 4, "num_key_value_heads": 4,
            "max_position_embeddings": 256,
        },
        norm_stats=NORM_STATS,
        auto_map={
            "AutoConfig": "configuration_tiny_vla.TinyVLAConfig",
            "AutoModelForVision2Seq": "modeling_tiny_vla.TinyVLAForActionPrediction",
        },
    )
    TinyVLAForActionPrediction(config).save_pretrained(out)
    tokenizer = _tokenizer()
    tokenizer.save_pretrained(out)
    with open(out / "processor_config.json", "w", encoding="utf-8") as f:
        json.dump({"auto_map": {"AutoProcessor": "processing_tiny_vla.TinyVLAProcessor"}, "image_size": 224}, f)
    for name in REMOTE_CODE:
        shutil.copy(HERE / name, out / name)
    return out
