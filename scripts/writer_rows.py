"""Training rows for the reader's span tagger from the offline scene writer (markup known by construction).

    .venv/bin/python scripts/writer_rows.py [--rows 600] [-o training/scene_tagger/rows_writer.jsonl]

The offline writer (``ladev_lib.scenes.writer``) describes sampled scenes in
its five styles; with ``annotate=True`` it also writes the same text in the
tagger's markup. These rows teach the tagger the writer's own forms (command
lines with coordinates, "1 random", "SET LIGHTING +0.28"), which the studies
compile. The output is the same for the same arguments.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.scenes.writer import STYLES, write_scene  # noqa: E402

TASKS = ("pick_up", "move_near", "put_on", "put_in")
ENVIRONMENTS = ("default", "lighting", "camera")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=600)
    parser.add_argument("-o", "--output", type=Path, default=ROOT / "training" / "scene_tagger" / "rows_writer.jsonl")
    parser.add_argument("--seed", type=int, default=90_000, help="first scene seed (the studies use small ones)")
    args = parser.parse_args()
    catalog = load_catalog(None)
    lines = []
    k = 0
    seed = args.seed
    while len(lines) < args.rows:
        task, env, style = TASKS[k % 4], ENVIRONMENTS[(k // 4) % 3], STYLES[(k // 12) % len(STYLES)]
        objects = 1 + (k // 60) % 5
        object_set = "ycb" if (k // 7) % 2 else "simpler"
        k += 1
        seed += 1
        try:
            written = write_scene(task, objects, object_set, env, seed, catalog, style=style, annotate=True)
        except Exception:  # a design the sampler cannot place: skip it, as the studies would
            continue
        lines.append(json.dumps({
            "id": f"wr{len(lines) + 1:04d}", "style": f"writer_{style}", "annotated": written.annotated,
            "instruction": written.instruction, "expected": None,
        }, ensure_ascii=False))
    args.output.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"{len(lines)} rows -> {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
