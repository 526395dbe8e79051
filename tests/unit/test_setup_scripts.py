"""The Vulkan set-up reads the machine's own Debian mirror (never a hard-coded host)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "setup_vulkan.sh"


def entry(apt_dir: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["bash", str(SCRIPT), "--backports-entry"],
        env={"LADEV_APT_DIR": str(apt_dir), "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
    )


@pytest.fixture
def apt(tmp_path: Path) -> Path:
    (tmp_path / "sources.list.d").mkdir()
    return tmp_path


def test_deb822_mirror_and_keyring_are_reused(apt: Path):
    (apt / "sources.list.d" / "debian.sources").write_text(
        "Types: deb\nURIs: http://mirror.example.org/debian\nSuites: bookworm bookworm-updates\n"
        "Components: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n\n"
        "Types: deb\nURIs: http://security.example.org/debian-security\nSuites: bookworm-security\n"
        "Components: main\n"
    )
    out = entry(apt)
    assert out.returncode == 0, out.stderr
    assert "URIs: http://mirror.example.org/debian\n" in out.stdout
    assert "Suites: bookworm-backports\n" in out.stdout
    assert "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" in out.stdout
    assert "security" not in out.stdout


def test_one_line_sources_list_is_understood(apt: Path):
    (apt / "sources.list").write_text(
        "# comment\ndeb [arch=amd64] http://ftp.example.net/debian bookworm main contrib\n"
        "deb http://security.debian.org/debian-security bookworm-security main\n"
    )
    out = entry(apt)
    assert out.returncode == 0, out.stderr
    assert "URIs: http://ftp.example.net/debian\n" in out.stdout
    assert "Signed-By" not in out.stdout


def test_no_bookworm_mirror_is_an_error(apt: Path):
    (apt / "sources.list").write_text("deb http://archive.ubuntu.com/ubuntu noble main\n")
    assert entry(apt).returncode != 0
