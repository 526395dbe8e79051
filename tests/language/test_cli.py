"""`ladev paraphrase` and `ladev validate-paraphrases`, run as a user would."""

from __future__ import annotations

import csv
import json

from click.testing import CliRunner

from ladev_lib.cli import cli


def test_paraphrase_prints_each_candidate_with_scores_parse_and_verdict(repo_root, minilm):
    result = CliRunner().invoke(
        cli, ["paraphrase", "put the carrot on the plate", "-k", "10", "--config-dir", str(repo_root / "conf")]
    )
    assert result.exit_code == 0, result.output
    lines = [line for line in result.output.splitlines() if line[:3].strip().isdigit() and line[3:5] == "  "]
    assert len(lines) == 10
    assert all("put_on(carrot, plate)" in line and "valid" in line for line in lines)
    assert "original: 'put the carrot on the plate' -> put_on(carrot, plate)" in result.output
    assert "10/10 valid" in result.output


def test_paraphrase_rejects_an_unknown_scene_object(repo_root):
    result = CliRunner().invoke(
        cli, ["paraphrase", "pick up the can", "--objects", "coke_cam", "--config-dir", str(repo_root / "conf")]
    )
    assert result.exit_code != 0
    assert "coke_cam" in result.output


def test_validate_paraphrases_writes_verdicts_and_scores_labels(repo_root, tmp_path, minilm):
    pairs = tmp_path / "pairs.csv"
    with open(pairs, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "original", "candidate", "label", "scene_objects"])
        w.writerow(["1", "pick up the coke can", "could you lift the can of coke?", "same", ""])
        w.writerow(["2", "pick up the coke can", "pick up the pepsi can", "different", ""])
        w.writerow(["3", "move the apple near the sponge", "move the sponge near the apple", "different", ""])
        w.writerow(["4", "pick up the coke can", "grab the can", "same", "coke_can;apple"])
    out = tmp_path / "out" / "verdicts.csv"
    result = CliRunner().invoke(
        cli, ["validate-paraphrases", str(pairs), "-o", str(out), "--config-dir", str(repo_root / "conf")]
    )
    assert result.exit_code == 0, result.output
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["valid"] for r in rows] == ["True", "False", "False", "True"]
    assert rows[0]["id"] == "1" and float(rows[0]["similarity"]) < float(rows[2]["similarity"])
    assert rows[1]["parsed_source"] == "pepsi_can" and "object changed" in rows[1]["reason"]
    assert "roles swapped" in rows[2]["reason"]
    assert rows[3]["parsed_source"] == "coke_can"
    assert "precision 1.000, recall 1.000" in result.output


def test_validate_paraphrases_names_missing_columns(repo_root, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("instruction,paraphrase\na,b\n")
    result = CliRunner().invoke(cli, ["validate-paraphrases", str(bad), "-o", str(tmp_path / "o.csv")])
    assert result.exit_code != 0
    assert "missing column(s) original, candidate" in result.output


def test_validate_paraphrases_takes_scene_names_or_ids_and_never_drops_a_row(repo_root, tmp_path, minilm):
    pairs = tmp_path / "pairs.csv"
    with open(pairs, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "original", "candidate", "scene_objects"])
        w.writerow(["names", "put the bowl on the plate", "put the bowl on the dinner plate", "black bowl; plate"])
        w.writerow(["ids", "put the bowl on the plate", "put the bowl on the dinner plate", "024_bowl;plate"])
        w.writerow(["unknown id", "pick up the coke can", "lift the coke can", "black"])
        w.writerow(["empty", "pick up the coke can", "", "coke_can"])
        w.writerow(["bad cell", "pick up the coke can", "lift the coke can", "@@@; coke_can"])
        w.writerow(["free nouns", "put the wine bottle on the rack", "set the bottle of wine on the rack", ""])
    out = tmp_path / "verdicts.csv"
    result = CliRunner().invoke(
        cli, ["validate-paraphrases", str(pairs), "-o", str(out), "--config-dir", str(repo_root / "conf")]
    )
    assert result.exit_code == 0, result.output
    with open(out, newline="") as f:
        rows = {r["id"]: r for r in csv.DictReader(f)}
    assert list(rows) == ["names", "ids", "unknown id", "empty", "bad cell", "free nouns"]
    assert rows["names"]["valid"] == "True" and rows["names"]["parsed_target"] == "plate"
    assert rows["ids"]["valid"] == "True" and "'dinner plate' -> plate" in rows["ids"]["groundings"]
    assert rows["unknown id"]["valid"] == "False" and "not in the scene" in rows["unknown id"]["reason"]
    assert rows["empty"]["valid"] == "False" and "empty instruction" in rows["empty"]["reason"]
    assert rows["bad cell"]["valid"] == "False" and "unreadable scene_objects" in rows["bad cell"]["reason"]
    assert rows["free nouns"]["valid"] == "True"
    frame = json.loads(rows["free nouns"]["candidate_frame"])
    assert frame["object"]["text"] == "wine bottle" and frame["destination"]["text"] == "rack"
