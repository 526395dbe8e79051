#!/usr/bin/env bash
# Make sure SAPIEN finds a Vulkan device it can render with.
#
# - A device that renders already (NVIDIA driver, a working Mesa): nothing changes.
# - Debian 12 (bookworm): Mesa 22's lavapipe cannot run SAPIEN; Mesa 25's
#   lavapipe from bookworm-backports can. The backports suite is added from the
#   Debian mirror this machine already uses (read from its apt sources).
# - Debian 13 or newer: Mesa's lavapipe from the main suite.
# - Anything else, or not root: print what to install and exit non-zero.
#
# usage: scripts/setup_vulkan.sh [PYTHON]   (a Python with sapien installed)
#        scripts/setup_vulkan.sh --backports-entry   (print the apt entry it would add; no changes)
set -euo pipefail
APT_DIR="${LADEV_APT_DIR:-/etc/apt}"
log() { printf '\033[1m[vulkan]\033[0m %s\n' "$*"; }

# The machine's own bookworm mirror and keyring, as a deb822 bookworm-backports entry.
backports_entry() {
    local uri="" keyring="-"
    if compgen -G "$APT_DIR/sources.list.d/*.sources" >/dev/null; then
        read -r uri keyring < <(awk '
            /^URIs:/      { uri=$2 }
            /^Suites:/    { main=0; for (i=2;i<=NF;i++) if ($i=="bookworm") main=1 }
            /^Signed-By:/ { key=$2 }
            /^$/          { if (main && uri!="") { print uri, (key==""?"-":key); exit } uri=""; key=""; main=0 }
            END           { if (main && uri!="") print uri, (key==""?"-":key) }
        ' "$APT_DIR"/sources.list.d/*.sources) || true
    fi
    if [ -z "$uri" ]; then
        uri=$(cat "$APT_DIR/sources.list" "$APT_DIR"/sources.list.d/*.list 2>/dev/null \
              | awk '$1=="deb" { s=2; if ($2 ~ /^\[/) { while ($s !~ /\]$/) s++; s++ } if ($(s+1)=="bookworm") { print $s; exit } }') || true
        keyring="-"
    fi
    [ -n "$uri" ] || return 1
    echo "Types: deb"
    echo "URIs: $uri"
    echo "Suites: bookworm-backports"
    echo "Components: main"
    if [ "$keyring" != "-" ]; then echo "Signed-By: $keyring"; fi
}

if [ "${1:-}" = "--backports-entry" ]; then
    backports_entry
    exit $?
fi
PY="${1:-python3}"

probe() { "$PY" -m ladev_lib.sim.render_probe --quiet; }

if probe; then
    log "rendering device OK: $("$PY" -m ladev_lib.sim.render_probe --name-only)"
    exit 0
fi

if command -v nvidia-smi >/dev/null 2>&1 || [ -e /proc/driver/nvidia/version ]; then
    log "an NVIDIA driver is present but SAPIEN cannot render with it."
    log "Install the driver's Vulkan ICD (e.g. libnvidia-gl-<version> / nvidia_icd.json) and libvulkan1;"
    log "this script does not change a machine with an NVIDIA driver."
    exit 1
fi

. /etc/os-release 2>/dev/null || true
if [ "${ID:-}" != "debian" ]; then
    log "no rendering device, and this is not Debian (${PRETTY_NAME:-unknown system})."
    log "Install a Vulkan driver SAPIEN can use: an NVIDIA driver, or Mesa >= 23 lavapipe"
    log "(Ubuntu 24.04: apt install mesa-vulkan-drivers libvulkan1), then run: make setup"
    exit 1
fi
if [ "$(id -u)" != "0" ]; then
    log "no rendering device. As root, run: bash scripts/setup_vulkan.sh $PY"
    log "(it installs Mesa's lavapipe software Vulkan driver from Debian's packages)"
    exit 1
fi

export DEBIAN_FRONTEND=noninteractive
suite_args=()
if [ "${VERSION_CODENAME:-}" = "bookworm" ]; then
    target="$APT_DIR/sources.list.d/ladev-bookworm-backports.sources"
    if ! grep -rqs "bookworm-backports" "$APT_DIR/sources.list" "$APT_DIR/sources.list.d/"; then
        if ! entry=$(backports_entry); then
            log "found no bookworm mirror in $APT_DIR/sources.list*; add bookworm-backports by hand,"
            log "then: apt-get install -t bookworm-backports mesa-vulkan-drivers libvulkan1"
            exit 1
        fi
        log "adding bookworm-backports from $(echo "$entry" | awk '/^URIs:/ {print $2}')"
        echo "$entry" > "$target"
    fi
    suite_args=(-t bookworm-backports)
fi

log "installing Mesa lavapipe (software Vulkan)"
apt-get update -qq
apt-get install -y -qq "${suite_args[@]}" mesa-vulkan-drivers libvulkan1 >/dev/null

if probe; then
    log "rendering device OK: $("$PY" -m ladev_lib.sim.render_probe --name-only)"
else
    log "lavapipe installed, but SAPIEN still cannot render; run: $PY -m ladev_lib.sim.render_probe"
    exit 1
fi
