"""A clean clone reproduces the committed ``dvc.lock``: ``dvc repro`` of the committed study
(``params.yaml``) in a fresh copy of the checkout gives, output for output, the hashes the
lock pins, except those of outputs that measure time or are caches with creation times:

- ``paths.timings_dir`` (episode timings and the host: different on every run);
- ``paths.llm_cache_dir`` and ``paths.episode_store_dir`` (SQLite stores that record when
  each item was made).

The committed lock must come from the committed code: after changing anything a stage
depends on, regenerate it with ``make run`` (or ``dvc repro`` with the Makefile's
environment) and commit it. The test names the outputs that differ.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.repo_copy import BIN, copy_repo, run

pytestmark = [pytest.mark.slow, pytest.mark.sim]
ROOT = Path(__file__).resolve().parents[2]


def outs(lock: dict[str, Any]) -> dict[str, str]:
    """Every stage output's path -> md5 in a lock file."""
    return {o["path"]: o["md5"] for body in lock["stages"].values() for o in body.get("outs", [])}


def deps(lock: dict[str, Any]) -> dict[tuple[str, str], str]:
    """(stage, dependency path) -> md5: the code and data each stage ran on."""
    return {(name, d["path"]): d["md5"] for name, body in lock["stages"].items() for d in body.get("deps", [])}


def excluded_prefixes(params: dict[str, Any]) -> tuple[str, ...]:
    paths = params["paths"]
    return tuple(str(paths[k]).rstrip("/") for k in ("timings_dir", "llm_cache_dir", "episode_store_dir"))


def is_excluded(path: str, prefixes: tuple[str, ...]) -> bool:
    return any(path == p or path.startswith(p + "/") for p in prefixes)


def makefile_assets(env: dict[str, str]) -> None:
    """The Makefile's choice: the asset pack beside the checkout, when the user chose none
    (the committed lock is made by ``make run``)."""
    if "MS_ASSET_DIR" in os.environ:
        return
    pack = ROOT.parent / "shared" / "assets"
    if (pack / "data").is_dir():
        env["MS_ASSET_DIR"] = str(pack.resolve())


def test_a_clean_clone_reproduces_every_outcome_hash_of_the_committed_lock(tmp_path: Path, monkeypatch):
    committed = yaml.safe_load((ROOT / "dvc.lock").read_text())
    params = yaml.safe_load((ROOT / "params.yaml").read_text())
    prefixes = excluded_prefixes(params)
    env: dict[str, str] = {}
    makefile_assets(env)
    for key, value in env.items():
        monkeypatch.setenv(key, value)

    # Beside the copy, what lies beside the checkout (the published figures, the asset pack)
    shared = ROOT.parent / "shared"
    if shared.is_dir():
        (tmp_path / "shared").symlink_to(shared, target_is_directory=True)
    repo = copy_repo(ROOT, tmp_path / "repo", commit=True)
    run([str(BIN / "dvc"), "repro"], repo, timeout=1800)
    fresh = yaml.safe_load((repo / "dvc.lock").read_text())

    produced = list(outs(committed))

    def made_by_a_stage(path: str) -> bool:  # compared below, as outputs
        return any(o == path or o.startswith(path + "/") or path.startswith(o + "/") for o in produced)

    stale = {
        k: v for k, v in deps(committed).items() if not made_by_a_stage(k[1]) and deps(fresh).get(k) != v
    }
    assert not stale, (
        f"the committed dvc.lock was made from other code or data ({sorted(stale)[:5]}...): "
        "run `make run` and commit dvc.lock"
    )
    want = {p: h for p, h in outs(committed).items() if not is_excluded(p, prefixes)}
    got = {p: h for p, h in outs(fresh).items() if not is_excluded(p, prefixes)}
    assert want and set(want) == set(got)
    assert any(p.startswith(str(params["paths"]["episodes_dir"])) for p in want)  # outcomes are compared
    differ = sorted(p for p in want if got[p] != want[p])
    assert not differ, f"outputs not reproduced by a clean clone: {differ}"
    # and the excluded ones are exactly the timing and cache outputs
    assert all(is_excluded(p, prefixes) for p in set(outs(fresh)) - set(got))
