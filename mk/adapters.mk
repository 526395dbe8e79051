# VLA adapter environments and their tests (included by the Makefile).
#
# RT-1 (TensorFlow + tf-agents), Octo (JAX/Flax), OpenVLA (transformers
# 4.40) and LeRobot (torch < 2.11, transformers 4.5x) cannot share the core
# environment, nor each other's: each family has
# its own .venv-<family>, created idempotently by scripts/setup_adapter_env.sh
# from mk/adapters/<family>.txt (a second run with nothing changed: seconds).
#
#   make test-adapters          all four environments and their tests
#   make test-rt1 | test-octo | test-openvla | test-lerobot
#   make adapter-env-octo OCTO_SPEC=/path/to/octo-checkout   (Octo's model code)

ADAPTER_PYTEST := -q -p no:cacheprovider
ADAPTER_ENV := TF_CPP_MIN_LOG_LEVEL=2 PYTHONPATH=$(CURDIR)

.PHONY: adapter-env-rt1 adapter-env-octo adapter-env-openvla adapter-env-lerobot \
        test-rt1 test-octo test-openvla test-lerobot test-adapters

adapter-env-rt1:
	@bash scripts/setup_adapter_env.sh rt1
adapter-env-octo:
	@bash scripts/setup_adapter_env.sh octo
adapter-env-openvla:
	@bash scripts/setup_adapter_env.sh openvla
adapter-env-lerobot:
	@bash scripts/setup_adapter_env.sh lerobot

test-rt1: adapter-env-rt1      ## RT-1 adapter on a tiny RT-1-format checkpoint
	$(ADAPTER_ENV) .venv-rt1/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_rt1.py
test-octo: adapter-env-octo    ## Octo adapter (JAX 0.4.20, Flax 0.7.5)
	$(ADAPTER_ENV) .venv-octo/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_octo_checkpoint.py tests/adapters/test_octo.py
test-openvla: adapter-env-openvla  ## OpenVLA adapter (transformers 4.40.1, remote code)
	$(ADAPTER_ENV) .venv-openvla/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_openvla.py

# LeRobot: the adapter's tests in .venv-lerobot, then one episode end to end: the
# core rollout (core venv, simulator) against `ladev serve-policy` run from
# .venv-lerobot. LADEV_REQUIRE_LEROBOT turns that test's skip into a failure.
test-lerobot: adapter-env-lerobot  ## LeRobot adapter (LeRobot 0.4.4, torch 2.10) on tiny ACT checkpoints
	$(ADAPTER_ENV) .venv-lerobot/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_lerobot_maps.py tests/adapters/test_lerobot.py tests/adapters/test_lerobot_vla.py
	$(ADAPTER_ENV) LADEV_REQUIRE_LEROBOT=1 $(BIN)/pytest $(ADAPTER_PYTEST) tests/adapters/test_lerobot_episode.py

test-adapters: test-rt1 test-octo test-openvla test-lerobot  ## every VLA adapter in its own environment
