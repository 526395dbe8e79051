"""Can SAPIEN render on this machine? A probe that takes one real picture.

Finding a Vulkan device is not enough (Debian 12's Mesa 22 lavapipe is found
but cannot run SAPIEN), so the probe builds a scene with a red box and checks
the pixel it renders. It runs in a child process, because a broken driver can
crash or hang the process that loads it.

    python -m ladev_lib.sim.render_probe            # prints the verdict
    python -m ladev_lib.sim.render_probe --quiet    # exit status only
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from dataclasses import asdict, dataclass

_CHILD = r"""
import json, re, warnings
warnings.filterwarnings("ignore")
import sapien
summary = sapien.render.get_device_summary()
m = re.search(r"GPU:\s*(.+)", summary)
scene = sapien.Scene()
scene.set_ambient_light([1.0, 1.0, 1.0])
builder = scene.create_actor_builder()
builder.add_box_visual(half_size=[0.2, 0.2, 0.2], material=[1.0, 0.0, 0.0])
builder.build_kinematic()
camera = scene.add_camera("probe", 32, 32, 1.0, 0.01, 10.0)
camera.set_local_pose(sapien.Pose([-1.0, 0.0, 0.0]))
scene.update_render()
camera.take_picture()
rgba = camera.get_picture("Color")
r, g, b = (float(v) for v in rgba[16, 16, :3])
print(json.dumps({"device": m.group(1).strip() if m else summary.strip(), "rgb": [r, g, b]}))
"""


@dataclass(frozen=True)
class RenderProbe:
    """Outcome of a probe: ``ok`` when a red box rendered red."""

    ok: bool
    device: str | None
    error: str | None


def probe_rendering(python: str = sys.executable, timeout_s: float = 120.0) -> RenderProbe:
    """Render one picture in a child process and report the device used."""
    try:
        done = subprocess.run(
            [python, "-c", _CHILD], capture_output=True, text=True, timeout=timeout_s
        )
    except subprocess.TimeoutExpired:
        return RenderProbe(False, None, f"rendering probe hung for {timeout_s:.0f} s")
    lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
    if done.returncode != 0 or not lines:
        tail = (done.stderr or done.stdout).strip().splitlines()[-1:] or ["no output"]
        return RenderProbe(False, None, f"exit {done.returncode}: {tail[0]}")
    result = json.loads(lines[-1])
    r, g, b = result["rgb"]
    if r > 0.3 and g < 0.2 and b < 0.2:
        return RenderProbe(True, result["device"], None)
    return RenderProbe(False, result["device"], f"rendered pixel {result['rgb']} is not red")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quiet", action="store_true", help="print nothing; exit status only")
    parser.add_argument("--name-only", action="store_true", help="print the device name")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    args = parser.parse_args(argv)
    result = probe_rendering()
    if args.json:
        print(json.dumps(asdict(result)))
    elif args.name_only:
        print(result.device or "none")
    elif not args.quiet:
        print(f"rendering: ok on {result.device}" if result.ok else f"rendering: FAILED ({result.error})")
    return 0 if result.ok else 1


if __name__ == "__main__":
    sys.exit(main())
