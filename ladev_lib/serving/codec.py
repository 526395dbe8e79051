"""msgpack with numpy arrays, in the wire format of openpi's ``openpi_client.msgpack_numpy``.

An array travels as a map ``{"__ndarray__": True, "data": <bytes>, "dtype":
<numpy dtype string>, "shape": [...]}`` and a numpy scalar as ``{"__npgeneric__":
True, "data": <value>, "dtype": ...}`` (keys as msgpack bytes), so LADEV's
server and client interoperate with openpi's.

Decoding is strict, because a policy server may face untrusted peers: only
plain numeric dtypes (bool, signed and unsigned integers, floats) are
accepted, the byte count must match the shape, sizes are bounded, msgpack
extension types are refused, and nothing is ever unpickled. Anything else
raises :class:`PayloadError`.
"""

from __future__ import annotations

import re
from typing import Any

import msgpack
import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.errors import LadevError

# Explicit byte order (or none for 1-byte types) + kind in {b, i, u, f} + size.
_DTYPE_RE = re.compile(r"^[<>|=]?[biuf][1248]$")
_ND_KEY, _GEN_KEY = b"__ndarray__", b"__npgeneric__"
MAX_ARRAY_BYTES = 256 * 1024 * 1024
MAX_NDIM = 8


class PayloadError(LadevError, ValueError):
    """A message that is not a well-formed, plain-numeric msgpack-numpy payload."""


def _plain_dtype(obj: Array | np.generic) -> np.dtype[Any]:
    dtype = obj.dtype
    if dtype.kind not in "biuf":
        raise PayloadError(f"cannot send numpy dtype {dtype!s}: only bool, int, uint, float")
    return dtype


def _encode_hook(obj: Any) -> Any:
    if isinstance(obj, np.ndarray):
        dtype = _plain_dtype(obj)
        return {
            _ND_KEY: True,
            b"data": np.ascontiguousarray(obj).tobytes(),
            b"dtype": dtype.str,
            b"shape": list(obj.shape),
        }
    if isinstance(obj, np.generic):
        dtype = _plain_dtype(obj)
        return {_GEN_KEY: True, b"data": obj.item(), b"dtype": dtype.str}
    raise TypeError(f"cannot encode {type(obj).__name__} (send numpy arrays, numbers, str, lists, dicts)")


def packb(obj: Any) -> bytes:
    """Encode a (nested) dict of numpy arrays, numbers and strings."""
    data: bytes = msgpack.packb(obj, default=_encode_hook, use_bin_type=True)
    return data


def _checked_dtype(raw: Any) -> np.dtype[Any]:
    text = raw.decode("ascii", "replace") if isinstance(raw, bytes) else raw
    if not isinstance(text, str) or not _DTYPE_RE.match(text):
        raise PayloadError(f"refused dtype {text!r}: only plain bool/int/uint/float dtypes")
    return np.dtype(text)


def _decode_array(obj: dict[Any, Any]) -> Array:
    dtype = _checked_dtype(obj.get(b"dtype"))
    shape = obj.get(b"shape")
    data = obj.get(b"data")
    if not isinstance(shape, list | tuple) or len(shape) > MAX_NDIM:
        raise PayloadError(f"array shape must be a list of at most {MAX_NDIM} ints")
    if not all(isinstance(n, int) and not isinstance(n, bool) and n >= 0 for n in shape):
        raise PayloadError(f"array shape must hold non-negative ints, got {shape!r}")
    if not isinstance(data, bytes):
        raise PayloadError("array data must be bytes")
    count = 1
    for n in shape:
        count *= n
    if count * dtype.itemsize != len(data) or len(data) > MAX_ARRAY_BYTES:
        raise PayloadError(
            f"array of shape {list(shape)} and dtype {dtype.str} needs "
            f"{count * dtype.itemsize} bytes, got {len(data)} (limit {MAX_ARRAY_BYTES})"
        )
    # A copy: the result must not alias (or keep alive) the message buffer.
    return np.frombuffer(data, dtype=dtype).reshape(shape).copy()


def _decode_generic(obj: dict[Any, Any]) -> np.generic:
    dtype = _checked_dtype(obj.get(b"dtype"))
    value = obj.get(b"data")
    if not isinstance(value, bool | int | float):
        raise PayloadError(f"numpy scalar data must be a number, got {type(value).__name__}")
    result: np.generic = dtype.type(value)
    return result


def _object_hook(obj: dict[Any, Any]) -> Any:
    if obj.get(_ND_KEY) is True:
        return _decode_array(obj)
    if obj.get(_GEN_KEY) is True:
        return _decode_generic(obj)
    return obj


def _refuse_ext(code: int, data: bytes) -> Any:
    raise PayloadError(f"msgpack extension type {code} is not accepted")


_LEAF_TYPES = (str, bytes, int, float, bool, type(None), np.ndarray, np.generic)


def _check_tree(obj: Any, depth: int = 0) -> None:
    if depth > 32:
        raise PayloadError("message nested deeper than 32 levels")
    if isinstance(obj, dict):
        for v in obj.values():
            _check_tree(v, depth + 1)
    elif isinstance(obj, list):
        for v in obj:
            _check_tree(v, depth + 1)
    elif not isinstance(obj, _LEAF_TYPES):
        raise PayloadError(f"refused value of type {type(obj).__name__}")


def unpackb(data: bytes) -> Any:
    """Decode a message, accepting only plain numeric arrays (see module doc)."""
    if not isinstance(data, bytes | bytearray | memoryview):
        raise PayloadError(f"expected a binary message, got {type(data).__name__}")
    try:
        result = msgpack.unpackb(
            data,
            object_hook=_object_hook,
            ext_hook=_refuse_ext,
            raw=False,
            strict_map_key=True,
            use_list=True,
            timestamp=0,
        )
    except PayloadError:
        raise
    except (ValueError, TypeError, msgpack.UnpackException) as exc:
        raise PayloadError(f"malformed msgpack message: {exc}") from exc
    _check_tree(result)
    return result


def str_keys(obj: Any) -> Any:
    """Turn bytes map keys into str (openpi peers may send either)."""
    if isinstance(obj, dict):
        return {
            (k.decode("utf-8", "replace") if isinstance(k, bytes) else k): str_keys(v)
            for k, v in obj.items()
        }
    if isinstance(obj, list):
        return [str_keys(v) for v in obj]
    return obj
