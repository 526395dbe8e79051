"""``ladev doctor``: what a user runs first when something fails."""

from __future__ import annotations

import importlib
import importlib.metadata
import os
import sys
from pathlib import Path

import click

from ladev_lib.assets import summarize_assets
from ladev_lib.sim.render_probe import probe_rendering

EXTRAS = {
    "ray": ["ray"],
    "rt1": ["tensorflow", "tf_agents"],
    "octo": ["jax", "flax", "octo.model.octo_model"],  # PyPI's "octo" is another package
    "openvla": ["transformers", "timm"],
    "lerobot": ["lerobot.policies.factory"],
}


# The VLA families' own environments (make adapter-env-<family>), and the
# distribution that shows each one is complete.
ADAPTER_ENVS = {
    "rt1": "tf_agents",
    "octo": "flax",
    "openvla": "transformers",
    "lerobot": "lerobot",
}


def adapter_env_status(root: Path, family: str) -> tuple[bool, str]:
    """(usable, detail) of ``root/.venv-<family>``, read from disk without starting it."""
    venv = root / f".venv-{family}"
    if not (venv / "bin" / "python").exists():
        return False, f"{venv} not found (make adapter-env-{family})"
    dist = ADAPTER_ENVS[family]
    found = sorted(venv.glob(f"lib/python*/site-packages/{dist}-*.dist-info"))
    if not found:
        return False, f"{venv} exists but has no {dist} (make adapter-env-{family} to finish it)"
    version = found[-1].name.removeprefix(f"{dist}-").removesuffix(".dist-info")
    ready = (venv / ".ladev-adapter-stamp").exists()
    return True, f"{venv} ({dist} {version}){'' if ready else ', set-up not finished'}"


def _version(dist: str) -> str:
    try:
        return importlib.metadata.version(dist)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


def _importable(module: str) -> bool:
    try:
        importlib.import_module(module)
        return True
    except Exception:  # noqa: BLE001 - any import failure means "not usable"
        return False


@click.command()
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(config_dir: str | None) -> None:
    """Check rendering, assets, optional extras and the LLM backend."""
    ok = True

    def line(status: str, what: str, detail: str = "") -> None:
        color = {"ok": "green", "warn": "yellow", "FAIL": "red", "info": "blue"}[status]
        click.echo(f"[{click.style(status, fg=color):>4}] {what}" + (f": {detail}" if detail else ""))

    line("info", "python", f"{sys.version.split()[0]} at {sys.executable}")
    for dist in ("ladev", "sapien", "mani-skill", "torch", "numpy", "mplib"):
        line("info", dist, _version(dist))

    probe = probe_rendering()
    if probe.ok:
        line("ok", "rendering (Vulkan)", f"device {probe.device}")
    else:
        ok = False
        line("FAIL", "rendering (Vulkan)", f"{probe.error}; run: make setup (installs Mesa lavapipe)")

    assets = summarize_assets()
    if assets.directory is None:
        raw = os.environ.get("MS_ASSET_DIR")
        detail = f"MS_ASSET_DIR={raw} does not exist" if raw else "MS_ASSET_DIR not set"
        line("warn", "assets", f"{detail}; objects are procedural stand-ins, robot panda only")
    else:
        sets = ", ".join(f"{s} {have}/{total} meshes" for s, (have, total) in assets.meshes_by_set.items())
        robots = ", ".join(f"{r} {'yes' if v else 'no'}" for r, v in assets.robots.items())
        line("ok", "assets", f"{assets.directory}: {sets}; robots: {robots}; {assets.overlays} backgrounds")

    for extra, modules in EXTRAS.items():
        present = [m for m in modules if _importable(m)]
        status = "ok" if len(present) == len(modules) else "info"
        detail = "importable" if status == "ok" else f"not installed (pip install 'ladev[{extra}]')"
        line(status, f"extra '{extra}'", detail)

    # Served from their own environments: `<env>/bin/ladev serve-policy <config>`.
    for family in ADAPTER_ENVS:
        usable, detail = adapter_env_status(Path.cwd(), family)
        line("ok" if usable else "info", f"{family} environment", detail)

    try:
        from ladev_lib.config import compose_config

        cfg = compose_config([], config_dir)
        llm = cfg.get("llm", {})
        backend = llm.get("backend", "?")
        if backend == "offline":
            line("ok", "LLM backend", "offline (deterministic rules and templates; no network)")
        else:
            key_env = llm.get("api_key_env") or "OPENAI_API_KEY"
            has_key = bool(os.environ.get(key_env))
            line(
                "ok" if has_key else "warn",
                "LLM backend",
                f"{backend} model={llm.get('model')} base_url={llm.get('base_url') or 'default'} "
                f"key ${key_env} {'set' if has_key else 'NOT set'}",
            )
    except Exception as exc:  # noqa: BLE001 - report, do not crash the doctor
        line("warn", "configuration", str(exc))

    if not ok:
        raise SystemExit(1)
