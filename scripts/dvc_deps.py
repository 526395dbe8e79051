"""Check (and with --fix, complete) dvc.yaml's deps against each stage script's import closure.

    python scripts/dvc_deps.py          # list what each stage misses; exit 1 if anything
    python scripts/dvc_deps.py --fix    # add the missing paths under each stage's script line

The closure is ``ladev_lib.fingerprint``'s, the one used for episode ids and
LLM cache keys. tests/pipeline/test_dvc_deps.py runs the check.
"""

from __future__ import annotations

import argparse
import sys

from ladev_lib.fingerprint import REPO_ROOT, dvc_missing_deps

DVC_YAML = REPO_ROOT / "dvc.yaml"


def fix(missing: dict[str, list[str]]) -> None:
    lines = DVC_YAML.read_text().splitlines(keepends=True)
    out = []
    for line in lines:
        out.append(line)
        stripped = line.strip()
        for name, paths in missing.items():
            if stripped == f"- stages/{name}.py" and paths:
                indent = line[: len(line) - len(line.lstrip())]
                out.extend(f"{indent}- {p}\n" for p in paths)
    DVC_YAML.write_text("".join(out))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fix", action="store_true", help="add the missing deps to dvc.yaml")
    args = parser.parse_args()
    missing = dvc_missing_deps(DVC_YAML)
    for name, paths in missing.items():
        for p in paths:
            print(f"{name}: missing dep {p}")
    if args.fix and any(missing.values()):
        fix(missing)
        print(f"added to {DVC_YAML.name}; re-run to check")
        return 0
    return 1 if any(missing.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
