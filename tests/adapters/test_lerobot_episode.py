"""One episode end to end: a LeRobot policy served from .venv-lerobot, rolled out by the core.

The LeRobot environment writes a tiny checkpoint (LeRobot's own classes and
save methods: ACT, and SmolVLA on a tiny local backbone) and serves it with
``ladev serve-policy`` (the registry name ``lerobot``, and the
``smolvla_libero`` config entry); the core
install's rollout stage (stages/rollout.py, the simulator, the ``remote``
policy) runs one Panda scene against that server and writes the judged
episode row to data/episodes/<label>.parquet.

Runs in the core environment. Without .venv-lerobot it is skipped (the core
suite does not build it); ``make test-lerobot`` builds it and sets
LADEV_REQUIRE_LEROBOT=1, which turns the skip into a failure.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from ladev_lib.catalog import load_catalog
from ladev_lib.scenes.spec import parse_scene_spec
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    EpisodeTimingRow,
    InstructionRow,
    read_table,
    write_table,
)

pytestmark = pytest.mark.sim
REPO = Path(__file__).resolve().parents[2]
LEROBOT_PYTHON = REPO / ".venv-lerobot" / "bin" / "python"
STEPS = 6


@pytest.fixture(scope="module")
def lerobot_python() -> Path:
    if not LEROBOT_PYTHON.exists():
        reason = f"{LEROBOT_PYTHON} does not exist (make adapter-env-lerobot builds it)"
        if os.environ.get("LADEV_REQUIRE_LEROBOT") == "1":
            pytest.fail(reason)
        pytest.skip(reason)
    return LEROBOT_PYTHON


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(REPO), "HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1"}


def _serve(python: Path, entry: str, overrides: dict[str, object]) -> tuple[subprocess.Popen[str], str]:
    embodiments = {"panda": {"image_size": [128, 128], "episode_steps": {"pick_up": STEPS}}}
    sets: list[str] = []
    for key, value in {**overrides, "robot": "panda", "device": "cpu", "embodiments": embodiments}.items():
        sets += ["--set", f"{key}={json.dumps(value)}"]
    proc = subprocess.Popen(
        [str(python), "-c", "from ladev_lib.cli import main; main()", "serve-policy", entry,
         "--port", "0", "--config-dir", str(REPO / "conf"), *sets],
        cwd=REPO, env=_env(), stderr=subprocess.PIPE, text=True,
    )
    assert proc.stderr is not None
    deadline = time.monotonic() + 180
    lines: list[str] = []
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        lines.append(line)
        if "serving " in line:
            return proc, line.split(" on ", 1)[1].split()[0]
        if not line and proc.poll() is not None:
            break
    proc.kill()
    raise AssertionError("serve-policy did not start:\n" + "".join(lines[-30:]))


# (tiny checkpoint, its state size, what `ladev serve-policy` serves, overrides):
# ACT by the registry name with the whole proprio (the Panda: 9 joints + TCP pose);
# SmolVLA by the conf/policy/smolvla_libero.yaml entry, with LIBERO's 8-value state.
SERVED = {
    "act": ("act", 16, "lerobot", {"state_layout": "proprio"}),
    "smolvla_libero": ("smolvla", 8, "smolvla_libero", {}),
}


@pytest.mark.parametrize("served", sorted(SERVED))
def test_core_rollout_against_a_served_lerobot_policy(served: str, lerobot_python: Path, tmp_path: Path) -> None:
    kind, state_dim, entry, overrides = SERVED[served]
    checkpoint = tmp_path / f"tiny-{kind}"
    built = subprocess.run(
        [str(lerobot_python), "-m", "tests.adapters.tiny_lerobot", kind, str(checkpoint),
         "--state-dim", str(state_dim), "--image", "64x64", "--std", "0.05"],
        cwd=REPO, env=_env(), capture_output=True, text=True, timeout=300,
    )
    assert built.returncode == 0, built.stderr
    assert (checkpoint / "config.json").exists() and (checkpoint / "policy_preprocessor.json").exists()

    spec = parse_scene_spec(
        {"scene_id": "mug", "robot": "panda",
         "objects": [{"name": "mug", "id": "coke_can", "x": 0.05, "y": -0.1, "role": "source"},
                     {"name": "apple", "id": "apple", "x": 0.05, "y": 0.1, "role": "distractor"}],
         "task": {"type": "pick_up", "source": "mug"}},
        catalog=load_catalog(),
    )
    data = tmp_path / "data"
    write_table([CompiledSceneRow(scene_id="mug", status="ok", spec_json=spec.to_json())],
                data / "compiled.parquet", CompiledSceneRow)
    write_table([InstructionRow(instruction_id="mug/basic", scene_id="mug", kind="basic",
                                text="lift the red can off the table", valid=True, selected=True)],
                data / "instructions.parquet", InstructionRow)

    proc, url = _serve(lerobot_python, entry, {**overrides, "checkpoint": str(checkpoint)})
    try:
        params = yaml.safe_load((REPO / "params.yaml").read_text())
        params["policy"] = {"lerobot_act": {"name": "remote", "url": url, "wait_for_server_s": 60}}
        params["executor"] = {"name": "serial"}
        params["rollout"]["video"] = "none"
        (tmp_path / "params.yaml").write_text(yaml.safe_dump(params))
        run = subprocess.run(
            [sys.executable, str(REPO / "stages/rollout.py"), "--policy", "lerobot_act", "--no-progress"],
            cwd=tmp_path, capture_output=True, text=True, timeout=900,
        )
        assert run.returncode == 0, run.stdout + run.stderr
    finally:
        proc.terminate()
        proc.wait(30)

    rows = read_table(data / "episodes/lerobot_act.parquet", EpisodeRow).to_dicts()
    assert len(rows) == 1, rows
    row = rows[0]
    # Judged, not an error: the policy's actions drove the whole episode.
    assert row["status"] in ("success", "failure"), row["error"]
    assert row["robot"] == "panda" and row["steps"] == STEPS
    assert row["instruction"] == "lift the red can off the table"
    assert "success" in json.loads(row["predicates_json"])
    timing = read_table(data / "timings/lerobot_act.parquet", EpisodeTimingRow).to_dicts()
    assert [t["episode_id"] for t in timing] == [row["episode_id"]] and timing[0]["policy_seconds"] > 0
