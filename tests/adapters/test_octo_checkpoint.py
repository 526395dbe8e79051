"""Octo checkpoint-config helpers (pure: run in the core install and the octo environment)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.octo import checkpoint_view, override_text_encoder

OCTO_CONFIG = {
    "model": {
        "task_tokenizers": {
            "language": {"kwargs": {"encoder": "t5-base", "finetune_encoder": False}, "module": "x"}
        },
        "heads": {"action": {"kwargs": {"action_horizon": 4}}},
    },
    "text_processor": {"kwargs": {"tokenizer_name": "t5-base", "encode_with_model": False}, "module": "y"},
}


def test_override_text_encoder_rewrites_every_hub_name() -> None:
    patched, n = override_text_encoder(OCTO_CONFIG, "/models/t5-base")
    assert n == 2
    assert patched["model"]["task_tokenizers"]["language"]["kwargs"]["encoder"] == "/models/t5-base"
    assert patched["text_processor"]["kwargs"]["tokenizer_name"] == "/models/t5-base"
    assert OCTO_CONFIG["text_processor"]["kwargs"]["tokenizer_name"] == "t5-base"  # a copy


def test_checkpoint_view_links_everything_but_the_config(tmp_path: Path) -> None:
    ckpt = tmp_path / "octo-small"
    (ckpt / "300000" / "default").mkdir(parents=True)
    (ckpt / "dataset_statistics.json").write_text("{}")
    (ckpt / "config.json").write_text(json.dumps(OCTO_CONFIG))
    view = Path(checkpoint_view(str(ckpt), str(tmp_path / "t5"), str(tmp_path / "work")))
    assert (view / "300000").is_symlink() and (view / "dataset_statistics.json").is_symlink()
    config = json.loads((view / "config.json").read_text())
    assert config["text_processor"]["kwargs"]["tokenizer_name"] == str((tmp_path / "t5").resolve())
    (ckpt / "config.json").write_text(json.dumps({"model": {}}))
    with pytest.raises(ConfigError, match="names no text encoder"):
        checkpoint_view(str(ckpt), str(tmp_path / "t5"), str(tmp_path / "work2"))
