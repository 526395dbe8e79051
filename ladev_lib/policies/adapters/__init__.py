"""Adapters for released VLA models, one module per family.

- ``rt1``: RT-1 / RT-1-X (TensorFlow SavedModels, tf-agents) — extra ``rt1``
- ``octo``: Octo-small / Octo-base (JAX, Octo's OctoModel) — extra ``octo``
- ``openvla``: OpenVLA-7b (transformers remote code) — extra ``openvla``
- ``lerobot_policy``: LeRobot checkpoints (SmolVLA, pi0, pi0.5, ACT, ...) through
  LeRobot's own classes — extra ``lerobot``; ``lerobot_maps``: its pure mappings
- ``common``: the per-embodiment pre/post-processing they share (pure numpy)

The families' stacks conflict, so each is imported only when its policy is
requested (``ladev_lib.policies.POLICIES``), and each has its own test
environment (``make test-rt1`` / ``test-octo`` / ``test-openvla`` / ``test-lerobot``).
"""
