"""Seeds: derived from names, and applied to every random generator an episode may draw from.

    seed = derive_seed(study_seed, scene_id)   # a scene's seed never changes when its study grows
    seed_episode(job.seed)                      # before the scene is loaded and the policy reset

The episode loop seeds here before each episode, and so does the policy server
when a client starts an episode with a seed (a served policy draws in its own
process).

An episode's outcome must not depend on the process it runs in, on which
episodes that process ran before, or on the clock. What can draw random
numbers during an episode, and how each is seeded here:

- Python's ``random``, NumPy's global generator and torch (when loaded);
- the C library's ``rand()``: Eigen's ``Random()`` draws from it, and so do
  Pinocchio's random configurations, which mplib's IK starts from;
- OMPL's generator (RRT-Connect in mplib): OMPL seeds each new sampler from a
  process-wide seed generator that starts from the clock unless told
  otherwise. mplib 0.1.1 does not expose ``ompl::RNG::setSeed``, so it is
  called through the shared library mplib ships, when mplib is loaded.

The seeds of the last two are derived from the episode seed, never 0 (OMPL
ignores 0).
"""

from __future__ import annotations

import contextlib
import ctypes
import functools
import hashlib
import os
import random
import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np


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


OMPL_SET_SEED = "_ZN4ompl3RNG7setSeedEm"
"""``ompl::RNG::setSeed(std::uint_fast32_t)`` (unsigned long on x86-64 Linux)."""


@functools.lru_cache(maxsize=1)
def _libc() -> ctypes.CDLL | None:
    try:
        return ctypes.CDLL(None)
    except OSError:
        return None


def _ompl_library() -> ctypes.CDLL | None:
    """OMPL as loaded by mplib, or None (mplib not imported yet, or built differently)."""
    mplib = sys.modules.get("mplib")
    where: str | None = getattr(mplib, "__file__", None) if mplib is not None else None
    if where is None:
        return None
    return _load_ompl(str(Path(where).resolve().parent))


@functools.lru_cache(maxsize=4)
def _load_ompl(mplib_dir: str) -> ctypes.CDLL | None:
    libs = sorted(Path(mplib_dir).parent.glob("mplib.libs/libompl*.so*"))
    for path in libs:
        try:
            lib = ctypes.CDLL(str(path))
        except OSError:
            continue
        if hasattr(lib, OMPL_SET_SEED):
            return lib
    return None


@contextlib.contextmanager
def _quiet_stderr() -> Iterator[None]:
    """OMPL logs an error when reseeded after first use (harmless here: every sampler of the
    episode is created after the reseed); keep it off the user's terminal."""
    sys.stderr.flush()
    saved = os.dup(2)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 2)
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        os.close(devnull)


def native_seed(seed: int, what: str) -> int:
    """A non-zero 31-bit seed for a native generator, derived from the episode seed."""
    return derive_seed(seed, what) or 1


def seed_ompl(seed: int) -> bool:
    """Seed OMPL's seed generator; False when OMPL is not loaded in this process."""
    lib = _ompl_library()
    if lib is None:
        return False
    fn = getattr(lib, OMPL_SET_SEED)
    fn.argtypes = [ctypes.c_ulong]
    fn.restype = None
    with _quiet_stderr():
        fn(native_seed(seed, "ompl"))
    return True


def seed_episode(seed: int) -> dict[str, bool]:
    """Seed every generator above from ``seed``; which native ones were reached."""
    random.seed(seed)
    np.random.seed(seed % 2**32)
    torch = sys.modules.get("torch")
    if torch is not None:
        torch.manual_seed(seed)
    libc = _libc()
    if libc is not None:
        libc.srand(ctypes.c_uint(native_seed(seed, "libc")))
    return {"libc": libc is not None, "ompl": seed_ompl(seed)}
