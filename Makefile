# LADEV: the two commands of the README are `make run` and `make test`.
# Every target sets up what it needs first (idempotent, seconds when done).
SHELL := /bin/bash
VENV ?= .venv
PY := $(VENV)/bin/python
BIN := $(VENV)/bin
# dvc.yaml's stage commands call `python`: make it the project's.
export PATH := $(abspath $(VENV))/bin:$(PATH)
# Two software-rendering workers on two cores: one thread each.
export LP_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1
export HF_HUB_OFFLINE ?= 1
export TOKENIZERS_PARALLELISM ?= false
# Use the asset pack beside the checkout when the user has not chosen one.
ifeq ($(origin MS_ASSET_DIR), undefined)
  ifneq ($(wildcard ../shared/assets/data),)
    export MS_ASSET_DIR := $(abspath ../shared/assets)
  endif
endif

.PHONY: setup run test test-fast lint typecheck bench doctor params clean-data

setup:                 ## venv + pinned Python stack + a Vulkan device SAPIEN can use
	@bash scripts/setup.sh

run: setup             ## the main job: the default study end to end, then its headline numbers
	$(BIN)/dvc repro
	$(BIN)/ladev summary

test: setup            ## every test, rendering and the VLA adapter environments included (what CI runs)
	@bash scripts/setup_latex.sh || echo "[latex] not installed: the pdflatex check of the LaTeX tables will be skipped"
	$(BIN)/pytest -q
	@$(MAKE) --no-print-directory test-adapters

test-fast: setup       ## tests that do not build simulator scenes
	$(BIN)/pytest -q -m "not sim and not slow"

lint: setup
	$(BIN)/ruff check ladev_lib stages tests benchmarks

typecheck: setup
	$(BIN)/mypy

doctor: setup
	$(BIN)/ladev doctor

params: setup          ## recompose params.yaml from conf/ (after editing conf/)
	$(BIN)/ladev config > params.yaml

bench: setup           ## benchmarks that print figures (not timed tests)
	@for b in benchmarks/bench_*.py; do echo "== $$b"; $(PY) $$b || exit 1; done

clean-data:            ## remove generated data and reports (keeps the caches)
	rm -rf data/*.parquet data/episodes data/media reports/*

# VLA adapter environments: make test-adapters (see mk/adapters.mk)
include mk/adapters.mk
