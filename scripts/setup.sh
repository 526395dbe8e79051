#!/usr/bin/env bash
# Set up LADEV on this machine: a virtual environment with the pinned Python
# stack, then a Vulkan device SAPIEN can render with. Idempotent: a second run
# with nothing changed takes a few seconds.
#
#   scripts/setup.sh            core install (+ dev tools)
#   LADEV_EXTRAS=dev scripts/setup.sh          (default dev,ray)
#   LADEV_VENV=/path/to/venv scripts/setup.sh
set -euo pipefail

cd "$(dirname "$0")/.."
VENV="${LADEV_VENV:-.venv}"
EXTRAS="${LADEV_EXTRAS:-dev,ray}"
PYTHON="${LADEV_PYTHON:-python3}"
# The CPU build of torch 2.13.0 is what the project is tested with. On a Linux
# machine with an NVIDIA GPU, set TORCH_SPEC to the build you want.
TORCH_SPEC="${TORCH_SPEC:-torch==2.13.0}"

log() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

if [ ! -x "$VENV/bin/python" ]; then
    log "creating virtual environment $VENV ($($PYTHON --version))"
    "$PYTHON" -m venv "$VENV"
fi
PY="$VENV/bin/python"

# Reinstall only when what decides the install changed.
stamp="$VENV/.ladev-install-stamp"
want="$(cat pyproject.toml scripts/setup.sh | sha256sum | cut -d' ' -f1) extras=$EXTRAS torch=$TORCH_SPEC"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
    export PIP_DISABLE_PIP_VERSION_CHECK=1
    # torch first: a package that depends on it must find it installed, or pip
    # resolves the newest CUDA build (several GB).
    if ! "$PY" -c "import torch" 2>/dev/null; then
        log "installing $TORCH_SPEC"
        "$PY" -m pip install -q "$TORCH_SPEC"
    fi
    log "installing ladev[$EXTRAS] and its pinned dependencies"
    "$PY" -m pip install -q -e ".[$EXTRAS]"
    echo "$want" > "$stamp"
else
    log "Python environment up to date ($VENV)"
fi

bash scripts/setup_vulkan.sh "$PY"
