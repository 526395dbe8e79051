"""A temporary copy of this checkout to run stages, ``dvc repro`` and sweeps in.

Tests that exercise the pipeline the way a user does need a repository of
their own: the tracked and untracked-but-not-ignored files of this checkout
(no data, no reports), in a fresh git repository, run with this interpreter's
``python`` and ``dvc`` first on PATH.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

BIN = Path(sys.executable).parent
GIT = ["git", "-c", "user.email=tests@ladev.invalid", "-c", "user.name=ladev tests"]


def stage_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"  # `python` in dvc.yaml is this interpreter
    env.pop("PYTHONPATH", None)  # the stage scripts put their own checkout first
    env.update({"HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1", "LP_NUM_THREADS": "1"})
    return env


def copy_repo(repo_root: Path, dest: Path, commit: bool = False) -> Path:
    listed = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
        cwd=repo_root, check=True, capture_output=True, text=True,
    ).stdout.split("\0")
    for rel in filter(None, listed):
        src = repo_root / rel
        if src.is_file() and not rel.startswith(("data/", "reports/")):
            (dest / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / rel)
    (dest / "data").mkdir(parents=True, exist_ok=True)
    subprocess.run(["git", "init", "-q"], cwd=dest, check=True)
    if commit:
        git_commit(dest, "copy of the checkout")
    return dest


def git_commit(repo: Path, message: str) -> None:
    subprocess.run([*GIT, "add", "-A"], cwd=repo, check=True)
    subprocess.run([*GIT, "commit", "-qm", message], cwd=repo, check=True)


def run(args: list[str], cwd: Path, timeout: float = 900) -> str:
    """Run a command in the copy; fail the test with its output's tail if it fails."""
    proc = subprocess.run(args, cwd=cwd, env=stage_env(), capture_output=True, text=True, timeout=timeout)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out[-4000:]
    return out
