"""Fixtures for the language tests: embedders, validators, catalog coverage, stage inputs."""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pytest
import yaml

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.scenes.sampling import target_candidates


class BagOfWordsEmbedder:
    """A deterministic stand-in for MiniLM: hashed bag of words, unit length.

    For tests of the validator's logic that do not need real semantics.
    """

    def __init__(self, dim: int = 256) -> None:
        self.dim = dim
        self.encoded = 0
        self.calls = 0

    def encode(self, texts: Sequence[str]) -> np.ndarray:
        self.calls += 1
        self.encoded += len(texts)
        out = np.zeros((len(texts), self.dim), dtype=np.float32)
        for i, text in enumerate(texts):
            for word in text.lower().replace("?", " ").replace(",", " ").split():
                h = int(hashlib.md5(word.encode()).hexdigest()[:8], 16)
                out[i, h % self.dim] += 1.0
            norm = np.linalg.norm(out[i])
            if norm:
                out[i] /= norm
        return out


@pytest.fixture()
def bow_embedder() -> BagOfWordsEmbedder:
    return BagOfWordsEmbedder()


@pytest.fixture(scope="session")
def minilm():
    from ladev_lib.language.embeddings import load_embedder

    return load_embedder()


@pytest.fixture(scope="session")
def validator(minilm):
    """The validator as configured by default (threshold, precision auto)."""
    from ladev_lib.language.config import ParaphraseConfig
    from ladev_lib.language.validator import ParaphraseValidator, resolve_precision

    cfg = ParaphraseConfig()
    return ParaphraseValidator(
        minilm, threshold=cfg.similarity_threshold, precision=resolve_precision(cfg.precision)
    )


def catalog_cases(catalog: Catalog) -> list[tuple[str, str, str | None]]:
    """(task, source, target) covering every graspable object as a source of each task and
    every object that can be a target as a target, with feasible pairs (same object set first)."""
    objects = list(catalog)
    sources = [o for o in objects if o.graspable]
    cases: list[tuple[str, str, str | None]] = []
    for task in ("pick_up", "move_near", "put_on", "put_in"):
        if task == "pick_up":
            cases += [(task, s.id, None) for s in sources]
            continue
        covered: set[str] = set()
        for n, s in enumerate(sources):
            pool = target_candidates(task, s, [o for o in objects if o.set == s.set]) or target_candidates(
                task, s, objects
            )
            if pool:
                t = pool[n % len(pool)]
                cases.append((task, s.id, t.id))
                covered.add(t.id)
        for t in objects:
            if t.id in covered:
                continue
            s = next((s for s in sources if target_candidates(task, s, [t])), None)
            if s is not None:
                cases.append((task, s.id, t.id))
                covered.add(t.id)
    return cases


@pytest.fixture(scope="session")
def all_catalog_cases() -> list[tuple[str, str, str | None]]:
    return catalog_cases(load_catalog())


def write_stage_inputs(root: Path, repo_root: Path, scenes_per_task: int = 1) -> dict:
    """Hand-made scenes.parquet + compiled.parquet and a params.yaml under ``root``.

    Scenes of the ``num_objects`` and ``instruction`` factors, all four tasks, both object
    sets, plus one scene whose generation failed and one that was rejected by compile.
    """
    from ladev_lib.config import compose_config
    from ladev_lib.language.instructions import basic_instruction
    from ladev_lib.scenes.sampling import sample_scene
    from ladev_lib.tables import CompiledSceneRow, SceneDesignRow, write_table

    catalog = load_catalog()
    cfg = compose_config([], repo_root / "conf")
    cfg["study"]["paraphrases_per_instruction"] = 4
    scenes, compiled = [], []
    n = 0
    for factor in ("num_objects", "instruction"):
        for task in ("pick_up", "move_near", "put_on", "put_in"):
            for object_set in ("simpler", "ycb"):
                for _ in range(scenes_per_task):
                    n += 1
                    sid = f"{task}-{factor}-{object_set}-{n:03d}"
                    spec = sample_scene(task, 2, object_set, np.random.default_rng(n), catalog, scene_id=sid, seed=n)
                    src = catalog.get(spec.source.id).display_name
                    tgt = catalog.get(spec.target.id).display_name if spec.target else None
                    level = "basic+paraphrase" if factor == "instruction" else "2"
                    scenes.append(SceneDesignRow(
                        scene_id=sid, study="test", task=task, factor=factor, level=level, num_objects=2,
                        object_set=object_set, environment="default", robot="panda", seed=n,
                        description="two objects", base_instruction=basic_instruction(task, src, tgt),
                        status="ok",
                    ))
                    compiled.append(CompiledSceneRow(scene_id=sid, status="ok", spec_json=spec.to_json()))
    common = dict(study="test", task="pick_up", factor="num_objects", level="1", num_objects=1,
                  object_set="simpler", environment="default", robot="panda", seed=0)
    scenes.append(SceneDesignRow(scene_id="failed-gen", description=None, base_instruction=None,
                                 status="failed", reason="no answer", **common))
    scenes.append(SceneDesignRow(scene_id="rejected", description="a unicorn",
                                 base_instruction="pick up the unicorn", status="ok", **common))
    compiled.append(CompiledSceneRow(scene_id="rejected", status="rejected", reason="unknown object 'unicorn'"))
    write_table(scenes, root / cfg["paths"]["scenes"], SceneDesignRow)
    write_table(compiled, root / cfg["paths"]["compiled"], CompiledSceneRow)
    with open(root / "params.yaml", "w", encoding="utf-8") as f:
        yaml.safe_dump(cfg, f, sort_keys=False)
    return cfg
