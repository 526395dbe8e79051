"""Every option of every group in conf/ composes, and every section validates with
the model of the subpackage that owns it. A new option or section is covered as
soon as it exists: the test walks conf/, not a hand-written list."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from ladev_lib.config import compose_config, section
from ladev_lib.language.config import ParaphraseConfig
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.pipeline.multirun import STAGE_ORDER
from ladev_lib.policies.config import PolicyConfig
from ladev_lib.report.config import ReportConfig
from ladev_lib.rollout.config import RolloutConfig, executor_config
from ladev_lib.scenes.compiler import CompileConfig
from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.sim.config import RobotConfig, SimConfig
from ladev_lib.study.design import StudyConfig, design_scenes

CONF = Path(__file__).resolve().parents[2] / "conf"
GROUPS = sorted(p.name for p in CONF.iterdir() if p.is_dir())
OPTIONS = [(g, o.stem) for g in GROUPS for o in sorted((CONF / g).glob("*.yaml"))]
PROMPT_JOBS = ["describe_scenes", "compile_scene", "paraphrase", "parse_instruction"]


def validate_all(cfg: dict[str, Any]) -> None:
    study = section(cfg, "study", StudyConfig)
    assert design_scenes(study), "a study with no scenes"
    SceneBounds.model_validate(cfg["study"]["bounds"])
    section(cfg, "llm", LLMConfig)
    section(cfg, "sim", SimConfig)
    section(cfg, "robot", RobotConfig)
    section(cfg, "report", ReportConfig)
    section(cfg, "compile", CompileConfig)
    section(cfg, "paraphrase", ParaphraseConfig)
    section(cfg, "rollout", RolloutConfig)
    executor_config(cfg)
    for label in cfg["policy"]:
        section(cfg["policy"], label, PolicyConfig)
    prompts = load_prompts(cfg, PROMPT_JOBS)
    assert sorted(prompts) == sorted(PROMPT_JOBS), "a prompt template is missing"


def test_the_groups_are_the_designs():
    assert GROUPS == ["executor", "llm", "policy", "prompts", "report", "robot", "sim", "study"]


@pytest.mark.parametrize(("group", "option"), OPTIONS, ids=[f"{g}={o}" for g, o in OPTIONS])
def test_option_composes_and_validates(group, option):
    override = f"{group}=[{option}]" if group == "policy" else f"{group}={option}"
    cfg = compose_config([override], CONF)
    validate_all(cfg)
    if group == "policy":
        assert list(cfg["policy"]) == [option]


def test_a_bad_value_names_its_key():
    cfg = compose_config(["study.bounds.max_objects=0"], CONF)
    with pytest.raises(Exception, match="max_objects"):
        validate_all(cfg)


def test_pipeline_runner_and_dvc_yaml_agree(repo_root):
    stages = yaml.safe_load((repo_root / "dvc.yaml").read_text())["stages"]
    assert tuple(stages) == STAGE_ORDER
    for name, stage in stages.items():
        cmd = stage["do"]["cmd"] if "foreach" in stage else stage["cmd"]
        assert cmd.startswith(f"python stages/{name}.py"), cmd
