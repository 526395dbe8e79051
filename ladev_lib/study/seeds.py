"""Seeds derived from names, so that a scene's seed never changes when its study grows."""

from __future__ import annotations

import hashlib


def derive_seed(base: int, key: str) -> int:
    """A non-negative 31-bit seed from a base seed and a key (e.g. a scene id)."""
    digest = hashlib.sha256(f"{base}:{key}".encode()).digest()
    return int.from_bytes(digest[:4], "big") & 0x7FFFFFFF


def trial_seed(scene_seed: int, trial: int) -> int:
    """The seed of trial ``trial`` of a scene: the scene's own seed for trial 0 (so a study with
    one trial per scene keeps its seeds), a derived one for the others."""
    if trial < 0:
        raise ValueError(f"trial must be >= 0, got {trial}")
    return scene_seed if trial == 0 else derive_seed(scene_seed, f"trial:{trial}")
