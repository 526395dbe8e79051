"""Registers the language jobs with the offline backend.

Importing this module adds ``paraphrase`` and ``parse_instruction`` to
``OFFLINE_JOBS``. The handlers' module lists in ``RULE_MODULES`` every module
the answers depend on, so the offline backend's rule fingerprint (part of
each cache key) changes when the grammar, the vocabulary or the templates do.
"""

from __future__ import annotations

from ladev_lib.language.llm_jobs import (
    PARAPHRASE_JOB,
    PARSE_JOB,
    offline_paraphrase_job,
    offline_parse_job,
)
from ladev_lib.llm.base import OFFLINE_JOBS

OFFLINE_JOBS.add(PARAPHRASE_JOB, offline_paraphrase_job)
OFFLINE_JOBS.add(PARSE_JOB, offline_parse_job)
