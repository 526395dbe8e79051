"""`ladev scene` and `ladev compile`, run as a user would (click's runner)."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from ladev_lib.cli import cli
from ladev_lib.cli import scene as scene_cli
from ladev_lib.scenes.spec import SceneSpec

PAPER_EXAMPLE = "three objects, one of them a plastic bottle on the left; lighting a bit darker"


@pytest.fixture
def conf(repo_root, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the LLM cache goes under ./data/cache/llm/cli
    return str(repo_root / "conf")


def test_scene_prints_operations_instruction_and_spec(conf, tmp_path, catalog):
    result = CliRunner().invoke(cli, ["scene", PAPER_EXAMPLE, "--task", "pick_up", "--config-dir", conf,
                                      "--save-spec", "spec.json"])
    assert result.exit_code == 0, result.output
    out = result.output
    assert '"op": "add_object"' in out and '"region": "left"' in out and '"intensity_delta": -0.15' in out
    assert "Instruction: pick up the blue plastic bottle" in out
    assert "blue_plastic_bottle" in out and "source" in out and "Lighting: -0.15" in out
    spec = SceneSpec.from_json((tmp_path / "spec.json").read_text(), catalog=catalog)
    assert len(spec.objects) == 3 and spec.source.id == "blue_plastic_bottle"
    assert (tmp_path / "data/cache/llm/cli/store.sqlite").exists()
    again = CliRunner().invoke(cli, ["scene", PAPER_EXAMPLE, "--task", "pick_up", "--config-dir", conf])
    assert "(offline:offline-rules-v1, cached)" in again.output


def test_scene_json_output_and_rejection_exit_code(conf):
    ok = CliRunner().invoke(cli, ["scene", "ADD coke can to (0.1, 0.05)\nADD bowl", "-i",
                                  "move the coke can near the bowl", "--json", "--config-dir", conf])
    assert ok.exit_code == 0, ok.output
    data = json.loads(ok.output)
    assert data["status"] == "ok" and data["spec"]["task"]["type"] == "move_near"
    assert data["spec"]["objects"][0]["x"] == 0.1
    bad = CliRunner().invoke(cli, ["scene", "asdf qwerty", "-i", "pick up the apple", "--config-dir", conf])
    assert bad.exit_code == 1 and "Rejected:" in bad.output and "could not be read" in bad.output


def test_render_uses_the_simulator_when_present_and_says_so_when_not(conf, tmp_path, monkeypatch):
    rendered = []
    def fake(spec, path, cfg):
        rendered.append((spec, path))
        return [path]

    monkeypatch.setattr(scene_cli, "find_renderer", lambda: fake)
    ok = CliRunner().invoke(cli, ["scene", PAPER_EXAMPLE, "--render", "scene.png", "--config-dir", conf])
    assert ok.exit_code == 0 and rendered and rendered[0][1].name == "scene.png"
    monkeypatch.setattr(scene_cli, "find_renderer", lambda: None)
    missing = CliRunner().invoke(cli, ["scene", PAPER_EXAMPLE, "--render", "out/scene.png", "--config-dir", conf])
    assert missing.exit_code == 2 and "cannot render" in missing.output
    assert SceneSpec.from_json((tmp_path / "out/scene.json").read_text()).objects


def test_compile_writes_one_line_per_input_with_status_and_reason(conf, tmp_path):
    lines = [
        json.dumps({"id": "a", "description": "two objects, one is an apple", "instruction": "pick up the apple"}),
        json.dumps({"id": "b", "description": "a sponge near the plate; camera 2 cm up", "task": "put_on"}),
        "{not json",
        json.dumps({"id": "d"}),
        json.dumps({"id": "e", "description": "a purple elephant", "instruction": "pick up the purple elephant"}),
        json.dumps({"id": "f", "description": "an apple and a plate", "instruction": "put the apple in the plate",
                    "seed": 5}),
    ]
    (tmp_path / "in.jsonl").write_text("\n".join(lines) + "\n\n")
    result = CliRunner().invoke(cli, ["compile", "in.jsonl", "-o", "out.jsonl", "--config-dir", conf])
    assert result.exit_code == 0, result.output
    out = [json.loads(line) for line in (tmp_path / "out.jsonl").read_text().splitlines()]
    assert [o["id"] for o in out] == ["a", "b", "line-3", "d", "e", "f"]
    assert [o["status"] for o in out] == ["ok", "ok", "rejected", "rejected", "rejected", "rejected"]
    assert out[0]["instruction"] == "pick up the apple" and len(out[0]["spec"]["objects"]) == 2
    assert out[1]["spec"]["task"]["type"] == "put_on" and out[1]["instruction"].startswith("put the ")
    assert out[1]["spec"]["camera"]["translation_m"][2] > 0 and out[1]["operations"]["operations"]
    assert "not JSON" in out[2]["reason"] and "description" in out[3]["reason"]
    assert "unknown object" in out[4]["reason"] and "not a container" in out[5]["reason"]
    assert "compiled 6 descriptions: 2 ok, 4 rejected" in result.output


@pytest.mark.sim
def test_scene_render_writes_a_picture_of_the_scene(conf, tmp_path):
    import numpy as np
    from PIL import Image

    result = CliRunner().invoke(cli, ["scene", PAPER_EXAMPLE, "--task", "pick_up", "--render", "scene.png",
                                      "--config-dir", conf])
    assert result.exit_code == 0, result.output
    assert "rendered to" in result.output
    image = np.asarray(Image.open(tmp_path / "scene.png"))
    assert image.ndim == 3 and image.shape[0] >= 128 and image.std() > 10  # a picture, not a blank


def test_scene_shows_how_the_tagged_reader_read_the_text(conf):
    text = "A bowl - no, make that a basket - and a plum. The plum goes in the basket."
    result = CliRunner().invoke(cli, ["scene", text, "--no-cache", "--config-dir", conf])
    assert result.exit_code == 0, result.output
    read_as = next(line for line in result.output.splitlines() if line.startswith("Read as:"))
    assert "[[a basket|OBJ]]" in read_as and "|SRC]]" in read_as
    rules = CliRunner().invoke(cli, ["scene", text, "compile.reader=rules", "--no-cache", "--config-dir", conf])
    assert rules.exit_code == 0 and "Read as:" not in rules.output
