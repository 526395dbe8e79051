"""A persistent, content-addressed key -> JSON store (SQLite).

Both item-level caches use it: LLM calls (prompt + model + settings -> response)
and episodes (spec + instruction + policy + seed + sim config -> result).
Every ``put`` is its own committed transaction, so a process killed mid-run
loses nothing it finished; WAL mode lets several processes read while one
writes. Keys are hex digests made by :func:`content_key`.
"""

from __future__ import annotations

import hashlib
import json
import sqlite3
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any


def canonical_json(value: Any) -> str:
    """JSON with sorted keys and no whitespace: equal values give equal text."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=False, default=str)


def content_key(*parts: Any, length: int = 24) -> str:
    """A hex digest of ``parts`` (any JSON-able values), ``length`` characters long."""
    digest = hashlib.sha256(canonical_json(list(parts)).encode("utf-8")).hexdigest()
    return digest[:length]


class ContentStore:
    """Key -> JSON value, persisted in ``<directory>/store.sqlite``."""

    def __init__(self, directory: str | Path) -> None:
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        self.path = self.directory / "store.sqlite"
        self._local = threading.local()
        with self._conn() as conn:
            conn.execute(
                "CREATE TABLE IF NOT EXISTS items ("
                " key TEXT PRIMARY KEY, value TEXT NOT NULL, created REAL NOT NULL)"
            )

    def _conn(self) -> sqlite3.Connection:
        conn: sqlite3.Connection | None = getattr(self._local, "conn", None)
        if conn is None:
            conn = sqlite3.connect(self.path, timeout=60.0, isolation_level=None)
            conn.execute("PRAGMA journal_mode=WAL")
            conn.execute("PRAGMA synchronous=NORMAL")
            self._local.conn = conn
        return conn

    def get(self, key: str) -> Any | None:
        row = self._conn().execute("SELECT value FROM items WHERE key = ?", (key,)).fetchone()
        return json.loads(row[0]) if row else None

    def get_many(self, keys: list[str]) -> dict[str, Any]:
        out: dict[str, Any] = {}
        conn = self._conn()
        for i in range(0, len(keys), 500):
            chunk = keys[i : i + 500]
            marks = ",".join("?" * len(chunk))
            for k, v in conn.execute(f"SELECT key, value FROM items WHERE key IN ({marks})", chunk):
                out[k] = json.loads(v)
        return out

    def put(self, key: str, value: Any) -> None:
        self._conn().execute(
            "INSERT OR REPLACE INTO items (key, value, created) VALUES (?, ?, ?)",
            (key, canonical_json(value), time.time()),
        )

    def __contains__(self, key: object) -> bool:
        row = self._conn().execute("SELECT 1 FROM items WHERE key = ?", (key,)).fetchone()
        return row is not None

    def __len__(self) -> int:
        return int(self._conn().execute("SELECT COUNT(*) FROM items").fetchone()[0])

    def keys(self) -> Iterator[str]:
        for (k,) in self._conn().execute("SELECT key FROM items ORDER BY created"):
            yield k

    def close(self) -> None:
        conn = getattr(self._local, "conn", None)
        if conn is not None:
            conn.close()
            self._local.conn = None
