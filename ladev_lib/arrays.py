"""Array aliases for annotations.

``mypy --strict`` wants numpy's generic ``ndarray`` parameterised. Most arrays
here are poses, points and images whose dtype the code does not depend on, so
one alias says "an ndarray" without pretending to know more.
"""

from __future__ import annotations

from typing import Any

import numpy.typing as npt

Array = npt.NDArray[Any]
"""Any numpy array (shape and dtype as documented where it matters)."""
