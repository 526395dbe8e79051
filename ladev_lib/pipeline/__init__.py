"""The pipeline: one module per stage, each the one entry point its stage script and CLI command call.

    generate.run_generate(params)      -> scenes table + GenerateSummary
    compile.run_compile(params)        -> compiled table + CompileSummary
    paraphrase.run_paraphrase(params)  -> instructions table + ParaphraseSummary
    rollout.run_rollout(params, label) -> episodes/<label>.parquet + RolloutSummary
    aggregate.run_aggregate(params)    -> report files + AggregateSummary
    multirun.run_pipeline(...)         -> every stage script in order (Hydra sweeps)

Each takes the composed configuration (``params.yaml``), validates the
sections it reads with their owners' models, calls the library that does the
work (``study.generation``, ``scenes.text_to_scene``, ``pipeline.instructions``,
``rollout.stage``, ``report.build``) and returns a result with ``messages()``:
what the stage prints. :func:`run_stage` is how every stage script runs one.

This package sits above every other one: nothing in ``ladev_lib`` below it
imports it. This module stays light (a stage's import closure includes it).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass

from ladev_lib.errors import LadevError


@dataclass(frozen=True)
class StageMessages:
    """What a stage tells its user: lines for stdout, lines for stderr, and its exit status."""

    out: tuple[str, ...]
    err: tuple[str, ...] = ()
    exit_code: int = 0


def run_stage(body: Callable[[], StageMessages]) -> int:
    """Run a stage's body; print its messages and return its exit status.

    A :class:`LadevError` (bad configuration, missing input) prints ``error: <message>``
    on stderr and returns 2, as the ``ladev`` command line does; ``LADEV_DEBUG=1``
    shows the traceback instead.
    """
    try:
        messages = body()
    except LadevError as exc:
        if os.environ.get("LADEV_DEBUG"):
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print("\n".join(messages.out))
    if messages.err:
        print("\n".join(messages.err), file=sys.stderr)
    return messages.exit_code
