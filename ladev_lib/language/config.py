"""The ``paraphrase:`` configuration section."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.language.validator import DEFAULT_THRESHOLD


class ParaphraseConfig(BaseModel):
    """How paraphrases are validated (k and the seed come from the study)."""

    model_config = ConfigDict(extra="forbid")

    embedding_model: str = Field(
        default="all-MiniLM-L6-v2",
        description="Sentence-transformers model: the packaged all-MiniLM-L6-v2, or a model directory.",
    )
    similarity_threshold: float = Field(
        default=DEFAULT_THRESHOLD,
        ge=0.0,
        le=1.0,
        description="Minimum cosine similarity (object names canonicalised) for a valid paraphrase.",
    )
    batch_size: int = Field(default=64, ge=1, le=4096, description="Sentences per embedding batch.")
    device: str = Field(default="cpu", description="Torch device for the embedding model.")
    precision: Literal["auto", "fp32", "bf16"] = Field(
        default="auto",
        description="Embedding arithmetic on CPU: auto and fp32 compute in fp32 on every machine, so "
        "verdicts do not depend on the CPU; bf16 autocast (about 1.6x faster where the CPU has native "
        "bf16, moves MiniLM similarities by up to 0.002) only when named.",
    )
    threads: int | None = Field(
        default=None, ge=1, le=256,
        description="Torch threads while embedding; null: every core of the machine (the paraphrase stage runs "
        "alone, unlike the rollout's workers, which the Makefile keeps at one thread each).",
    )
    second_reading: bool = Field(
        default=True,
        description="Where the reader cannot read an original or a candidate, read it again with the span "
        "tagger (ladev_lib.language.tagged_frames) and compare that frame.",
    )
    reader: Literal["auto", "offline", "llm"] = Field(
        default="auto",
        description="Who reads candidates back into (task, source, target): the offline parser, the "
        "LLM's parse_instruction job, or auto (the parser with the offline backend, the LLM otherwise).",
    )
