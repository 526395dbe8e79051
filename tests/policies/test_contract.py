"""The interface contract, for every registered policy that can be built here.

Every policy builds from its default config and declares a valid ``PolicyInfo``
(``remote`` against a policy server started here). Policies that need neither
the simulator's state nor a server also answer a step here: a finite action of
the action space's shape, inside its bounds, the same for the same episode
seed. Privileged policies (oracle, grounded) answer steps in the simulator
tests; ``remote`` in the policy-server tests. VLA families are skipped when
their optional extra is missing, as the registry says, or when they need a
checkpoint this machine does not have (their adapters are tested with tiny
models in tests/adapters).
"""

from __future__ import annotations

import importlib.util
from collections.abc import Iterator

import numpy as np
import pytest

from ladev_lib.errors import MissingExtraError
from ladev_lib.policies import POLICIES, EpisodeContext, Observation, Policy, PolicyInfo, PolicyStep

ACTION_DIM = 7
NEEDS_A_SERVER = {"remote"}


def build(name: str, **config: object) -> Policy:
    module = POLICIES.module_of(name)
    try:
        present = importlib.util.find_spec(module) is not None
    except ModuleNotFoundError:
        present = False
    if not present:
        pytest.skip(f"{module} is not in this checkout")
    try:
        factory = POLICIES.get(name)
    except MissingExtraError as exc:
        pytest.skip(str(exc))
    if POLICIES.extra_of(name) is None:
        return factory(**config)
    try:
        return factory(**config)
    except MissingExtraError as exc:
        pytest.skip(str(exc))
    except Exception as exc:  # noqa: BLE001 - a VLA family without its checkpoint here
        pytest.skip(f"{name} cannot be built here: {type(exc).__name__}: {str(exc)[:200]}")


@pytest.fixture
def built(request: pytest.FixtureRequest) -> Iterator[Policy]:
    name = request.param
    if name != "remote":
        policy = build(name)
        yield policy
        policy.close()
        return
    from tests.serving.conftest import serve_in_thread
    from tests.serving.scripted import ScriptedPolicy

    with serve_in_thread(ScriptedPolicy()) as (url, _server):
        policy = build("remote", url=url, wait_for_server_s=10)
        yield policy
        policy.close()


@pytest.mark.parametrize("built", POLICIES.names(), indirect=True)
def test_info_is_declared(built):
    policy = built
    info = policy.info
    assert isinstance(policy, Policy) and isinstance(info, PolicyInfo)
    assert info.robots and all(isinstance(r, str) and r for r in info.robots)
    assert isinstance(info.control_mode, str) and info.control_mode
    if info.image_size is not None:
        w, h = info.image_size
        assert int(w) > 0 and int(h) > 0
    assert isinstance(info.privileged, bool)


def stateless_policies() -> list[str]:
    return [n for n in POLICIES.names() if n not in NEEDS_A_SERVER and POLICIES.extra_of(n) is None]


def episode(policy: Policy, seed: int, steps: int = 4) -> list[np.ndarray]:
    low, high = -np.ones(ACTION_DIM), np.ones(ACTION_DIM)
    policy.begin_episode(EpisodeContext(seed=seed, robot=policy.info.robots[0], action_low=low, action_high=high))
    policy.reset("pick up the coke can")
    size = policy.info.image_size
    actions = []
    for step in range(steps):
        image = np.zeros((size[1], size[0], 3), np.uint8) if size else None
        out = policy.step(Observation(image=image, proprio=np.zeros(16, np.float32), step=step))
        assert isinstance(out, PolicyStep)
        action = np.asarray(out.action, dtype=np.float64)
        assert action.shape == (ACTION_DIM,)
        assert np.all(np.isfinite(action)) and np.all(action >= low) and np.all(action <= high)
        actions.append(action)
    return actions


@pytest.mark.parametrize("name", stateless_policies())
def test_steps_are_actions_of_the_space_and_reproducible(name):
    policy = build(name)
    if policy.info.privileged:
        pytest.skip("privileged: stepped in the simulator tests")
    first, again = episode(policy, seed=1), episode(policy, seed=1)
    assert all(np.array_equal(a, b) for a, b in zip(first, again, strict=True))


def test_random_differs_between_seeds_and_noop_holds_still():
    rand = build("random")
    assert not np.array_equal(episode(rand, 1)[0], episode(rand, 2)[0])
    noop = episode(build("noop"), 1)
    assert all(np.array_equal(a, noop[0]) for a in noop)
    assert np.all(noop[0][:-1] == 0) and noop[0][-1] == 1.0  # no motion, gripper open


def test_the_registry_remembers_an_entrys_extra_after_importing_it():
    from ladev_lib.registry import Registry

    reg: Registry[object] = Registry("thing")
    reg.add_lazy("json", "json:dumps", extra="fancy")
    assert reg.extra_of("json") == "fancy"
    reg.get("json")
    assert reg.extra_of("json") == "fancy" and reg.module_of("json") == "json"
