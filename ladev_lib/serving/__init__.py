"""Policies over the network: openpi's websocket protocol, server side.

    from ladev_lib.serving import PolicyServer
    PolicyServer(policy, port=8000).run()

The client is the ``remote`` policy (:mod:`ladev_lib.policies.remote`); it
needs only websockets, msgpack and numpy. The wire format is in
:mod:`.codec` (msgpack-numpy, strict decoding) and :mod:`.protocol` (keys,
metadata).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ladev_lib.serving.codec import PayloadError, packb, unpackb
from ladev_lib.serving.protocol import WireKeys

if TYPE_CHECKING:
    from ladev_lib.serving.server import PolicyServer


def __getattr__(name: str) -> object:
    # The server pulls in websockets' asyncio server; import it only when used.
    if name == "PolicyServer":
        from ladev_lib.serving.server import PolicyServer

        return PolicyServer
    raise AttributeError(name)


__all__ = ["PayloadError", "PolicyServer", "WireKeys", "packb", "unpackb"]
