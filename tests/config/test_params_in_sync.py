"""params.yaml (what DVC runs) must be conf/ composed: no silent drift."""

from __future__ import annotations

import yaml

from ladev_lib.cli.config import render_params


def test_params_yaml_is_conf_composed(repo_root):
    committed = yaml.safe_load((repo_root / "params.yaml").read_text())
    composed = yaml.safe_load(render_params([], str(repo_root / "conf")))
    assert committed == composed, "params.yaml is stale: run `make params`"
