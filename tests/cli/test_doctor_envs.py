"""``ladev doctor``'s report of the VLA families' own environments (read from disk)."""

from __future__ import annotations

from pathlib import Path

from ladev_lib.cli.doctor import adapter_env_status


def _venv(root: Path, family: str, dist: str | None, stamp: bool = True) -> None:
    venv = root / f".venv-{family}"
    (venv / "bin").mkdir(parents=True)
    (venv / "bin" / "python").write_text("")
    if dist:
        (venv / "lib/python3.11/site-packages" / f"{dist}.dist-info").mkdir(parents=True)
    if stamp:
        (venv / ".ladev-adapter-stamp").write_text("x")


def test_missing_environment_says_how_to_build_it(tmp_path: Path) -> None:
    usable, detail = adapter_env_status(tmp_path, "lerobot")
    assert not usable and "make adapter-env-lerobot" in detail


def test_complete_environment_reports_the_version(tmp_path: Path) -> None:
    _venv(tmp_path, "lerobot", "lerobot-0.4.4")
    usable, detail = adapter_env_status(tmp_path, "lerobot")
    assert usable and "lerobot 0.4.4" in detail and "not finished" not in detail


def test_half_built_environment_is_not_usable(tmp_path: Path) -> None:
    _venv(tmp_path, "lerobot", None, stamp=False)
    usable, detail = adapter_env_status(tmp_path, "lerobot")
    assert not usable and "has no lerobot" in detail
    _venv(tmp_path, "openvla", "transformers-4.40.1", stamp=False)
    usable, detail = adapter_env_status(tmp_path, "openvla")
    assert usable and "set-up not finished" in detail
