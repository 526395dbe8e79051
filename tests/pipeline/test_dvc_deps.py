"""dvc.yaml's hand-written deps are checked against the import closure of each stage script.

The closure is the one ``ladev_lib.fingerprint`` computes for episode ids and LLM
cache keys: a stage whose code or data changes must re-run under ``dvc repro``.
"""

from __future__ import annotations

from pathlib import Path

from ladev_lib.fingerprint import REPO_ROOT, dvc_missing_deps


def test_dvc_deps_cover_every_stage_closure() -> None:
    missing = dvc_missing_deps()
    assert set(missing) == {"generate", "compile", "paraphrase", "rollout", "aggregate"}
    assert not any(missing.values()), f"run `python scripts/dvc_deps.py --fix`; missing: {missing}"


def test_every_dep_dvc_yaml_names_exists() -> None:
    import yaml

    stages = yaml.safe_load((REPO_ROOT / "dvc.yaml").read_text())["stages"]
    for name, body in stages.items():
        body = body["do"] if "foreach" in body else body
        for dep in body["deps"]:
            if "${" not in dep:
                assert (REPO_ROOT / dep).exists(), f"stage {name}: dep {dep!r} does not exist"


def test_the_check_sees_a_missing_dep(tmp_path: Path) -> None:
    # A copy of dvc.yaml without the report package: the aggregate stage misses it.
    text = (REPO_ROOT / "dvc.yaml").read_text()
    assert "      - ladev_lib/report\n" in text
    (tmp_path / "stages").symlink_to(REPO_ROOT / "stages")
    (tmp_path / "dvc.yaml").write_text(text.replace("      - ladev_lib/report\n", ""))
    missing = dvc_missing_deps(tmp_path / "dvc.yaml")
    assert "ladev_lib/report/build.py" in missing["aggregate"]
    assert "ladev_lib/report/templates/report.html.jinja" in missing["aggregate"]
    assert not missing["compile"]
