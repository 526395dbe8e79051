"""Exceptions for the programmer and the user who configures LADEV.

Problems with *data* (an invalid LLM answer, an unsolvable scene, a crashed
episode) are not exceptions: they are recorded as rows with a status and a
reason. These exceptions are for bugs and bad configuration, and their message
says what to fix.
"""

from __future__ import annotations


class LadevError(Exception):
    """Base class of LADEV's own exceptions."""


class ConfigError(LadevError):
    """A configuration value is missing or out of range."""


class UnknownNameError(LadevError, KeyError):
    """A registry lookup used a name that is not registered."""

    def __init__(self, kind: str, name: str, known: list[str]) -> None:
        self.kind, self.name, self.known = kind, name, known
        super().__init__(f"unknown {kind} {name!r}; known: {', '.join(sorted(known)) or '(none)'}")

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0])


class MissingExtraError(LadevError, ImportError):
    """An optional dependency is not installed."""

    def __init__(self, what: str, extra: str, cause: BaseException | None = None) -> None:
        detail = f" ({cause})" if cause else ""
        super().__init__(
            f"{what} needs the optional extra '{extra}': pip install 'ladev[{extra}]'{detail}"
        )


class LLMCallError(LadevError):
    """An LLM call failed after its retries (rate limits, server errors, timeouts).

    Stages record it on the rows the call was for and go on.
    """
