"""The msgpack-numpy codec: round trips, openpi's wire format, refusal of unsafe payloads."""

from __future__ import annotations

import pickle

import msgpack
import numpy as np
import pytest

from ladev_lib.serving.codec import PayloadError, packb, str_keys, unpackb


def test_round_trip_of_nested_arrays_scalars_and_strings() -> None:
    msg = {
        "observation/image": np.arange(24, dtype=np.uint8).reshape(2, 4, 3),
        "observation/state": np.linspace(-1, 1, 8, dtype=np.float32),
        "nested": {"flag": np.bool_(True), "count": np.int64(7), "values": [1, 2.5, "x"]},
        "prompt": "pick up the coke can",
    }
    out = unpackb(packb(msg))
    np.testing.assert_array_equal(out["observation/image"], msg["observation/image"])
    assert out["observation/image"].dtype == np.uint8
    assert out["observation/state"].dtype == np.float32
    assert out["nested"]["flag"] == np.bool_(True) and isinstance(out["nested"]["flag"], np.bool_)
    assert out["nested"]["count"] == 7 and out["nested"]["values"] == [1, 2.5, "x"]
    assert out["prompt"] == "pick up the coke can"
    out["observation/image"][0, 0, 0] = 99  # decoded arrays are writable copies


def test_wire_format_is_openpis() -> None:
    """Arrays are maps with bytes keys __ndarray__/data/dtype/shape, as openpi_client writes."""
    arr = np.array([[1.5, -2.0]], dtype="<f8")
    raw = msgpack.unpackb(packb({"a": arr}), raw=False)
    enc = raw["a"]
    assert enc[b"__ndarray__"] is True
    assert enc[b"dtype"] == "<f8" and enc[b"shape"] == [1, 2]
    assert enc[b"data"] == arr.tobytes()


def test_decodes_what_openpi_client_encodes() -> None:
    openpi = pytest.importorskip("openpi_client.msgpack_numpy")
    msg = {"actions": np.ones((4, 7), dtype=np.float32), "t": np.float32(0.5)}
    out = unpackb(openpi.packb(msg))
    np.testing.assert_array_equal(out["actions"], msg["actions"])
    back = openpi.unpackb(packb(msg))
    np.testing.assert_array_equal(back["actions"], msg["actions"])


class _Payload:
    """Would write a file if it were ever unpickled."""

    def __init__(self, marker: str) -> None:
        self.marker = marker

    def __reduce__(self) -> tuple[object, tuple[str, str]]:
        return (_touch, (self.marker, "pwned"))


def _touch(path: str, text: str) -> None:
    with open(path, "w") as f:
        f.write(text)


@pytest.mark.parametrize("dtype", ["|O", "O", "<U3", "|S4", "|V8", "<M8[s]", "<c16", "[('a', 'O')]"])
def test_refuses_non_numeric_dtypes(dtype: str, tmp_path) -> None:
    marker = tmp_path / "marker"
    evil = {b"__ndarray__": True, b"data": pickle.dumps(_Payload(str(marker))), b"dtype": dtype, b"shape": [1]}
    with pytest.raises(PayloadError, match="refused dtype"):
        unpackb(msgpack.packb({"x": evil}, use_bin_type=True))
    assert not marker.exists()


def test_refuses_pickle_based_msgpack_numpy_objects(tmp_path) -> None:
    """msgpack-numpy (lebedov) pickles object arrays under b"kind": b"O"; we never unpickle."""
    marker = tmp_path / "marker"
    evil = {b"nd": True, b"type": "|O", b"kind": b"O", b"shape": [1], b"data": pickle.dumps(_Payload(str(marker)))}
    out = unpackb(msgpack.packb({"x": evil}, use_bin_type=True))
    # Not an array marker we know: it stays an inert map of bytes, never unpickled.
    assert isinstance(out["x"], dict) and not marker.exists()


@pytest.mark.parametrize(
    "bad",
    [
        {b"__ndarray__": True, b"data": b"\x00" * 7, b"dtype": "<f8", b"shape": [1]},  # short
        {b"__ndarray__": True, b"data": b"\x00" * 8, b"dtype": "<f8", b"shape": [-1]},
        {b"__ndarray__": True, b"data": b"\x00" * 8, b"dtype": "<f8", b"shape": "8"},
        {b"__ndarray__": True, b"data": "text", b"dtype": "<f8", b"shape": [1]},
        {b"__npgeneric__": True, b"data": b"xx", b"dtype": "<f8"},
    ],
)
def test_refuses_malformed_arrays(bad: dict) -> None:
    with pytest.raises(PayloadError):
        unpackb(msgpack.packb({"x": bad}, use_bin_type=True))


def test_refuses_extension_types_and_garbage() -> None:
    with pytest.raises(PayloadError, match="extension"):
        unpackb(msgpack.packb({"x": msgpack.ExtType(5, b"abc")}))
    with pytest.raises(PayloadError):
        unpackb(b"\xc1\xff\x00")
    with pytest.raises(PayloadError):
        unpackb("not bytes")  # type: ignore[arg-type]


def test_encoder_refuses_object_arrays() -> None:
    with pytest.raises(PayloadError):
        packb({"x": np.array([object()], dtype=object)})


def test_str_keys_decodes_bytes_keys() -> None:
    assert str_keys({b"a": [{b"b": 1}]}) == {"a": [{"b": 1}]}
