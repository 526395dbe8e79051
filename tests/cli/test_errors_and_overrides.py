"""Bad input to the CLI is a message, not a traceback; policy overrides are checked."""

from __future__ import annotations

import pytest

from ladev_lib.cli import main
from ladev_lib.errors import ConfigError
from ladev_lib.policies import make_policy
from ladev_lib.policies.configured import policy_config


def test_an_override_of_name_picks_another_registry_entry() -> None:
    assert policy_config("random", overrides={"name": "noop"})[0] == "noop"
    name, kwargs = policy_config("random", overrides={"action_dim": 7})
    assert name == "random" and kwargs["action_dim"] == 7
    with pytest.raises(ConfigError, match="not a registered policy"):
        policy_config("random", overrides={"name": "no_such_policy"})


def test_an_option_the_policy_does_not_take_names_the_ones_it_does() -> None:
    with pytest.raises(ConfigError, match=r"does not take 'bogus'.*action_dim"):
        make_policy("random", bogus=1)
    assert make_policy("random", action_dim=4).info.name == "random"


def test_main_prints_a_ladev_error_and_exits_2(capsys, monkeypatch) -> None:
    monkeypatch.delenv("LADEV_DEBUG", raising=False)
    with pytest.raises(SystemExit) as exit_info:
        main(["serve-policy", "random", "--set", "bogus=1", "--port", "0"])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert "error: policy 'random' does not take 'bogus'" in err
    assert "Traceback" not in err
    monkeypatch.setenv("LADEV_DEBUG", "1")
    with pytest.raises(ConfigError):
        main(["serve-policy", "random", "--set", "bogus=1", "--port", "0"])
