"""Seeds derived from names, so that a scene's seed never changes when its study grows."""

from __future__ import annotations

import hashlib


def derive_seed(base: int, key: str) -> int:
    """A non-negative 31-bit seed from a base seed and a key (e.g. a scene id)."""
    digest = hashlib.sha256(f"{base}:{key}".encode()).digest()
    return int.from_bytes(digest[:4], "big") & 0x7FFFFFFF
