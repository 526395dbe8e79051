"""A ``conf/policy/<label>.yaml`` entry: which registered policy, with which arguments."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.vocabulary import Robot, TaskType


class PolicyConfig(BaseModel):
    """One ``policy.<label>`` entry: the registry name and the factory's keyword arguments."""

    model_config = ConfigDict(extra="allow", frozen=True)

    name: str = Field(min_length=1, description="Registry name (ladev_lib.policies.POLICIES).")
    robot_by_task: dict[TaskType, Robot] = Field(
        default_factory=dict,
        description="Task -> robot to evaluate it on, the policy built with robot=<robot> for each "
        "(the paper: pick up / move near on the Google robot, put on / put in on WidowX). "
        "Empty: the scene's robot, or the policy's own.",
    )

    @property
    def kwargs(self) -> dict[str, Any]:
        """Everything but ``name`` and ``robot_by_task``: passed to the policy's factory."""
        return dict(self.model_extra or {})

    @property
    def identity(self) -> dict[str, Any]:
        """What decides this policy's episodes: its factory arguments and robot choice."""
        out = self.kwargs
        if self.robot_by_task:
            out["robot_by_task"] = dict(sorted(self.robot_by_task.items()))
        return out
