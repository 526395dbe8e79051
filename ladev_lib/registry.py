"""Registries of named components (policies, LLM backends, tasks, robots, executors).

Names, not import strings, appear in configs. An unknown name lists the known
ones; an entry whose optional dependency is missing names the extra to install.
Entries can be registered lazily (``module:attribute``) so that listing or
looking up a name never imports a heavy stack that is not used.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Generic, TypeVar

from ladev_lib.errors import MissingExtraError, UnknownNameError

T = TypeVar("T")


@dataclass(frozen=True)
class _LazyEntry:
    target: str  # "package.module:attribute"
    extra: str | None


class Registry(Generic[T]):
    """A mapping from short names to objects of one kind."""

    def __init__(self, kind: str) -> None:
        self.kind = kind
        self._entries: dict[str, T | _LazyEntry] = {}
        self._extras: dict[str, str] = {}  # kept after a lazy entry resolves

    def register(self, name: str) -> Callable[[T], T]:
        """Decorator: ``@POLICIES.register("oracle")``."""

        def decorate(obj: T) -> T:
            self.add(name, obj)
            return obj

        return decorate

    def add(self, name: str, obj: T) -> None:
        if name in self._entries and self._entries[name] is not obj:
            raise ValueError(f"{self.kind} {name!r} is registered twice")
        self._entries[name] = obj

    def add_lazy(self, name: str, target: str, *, extra: str | None = None) -> None:
        """Register ``target`` ("module:attr"), imported on first lookup."""
        if ":" not in target:
            raise ValueError(f"lazy target must be 'module:attribute', got {target!r}")
        self._entries.setdefault(name, _LazyEntry(target, extra))
        if extra and isinstance(self._entries[name], _LazyEntry):
            self._extras.setdefault(name, extra)

    def get(self, name: str) -> T:
        try:
            entry = self._entries[name]
        except KeyError:
            raise UnknownNameError(self.kind, name, list(self._entries)) from None
        if isinstance(entry, _LazyEntry):
            module_name, attr = entry.target.split(":")
            try:
                module = importlib.import_module(module_name)
            except ImportError as exc:
                if entry.extra:
                    raise MissingExtraError(f"{self.kind} {name!r}", entry.extra, exc) from exc
                raise
            resolved: T = getattr(module, attr)
            self._entries[name] = resolved
            return resolved
        return entry

    def extra_of(self, name: str) -> str | None:
        """The optional extra a lazily registered entry needs (also after it was imported)."""
        return self._extras.get(name)

    def module_of(self, name: str) -> str:
        """The module that defines ``name``'s entry, without importing a lazy one."""
        try:
            entry = self._entries[name]
        except KeyError:
            raise UnknownNameError(self.kind, name, list(self._entries)) from None
        if isinstance(entry, _LazyEntry):
            return entry.target.split(":")[0]
        return str(getattr(entry, "__module__", "") or "")

    def names(self) -> list[str]:
        return sorted(self._entries)

    def __contains__(self, name: object) -> bool:
        return name in self._entries

    def __iter__(self) -> Iterator[str]:
        return iter(self.names())
