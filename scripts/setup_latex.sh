#!/usr/bin/env bash
# Optional: a LaTeX toolchain so the tests compile the generated tables with
# pdflatex (they skip that check without it). The tables need only booktabs.
#
# Debian/Ubuntu, as root: texlive-latex-base + texlive-latex-recommended
# (17 packages, about 35 s on the 2-core development machine). Elsewhere, or
# not root: print what to install and exit non-zero.
#
# usage: scripts/setup_latex.sh
set -euo pipefail
log() { printf '\033[1m[latex]\033[0m %s\n' "$*"; }

if command -v pdflatex >/dev/null 2>&1 && kpsewhich booktabs.sty >/dev/null 2>&1; then
    log "pdflatex with booktabs: OK"
    exit 0
fi
if ! command -v apt-get >/dev/null 2>&1; then
    log "no apt-get: install a TeX distribution with pdflatex and booktabs (e.g. TeX Live)"
    exit 1
fi
if [ "$(id -u)" != "0" ]; then
    log "as root, run: bash scripts/setup_latex.sh"
    log "(apt-get install --no-install-recommends texlive-latex-base texlive-latex-recommended)"
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get install -y -q --no-install-recommends texlive-latex-base texlive-latex-recommended >/dev/null \
    || { apt-get update -q >/dev/null && apt-get install -y -q --no-install-recommends \
         texlive-latex-base texlive-latex-recommended >/dev/null; }
log "installed: $(pdflatex --version | head -1)"
