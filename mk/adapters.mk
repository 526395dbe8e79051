# VLA adapter environments and their tests (included by the Makefile).
#
# RT-1 (TensorFlow + tf-agents), Octo (JAX/Flax) and OpenVLA (transformers
# 4.40) cannot share the core environment, nor each other's: each family has
# its own .venv-<family>, created idempotently by scripts/setup_adapter_env.sh
# from mk/adapters/<family>.txt (a second run with nothing changed: seconds).
#
#   make test-adapters          all three environments and their tests
#   make test-rt1 | test-octo | test-openvla
#   make adapter-env-octo OCTO_SPEC=/path/to/octo-checkout   (Octo's model code)

ADAPTER_PYTEST := -q -p no:cacheprovider
ADAPTER_ENV := TF_CPP_MIN_LOG_LEVEL=2 PYTHONPATH=$(CURDIR)

.PHONY: adapter-env-rt1 adapter-env-octo adapter-env-openvla \
        test-rt1 test-octo test-openvla test-adapters

adapter-env-rt1:
	@bash scripts/setup_adapter_env.sh rt1
adapter-env-octo:
	@bash scripts/setup_adapter_env.sh octo
adapter-env-openvla:
	@bash scripts/setup_adapter_env.sh openvla

test-rt1: adapter-env-rt1      ## RT-1 adapter on a tiny RT-1-format checkpoint
	$(ADAPTER_ENV) .venv-rt1/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_rt1.py
test-octo: adapter-env-octo    ## Octo adapter (JAX 0.4.20, Flax 0.7.5)
	$(ADAPTER_ENV) .venv-octo/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_octo_checkpoint.py tests/adapters/test_octo.py
test-openvla: adapter-env-openvla  ## OpenVLA adapter (transformers 4.40.1, remote code)
	$(ADAPTER_ENV) .venv-openvla/bin/pytest $(ADAPTER_PYTEST) tests/adapters/test_common.py tests/adapters/test_openvla.py

test-adapters: test-rt1 test-octo test-openvla  ## every VLA adapter in its own environment
