#!/usr/bin/env bash
# Create (idempotently) the virtual environment one VLA family's adapter runs
# and is tested in: .venv-<family> with that family's pinned stack, ladev
# installed --no-deps on top, and the light dependencies ladev's own modules
# and tests need. The stacks of RT-1 (TensorFlow + tf-agents), Octo (JAX/Flax),
# OpenVLA (transformers 4.40 + timm 0.9) and LeRobot (torch < 2.11,
# transformers 4.57) conflict with each other and with the core install,
# hence one environment each.
#
#   scripts/setup_adapter_env.sh rt1|octo|openvla|lerobot
#   TF_SPEC / JAX_SPEC / TORCH_SPEC   the framework build (CPU by default; for
#                                     lerobot PyPI's torch 2.10, a CUDA build)
#   OCTO_SPEC                         where to install Octo's model code from
#                                     (a local checkout or a git URL); PyPI's
#                                     "octo" is an unrelated package
#   ADAPTER_VENV                      the environment's path
set -euo pipefail

cd "$(dirname "$0")/.."
FAMILY="${1:?usage: setup_adapter_env.sh rt1|octo|openvla|lerobot}"
PYTHON="${LADEV_PYTHON:-python3}"
VENV="${ADAPTER_VENV:-.venv-$FAMILY}"
case "$FAMILY" in
    rt1) FRAMEWORK="${TF_SPEC:-tensorflow-cpu==2.15.1}" ;;
    octo) FRAMEWORK="${JAX_SPEC:-jax[cpu]==0.4.20}" ;;
    # The CPU wheel the core install uses; on a GPU machine pick a CUDA build.
    openvla) FRAMEWORK="${TORCH_SPEC:-torch==2.13.0}" ;;
    # LeRobot 0.4.4 pins torch < 2.11: the newest release of that range (from
    # PyPI, a CUDA build on x86_64; the CPU wheel on this disk is too new).
    lerobot) FRAMEWORK="${TORCH_SPEC:-torch==2.10.0}" ;;
    *) echo "unknown adapter family '$FAMILY' (rt1, octo, openvla, lerobot)" >&2; exit 2 ;;
esac
REQ="mk/adapters/$FAMILY.txt"
NODEPS="mk/adapters/$FAMILY.nodeps.txt"
WRITER="mk/adapters/$FAMILY.writer.txt"
EXTRA_SRC=""
[ "$FAMILY" = octo ] && EXTRA_SRC="${OCTO_SPEC:-}"

log() { printf '\033[1m[adapter-env %s]\033[0m %s\n' "$FAMILY" "$*"; }

start=$(date +%s)
if [ ! -x "$VENV/bin/python" ]; then
    log "creating $VENV ($($PYTHON --version))"
    "$PYTHON" -m venv "$VENV"
fi
PY="$VENV/bin/python"
stamp="$VENV/.ladev-adapter-stamp"
inputs=(mk/adapters/base.txt "$REQ" scripts/setup_adapter_env.sh)
[ -f "$NODEPS" ] && inputs+=("$NODEPS")
[ -f "$WRITER" ] && inputs+=("$WRITER")
want="$(cat "${inputs[@]}" | sha256sum | cut -d' ' -f1) framework=$FRAMEWORK src=$EXTRA_SRC"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    log "up to date ($VENV)"
    exit 0
fi
export PIP_DISABLE_PIP_VERSION_CHECK=1
# The framework first: what depends on it must find it installed (torch: or
# pip resolves the newest CUDA build).
log "installing $FRAMEWORK"
"$PY" -m pip install -q "$FRAMEWORK"
log "installing $REQ and mk/adapters/base.txt"
"$PY" -m pip install -q "$FRAMEWORK" -r "$REQ" -r mk/adapters/base.txt
if [ -f "$NODEPS" ]; then
    log "installing $NODEPS without dependencies"
    "$PY" -m pip install -q --no-deps -r "$NODEPS"
fi
if [ -f "$WRITER" ]; then
    log "installing $WRITER into $VENV/writer-site (test checkpoint writer only)"
    "$PY" -m pip install -q --no-deps --upgrade --target "$VENV/writer-site" -r "$WRITER"
fi
if [ -n "$EXTRA_SRC" ]; then
    log "installing model code from $EXTRA_SRC"
    "$PY" -m pip install -q --no-deps "$EXTRA_SRC"
fi
log "installing ladev (editable, --no-deps)"
"$PY" -m pip install -q --no-deps --no-build-isolation -e . 2>/dev/null \
    || "$PY" -m pip install -q --no-deps -e .
echo "$want" > "$stamp"
log "ready in $(( $(date +%s) - start )) s; size $(du -sh "$VENV" | cut -f1)"
