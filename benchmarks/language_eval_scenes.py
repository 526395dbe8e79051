"""Scene descriptions -> compiled scenes, scored against labelled rows (scene-exact and per field).

    PYTHONPATH=$PWD .venv/bin/python benchmarks/language_eval_scenes.py \
        [--rows ../shared/dev/scene_descriptions_dev.jsonl] [--json out.json] [--errors]

Uses the configured compiler (the offline backend by default) with no cache,
and prints the scores and compile rate. ``--errors`` lists each row that is
not scene-exact with the fields it got wrong.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ladev_lib.scenes.description_eval import (  # noqa: E402
    evaluate_descriptions,
    format_table,
    load_description_rows,
    offline_compile_fn,
)


def main() -> int:
    root = Path(__file__).resolve().parents[1]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=Path, default=root.parent / "shared" / "dev" / "scene_descriptions_dev.jsonl")
    parser.add_argument("--json", type=Path, default=None, help="write the summary and each row's errors here")
    parser.add_argument("--errors", action="store_true", help="print the rows that are not scene-exact")
    parser.add_argument("--label", default="LADEV")
    args = parser.parse_args()
    if not args.rows.exists():
        print(f"no rows at {args.rows}", file=sys.stderr)
        return 2
    rows = load_description_rows(args.rows)
    compile_fn, catalog, resolver = offline_compile_fn(root / "conf")
    start = time.perf_counter()
    result = evaluate_descriptions(rows, compile_fn, catalog, resolver)
    secs = time.perf_counter() - start
    print(f"language_eval_scenes: {len(rows)} descriptions from {args.rows}")
    print(format_table({args.label: result}))
    print(f"compiled in {secs:.2f} s ({len(rows) / secs:.1f} descriptions/s, no cache)")
    if args.errors:
        by_id = {r["id"]: r for r in rows}
        for r in result.rows:
            if not r.exact:
                print(f"\n{r.id} [{r.style}] {by_id[r.id]['description']}")
                for f, why in r.errors.items():
                    print(f"   {f}: {why}")
    if args.json is not None:
        out = {"label": args.label, **result.summary(),
               "errors": {r.id: r.errors for r in result.rows if not r.exact}}
        args.json.write_text(json.dumps(out, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
