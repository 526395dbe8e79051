"""Episode ids are content addresses: what decides an outcome changes the id, nothing else does."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from ladev_lib import fingerprint as fingerprint_module
from ladev_lib.rollout.identity import code_fingerprint, episode_id, module_closure
from ladev_lib.scenes.sampling import sample_scene


@pytest.fixture(scope="module")
def spec(catalog):
    return sample_scene("put_on", 2, "simpler", np.random.default_rng(3), catalog, seed=3, scene_id="s")


def ids(spec, **over):
    args = dict(
        spec=spec, instruction="put the carrot on the plate", policy_name="grounded",
        policy_config={"max_attempts": 3}, seed=3, sim_config={"image_size": [256, 256]},
        robot_config={"name": "panda"}, code="abc",
    )
    args.update(over)
    return episode_id(**args)


def test_same_content_same_id(spec):
    assert ids(spec) == ids(spec)
    assert len(ids(spec)) == 24


@pytest.mark.parametrize(
    "change",
    [
        {"seed": 4},
        {"instruction": "place the carrot onto the plate"},
        {"policy_name": "oracle"},
        {"policy_config": {"max_attempts": 1}},
        {"sim_config": {"image_size": [128, 128]}},
        {"robot_config": {"name": "widowx"}},
        {"code": "abd"},
    ],
    ids=lambda c: next(iter(c)),
)
def test_each_input_changes_the_id(spec, change):
    assert ids(spec, **change) != ids(spec)


def test_a_moved_object_changes_the_id(spec):
    moved = spec.model_copy(update={"objects": (spec.objects[0].model_copy(update={"x": 0.01}), *spec.objects[1:])})
    assert ids(moved) != ids(spec)


def test_mesh_availability_changes_the_id(spec, monkeypatch, tmp_path):
    monkeypatch.delenv("MS_ASSET_DIR", raising=False)
    without = ids(spec)
    src = spec.source
    mesh_dir = tmp_path / "data/tasks/bridge_v2_real2sim_dataset/custom/models"
    from ladev_lib.catalog import load_catalog

    model = load_catalog().get(src.id).mesh
    if model is None:
        pytest.skip("the sampled source has no mesh in the catalog")
    (mesh_dir / model.model).mkdir(parents=True)
    (mesh_dir / model.model / "collision.obj").write_text("")
    monkeypatch.setenv("MS_ASSET_DIR", str(tmp_path))
    assert ids(spec) != without


def test_closure_follows_imports_not_the_whole_package():
    grounded = {p.name for p in module_closure(["ladev_lib.policies.grounded"])}
    baselines = {p.name for p in module_closure(["ladev_lib.policies.baselines"])}
    assert {"grounded.py", "skills.py", "embeddings.py", "feasibility.py"} <= grounded
    assert "skills.py" not in baselines and "grounded.py" not in baselines
    assert code_fingerprint("ladev_lib.policies.grounded") != code_fingerprint("ladev_lib.policies.baselines")


def _copy_package(tmp_path: Path) -> Path:
    root = tmp_path / "ladev_lib"
    shutil.copytree(fingerprint_module.PACKAGE_ROOT, root, ignore=shutil.ignore_patterns("__pycache__"))
    return root


def test_fingerprint_changes_with_the_code_an_outcome_depends_on(tmp_path, monkeypatch):
    root = _copy_package(tmp_path)
    monkeypatch.setattr(fingerprint_module, "PACKAGE_ROOT", root)
    monkeypatch.setattr(fingerprint_module, "REPO_ROOT", tmp_path)

    def fingerprint() -> str:
        code_fingerprint.cache_clear()
        return code_fingerprint("ladev_lib.policies.baselines")

    before = fingerprint()
    # A module no baseline episode depends on: same fingerprint.
    (root / "policies/grounded.py").write_text((root / "policies/grounded.py").read_text() + "\n# edit\n")
    assert fingerprint() == before
    # The simulator, the episode loop, the policy's module, the catalog: new fingerprint.
    for rel in ("sim/tasks.py", "rollout/episode.py", "policies/baselines.py", "catalog/objects.yaml"):
        path = root / rel
        original = path.read_text()
        path.write_text(original + "\n# edit\n")
        assert fingerprint() != before, rel
        path.write_text(original)
        assert fingerprint() == before
    code_fingerprint.cache_clear()
