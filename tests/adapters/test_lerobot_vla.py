"""SmolVLA, pi0 and pi0.5 through the LeRobot adapter, as far as offline allows (make test-lerobot).

SmolVLA: built whole, from LeRobot's SmolVLAConfig / SmolVLAPolicy, on a tiny
local stand-in for the SmolVLM2 backbone's hub files (config, tokenizer,
processor): saved, loaded through the adapter's real path, fed a rendered
frame and the instruction (tokenised by the checkpoint's own preprocessor).
Without those files the adapter says which hub name is missing.

pi0 / pi0.5: their smallest configurations are PaliGemma 2B plus a 300M action
expert (no tiny variant in LeRobot's config), and their model refuses PyPI's
transformers (it needs LeRobot's patched one). What is tested is the
adapter's clear refusal, naming what to install, from a real config.json.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("lerobot", reason="the LeRobot environment: make test-lerobot")

from lerobot.configs.types import FeatureType  # noqa: E402

from ladev_lib.errors import ConfigError  # noqa: E402
from ladev_lib.policies import make_policy  # noqa: E402
from ladev_lib.policies.base import Observation  # noqa: E402
from tests.adapters.conftest import load_frame  # noqa: E402
from tests.adapters.tiny_lerobot import (  # noqa: E402
    ACTION_MEAN,
    TINY_VOCAB,
    build_tiny_smolvla,
    build_tiny_smolvlm,
    tiny_features,
)

PANDA_PROPRIO = np.r_[np.linspace(-1, 1, 7), [0.04, 0.04], [0.3, 0.0, 0.2, 1.0, 0.0, 0.0, 0.0]].astype(np.float32)


@pytest.fixture(scope="module")
def smolvla(tmp_path_factory: pytest.TempPathFactory) -> str:
    root = tmp_path_factory.mktemp("smolvla")
    backbone = build_tiny_smolvlm(root / "tiny-smolvlm")
    return str(build_tiny_smolvla(root / "tiny-smolvla", backbone))


def test_smolvla_end_to_end_on_a_tiny_backbone(smolvla: str) -> None:
    policy = make_policy("lerobot", checkpoint=smolvla, robot="panda", device="cpu", policy_type="smolvla",
                         state_layout="libero", action_layout="ee_delta_axis_angle",
                         gripper_convention="open_is_1")
    assert policy.cfg.type == "smolvla" and policy.info.control_mode == "pd_ee_delta_pose"
    # Two cameras declared (LIBERO's agent and wrist views); LADEV's camera feeds the
    # first, SmolVLA leaves the missing one out.
    assert list(policy.image_features) == ["observation.images.image"]
    policy.reset("pick up the red can")
    obs = Observation(image=load_frame("widowx"), proprio=PANDA_PROPRIO)
    processed = policy.preprocessor(policy.batch(obs))
    tokens = processed["observation.language.tokens"][0].tolist()
    mask = processed["observation.language.attention_mask"][0].tolist()
    words = [TINY_VOCAB[t] for t, m in zip(tokens, mask, strict=True) if m]
    assert "pick" in words and "red" in words and "can" in words  # the instruction, tokenised
    calls = []
    original = policy.model._get_action_chunk  # what SmolVLA's select_action calls on an empty queue
    policy.model._get_action_chunk = lambda *a, **kw: calls.append(1) or original(*a, **kw)
    actions = [policy.step(obs).action for _ in range(5)]
    assert len(calls) == 2  # a chunk of 4, then the next
    for action in actions:
        assert action.shape == (7,) and np.all(np.isfinite(action))
        assert action[6] in (-1.0, 1.0)
        # mean + 0.05 * (flow output): near the statistics' mean
        assert np.all(np.abs(action[:3] - ACTION_MEAN[:3]) < 0.05 * 8)


def _config_only(tmp_path: Path, cfg) -> str:
    out = tmp_path / cfg.type
    cfg.save_pretrained(out)  # config.json, as in a downloaded checkpoint
    return str(out)


def test_smolvla_without_its_backbone_files_names_them(tmp_path: Path, monkeypatch) -> None:
    from lerobot.policies.smolvla.configuration_smolvla import SmolVLAConfig

    monkeypatch.setenv("HF_HUB_OFFLINE", "1")
    inputs, outputs = tiny_features(8, (64, 64))
    ckpt = _config_only(tmp_path, SmolVLAConfig(input_features=inputs, output_features=outputs, device="cpu"))
    with pytest.raises(ConfigError, match=r"HuggingFaceTB/SmolVLM2-500M-Video-Instruct .*vlm_model_name"):
        make_policy("lerobot", checkpoint=ckpt, robot="panda", device="cpu")


@pytest.mark.parametrize("kind", ["pi0", "pi05"])
def test_pi0_family_names_what_to_install(kind: str, tmp_path: Path) -> None:
    from lerobot.policies.pi0.configuration_pi0 import PI0Config
    from lerobot.policies.pi05.configuration_pi05 import PI05Config

    if importlib.util.find_spec("transformers.models.siglip.check") is not None:
        pytest.skip("LeRobot's patched transformers is installed here")
    inputs, outputs = tiny_features(8, (224, 224), ("image", "image2"))
    cfg = {"pi0": PI0Config, "pi05": PI05Config}[kind](input_features=inputs, output_features=outputs, device="cpu")
    assert cfg.image_features and cfg.input_features["observation.state"].type is FeatureType.STATE
    ckpt = _config_only(tmp_path, cfg)
    with pytest.raises(ConfigError, match=rf"{kind} needs its patched transformers .*\[pi\]"):
        make_policy("lerobot", checkpoint=ckpt, robot="panda", device="cpu", policy_type=kind)


def test_sampling_noise_is_seeded_per_episode(smolvla: str) -> None:
    from ladev_lib.policies.base import EpisodeContext

    policy = make_policy("lerobot", checkpoint=smolvla, robot="panda", device="cpu", state_layout="libero")
    obs = Observation(image=load_frame("widowx"), proprio=PANDA_PROPRIO)

    def first_action(seed: int | None, instruction: str = "pick up the red can") -> np.ndarray:
        if seed is not None:
            bounds = np.ones(7)
            policy.begin_episode(EpisodeContext(seed=seed, robot="panda", action_low=-bounds, action_high=bounds))
        policy.reset(instruction)
        policy.step(obs)
        return policy.last_raw_action.copy()

    # In process: the episode seed decides the flow-matching noise.
    np.testing.assert_array_equal(first_action(1), first_action(1))
    assert not np.allclose(first_action(1), first_action(2))
    # Served (no seed on the wire): the config's seed and the instruction decide it.
    np.testing.assert_array_equal(first_action(None), first_action(None))
    assert not np.allclose(first_action(None), first_action(None, "put the mug in the bowl"))


REPO = Path(__file__).resolve().parents[2]


def test_the_smolvla_config_entry_drives_the_panda(smolvla: str) -> None:
    """conf/policy/smolvla_libero.yaml as `ladev serve-policy` composes it, on the tiny checkpoint."""
    from ladev_lib.policies.configured import make_configured_policy

    policy = make_configured_policy("smolvla_libero", REPO / "conf", {"checkpoint": smolvla, "device": "cpu"})
    assert policy.info.robots == ("panda",) and policy.info.control_freq_hz == 20.0
    assert policy.info.image_size == (256, 256) and policy.info.control_mode == "pd_ee_delta_pose"
    policy.reset("put the mug in the bowl")
    step = policy.step(Observation(image=np.zeros((256, 256, 3), np.uint8), proprio=PANDA_PROPRIO))
    raw = policy.last_raw_action
    # LIBERO's conventions: translation x 0.5, axis-angle x 5, gripper +1 close -> -1 close.
    np.testing.assert_allclose(step.action[:3], raw[:3] * 0.5, rtol=1e-9)
    np.testing.assert_allclose(step.action[3:6], raw[3:6] * 5.0, rtol=1e-9)
    assert step.action[6] == (1.0 if (1.0 - raw[6]) / 2.0 > 0.5 else -1.0)


@pytest.mark.parametrize("entry", ["pi0_libero", "pi05_libero"])
def test_the_pi0_config_entries_refuse_clearly(entry: str, tmp_path: Path) -> None:
    from lerobot.policies.pi0.configuration_pi0 import PI0Config
    from lerobot.policies.pi05.configuration_pi05 import PI05Config

    from ladev_lib.policies.configured import make_configured_policy

    if importlib.util.find_spec("transformers.models.siglip.check") is not None:
        pytest.skip("LeRobot's patched transformers is installed here")
    inputs, outputs = tiny_features(8, (224, 224), ("image", "image2"))
    cls = PI0Config if entry == "pi0_libero" else PI05Config
    ckpt = _config_only(tmp_path, cls(input_features=inputs, output_features=outputs, device="cpu"))
    with pytest.raises(ConfigError, match="patched transformers"):
        make_configured_policy(entry, REPO / "conf", {"checkpoint": ckpt, "device": "cpu"})


@pytest.mark.manual
def test_gpu_steps(smolvla: str, tmp_path: Path) -> None:
    """The tiny ACT and SmolVLA on a GPU through the same adapter code (LADEV_MANUAL=1).

    .venv-lerobot's torch is PyPI's CUDA build: on a GPU machine nothing else is needed.
    """
    from tests.adapters.tiny_lerobot import build_tiny_act

    if not torch.cuda.is_available():
        pytest.skip("no CUDA device")
    act = str(build_tiny_act(tmp_path / "act", state_dim=8))
    for ckpt in (act, smolvla):
        policy = make_policy("lerobot", checkpoint=ckpt, robot="panda", state_layout="libero")  # device: auto
        assert policy.device == "cuda" and next(policy.model.parameters()).device.type == "cuda"
        policy.reset("pick up the red can")
        obs = Observation(image=load_frame("widowx"), proprio=PANDA_PROPRIO)
        actions = [policy.step(obs).action for _ in range(10)]
        assert all(a.shape == (7,) and np.all(np.isfinite(a)) for a in actions)


@pytest.mark.manual
def test_real_checkpoint() -> None:
    """A real LeRobot checkpoint through a conf/policy entry (LADEV_MANUAL=1):
    LADEV_LEROBOT_CHECKPOINT=<dir or hub id>, LADEV_LEROBOT_ENTRY (default smolvla_libero)."""
    import os

    from ladev_lib.policies.configured import make_configured_policy

    checkpoint = os.environ.get("LADEV_LEROBOT_CHECKPOINT")
    if not checkpoint:
        pytest.skip("set LADEV_LEROBOT_CHECKPOINT")
    entry = os.environ.get("LADEV_LEROBOT_ENTRY", "smolvla_libero")
    policy = make_configured_policy(entry, REPO / "conf", {"checkpoint": checkpoint})
    policy.reset("pick up the red can")
    obs = Observation(image=np.zeros((256, 256, 3), np.uint8), proprio=PANDA_PROPRIO)
    actions = [policy.step(obs).action for _ in range(10)]
    assert all(a.shape == (7,) and np.all(np.isfinite(a)) for a in actions)


def test_local_copies_of_the_backbone_replace_the_names_saved(tmp_path: Path) -> None:
    """What a user without a hub does: point vlm_model_name and the tokenizer at local copies."""
    import shutil

    backbone = build_tiny_smolvlm(tmp_path / "downloaded-smolvlm")
    ckpt = str(build_tiny_smolvla(tmp_path / "smolvla", backbone))
    moved = tmp_path / "models" / "SmolVLM2"
    shutil.move(str(backbone), moved)  # the name saved in the checkpoint no longer resolves
    with pytest.raises(ConfigError, match=r"downloaded-smolvlm .*vlm_model_name"):
        make_policy("lerobot", checkpoint=ckpt, robot="panda", device="cpu", state_layout="libero")
    policy = make_policy("lerobot", checkpoint=ckpt, robot="panda", device="cpu", state_layout="libero",
                         config_overrides={"vlm_model_name": str(moved)}, tokenizer=str(moved))
    policy.reset("pick up the red can")
    step = policy.step(Observation(image=load_frame("widowx"), proprio=PANDA_PROPRIO))
    assert step.action.shape == (7,) and np.all(np.isfinite(step.action))
    with pytest.raises(ConfigError, match="no field 'vlm_name'"):
        make_policy("lerobot", checkpoint=ckpt, robot="panda", device="cpu", config_overrides={"vlm_name": "x"})
