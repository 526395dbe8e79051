"""The policy server and the remote policy end to end on loopback."""

from __future__ import annotations

import threading
import time
import urllib.request

import msgpack
import numpy as np
import pytest
from websockets.sync.client import connect

from ladev_lib.errors import ConfigError
from ladev_lib.policies import make_policy
from ladev_lib.policies.base import Observation, PolicyStep
from ladev_lib.policies.remote import RemotePolicy, RemotePolicyError, resize_with_pad
from ladev_lib.serving.codec import packb, unpackb
from tests.serving.conftest import serve_in_thread
from tests.serving.scripted import ScriptedPolicy

IMAGE = np.full((48, 64, 3), 10, dtype=np.uint8)
PROPRIO = np.array([0.5, 0.25, 0.25], dtype=np.float32)


def _obs() -> Observation:
    return Observation(image=IMAGE, proprio=PROPRIO)


def test_handshake_announces_policy_info_and_keys() -> None:
    with serve_in_thread(ScriptedPolicy()) as (url, _):
        policy = make_policy("remote", url=url, wait_for_server_s=5)
        try:
            assert policy.server_metadata["protocol"] == "openpi-websocket"
            assert policy.server_metadata["server"] == "ladev"
            info = policy.info
            assert info.name == "scripted" and info.robots == ("widowx",)
            assert info.control_mode.startswith("arm_pd_ee_target_delta_pose")
            assert info.image_size == (64, 48) and info.camera == "3rd_view_camera"
            assert info.episode_steps_for("put_in") == 120 and info.episode_steps_for("put_on") == 60
        finally:
            policy.close()


def test_inference_episodes_and_reset() -> None:
    scripted = ScriptedPolicy()
    with (
        serve_in_thread(scripted) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5) as policy,
    ):
        policy.reset("put the spoon on the towel")
        steps = [policy.step(_obs()) for _ in range(3)]
        first = steps[0].action
        assert first.shape == (7,)
        assert first[0] == 0 and first[1] == len("put the spoon on the towel")
        assert first[2] == pytest.approx(10.0) and first[3] == pytest.approx(1.0)
        assert [s.action[0] for s in steps] == [0, 1, 2]
        assert [s.terminate for s in steps] == [False, False, True]
        # Same instruction again: the reset flag still starts a new episode on the server.
        policy.reset("put the spoon on the towel")
        again = policy.step(_obs())
        assert again.action[0] == 0 and again.action[4] == 2
    assert scripted.resets == 2


def test_healthz_and_inference_off_the_event_loop() -> None:
    """/healthz answers while a slow step runs: inference does not block the loop."""
    with serve_in_thread(ScriptedPolicy(delay_s=1.5)) as (url, _):
        http_url = url.replace("ws://", "http://") + "/healthz"
        with RemotePolicy(url=url, wait_for_server_s=5, step_timeout_s=10) as policy:
            policy.reset("pick up the coke can")
            worker = threading.Thread(target=policy.step, args=(_obs(),))
            worker.start()
            time.sleep(0.3)
            started = time.monotonic()
            with urllib.request.urlopen(http_url, timeout=5) as resp:
                assert resp.status == 200 and resp.read() == b"OK\n"
            assert time.monotonic() - started < 1.0
            worker.join(10)


def test_server_error_is_reported_with_its_traceback() -> None:
    with (
        serve_in_thread(ScriptedPolicy(fail_at_step=1)) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5) as policy,
    ):
        policy.reset("pick up the coke can")
        policy.step(_obs())
        with pytest.raises(RemotePolicyError, match="reported an error") as err:
            policy.step(_obs())
        assert "ValueError: scripted failure at step 1" in str(err.value)
        # The next episode reconnects and works.
        policy.reset("pick up the coke can")
        assert policy.step(_obs()).action[0] == 0


def test_slow_server_beyond_the_timeout() -> None:
    with (
        serve_in_thread(ScriptedPolicy(delay_s=1.0)) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5, step_timeout_s=0.3) as policy,
    ):
        policy.reset("pick up the coke can")
        started = time.monotonic()
        with pytest.raises(RemotePolicyError, match=r"no action within 0.3 s"):
            policy.step(_obs())
        assert time.monotonic() - started < 0.9


def test_server_killed_mid_episode_then_restarted(server_process) -> None:
    server = server_process()
    policy = RemotePolicy(url=server.url, wait_for_server_s=10, retry_interval_s=0.2)
    try:
        policy.reset("move the apple near the sponge")
        assert policy.step(_obs()).action[0] == 0
        server.kill()
        with pytest.raises(RemotePolicyError, match="lost"):
            policy.step(_obs())
        # A server back on the same port: the next episode reconnects.
        restarted = server_process("--port", str(server.port))
        assert restarted.port == server.port
        policy.reset("move the apple near the sponge")
        assert policy.step(_obs()).action[0] == 0
        # Killed between episodes: the next reset notices and reconnects, no error.
        restarted.kill()
        again = server_process("--port", str(server.port))
        policy.reset("move the apple near the sponge")
        assert policy.step(_obs()).action[0] == 0
        assert again.proc.poll() is None
    finally:
        policy.close()


def test_no_server_fails_after_the_retry_window() -> None:
    started = time.monotonic()
    with pytest.raises(RemotePolicyError, match="no policy server reachable"):
        RemotePolicy(url="ws://127.0.0.1:9", wait_for_server_s=0.5, retry_interval_s=0.1)
    assert time.monotonic() - started < 5


def test_api_key_required(monkeypatch: pytest.MonkeyPatch) -> None:
    with serve_in_thread(ScriptedPolicy(), api_key="s3cret") as (url, _):
        with pytest.raises(RemotePolicyError, match="refused the API key"):
            RemotePolicy(url=url, wait_for_server_s=1)
        monkeypatch.setenv("TEST_POLICY_KEY", "wrong")
        with pytest.raises(RemotePolicyError, match="refused the API key"):
            RemotePolicy(url=url, wait_for_server_s=1, api_key_env="TEST_POLICY_KEY")
        monkeypatch.setenv("TEST_POLICY_KEY", "s3cret")
        with RemotePolicy(url=url, wait_for_server_s=1, api_key_env="TEST_POLICY_KEY") as policy:
            policy.reset("pick up the coke can")
            assert policy.step(_obs()).action.shape == (7,)
        # Health checks need no key.
        with urllib.request.urlopen(url.replace("ws://", "http://") + "/healthz", timeout=5) as resp:
            assert resp.status == 200


def test_missing_api_key_env_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match="NOT_SET_ANYWHERE"):
        RemotePolicy(url="ws://127.0.0.1:9", api_key_env="NOT_SET_ANYWHERE")


def test_binds_to_loopback_by_default() -> None:
    with serve_in_thread(ScriptedPolicy()) as (url, _):
        assert url.startswith("ws://127.0.0.1:")
    from ladev_lib.serving.server import PolicyServer

    assert PolicyServer(ScriptedPolicy()).host == "127.0.0.1"


def test_malicious_payload_is_refused_without_unpickling(tmp_path) -> None:
    import pickle

    from tests.serving.test_codec import _Payload

    marker = tmp_path / "marker"
    scripted = ScriptedPolicy()
    with serve_in_thread(scripted) as (url, _), connect(url, open_timeout=5) as ws:
        unpackb(ws.recv(timeout=5))  # metadata
        evil = {
            b"__ndarray__": True,
            b"data": pickle.dumps(_Payload(str(marker))),
            b"dtype": "|O",
            b"shape": [1],
        }
        ws.send(msgpack.packb({"prompt": "x", "observation/image": evil}, use_bin_type=True))
        reply = ws.recv(timeout=5)
        assert isinstance(reply, str) and "refused dtype" in reply
    assert not marker.exists() and scripted.resets == 0


def test_second_client_is_refused_while_one_is_connected() -> None:
    with (
        serve_in_thread(ScriptedPolicy()) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5),
        pytest.raises(RemotePolicyError, match="server busy"),
    ):
        RemotePolicy(url=url, wait_for_server_s=1)


def test_bad_observation_is_a_server_error() -> None:
    with serve_in_thread(ScriptedPolicy()) as (url, _), connect(url, open_timeout=5) as ws:
        unpackb(ws.recv(timeout=5))
        ws.send(packb({"prompt": "x", "observation/image": np.zeros((4, 4), dtype=np.float32)}))
        reply = ws.recv(timeout=5)
        assert isinstance(reply, str) and "(H, W, 3) uint8" in reply


@pytest.mark.filterwarnings(r"ignore:connect\(\) must be used:DeprecationWarning")
def test_openpi_client_talks_to_our_server() -> None:
    client_mod = pytest.importorskip("openpi_client.websocket_client_policy")
    with serve_in_thread(ScriptedPolicy()) as (url, _):
        port = int(url.rsplit(":", 1)[1])
        client = client_mod.WebsocketClientPolicy(host="127.0.0.1", port=port)
        assert client.get_server_metadata()["policy"]["name"] == "scripted"
        out = client.infer({"observation/image": IMAGE, "observation/state": PROPRIO, "prompt": "pick up"})
        assert out["actions"].shape == (7,) and out["actions"][1] == len("pick up")
        assert "infer_ms" in out["server_timing"]
        # No reset flag from openpi's client: a new prompt starts a new episode.
        out = client.infer({"observation/image": IMAGE, "prompt": "pick up"})
        assert out["actions"][0] == 1
        out = client.infer({"observation/image": IMAGE, "prompt": "open the drawer"})
        assert out["actions"][0] == 0


def test_openpi_style_server_with_chunks_and_custom_keys() -> None:
    """An openpi-like server (no LADEV metadata, nested keys, action chunks)."""
    import asyncio

    from websockets.asyncio.server import serve

    seen: list[dict] = []

    async def handler(ws):
        await ws.send(packb({"some": "openpi metadata"}))
        async for message in ws:
            obs = unpackb(message)
            seen.append(obs)
            chunk = np.arange(10 * 8, dtype=np.float32).reshape(10, 8) + 1000 * len(seen)
            await ws.send(packb({"actions": chunk, "server_timing": {"infer_ms": 1.0}}))

    loop = asyncio.new_event_loop()
    ready = threading.Event()
    port: list[int] = []
    stop = asyncio.Event()

    async def main():
        async with serve(handler, "127.0.0.1", 0) as srv:
            port.append(srv.sockets[0].getsockname()[1])
            ready.set()
            await stop.wait()

    thread = threading.Thread(target=loop.run_until_complete, args=(main(),), daemon=True)
    thread.start()
    assert ready.wait(10)
    try:
        with pytest.raises(ConfigError, match="set robots, control_mode"):
            RemotePolicy(url=f"ws://127.0.0.1:{port[0]}", wait_for_server_s=2)
        policy = RemotePolicy(
            url=f"ws://127.0.0.1:{port[0]}",
            keys={"image": "images.cam_high", "state": "state", "prompt": "prompt", "reset": None,
                  "action": "actions", "terminate": None},
            robots=["widowx"],
            control_mode="arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos",
            image_size=[640, 480],
            replan_steps=4,
            action_dim=7,
            resize_to=[224, 224],
        )
        with policy:
            assert policy.info.image_size == (640, 480) and policy.info.robots == ("widowx",)
            policy.reset("put eggplant into basket")
            frame = np.full((480, 640, 3), 200, dtype=np.uint8)
            actions = [policy.step(Observation(image=frame, proprio=np.zeros(3))).action for _ in range(6)]
        assert len(seen) == 2  # steps 0-3 from the first chunk, 4-5 from the second
        assert set(seen[0]) == {"images", "state", "prompt"}
        assert seen[0]["images"]["cam_high"].shape == (224, 224, 3)
        assert [a.shape for a in actions] == [(7,)] * 6
        assert actions[0][0] == 1000 and actions[3][0] == 1000 + 3 * 8 and actions[4][0] == 2000
    finally:
        loop.call_soon_threadsafe(stop.set)
        thread.join(10)


def test_resize_with_pad_keeps_aspect_ratio() -> None:
    img = np.full((480, 640, 3), 255, dtype=np.uint8)
    out = resize_with_pad(img, 224, 224)
    assert out.shape == (224, 224, 3)
    assert out[:27].max() == 0 and out[-27:].max() == 0  # 640x480 -> 224x168, 28 rows pad
    assert out[112, 112].tolist() == [255, 255, 255]


def test_plain_http_server_is_not_a_policy_server() -> None:
    import http.server

    httpd = http.server.HTTPServer(("127.0.0.1", 0), http.server.SimpleHTTPRequestHandler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    try:
        with pytest.raises(RemotePolicyError, match="HTTP|handshake"):
            RemotePolicy(url=f"ws://127.0.0.1:{httpd.server_port}", wait_for_server_s=1)
    finally:
        httpd.shutdown()


class _Sampling(ScriptedPolicy):
    """Draws its action from NumPy's global generator, as sampling policies do."""

    def step(self, obs: Observation) -> PolicyStep:
        return PolicyStep(action=np.random.uniform(-1, 1, size=7).astype(np.float32))


def test_the_episode_seed_reaches_the_server_and_seeds_its_generators() -> None:
    from ladev_lib.policies.base import EpisodeContext

    def episode(policy: RemotePolicy, seed: int) -> list[float]:
        policy.begin_episode(EpisodeContext(seed=seed, robot="widowx",
                                            action_low=-np.ones(7), action_high=np.ones(7)))
        policy.reset("put the spoon on the towel")
        return [float(v) for _ in range(2) for v in policy.step(_obs()).action]

    with (
        serve_in_thread(_Sampling()) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5) as policy,
    ):
        first, other, again = episode(policy, 7), episode(policy, 8), episode(policy, 7)
    assert first == again and first != other
    # Without a seed key the server leaves its generators alone.
    with (
        serve_in_thread(_Sampling()) as (url, _),
        RemotePolicy(url=url, wait_for_server_s=5, keys={"seed": None}) as policy,
    ):
        assert episode(policy, 7) != episode(policy, 7)
