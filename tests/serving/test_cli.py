"""``ladev serve-policy`` as a user runs it (a subprocess), relaying to a scripted server."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

from click.testing import CliRunner

from ladev_lib.cli import cli
from ladev_lib.policies.remote import RemotePolicy
from tests.serving.test_server_client import _obs

REPO = Path(__file__).resolve().parents[2]


def test_help_lists_the_options() -> None:
    result = CliRunner().invoke(cli, ["serve-policy", "--help"])
    assert result.exit_code == 0
    for option in ("--port", "--host", "--api-key-env", "--set", "--max-connections"):
        assert option in result.output


def test_unknown_policy_is_a_clear_error() -> None:
    result = CliRunner().invoke(cli, ["serve-policy", "no_such_policy", "--config-dir", str(REPO / "conf")])
    assert result.exit_code != 0 and "unknown policy 'no_such_policy'" in str(result.exception)


def test_missing_api_key_variable_is_a_usage_error() -> None:
    result = CliRunner().invoke(cli, ["serve-policy", "remote", "--api-key-env", "LADEV_TEST_UNSET_KEY"])
    assert result.exit_code == 2 and "LADEV_TEST_UNSET_KEY" in result.output


def test_serve_policy_end_to_end(server_process, monkeypatch) -> None:
    """The CLI serves the `remote` policy (from conf/policy/remote.yaml) pointed at a scripted server."""
    upstream = server_process()
    env = {**os.environ, "PYTHONPATH": str(REPO), "LADEV_TEST_KEY": "k3y"}
    proc = subprocess.Popen(
        [sys.executable, "-c", "from ladev_lib.cli import main; main()", "serve-policy", "remote",
         "--port", "0", "--config-dir", str(REPO / "conf"), "--api-key-env", "LADEV_TEST_KEY",
         "--set", f"url={upstream.url}", "--set", "wait_for_server_s=5"],
        cwd=REPO, env=env, stderr=subprocess.PIPE, text=True,
    )
    try:
        url = None
        deadline = time.monotonic() + 60
        assert proc.stderr is not None
        while url is None and time.monotonic() < deadline:
            line = proc.stderr.readline()
            if "serving " in line:
                url = line.split(" on ", 1)[1].split()[0]
            assert line or proc.poll() is None, "serve-policy exited early"
        assert url is not None and url.startswith("ws://127.0.0.1:")
        with urllib.request.urlopen(url.replace("ws://", "http://") + "/healthz", timeout=5) as resp:
            assert resp.status == 200
        monkeypatch.setenv("LADEV_TEST_KEY", "k3y")
        with RemotePolicy(url=url, api_key_env="LADEV_TEST_KEY", wait_for_server_s=5) as policy:
            # The relay announces the upstream policy's info.
            assert policy.info.name == "scripted" and policy.info.robots == ("widowx",)
            policy.reset("put the spoon on the towel")
            steps = [policy.step(_obs()) for _ in range(3)]
        assert [s.action[0] for s in steps] == [0, 1, 2]
        assert steps[0].action[1] == len("put the spoon on the towel") and steps[2].terminate
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(15) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(10)
