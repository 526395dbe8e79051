"""A temporary copy of the repository to run stages (and dvc) in."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent


def stage_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"  # `python` in dvc.yaml is this interpreter
    env.pop("PYTHONPATH", None)  # the stage scripts put their own checkout first
    env.update({"HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1", "LP_NUM_THREADS": "1", "PYTHONDONTWRITEBYTECODE": "0"})
    return env


@pytest.fixture
def repo_copy(repo_root: Path, tmp_path: Path) -> Path:
    """Tracked and untracked-but-not-ignored files of this checkout, in a fresh git repo."""
    listed = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
        cwd=repo_root, check=True, capture_output=True, text=True,
    ).stdout.split("\0")
    dest = tmp_path / "repo"
    for rel in filter(None, listed):
        src = repo_root / rel
        if src.is_file() and not rel.startswith(("data/", "reports/")):
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / rel)
    (dest / "data").mkdir(exist_ok=True)
    subprocess.run(["git", "init", "-q"], cwd=dest, check=True)
    return dest


def run(args: list[str], cwd: Path, timeout: float = 600) -> str:
    proc = subprocess.run(args, cwd=cwd, env=stage_env(), capture_output=True, text=True, timeout=timeout)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out[-4000:]
    return out
