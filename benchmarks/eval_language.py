"""The language report: instruction validation and scene descriptions, baseline vs LADEV.

    PYTHONPATH=$PWD .venv/bin/python benchmarks/eval_language.py [-o reports/language_eval.md]

Instruction sections: on every labelled pair set, side by side, the
similarity-only check (the paper's: cosine similarity of the sentences as
written, at the project threshold and at the threshold best for that very
set), main's validator before issue 11 (figures stored in
``reports/instruction_validator_baseline.json``, measured with
the same script against commit 920fa62), and LADEV's validator (similarity AND
equal grounded frames, in scene context when the set gives ``scene_objects``).
LIBERO-PRO's pairs (``../shared/dev/libero_pro_pairs.csv``) are scored per
suite. The scene-description section comes from
:func:`ladev_lib.scenes.description_eval.scene_description_section`.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from pathlib import Path

os.environ.setdefault("HF_HUB_OFFLINE", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ladev_lib.language.embeddings import load_embedder  # noqa: E402
from ladev_lib.language.evaluation import (  # noqa: E402
    LabelledPair,
    Scores,
    best_f1,
    load_labelled_pairs,
    score,
    threshold_sweep,
)
from ladev_lib.language.validator import DEFAULT_THRESHOLD, ParaphraseValidator, Verdict  # noqa: E402

DEV = ROOT.parent / "shared" / "dev"
SETS: dict[str, tuple[Path, str]] = {
    "paraphrase_pairs": (ROOT / "tests/data/paraphrase_pairs.csv", "project set, written before the parser (development)"),
    "paraphrase_pairs_holdout": (ROOT / "tests/data/paraphrase_pairs_holdout.csv", "project held-out set"),
    "open_vocab": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab.csv",
        "open vocabulary (office, kitchen, LIBERO-like), written for issue 11 (development)",
    ),
    "open_vocab_holdout": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout.csv",
        "open vocabulary held-out, written for issue 11 before it was first scored",
    ),
    "open_vocab_holdout2": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout2.csv",
        "second open-vocabulary held-out set (carrying to a receptacle, above, part synonyms, "
        "step-by-step and lift-from-move-to forms), written before it was first scored",
    ),
    "open_vocab_holdout3": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout3.csv",
        "third open-vocabulary held-out set (the four tasks; requests, needs, end states, clefts and "
        "fronting, step-by-step forms, verb / noun / modifier synonyms, with and without scene_objects), "
        "written blind (without reading the reader's code or tests) before it was scored, and scored once",
    ),
    "open_vocab_holdout4": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout4.csv",
        "fourth open-vocabulary held-out set (kitchen, office, workshop, LIBERO-like, play room; 30 with "
        "scene_objects), written blind by a helper that read neither code nor tests, scored once at b84dd1b",
    ),
    "open_vocab_holdout5": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout5.csv",
        "fifth open-vocabulary held-out set (bathroom, lab bench, garden shed, dining table, LIBERO-like "
        "kitchen, toys), written blind, scored once at c1f5114",
    ),
    "open_vocab_holdout6": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout6.csv",
        "sixth open-vocabulary held-out set (laundry, pharmacy, classroom, kitchen, LIBERO-like, SimplerEnv-like; "
        "35 with scene_objects), written blind, scored once at ea10124",
    ),
    "open_vocab_holdout7": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout7.csv",
        "seventh open-vocabulary held-out set (hospital tray, craft table, bakery, mechanic's bench, LIBERO-like, "
        "SimplerEnv-like; terse, rambling, dictated, non-native, LLM-verbose), written blind, scored once at 755df16",
    ),
    "open_vocab_holdout8": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout8.csv",
        "eighth open-vocabulary held-out set (recycling, nursery, picnic, laboratory, sewing, LIBERO-like, "
        "SimplerEnv-like), written blind, scored once at 2130271",
    ),
    "open_vocab_holdout9": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout9.csv",
        "ninth open-vocabulary held-out set (garden, lab, workshop, toys, bathroom, office; plurals, context "
        "sentences, step-by-step forms; 40 with scene_objects), written blind, scored once at 4d30df5",
    ),
    "open_vocab_holdout10": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout10.csv",
        "tenth open-vocabulary held-out set (hospital, school, garage, camping, pets, music room; learner "
        "English, chatty context, very short commands; 41 with scene_objects), written blind, scored once at 86ba673",
    ),
    "open_vocab_holdout11": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout11.csv",
        "eleventh open-vocabulary held-out set (100; fourteen kinds of rewording and twelve of meaning change, "
        "41 with scene_objects), written blind; scored once with the parser alone at 152d3a6 (1.000 / 0.673) and "
        "once with the second reading by the span tagger (0.962 / 0.909), before its rows were read",
    ),
    "open_vocab_holdout12": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout12.csv",
        "twelfth open-vocabulary held-out set (100; the same kinds, 42 with scene_objects), written blind after the "
        "second reading was settled; scored once with the parser alone at 152d3a6 (1.000 / 0.782) and once with "
        "the second reading (1.000 / 0.927), before its rows were read",
    ),
    "open_vocab_holdout13": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout13.csv",
        "thirteenth open-vocabulary held-out set (100, 55 same / 45 different, 41 with scene_objects), written blind "
        "by a helper given only the labelling rules; scored once at 8e7223f (with the retrained tagger) before its rows "
        "were read: 1.000 / 0.873 with the second reading, parser alone 1.000 / 0.800",
    ),
    "open_vocab_holdout14": (
        ROOT / "tests/data/paraphrase_pairs_open_vocab_holdout14.csv",
        "fourteenth open-vocabulary held-out set (100, 55 same / 45 different, 57 with scene_objects; kitchens, "
        "offices, labs, LIBERO-like scenes; end states, clefts, dictation, learner English among the rewordings, "
        "near-synonym swaps of objects present in the scene among the changes), written blind by a helper given "
        "only the labelling rules; scored once at 047f13e, before its rows were read: 1.000 / 1.000",
    ),
    "libero_pro": (DEV / "libero_pro_pairs.csv", "LIBERO-PRO paraphrases and task changes (dev data, written outside the team)"),
}
FIRST_SCORES: dict[str, tuple[float, float, str]] = {
    # set -> (precision, recall, how): the set's first score, before any change made for it
    "open_vocab_holdout": (0.889, 0.941, "written before scoring"),
    "open_vocab_holdout2": (1.000, 0.250, "written before scoring"),
    "open_vocab_holdout3": (0.933, 0.824, "blind"),
    "open_vocab_holdout4": (0.939, 0.920, "blind"),
    "open_vocab_holdout5": (1.000, 0.860, "blind"),
    "open_vocab_holdout6": (0.957, 0.818, "blind"),
    "open_vocab_holdout7": (0.981, 0.927, "blind"),
    "open_vocab_holdout8": (1.000, 0.927, "blind"),
    "open_vocab_holdout9": (0.930, 0.727, "blind"),
    "open_vocab_holdout10": (1.000, 0.782, "blind"),
    "open_vocab_holdout11": (0.962, 0.909, "blind, with the second reading; parser alone 1.000 / 0.673"),
    "open_vocab_holdout12": (1.000, 0.927, "blind, with the second reading; parser alone 1.000 / 0.782"),
    "open_vocab_holdout13": (1.000, 0.873, "blind, with the second reading; parser alone 1.000 / 0.800"),
    "open_vocab_holdout14": (1.000, 1.000, "blind, at 047f13e"),
}
"""First scores of the held-out sets: the held-out figures. Every later figure of a set is a
development figure (its errors were looked at and general fixes followed)."""
LIBERO_PRO_CITATION = (
    "LIBERO-PRO pairs: the language perturbations (labelled same) and task perturbations (labelled "
    "different) of LIBERO instructions from LIBERO-PRO (github.com/Zxy-MLlab/LIBERO-PRO, "
    "`libero_ood/ood_language.yaml`, `libero_ood/ood_task.yaml`), data under CC BY 4.0; the 111-pair "
    "subset in `../shared/dev/libero_pro_pairs.csv`. Cite LIBERO-PRO when reporting on it."
)


NOTES = (
    "LADEV now reads each sentence with the instruction parser and, where the parser cannot read an original "
    "or a candidate (\"not understood\"), reads it again with the span tagger (`paraphrase.second_reading`, "
    "`ladev_lib/language/tagged_frames.py`): the tagger marks the task's object and destination, the words of "
    "the task, a negation of it and anything asked beyond it, and each marked phrase is read by the parser "
    "alone. Where the parser did read the sentence and names what it does instead of the task (a negation, a "
    "spatial relation outside the four, taking the object away, another action), its reading stands. The "
    "tagger was trained on 1,905 annotated instructions written for it (`training/instruction_tagger/`) with "
    "the scene rows; none of the sets below. The 'parser alone' column is the same validator without the "
    "second reading.",
    "`open_vocab_holdout` was written before it was first scored and scored once: precision 0.889, "
    "recall 0.941 (2 false valid: \"water bottle\" for \"wine bottle\" accepted because an unknown "
    "modifier was ignored against a catalog object; \"dish\" for \"plate\" in a scene holding both, "
    "two scene names of one catalog object merged; 1 false invalid: \"move to the ladle, grasp it\", "
    "a pronoun after a movement to the object). The three general fixes that followed are in the "
    "figures below, so from then on it is a development set too.",
    "`open_vocab_holdout2` (42 pairs: carrying verbs + \"to\" a receptacle, \"above\", part and "
    "position synonyms, step-by-step and \"lift X from Y and move to Z\" forms) was written before it "
    "was first scored and scored once, before any change for it: precision 1.000, recall 0.250 (0 false "
    "valid, 15 false invalid: 6 carrying verb + \"to\" a receptacle read as move_near, 1 \"above\" "
    "not read as on, 4 part / position synonyms (rear/back, slot/compartment, upper/top, lower/bottom), "
    "1 \"lift ... from ... and move to\" read as taking away, 1 \"over to the rack and set it on "
    "top\" read as an extra step, and 2 rows whose original names a noun several catalog objects fit "
    "(\"the bottle\", \"the cup\") with no scene).",
    "After that first score, general rules (developed on LIBERO-PRO and on this set's errors): a "
    "carrying verb (move, bring, carry, take, transfer) + \"to\" a surface or receptacle head noun "
    "puts the object on / in it, \"to\" anything else stays near (\"over to\", sliding and pushing "
    "too); \"above\" after a putting verb is on; \"lift X from Y and move to Z\" carries X; \"over "
    "to the rack and set it on top\" completes the destination; rear/back, middle/center, upper/top, "
    "lower/bottom, slot/section/cubby/compartment compare as one word; at / in / on / from before a "
    "position (\"in the middle of the table\", \"from table center\") locate alike. Both sets are "
    "development sets from then on: no held-out figure after these fixes exists yet.",
    "Left: `open_vocab_holdout2`'s 2 rows whose original names a noun several catalog objects fit "
    "(\"the bottle\", \"the cup\") with no scene (not understood, by the catalog convention); "
    "`open_vocab`'s \"vessel\" for a scene's bowl (no name or head fits; MiniLM cosine of \"vessel\" "
    "and \"bowl\" 0.24, below the 0.60 grounding threshold).",
    "`open_vocab_holdout3` (67 pairs, 34 same / 33 different: the four tasks with requests, needs, "
    "end states, clefts and fronting, step-by-step forms, verb / noun / modifier synonyms, with and "
    "without `scene_objects`) was written blind (without reading the reader's code or tests) before "
    "it was first scored, and scored once with the reader unchanged: precision 0.933, recall 0.824 "
    "(2 false valid, 6 false invalid). False valid: 2 size / position modifiers on a non-catalog "
    "noun ignored (\"the small pot\" for \"the large pot\", \"the notebook on the right\" for \"the left "
    "notebook\"). False invalid: 2 step-by-step pick-ups (\"grab the hammer and lift it off the "
    "workbench\" read as an extra step and another object; \"move your gripper to the tape measure, "
    "close the gripper on it, and raise your arm\": no object found); 1 pseudo-cleft (\"next to the "
    "notebook is where the glue stick should go\": no object found); 1 verb restructuring (\"cover the"
    " pot with the lid\": \"cover\" is not a task); 2 groundings in a scene (scene \"bottle; glass; "
    "tray\": \"the bottle\" still ambiguous across the catalog; scene \"small bowl; large bowl; spoon\": "
    "both bowls grounded on the one catalog bowl, so source = destination). The fix that followed "
    "(sizes and positions stated on both sides must agree, a side after a determiner is a place, "
    "\"at the back\" after a destination says which part) removed both false valids with no other "
    "figure changing; from then on it is a development set too, in the zero-false-valid test. "
    "A second fix (the reader reads in the scene's context when no scene object is a catalog object; "
    "a size word fits only a scene object of that size; a source and destination the catalog reads "
    "as one object but the scene grounds on two are two objects) removed the 2 scene-grounding false "
    "invalids.",
    "Blind rounds (`open_vocab_holdout4` to `open_vocab_holdout10`, 90-100 pairs each): each set was written "
    "by a helper that read neither the reader's code nor its tests nor the earlier sets, only the labelling "
    "rules; it was scored once, at the commit named, before anything was changed for it (the 'first score' "
    "column); its errors were then read and general fixes made, so its later figure is a development "
    "figure. First scores, in order: 0.939 / 0.920, 1.000 / 0.860, 0.957 / 0.818, 0.981 / 0.927, "
    "1.000 / 0.927, 0.930 / 0.727, 1.000 / 0.782 (precision / recall; the targets are 0.97 / 0.90, met by rounds 7 "
    "and 8 only; rounds 9 and 10 brought plural objects, context sentences before the command, learner English "
    "and longer step-by-step forms). What the rounds "
    "taught (each a general rule with tests in our own words): step-by-step pick-ups and placements "
    "spelled as gripper motions (closing the gripper on a thing grasps it, lifting it off where it lies is "
    "a pick, moved above a thing and lowered inside / released onto it is put in / on); pseudo-clefts and "
    "stranded-preposition clefts; \"cover X with Y\"; \"what I'd like is for X to ...\"; result and "
    "manner clauses that restate the end state; \"the blue one\"; compound nouns ending in a verb form; "
    "measure nouns (\"a stick of chalk\"); a name the catalog reads as several objects stays free text "
    "that never equals one of them; two phrases the catalog reads as one object but with different head "
    "nouns are two objects (the lid and the pan); plain scene names with a phrase's head noun make a bare "
    "noun ambiguous; a destination is never the object moved; WordNet's noun hierarchy grounds generic "
    "words on plain names (\"the tool\" for a trowel, \"the cover\" for a lid, \"the drink\" for a "
    "milk carton).",
    "No scene given: a phrase grounds on the catalog, so \"plate\" and \"dinner plate\" (two catalog "
    "plates) stay different objects; with `scene_objects` (ids or names) \"dinner plate\" is the scene's "
    "plate.",
)


def _suites(path: Path) -> list[str]:
    import csv

    with open(path, newline="", encoding="utf-8") as f:
        return [(r.get("suite") or "") for r in csv.DictReader(f)]


def _pr(s: Scores) -> str:
    return f"{s.precision:.3f} / {s.recall:.3f}"


def _stored(baseline: dict[str, object], name: str) -> dict[str, object] | None:
    sets = baseline.get("sets")
    if isinstance(sets, dict):
        entry = sets.get(name)
        return entry if isinstance(entry, dict) else None
    return None


def instruction_sections(
    validator: ParaphraseValidator,
    baseline: dict[str, object],
    only: Sequence[str] | None = None,
    parser_only: ParaphraseValidator | None = None,
) -> tuple[list[str], dict[str, object]]:
    lines = [
        "## Instructions: paraphrase validation",
        "",
        f"Positive class: *valid* (same meaning). Cells are precision / recall. Similarity-only: "
        f"cosine similarity of the sentences as written (all-MiniLM-L6-v2, fp32), valid when >= the "
        f"threshold: the project's {validator.threshold:.2f}, and the threshold best (F1) for that very "
        "set, which flatters it. Main before issue 11: the validator at 920fa62 (stored figures). "
        "LADEV: similarity AND equal grounded frames (task, object, destination; scene context where "
        "the set has `scene_objects`).",
        "",
        *(f"- {n}" for n in NOTES),
        "",
        "| set | pairs (same/different) | similarity >= 0.45 | similarity, best-F1 threshold | "
        "main before issue 11 | LADEV first score (held out) | parser alone now | LADEV now | "
        "LADEV false valid / false invalid |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    figures: dict[str, object] = {}
    details: list[str] = []
    for name, (path, about) in SETS.items():
        if only and name not in only:
            continue
        if not path.exists():
            lines.append(f"| {name} | (missing: {path}) | | | | | | | |")
            continue
        pairs = load_labelled_pairs(path)
        verdicts = validator.validate_pairs(
            [(p.original, p.candidate) for p in pairs], [p.scene_objects for p in pairs]
        )
        actual = [p.same for p in pairs]
        sims = [v.similarity for v in verdicts]
        fixed = score([s >= validator.threshold for s in sims], actual, validator.threshold)
        best = best_f1(threshold_sweep(sims, actual))
        ladev = score([v.valid for v in verdicts], actual, validator.threshold)
        alone = "-"
        if parser_only is not None:
            plain = parser_only.validate_pairs(
                [(p.original, p.candidate) for p in pairs], [p.scene_objects for p in pairs]
            )
            alone = _pr(score([v.valid for v in plain], actual, validator.threshold))
        stored = _stored(baseline, name)
        main_cell = (
            f"{float(stored['precision']):.3f} / {float(stored['recall']):.3f}"  # type: ignore[arg-type]
            if stored
            else "-"
        )
        n_same = sum(actual)
        first = FIRST_SCORES.get(name)
        first_cell = f"{first[0]:.3f} / {first[1]:.3f} ({first[2]})" if first else "-"
        lines.append(
            f"| {name} | {len(pairs)} ({n_same}/{len(pairs) - n_same}) | {_pr(fixed)} | {_pr(best)} "
            f"(t={best.threshold:.3f}) | {main_cell} | {first_cell} | {alone} | **{_pr(ladev)}** | "
            f"{ladev.fp} / {ladev.fn} |"
        )
        figures[name] = {"precision": ladev.precision, "recall": ladev.recall, "fp": ladev.fp, "fn": ladev.fn}
        details += [f"### {name}: {about}", ""]
        if name == "libero_pro":
            details += _per_suite(path, pairs, verdicts, sims, validator.threshold, stored)
        details += _errors(pairs, verdicts)
    lines += ["", *details]
    return lines, figures


def _per_suite(
    path: Path,
    pairs: list[LabelledPair],
    verdicts: list[Verdict],
    sims: list[float],
    threshold: float,
    stored: dict[str, object] | None,
) -> list[str]:
    suites = _suites(path)
    stored_suites = stored.get("suites", {}) if stored else {}
    out = [
        LIBERO_PRO_CITATION,
        "",
        "| suite | pairs | similarity >= 0.45 | main before issue 11 | LADEV |",
        "|---|---|---|---|---|",
    ]
    for suite in sorted(set(suites)):
        idx = [i for i, s in enumerate(suites) if s == suite]
        actual = [pairs[i].same for i in idx]
        fixed = score([sims[i] >= threshold for i in idx], actual)
        ladev = score([verdicts[i].valid for i in idx], actual)
        st = stored_suites.get(suite) if isinstance(stored_suites, dict) else None
        main_cell = f"{st['precision']:.3f} / {st['recall']:.3f}" if isinstance(st, dict) else "-"
        out.append(f"| {suite} | {len(idx)} | {_pr(fixed)} | {main_cell} | {_pr(ladev)} |")
    return [*out, ""]


def _errors(pairs: list[LabelledPair], verdicts: list[Verdict]) -> list[str]:
    wrong = [(p, v) for p, v in zip(pairs, verdicts, strict=True) if v.valid != p.same]
    out = [f"LADEV errors ({len(wrong)}):", ""]
    for p, v in wrong[:30]:
        verdict = "valid" if v.valid else f"invalid ({v.reason})"
        out.append(f"- [{p.category}] \"{p.original}\" -> \"{p.candidate}\": {verdict}")
    if not wrong:
        out.append("- none")
    return [*out, ""]


SCENE_SETS: dict[str, tuple[Path, str]] = {
    "scene_descriptions_dev": (
        DEV / "scene_descriptions_dev.jsonl",
        "dev set written outside the team (development: the reader was worked on while looking at it)",
    ),
    "scene_descriptions_holdout": (
        ROOT / "tests/data/scene_descriptions_holdout.jsonl",
        "project held-out set, written for issue 11 before the reader's fixes and first scored once",
    ),
    "scene_descriptions_holdout2": (
        ROOT / "tests/data/scene_descriptions_holdout2.jsonl",
        "second held-out set (40), written blind by a helper that read only the dev README's conventions, "
        "scored once at b84dd1b",
    ),
    "scene_descriptions_holdout3": (
        ROOT / "tests/data/scene_descriptions_holdout3.jsonl",
        "third held-out set (40), written blind, scored once at c1f5114",
    ),
    "scene_descriptions_holdout4": (
        ROOT / "tests/data/scene_descriptions_holdout4.jsonl",
        "fourth held-out set (50), written blind, scored once at ea10124",
    ),
    "scene_descriptions_holdout5": (
        ROOT / "tests/data/scene_descriptions_holdout5.jsonl",
        "fifth held-out set (50; hurried, careful, non-native, config-pasted, dictated, rambling writers), "
        "written blind, scored once at 755df16",
    ),
    "scene_descriptions_holdout6": (
        ROOT / "tests/data/scene_descriptions_holdout6.jsonl",
        "sixth held-out set (60; spec writers, students, non-native, config snippets, dictation, rambling, "
        "minimal notes, reordered), written blind, scored once at 2130271",
    ),
    "scene_descriptions_holdout7": (
        ROOT / "tests/data/scene_descriptions_holdout7.jsonl",
        "seventh held-out set (60; YAML and bracketed configs, dictation, learner English, end states), "
        "written blind, scored once at 4d30df5",
    ),
    "scene_descriptions_holdout8": (
        ROOT / "tests/data/scene_descriptions_holdout8.jsonl",
        "eighth held-out set (60; Python-dict, INI, CSV and JSON configs, bug reports, test-plan rows, "
        "dictation without punctuation), written blind, scored once at c483889",
    ),
    "scene_descriptions_holdout9": (
        ROOT / "tests/data/scene_descriptions_holdout9.jsonl",
        "ninth held-out set (60; mostly prose and notes: lab members, students, a manager, non-native "
        "writers), written blind, scored once at 86ba673",
    ),
    "scene_descriptions_holdout10": (
        ROOT / "tests/data/scene_descriptions_holdout10.jsonl",
        "tenth held-out set (60; researchers, technicians, managers, non-native writers, dictation, chat "
        "notes), written blind, scored once at 2fd1a43",
    ),
    "scene_descriptions_holdout11": (
        ROOT / "tests/data/scene_descriptions_holdout11.jsonl",
        "eleventh held-out set (60; heavier on corrections and lighting / camera wording), written blind, "
        "scored once at f9f3af7",
    ),
    "scene_descriptions_holdout12": (
        ROOT / "tests/data/scene_descriptions_holdout12.jsonl",
        "twelfth held-out set (60; six styles, 10 each), written blind, scored once at af16970",
    ),
    "scene_descriptions_holdout13": (
        ROOT / "tests/data/scene_descriptions_holdout13.jsonl",
        "thirteenth held-out set (80; seven styles), written blind while the tagged reader was built; the rule "
        "reader scored once at 152d3a6, the tagged reader once (at 246068e) before its rows were read; the tagged "
        "reader's assembly was then fixed on its errors (a development set since)",
    ),
    "scene_descriptions_holdout14": (
        ROOT / "tests/data/scene_descriptions_holdout14.jsonl",
        "fourteenth held-out set (80; eight styles, data-like snippets among them), written blind; the rule reader "
        "scored once at 152d3a6, the tagged reader once at 1bcc10b (its final form this session), before its rows "
        "were read",
    ),
    "scene_descriptions_holdout15": (
        ROOT / "tests/data/scene_descriptions_holdout15.jsonl",
        "fifteenth held-out set (100; eight styles, 12-13 each: the paper's structure, prose, terse lists, command "
        "lines, unspecified objects, conversation, corrections, data snippets), written blind by a helper that read "
        "only the dev README; both readers scored once at 8e7223f (the retrained tagger), before its rows were read; "
        "developed on since",
    ),
    "scene_descriptions_holdout16": (
        ROOT / "tests/data/scene_descriptions_holdout16.jsonl",
        "sixteenth held-out set (100; seven styles, 14-15 each: the paper's structure, prose, terse lists, command "
        "lines, unspecified objects, conversation, negations and corrections), written blind by a helper that read "
        "only the dev README; both readers scored once at 047f13e, before its rows were read; developed on since "
        "(df075bc)",
    ),
}
def _figures(label: str, exact: float, fields: Sequence[float]) -> dict[str, object]:
    names = ("n_objects", "required_objects", "task", "lighting", "camera", "positions", "unavailable", "feasibility")
    return {"label": label, "scene_exact": exact, "per_field": dict(zip(names, fields, strict=True))}


SCENE_FIRST: dict[str, list[dict[str, object]]] = {
    # LADEV before the issue-11 scene work (commit 8bda385), as reported then
    "scene_descriptions_dev": [
        _figures("LADEV at 8bda385 (first)", 0.793, (0.880, 0.940, 0.927, 0.993, 0.993, 0.913, 0.973, 0.947)),
    ],
    # scored once with the code of 8bda385: as written, then with two impossible tasks of the set rewritten
    "scene_descriptions_holdout": [
        _figures("first, as written", 0.767, (0.833, 0.900, 0.900, 1.0, 1.0, 1.0, 0.900, 0.933)),
        _figures("first, 2 tasks fixed", 0.800, (0.867, 0.933, 0.967, 1.0, 1.0, 1.0, 0.900, 1.0)),
    ],
    "scene_descriptions_holdout2": [
        _figures("first (blind, b84dd1b)", 0.675, (0.800, 0.825, 0.775, 0.975, 0.975, 1.0, 0.900, 0.900)),
    ],
    "scene_descriptions_holdout3": [
        _figures("first (blind, c1f5114)", 0.600, (0.750, 0.925, 0.850, 0.925, 0.975, 0.975, 0.925, 0.975)),
    ],
    "scene_descriptions_holdout4": [
        _figures("first (blind, ea10124)", 0.700, (0.940, 0.960, 0.860, 0.960, 0.900, 0.960, 0.960, 0.980)),
    ],
    "scene_descriptions_holdout5": [
        _figures("first (blind, 755df16)", 0.740, (0.960, 1.000, 0.900, 0.940, 0.980, 0.980, 0.940, 1.000)),
    ],
    "scene_descriptions_holdout6": [
        _figures("first (blind, 2130271)", 0.633, (0.767, 0.967, 0.850, 0.917, 0.933, 0.983, 0.967, 0.983)),
    ],
    "scene_descriptions_holdout7": [
        _figures("first (blind, 4d30df5)", 0.683, (0.850, 0.933, 0.850, 0.950, 0.917, 0.900, 0.933, 0.933)),
    ],
    "scene_descriptions_holdout8": [
        _figures("first (blind, c483889)", 0.633, (0.800, 0.933, 0.867, 0.900, 0.867, 0.983, 0.950, 0.950)),
    ],
    "scene_descriptions_holdout9": [
        _figures("first (blind, 86ba673)", 0.817, (0.933, 0.983, 0.950, 0.967, 0.950, 0.950, 1.000, 0.983)),
    ],
    "scene_descriptions_holdout10": [
        _figures("first (blind, 2fd1a43)", 0.783, (0.933, 0.967, 0.933, 0.933, 0.983, 0.950, 0.967, 0.983)),
    ],
    "scene_descriptions_holdout11": [
        _figures("first (blind, f9f3af7)", 0.667, (0.850, 0.917, 0.900, 0.950, 0.983, 0.950, 0.933, 0.967)),
    ],
    "scene_descriptions_holdout12": [
        _figures("first (blind, af16970)", 0.767, (0.950, 1.000, 0.917, 0.950, 0.950, 1.000, 0.933, 1.000)),
    ],
    "scene_descriptions_holdout13": [
        _figures("rules, first (blind, 152d3a6)", 0.800, (0.950, 0.988, 0.988, 0.963, 0.925, 0.988, 0.950, 1.000)),
        _figures("tagged, first (blind, 246068e)", 0.850, (0.975, 1.000, 1.000, 0.963, 0.913, 1.000, 1.000, 1.000)),
    ],
    "scene_descriptions_holdout15": [
        _figures("rules, first (blind, 8e7223f)", 0.570, (0.700, 0.850, 0.780, 0.920, 0.900, 0.940, 0.880, 0.880)),
        _figures("tagged, first (blind, 8e7223f)", 0.780, (0.890, 0.940, 0.910, 0.980, 0.940, 0.980, 0.990, 0.970)),
    ],
    "scene_descriptions_holdout16": [
        _figures("rules, first (blind, 047f13e)", 0.750, (0.880, 0.960, 0.930, 0.970, 0.960, 0.970, 0.950, 0.990)),
        _figures("tagged, first (blind, 047f13e)", 0.940, (0.970, 0.990, 0.980, 0.990, 0.990, 0.990, 0.990, 0.990)),
    ],
    "scene_descriptions_holdout14": [
        _figures("rules, first (blind, 152d3a6)", 0.675, (0.838, 0.925, 0.887, 0.925, 0.887, 0.938, 0.900, 0.950)),
        _figures("tagged, first (blind, 1bcc10b)", 0.863, (0.963, 0.988, 0.963, 0.988, 0.925, 1.000, 1.000, 0.988)),
    ],
}
TAGGED_NOTES = (
    "The default offline reader (`compile.reader: tagged`) is a learned span tagger with the value rules: "
    "all-MiniLM-L6-v2 (the embedding model the project ships) with low-rank adapters and a tagging head marks "
    "which phrases put objects in the scene, which are only mentioned again or taken back, the random fill and "
    "the total, the task's object, destination and relation, positions, and the lighting and camera words "
    "that still hold after the writer's corrections (`ladev_lib/language/tagging/`); the scene is assembled "
    "from the marked phrases by `ladev_lib/language/scene/tagged.py` (catalog names, counts, regions, amounts "
    "and directions read by rules, grounding by the instruction reader). The rule reader of the earlier rounds "
    "stays available as `compile.reader: rules`.",
    "The tagger is trained (`ladev train-reader`, about 27 min on two cores) on 5,100 annotated descriptions "
    "(4,600 written for it by twenty helpers that read only the annotation guide and the dev README's "
    "conventions, 500 of the offline writer's own styles) and 1,905 annotated instructions, counted twice "
    "(`training/`). No row of any set below trains it.",
    "The two parts are measured apart by `benchmarks/eval_reader_parts.py` on the training rows, whose tags are "
    "known: the assembly reading each row's own tags (no tagger) gives 0.980 scene-exact on all 4,600 written "
    "rows (0.902 when this was first measured; it was developed on rows a-p, and rows q-t, written later, read "
    "0.948 and 0.904 the first time); the same 305 rows held out of the tagger's training give 0.980 on their own "
    "tags and 0.843 through the tagger (0.849 with the checks of the tags' surroundings added since, and 0.981 on "
    "their own tags), so the tagger's marks, not the assembly, are most of what is lost on new text.",
    "Since the tagger errs in repeatable ways (a list item marked as taken back with no word that takes it back, "
    "a replacement or a correction left as a plain mention, a corrected camera amount tagged without the words "
    "of the motion it corrects), the assembly checks each mark against the words around it: a taken-back mark "
    "needs words that take it back near it or at another mention of the object; 'replace / swap / substitute / "
    "instead of / not ... after all / make that' take objects out; a correction of a motion or a lighting amount "
    "is read into the statement it corrects (`ladev_lib/language/scene/tagged.py`).",
    "Blind rounds for the tagged reader, first scores (rule reader in brackets): round 13 (80) 0.850 (0.800); "
    "round 14 (80) 0.863 (0.675); round 15 (100, written with data snippets, command lines and corrections "
    "as a quarter of its rows) 0.780 (0.570) - by style 1.000 for the paper's structure, 0.92 for prose, "
    "conversation and terse lists, 0.83 for unspecified objects, 0.58 for corrections, 0.54 for command lines "
    "and 0.50 for data snippets; round 16 (100, seven styles, at 047f13e) **0.940** (0.750) - 1.000 for command "
    "lines, terse lists and unspecified objects, 0.93 for the paper's structure and prose, 0.86 for conversation "
    "and for negations and corrections. The target (0.95 on text not tuned on) is not met. Sets 1-12 were not "
    "read while the tagged reader and its tagger were built (their pooled score, 0.883 at 8f84444, was watched); "
    "at 2daee45 they read 0.933 pooled, and at that point their failing rows were read and developed on, with "
    "rounds 13-15 and the dev set: all of them are development sets now. Round 16 was scored once, at 047f13e; "
    "three general fixes from its errors followed (df075bc: an amount below or above the baseline, 'leave X out', a "
    "motion of the same axis said again after a correction), so it is a development set since.",
)
SCENE_NOTES = (
    "`scene_descriptions_holdout` (30 rows, `tests/data/`) was written in our own words before the reader "
    "was changed for issue 11 and scored once with the code of commit 8bda385: scene-exact 0.767. Two of "
    "those failures were the set's own errors (tasks the compiler rightly rejects as physically impossible: "
    "a peach on a 3 cm cube, a banana in the basket); only those two tasks were rewritten, and the same code "
    "then gave 0.800. The fixes were developed on the dev set; the held-out set was then only measured, "
    "except for one regression it showed (a category word as a modifier, \"a fruit test\", read as a "
    "random fruit after the vocabulary fix), which was fixed.",
    "Causes fixed (general readers, each with tests in our own words): a header governed its whole line, "
    "so \"Number and details of objects: ... Environmental setup: ...\" on one line read the objects as "
    "environment; the vocabulary knew only the last catalog object's id and category (a loop bug), so tasks "
    "could not be read in their scene (\"pick up bottle\"); groups took \"one\" from a later plural "
    "(\"two cubes, a green one ... 3 degrees\"); chat read as objects (\"this time\", \"nothing fancy\", "
    "\"no idea why\", \"one more example\", \"aubergines\" as a kind); positions said of coordinated "
    "objects (\"a bowl and a mug go on the left\", \"both near the center\"), by pronoun (\"next to it\"), "
    "by relative clause, by head noun (\"the can on the left\") and \"swap them\"; tasks said about the "
    "robot that only the scene resolves (\"moves the green brick near the pink one\"), with an inline tag "
    "(\"(that's the task)\"), verbless (\"plum into the cup\"), as a question (\"can the arm pick up X "
    "when ...\"); removal by one word (\"remove the Windex\"); \"a box of Jell-O gelatin\"; objects at "
    "coordinates read from a description move to the nearest clear point when their points collide (the "
    "dev README: such coordinates state no frame), with a note, and fixed objects turn together to clear "
    "each other.",
    "Dev rows left (2): dv032, an iPhone reported as 'iphone' where the set's convention names it "
    "'smartphone' (no brand-to-generic table for objects outside the catalog); dv114, one towel mentioned "
    "twice with \"a\" (\"has a towel on it ... to match: a towel on the left\") read as two. dv116 and dv139 "
    "(a ball / a pear the strict fit rule kept out of a cup) pass since a task a person names is checked as "
    "a person would place it (thinner walls, no clearance, leaning allowed; the episode's solvability "
    "check proves the scene).",
    "The first held-out set's five failures (a bare `+ random` line, \"so that there are five in all\", "
    "\"that's what I want the robot to do\", a correction inside dashes losing the random fill, \"but not "
    "the knife after all\") were fixed by general rules after the blind rounds below began.",
    "Blind rounds (`scene_descriptions_holdout2` to `scene_descriptions_holdout12`, 40-60 descriptions each): "
    "each set was written by a helper that read only the dev README's conventions (not the reader's code, "
    "tests or the other sets) and scored once at the commit named before anything changed for it; its "
    "errors were then read and general fixes made, so its current figure is a development figure. First "
    "scene-exact scores, in order: 0.675, 0.600, 0.700, 0.740, 0.633, 0.683, 0.633, 0.817, 0.783, 0.667, 0.767 "
    "(target 0.95: not met; rounds 9 and 10, mostly prose and notes, were the first above 0.75; round 11 "
    "fell back to 0.667 on self-corrections, 2 of its 10 correction rows exact). The rounds' lessons, "
    "each a general rule with tests in our own words: tasks stated as wishes (\"I need the X on the Y\"), "
    "aims and end states (\"the aim is for the manipulator to ...\", \"success means ...\", \"at the end "
    "of the episode ...\"), end-state sentences (\"the carrot goes on the red plate\"), calls and arrows "
    "(`put_on(a, b)`, `a -> near b`), retractions (\"hmm, no, put it in the cup instead\") and corrected "
    "relations or noun phrases inside the task statement; commands whose objects only the scene resolves; "
    "settings said with placing verbs (\"drop the brightness\") are no task; groups and counts (\"a pair "
    "of\", \"Nx\", bare adjective members, a count that starts a list, another kind of the same noun); "
    "one object for another (\"instead of the bowl use the basket\", \"swap X for Y\", \"make that the red "
    "plate\" replacing only the plate); unknown objects named again by their head noun, lamps and category "
    "words as modifiers of unknown objects; lighting fractions, factors and corrected amounts; camera verbs "
    "that carry their direction (lift, dolly), several motions in one sentence, key-value and numbered "
    "lists, dictated text without punctuation; descriptions written as data (YAML / JSON blocks, Python "
    "literals, INI sections, a CSV header and row, bracketed, aliased and unit-suffixed keys such as "
    "`lgt=`, `cam=(dz -4cm)`, `camera_x_cm`), value-before-axis camera values (`+2cm z`), dictation fillers, "
    "learner grammar (\"robot is put X in Y\"), verbless tasks (\"apple in bowl\"), labelled end states, "
    "asides in brackets, restated and next-sentence corrections, brand names for their can (\"swap the Red "
    "Bull for a 7UP\"), defaults that reset an earlier setting, and a named object balancing on a smaller "
    "top (a can on a 3 cm cube: the placement tolerance and a bounded overhang, not half the width).",
)


READERS = (("tagged", ["compile.reader=tagged"]), ("rules", ["compile.reader=rules"]))
"""The two offline readers, measured now: the default (the span tagger and the value rules) and the rule reader."""


def scene_section() -> list[str]:
    lines = ["## Scene descriptions", "", *(f"- {n}" for n in TAGGED_NOTES), "", *(f"- {n}" for n in SCENE_NOTES), ""]
    try:
        from ladev_lib.scenes.description_eval import (
            FIELDS,
            evaluate_descriptions,
            load_description_rows,
            offline_compile_fn,
        )
    except ImportError as exc:  # the scene reader's evaluation is not merged in this checkout
        return [*lines, f"(scene-description evaluation unavailable: {exc})", ""]
    baseline_path = ROOT / "reports/scene_descriptions_baseline.json"
    baseline = json.loads(baseline_path.read_text(encoding="utf-8")) if baseline_path.exists() else None
    compilers = {label: offline_compile_fn(ROOT / "conf", overrides) for label, overrides in READERS}
    measured: dict[str, dict[str, dict[str, object]]] = {}
    counts: dict[str, int] = {}
    for name, (rows_path, _about) in SCENE_SETS.items():
        if not rows_path.exists():
            continue
        rows = load_description_rows(rows_path)
        counts[name] = len(rows)
        measured[name] = {
            label: evaluate_descriptions(rows, fn, catalog, resolver).summary()
            for label, (fn, catalog, resolver) in compilers.items()
        }

    def first(name: str, prefix: str) -> str:
        got = [f for f in SCENE_FIRST.get(name, []) if str(f["label"]).startswith(prefix)]
        return f"{float(got[-1]['scene_exact']):.3f}" if got else "-"  # type: ignore[arg-type]

    lines += [
        "### All sets: scene-exact", "",
        "| set | rows | rule reader, first score | rule reader now (developed on) | tagged reader, first score | "
        "tagged reader now |",
        "|---|---|---|---|---|---|",
    ]
    for name in measured:
        rules_first = first(name, "rules") if first(name, "rules") != "-" else first(name, "first")
        lines.append(
            f"| {name} | {counts[name]} | {rules_first} | {float(measured[name]['rules']['scene_exact']):.3f} | "  # type: ignore[arg-type]
            f"{first(name, 'tagged')} | **{float(measured[name]['tagged']['scene_exact']):.3f}** |"  # type: ignore[arg-type]
        )
    # sets 1-12 pooled (read since 2daee45, developed on: a development figure, kept for comparison)
    unseen = [n for n in measured if n not in (
        "scene_descriptions_dev", "scene_descriptions_holdout13", "scene_descriptions_holdout14",
        "scene_descriptions_holdout15", "scene_descriptions_holdout16",
    )]
    for label in ("tagged", "rules"):
        total = sum(counts[n] for n in unseen)
        exact = sum(float(measured[n][label]["scene_exact"]) * counts[n] for n in unseen) / max(total, 1)  # type: ignore[arg-type]
        lines.append(f"| sets 1-12 pooled (developed on since 2daee45), {label} reader now | {total} | | | | {exact:.3f} |")
    lines.append("")
    for name, (rows_path, about) in SCENE_SETS.items():
        lines += [f"### {name}: {about}", ""]
        if name not in measured:
            lines += [f"(no rows at {rows_path})", ""]
            continue
        stored = ([baseline] if baseline is not None and name == "scene_descriptions_dev" else []) + list(
            SCENE_FIRST.get(name, [])
        )
        cols: dict[str, dict[str, object]] = {str(b["label"]): b for b in stored}
        cols.update({f"{label} now": measured[name][label] for label in ("rules", "tagged")})
        lines.append(f"{counts[name]} descriptions ({rows_path.name}); the compiler reads the task from the text.")
        lines.append("")
        lines.append("| measure | " + " | ".join(cols) + " |")
        lines.append("|---|" + "---|" * len(cols))
        lines.append("| scene-exact | " + " | ".join(f"{float(c['scene_exact']):.3f}" for c in cols.values()) + " |")  # type: ignore[arg-type]
        for f in FIELDS:
            lines.append(f"| {f} | " + " | ".join(
                f"{float(c['per_field'].get(f, 0.0)):.3f}" for c in cols.values()  # type: ignore[attr-defined]
            ) + " |")
        lines.append("")
    return lines


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", type=Path, default=ROOT / "reports/language_eval.md")
    ap.add_argument("--no-scenes", action="store_true", help="skip the scene-description section")
    ap.add_argument("--sets", nargs="*", default=None, help=f"only these instruction sets ({', '.join(SETS)})")
    args = ap.parse_args()
    baseline_path = ROOT / "reports/instruction_validator_baseline.json"
    baseline = json.loads(baseline_path.read_text(encoding="utf-8")) if baseline_path.exists() else {}
    validator = ParaphraseValidator(load_embedder(), threshold=DEFAULT_THRESHOLD, precision="fp32")
    parser_only = ParaphraseValidator(
        load_embedder(), threshold=DEFAULT_THRESHOLD, precision="fp32", second_reading=False
    )
    lines = [
        "# Language evaluation: baseline vs LADEV",
        "",
        "Regenerated by `PYTHONPATH=$PWD .venv/bin/python benchmarks/eval_language.py`.",
        "",
    ]
    inst, figures = instruction_sections(validator, baseline, args.sets, parser_only)
    lines += inst
    if not args.no_scenes:
        lines += scene_section()
    text = "\n".join(lines).rstrip() + "\n"
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(text, encoding="utf-8")
    print(text)
    print(json.dumps(figures))
    print(f"written: {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
