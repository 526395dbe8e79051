"""Score the scene compiler on labelled scene descriptions (scene-exact and per field).

    rows = load_description_rows(Path("../shared/dev/scene_descriptions_dev.jsonl"))
    result = evaluate_descriptions(rows, compile_fn)
    result.summary()["scene_exact"], result.per_field

A row is ``{"id", "style", "description", "expected": {...}}`` in the
conventions of ``../shared/dev/README.md``: object names are catalog display
names, lighting is a direction and a positive magnitude (``null``: no change),
the camera is ``translate_cm`` ``[x, y, z]`` in the camera's frame (x right,
y forward, z up) and ``rotate_deg`` with yaw + = pan right, pitch + = tilt up,
roll + = clockwise seen from behind. The scene spec's own frame differs
(x away from the robot, y to its left; yaw + pans left, pitch + tilts down);
:func:`camera_in_description_frame` converts.

What is scored, per row, from one compile of the description (no instruction
given, the task read from the text):

- ``n_objects``: the compiled scene's object count;
- ``required_objects``: every named object (a multiset) is in the scene;
- ``task``: type, object and target (for an infeasible task, the names read);
- ``lighting`` / ``camera``: what was asked for (before clamping to the
  study's bounds, so that out-of-range requests are scored on the reading);
- ``positions``: each stated coarse location is read for its object;
- ``unavailable``: the objects reported as not in the catalog, by name;
- ``feasibility``: the scene compiles exactly when its task is feasible.

A row is scene-exact when every field is right. Nothing here raises for a bad
row: a compile that fails counts against the fields it decides.
"""

from __future__ import annotations

import json
import re
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ladev_lib.catalog import Catalog
from ladev_lib.scenes.operations import SceneOperations
from ladev_lib.scenes.resolve import ObjectResolver
from ladev_lib.scenes.spec import SceneBounds, SceneSpec

FIELDS = (
    "n_objects", "required_objects", "task", "lighting", "camera", "positions", "unavailable", "feasibility",
)
_TOL_CM = 0.05
_TOL_DEG = 0.05
_TOL_LIGHT = 0.005


@dataclass(frozen=True)
class CompileView:
    """What one compile gave, as the scorer needs it (no dependency on the compiler's classes)."""

    status: str
    reason: str | None
    operations: SceneOperations | None
    spec: SceneSpec | None
    notes: tuple[str, ...] = ()


CompileFn = Callable[[str], CompileView]
"""Description text -> its compile."""


@dataclass
class RowScore:
    id: str
    style: str
    fields: dict[str, bool]
    errors: dict[str, str] = field(default_factory=dict)
    status: str = ""
    reason: str | None = None

    @property
    def exact(self) -> bool:
        return all(self.fields.values())


@dataclass
class DescriptionEval:
    rows: list[RowScore]

    @property
    def per_field(self) -> dict[str, float]:
        n = len(self.rows) or 1
        return {f: sum(r.fields[f] for r in self.rows) / n for f in FIELDS}

    @property
    def scene_exact(self) -> float:
        return sum(r.exact for r in self.rows) / (len(self.rows) or 1)

    def per_style(self) -> dict[str, float]:
        styles: dict[str, list[bool]] = {}
        for r in self.rows:
            styles.setdefault(r.style, []).append(r.exact)
        return {s: sum(v) / len(v) for s, v in sorted(styles.items())}

    def summary(self) -> dict[str, Any]:
        return {
            "rows": len(self.rows),
            "scene_exact": round(self.scene_exact, 3),
            "per_field": {k: round(v, 3) for k, v in self.per_field.items()},
            "per_style": {k: round(v, 3) for k, v in self.per_style().items()},
        }


def load_description_rows(path: Path) -> list[dict[str, Any]]:
    """The labelled rows of a JSONL file (blank lines skipped)."""
    rows = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip():
            rows.append(json.loads(line))
    return rows


# -- conversions ----------------------------------------------------------------------


def camera_in_description_frame(
    translation_m: Sequence[float], rotation_deg: Sequence[float]
) -> tuple[list[float], dict[str, float]]:
    """Spec camera offset -> (translate_cm [right, forward, up], {yaw, pitch, roll}) of the dev conventions."""
    tx, ty, tz = translation_m
    roll, pitch, yaw = rotation_deg
    cm = [round(-ty * 100, 3), round(tx * 100, 3), round(tz * 100, 3)]
    return cm, {"yaw": round(-yaw, 3), "pitch": round(-pitch, 3), "roll": round(-roll, 3)}


def _norm(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", " ", text.lower()).strip()


class _Names:
    """Expected display names and read mentions -> catalog ids."""

    def __init__(self, catalog: Catalog, resolver: ObjectResolver) -> None:
        self.catalog, self.resolver = catalog, resolver
        self._cache: dict[str, str | None] = {}

    def id_of(self, name: str | None) -> str | None:
        if not name:
            return None
        if name not in self._cache:
            res = self.resolver.resolve(name)
            self._cache[name] = res.obj.id if res.obj is not None else None
        return self._cache[name]


def _requested_lighting(ops: SceneOperations | None) -> dict[str, Any] | None:
    if ops is None or not ops.lighting:
        return None
    op = ops.lighting[-1]
    if op.random or abs(op.intensity_delta) < 1e-9:
        return None if not op.random else {"direction": "random", "magnitude": None}
    return {"direction": "brighter" if op.intensity_delta > 0 else "darker", "magnitude": abs(op.intensity_delta)}


def _requested_camera(ops: SceneOperations | None) -> tuple[list[float], dict[str, float]] | None:
    if ops is None or not ops.camera:
        return None
    t = [sum(op.translation_m[k] for op in ops.camera) for k in range(3)]
    r = [sum(op.rotation_deg[k] for op in ops.camera) for k in range(3)]
    if not any(abs(v) > 1e-9 for v in (*t, *r)):
        return None
    return camera_in_description_frame(t, r)


def _score_lighting(expected: dict[str, Any] | None, got: dict[str, Any] | None) -> str | None:
    if expected is None:
        return None if got is None else f"expected no change, read {got}"
    if got is None:
        return f"expected {expected}, read no change"
    if got["direction"] != expected["direction"]:
        return f"expected {expected}, read {got}"
    if expected.get("magnitude") is not None and abs(got["magnitude"] - expected["magnitude"]) > _TOL_LIGHT:
        return f"expected {expected}, read {got}"
    return None


def _score_camera(expected: dict[str, Any] | None, got: tuple[list[float], dict[str, float]] | None) -> str | None:
    want_t = (expected or {}).get("translate_cm") or [0.0, 0.0, 0.0]
    want_r = {"yaw": 0.0, "pitch": 0.0, "roll": 0.0, **((expected or {}).get("rotate_deg") or {})}
    have_t, have_r = got if got is not None else ([0.0, 0.0, 0.0], {"yaw": 0.0, "pitch": 0.0, "roll": 0.0})
    ok = all(abs(a - b) <= _TOL_CM for a, b in zip(want_t, have_t, strict=True)) and all(
        abs(want_r[k] - have_r[k]) <= _TOL_DEG for k in ("yaw", "pitch", "roll")
    )
    return None if ok else f"expected {expected}, read translate_cm={have_t} rotate_deg={have_r}"


def _read_positions(ops: SceneOperations | None, names: _Names) -> list[tuple[str | None, str]]:
    """(object id, where) for every object the reading placed coarsely."""
    out: list[tuple[str | None, str]] = []
    if ops is None:
        return out
    for op in ops.objects:
        pos = op.position
        if pos is None:
            continue
        oid = names.id_of(op.object)
        if pos.region is not None:
            for part in pos.region.split("_"):
                out.append((oid, part))
        if pos.relation is not None and pos.reference:
            ref = names.id_of(pos.reference)
            kind = {"left_of": "left", "right_of": "right", "in_front_of": "front", "behind": "back"}.get(
                pos.relation, "near"
            )
            out.append((oid, f"{kind}:{ref}" if kind != "near" else f"near:{ref}"))
            if kind != "near":
                out.append((oid, f"near:{ref}"))
    return out


def _unavailable(view: CompileView, names: _Names) -> list[str]:
    """Mentions the reading named that are not in the catalog."""
    ops = view.operations
    if ops is None:
        return []
    mentions = [op.object for op in ops.objects if op.object]
    if ops.task is not None:
        mentions += [m for m in (ops.task.source, ops.task.target) if m]
    out: list[str] = []
    for m in mentions:
        res = names.resolver.resolve(m)
        if not res.ok and _norm(m) not in {_norm(x) for x in out}:
            out.append(m)
    return out


def _same_unavailable(expected: str, read: str) -> bool:
    e, r = _norm(expected), _norm(read)
    return e == r or e in r.split() or f" {e} " in f" {r} " or e.rstrip("s") == r.rstrip("s")


def score_row(row: dict[str, Any], view: CompileView, names: _Names) -> RowScore:
    exp = row["expected"]
    errors: dict[str, str] = {}
    spec = view.spec
    feasible = exp.get("task_feasible", True)

    # feasibility: compiles exactly when the task is feasible
    if feasible and view.status != "ok":
        errors["feasibility"] = f"rejected: {view.reason}"
    elif not feasible and view.status == "ok":
        errors["feasibility"] = "compiled a scene whose task names an unavailable object"

    ids = [o.id for o in spec.objects] if spec is not None else []
    if feasible:
        if spec is None or len(ids) != exp["n_objects"]:
            errors["n_objects"] = f"expected {exp['n_objects']}, got {len(ids) if spec else 'no scene'}"
        want = Counter(names.id_of(n) for n in exp["required_objects"])
        missing = want - Counter(ids)
        if missing:
            errors["required_objects"] = f"missing {sorted(str(k) for k in missing.elements())} in {ids}"
    else:
        # no scene is expected: the count and the required objects are judged on the reading
        read_ids = [names.id_of(op.object) for op in view.operations.objects] if view.operations else []
        task_op = view.operations.task if view.operations is not None else None
        for mention in (task_op.source, task_op.target) if task_op is not None else ():
            oid = names.id_of(mention)
            if oid is not None and oid not in read_ids:
                read_ids.append(oid)  # the task's objects are the scene's (added when not described)
        read_ok = [i for i in read_ids if i is not None]
        n_read = len(read_ok) + sum(1 for op in (view.operations.objects if view.operations else []) if not op.object)
        if n_read != exp["n_objects"]:
            errors["n_objects"] = f"expected {exp['n_objects']}, read {n_read}"
        missing = Counter(names.id_of(n) for n in exp["required_objects"]) - Counter(read_ok)
        if missing:
            errors["required_objects"] = f"missing {sorted(str(k) for k in missing.elements())}"

    want_task = exp["task"]
    if spec is not None:
        got_task = (spec.task.type, spec.source.id, spec.target.id if spec.target is not None else None)
        want_ids = (want_task["type"], names.id_of(want_task["object"]), names.id_of(want_task.get("target")))
        if got_task != want_ids:
            errors["task"] = f"expected {want_ids}, got {got_task}"
    else:
        ops_task = view.operations.task if view.operations is not None else None
        if feasible or ops_task is None:
            errors["task"] = f"no scene ({view.reason})"
        else:
            got = (ops_task.type, _norm(ops_task.source or ""), _norm(ops_task.target or ""))
            want_names = (want_task["type"], _norm(want_task["object"]), _norm(want_task.get("target") or ""))
            if got[0] != want_names[0] or not all(
                (w == g) or (w and _same_unavailable(w, g)) or names.id_of(w) == names.id_of(g)
                for w, g in zip(want_names[1:], got[1:], strict=True)
            ):
                errors["task"] = f"expected {want_names}, read {got}"

    why = _score_lighting(exp.get("lighting"), _requested_lighting(view.operations))
    if why:
        errors["lighting"] = why
    why = _score_camera(exp.get("camera"), _requested_camera(view.operations))
    if why:
        errors["camera"] = why

    read_pos = _read_positions(view.operations, names)
    for p in exp.get("positions", []):
        oid = names.id_of(p["object"])
        where = p["where"]
        if where.startswith("near:"):
            where = f"near:{names.id_of(where[5:])}"
        if (oid, where) not in read_pos:
            errors["positions"] = f"{p['object']} {p['where']} not read (read {read_pos})"
            break

    got_unavail = _unavailable(view, names)
    want_unavail = list(exp.get("unavailable", []))
    matched = all(any(_same_unavailable(w, g) for g in got_unavail) for w in want_unavail)
    if not matched or len(got_unavail) != len(want_unavail):
        errors["unavailable"] = f"expected {want_unavail}, reported {got_unavail}"

    return RowScore(
        id=row["id"], style=row.get("style", ""), fields={f: f not in errors for f in FIELDS},
        errors=errors, status=view.status, reason=view.reason,
    )


def evaluate_descriptions(
    rows: Iterable[dict[str, Any]], compile_fn: CompileFn, catalog: Catalog, resolver: ObjectResolver
) -> DescriptionEval:
    """Compile each row's description and score it field by field."""
    names = _Names(catalog, resolver)
    scored = []
    for row in rows:
        try:
            view = compile_fn(str(row.get("description") or ""))
        except Exception as exc:  # a crash is a row with its reason, not an aborted evaluation
            view = CompileView("rejected", f"crashed: {type(exc).__name__}: {exc}", None, None)
        scored.append(score_row(row, view, names))
    return DescriptionEval(scored)


def format_table(results: dict[str, DescriptionEval]) -> str:
    """A Markdown table: one column per system, scene-exact and each field."""
    systems = list(results)
    head = "| measure | " + " | ".join(systems) + " |\n|---|" + "---|" * len(systems) + "\n"
    lines = [
        "| scene-exact | " + " | ".join(f"{results[s].scene_exact:.3f}" for s in systems) + " |"
    ]
    for f in FIELDS:
        lines.append(f"| {f} | " + " | ".join(f"{results[s].per_field[f]:.3f}" for s in systems) + " |")
    styles = sorted({r.style for s in systems for r in results[s].rows})
    for st in styles:
        lines.append(
            f"| exact, {st} | "
            + " | ".join(f"{results[s].per_style().get(st, 0.0):.3f}" for s in systems)
            + " |"
        )
    return head + "\n".join(lines) + "\n"


def offline_compile_fn(
    conf_dir: Path, overrides: Sequence[str] = (), max_objects: int = 7
) -> tuple[CompileFn, Catalog, ObjectResolver]:
    """The project's compiler as configured (offline backend unless overridden), without a cache."""
    from ladev_lib.catalog import load_catalog
    from ladev_lib.config import compose_config, section
    from ladev_lib.llm.config import LLMConfig, make_client
    from ladev_lib.llm.prompts import load_prompts
    from ladev_lib.scenes.compiler import CompileConfig
    from ladev_lib.scenes.text_to_scene import SceneCompiler, SceneText

    cfg = compose_config(list(overrides), conf_dir)
    llm = section(cfg, "llm", LLMConfig)
    compile_cfg = section(cfg, "compile", CompileConfig)
    prompt = load_prompts(cfg, ["compile_scene"])["compile_scene"]
    catalog = load_catalog(cfg.get("catalog"))
    # The study's bounds, with room for the largest scene the dev set describes (7 objects).
    bounds = SceneBounds(max_objects=max_objects)
    compiler = SceneCompiler(make_client(llm, None), prompt, llm, catalog, bounds, compile_cfg)
    counter = iter(range(1, 10**9))

    def compile_fn(text: str) -> CompileView:
        done = compiler.compile(SceneText(f"eval{next(counter)}", text, seed=0))
        return CompileView(done.status, done.reason, done.operations, done.spec, tuple(done.notes))

    return compile_fn, catalog, compiler.resolver


def scene_description_section(
    rows_path: Path,
    conf_dir: Path,
    baseline: dict[str, Any] | Sequence[dict[str, Any]] | None = None,
    systems: Sequence[tuple[str, Sequence[str]]] = (("LADEV", ()),),
) -> str:
    """The scene-description part of ``reports/language_eval.md``: stored figures, then each system per field.

    ``baseline``: one or more stored summaries (``label``, ``scene_exact``, ``per_field``), shown
    left of the measured columns in the given order. ``systems``: (label, config overrides) of the
    compilers measured now (``[("tagged", ["compile.reader=tagged"]), ("rules", ["compile.reader=rules"])]``).
    """
    rows = load_description_rows(rows_path)
    stored = [baseline] if isinstance(baseline, dict) else list(baseline or [])
    cols: dict[str, dict[str, Any]] = {str(b.get("label", "baseline")): b for b in stored}
    for label, overrides in systems:
        compile_fn, catalog, resolver = offline_compile_fn(conf_dir, overrides)
        cols[label] = evaluate_descriptions(rows, compile_fn, catalog, resolver).summary()
    names = list(cols)
    out = [f"{len(rows)} descriptions ({rows_path.name}); the compiler reads the task from the text.", ""]
    out.append("| measure | " + " | ".join(names) + " |")
    out.append("|---|" + "---|" * len(names))
    out.append("| scene-exact | " + " | ".join(f"{cols[n]['scene_exact']:.3f}" for n in names) + " |")
    for f in FIELDS:
        out.append(f"| {f} | " + " | ".join(f"{cols[n]['per_field'].get(f, 0.0):.3f}" for n in names) + " |")
    return "\n".join(out) + "\n"
