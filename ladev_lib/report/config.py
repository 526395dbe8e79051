"""The ``report`` config section (``conf/report/<name>.yaml``): what the aggregate stage writes.

Only this section and ``study.name`` feed the ``aggregate`` stage, so changing
any of these options re-runs that stage alone.
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

TableFormat = Literal["md", "tex", "csv"]
ALL_FORMATS: tuple[TableFormat, ...] = ("md", "tex", "csv")

# Where the LADEV paper's published cells live beside a checkout (../shared/...).
DEFAULT_REFERENCE_CSV = Path("..") / "shared" / "reference" / "ladev_paper_tables.csv"


class PublishedConfig(BaseModel):
    """Published figures shown next to a study's results, clearly labelled as such."""

    model_config = ConfigDict(extra="forbid")

    enabled: bool = Field(default=True, description="Add published rows under each mapped model.")
    reference_csv: str | None = Field(
        default=None,
        description="Long-format CSV of published cells (table,factor,level,model,task,"
        "success_rate_pct,n_scenes). null: ../shared/reference/ladev_paper_tables.csv "
        "relative to the working directory, skipped quietly when absent.",
    )
    source: str = Field(default="LADEV paper", description="How published rows are labelled.")


class GalleryConfig(BaseModel):
    """The gallery of failed episodes in the HTML report."""

    model_config = ConfigDict(extra="forbid")

    size: int = Field(default=12, ge=0, description="Failed episodes shown (spread over policy x task).")
    embed_frames: bool = Field(
        default=True, description="Embed first/last frames in the HTML (else copy them beside it)."
    )
    copy_videos: bool = Field(
        default=True,
        description="Copy the shown episodes' videos under figures/gallery so the report folder "
        "zips whole (else link them where rollout wrote them).",
    )


class ReportConfig(BaseModel):
    """Options of the aggregate stage."""

    model_config = ConfigDict(extra="forbid")

    formats: list[TableFormat] = Field(
        default_factory=lambda: list(ALL_FORMATS), description="Table formats to write."
    )
    intervals: bool = Field(
        default=False, description="Show the Wilson interval in rendered (md/tex) table cells."
    )
    show_n: bool = Field(default=False, description="Show n in rendered (md/tex) table cells.")
    confidence: float = Field(default=0.95, gt=0.5, lt=1.0, description="Interval confidence level.")
    decimals: int = Field(
        default=0, ge=0, le=3, description="Decimals of a rate; averages get one more, as in the paper."
    )
    model_labels: dict[str, str] = Field(
        default_factory=dict,
        description="Policy name -> model label in tables (e.g. rt1_400k: RT-1-400k). Also picks "
        "the published rows: a label equal to a published model name gets them. Row order "
        "follows this mapping; other policies come after, by name.",
    )
    published: PublishedConfig = Field(default_factory=PublishedConfig)
    gallery: GalleryConfig = Field(default_factory=GalleryConfig)
    figures: bool = Field(default=True, description="Write PNG figures.")
    html: bool = Field(default=True, description="Write the HTML report.")
    success: Literal["end", "any"] = Field(
        default="end",
        description="Success definition of every table: at the final step (end) or at any step "
        "(any). Named in every caption; the summary shows both.",
    )
    bootstrap_samples: int = Field(
        default=2000, ge=100, le=100_000, description="Resamples of the cluster bootstrap over scenes."
    )
    bootstrap_seed: int = Field(default=0, ge=0, description="Seed of the cluster bootstrap (intervals repeat exactly).")
    mdd_power: float = Field(default=0.8, gt=0.5, lt=1.0, description="Power of the minimum detectable difference.")
    mdd_alpha: float = Field(default=0.05, gt=0.0, lt=0.5, description="Two-sided level of the minimum detectable difference.")

    def label(self, policy: str) -> str:
        return self.model_labels.get(policy, policy)
