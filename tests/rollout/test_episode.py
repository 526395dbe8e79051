"""The episode loop on the toy simulator: outcomes, error rows, observations, media."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.rollout.episode import run_episode
from ladev_lib.rollout.jobs import EpisodeJob, MediaOptions
from ladev_lib.rollout.simulator import SimSetup
from ladev_lib.scenes.sampling import sample_scene
from tests.rollout.doubles import MAX_STEPS, ScriptedToyPolicy, ToySim


@pytest.fixture
def spec(catalog):
    return sample_scene("pick_up", 2, "simpler", np.random.default_rng(0), catalog, seed=0, scene_id="ep")


def toy_sim(image_size=(32, 24)):
    return ToySim(SimSetup({}, {}, "panda", "toy_delta_xy", image_size))


def job(spec, instruction="pick it up", seed=0, stop_on_success=False):
    return EpisodeJob("e1", spec, instruction, seed, stop_on_success)


class RecordingPolicy(Policy):
    """Not privileged; records what it was shown; stops after ``stop_after`` steps."""

    def __init__(self, image_size=None, stop_after=None):
        self.info = PolicyInfo("recording", ("panda",), "toy_delta_xy", image_size=image_size)
        self.seen: list[Observation] = []
        self.stop_after = stop_after

    def reset(self, instruction):
        self.seen.clear()

    def step(self, obs):
        self.seen.append(obs)
        stop = self.stop_after is not None and len(self.seen) >= self.stop_after
        return PolicyStep(np.zeros(2), terminate=stop)


class LeavingPolicy(ScriptedToyPolicy):
    """Reaches the goal, then drives away from it after ``leave_at`` steps."""

    def __init__(self, leave_at: int) -> None:
        super().__init__()
        self.leave_at = leave_at

    def step(self, obs):
        if obs.step >= self.leave_at:
            return PolicyStep(np.ones(2))
        return super().step(obs)


def test_episode_runs_to_the_limit_and_records_the_first_success(spec):
    out = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec))
    assert out.status == "success" and out.success is True and out.success_any is True
    assert out.predicates == {"reached": True, "success": True}
    assert out.steps == MAX_STEPS  # SimplerEnv's protocol: success does not end the episode
    assert 0 < out.first_success_step < MAX_STEPS
    assert out.total_seconds >= out.sim_seconds + out.policy_seconds - 1e-3


def test_stop_on_success_ends_at_the_first_success(spec):
    out = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec, stop_on_success=True))
    full = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec))
    assert out.success is True and out.steps == out.first_success_step == full.first_success_step


def test_success_lost_before_the_end_counts_at_any_step_only(spec):
    out = run_episode(toy_sim(), LeavingPolicy(leave_at=30), job(spec))
    assert (out.status, out.success, out.success_any) == ("failure", False, True)
    assert out.first_success_step is not None and out.first_success_step <= 30
    never = run_episode(toy_sim(), ScriptedToyPolicy(gain=0.0), job(spec))
    assert (never.success, never.success_any, never.first_success_step) == (False, False, None)


def test_step_limit_is_a_failure(spec):
    out = run_episode(toy_sim(), ScriptedToyPolicy(gain=0.0), job(spec))
    assert (out.status, out.success, out.steps) == ("failure", False, MAX_STEPS)


def test_terminate_flag_stops_early(spec):
    policy = RecordingPolicy(stop_after=3)
    out = run_episode(toy_sim(), policy, job(spec))
    assert (out.status, out.steps) == ("failure", 3)


def test_observations_hold_only_what_the_policy_declares(spec):
    blind = RecordingPolicy(image_size=None, stop_after=2)
    run_episode(toy_sim(), blind, job(spec))
    assert all(o.image is None and o.privileged is None for o in blind.seen)
    assert [o.step for o in blind.seen] == [0, 1]
    assert blind.seen[0].proprio is not None

    seeing = RecordingPolicy(image_size=(32, 24), stop_after=1)
    run_episode(toy_sim(), seeing, job(spec))
    assert seeing.seen[0].image.shape == (24, 32, 3)
    assert seeing.seen[0].privileged is None


def test_a_rerun_gives_the_same_outcome(spec):
    a = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec, seed=5))
    b = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec, seed=5))
    keep = {"status", "success", "predicates", "steps", "robot", "error"}
    assert a.model_dump(include=keep) == b.model_dump(include=keep)


@pytest.mark.parametrize(
    ("instruction", "scene_id", "status", "error_start"),
    [
        ("pick it up", "x-sim-crash", "error", "simulator: RuntimeError: injected simulator failure"),
        ("raise", "x", "error", "policy: ValueError: injected policy failure"),
        ("nan", "x", "error", "action: step 1: contains NaN"),
        ("shape", "x", "error", "action: step 1: shape (3,), the action space is (2,)"),
        ("pick it up", "x-bad-scene", "invalid_scene", "objects interpenetrate at spawn"),
    ],
)
def test_failures_become_rows_with_reasons(catalog, instruction, scene_id, status, error_start):
    spec = sample_scene("pick_up", 1, "simpler", np.random.default_rng(1), catalog, seed=1, scene_id=scene_id)
    out = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec, instruction))
    assert out.status == status and out.success is None
    assert out.error is not None and out.error.startswith(error_start), out.error


def test_frames_and_video_of_failures(spec, tmp_path):
    media = MediaOptions(root=str(tmp_path), prefix="media/toy", video="failures", frames=True, fps=5)
    ok = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec), media)
    assert ok.video_path is None  # a success: no video under "failures"
    assert ok.first_frame_path == "media/toy/e1_first.png"
    first = np.asarray(Image.open(tmp_path / "e1_first.png"))
    last = np.asarray(Image.open(tmp_path / "e1_last.png"))
    assert first.shape == (24, 32, 3) and not np.array_equal(first, last)

    failed = run_episode(toy_sim(), ScriptedToyPolicy(gain=0.0), job(spec), media)
    assert failed.video_path == "media/toy/e1.mp4"
    import imageio.v2 as imageio

    frames = imageio.mimread(tmp_path / "e1.mp4")
    assert len(frames) == MAX_STEPS + 1  # every observation and the final state


def test_invalid_scene_keeps_a_picture_of_what_was_judged(catalog, tmp_path):
    spec = sample_scene("pick_up", 1, "simpler", np.random.default_rng(1), catalog, seed=1, scene_id="x-bad-scene")
    media = MediaOptions(root=str(tmp_path), prefix="m", video="all", frames=True)
    out = run_episode(toy_sim(), ScriptedToyPolicy(), job(spec), media)
    assert out.status == "invalid_scene"
    assert out.first_frame_path == "m/e1_first.png" and (tmp_path / "e1_first.png").exists()
    assert out.video_path is None


def test_a_scene_for_another_robot_runs_with_the_policys_first_robot(catalog, tmp_path):
    from ladev_lib.rollout.episode import choose_robot
    from ladev_lib.rollout.jobs import WorkerSpec
    from ladev_lib.rollout.worker import EpisodeWorker
    from tests.rollout.doubles import make_scripted_policy, make_toy_sim

    assert choose_robot("widowx", ("panda", "widowx")) == "widowx"
    assert choose_robot("widowx", ("panda",)) == "panda"
    spec = sample_scene("pick_up", 1, "simpler", np.random.default_rng(2), catalog, robot="widowx", seed=2)
    worker = EpisodeWorker(WorkerSpec("toy", {}, {}, {}, MediaOptions(str(tmp_path), "m", frames=False),
                                      sim_factory=make_toy_sim, policy_factory=make_scripted_policy))
    out = worker.run(job(spec))
    assert out.robot == "panda" and out.status == "success"
    (built,) = worker._sims.values()
    assert built.setup.robot == "panda"
