"""Paraphrase validation speed: similarity part (batched embeddings), parser, generator.

    LP_NUM_THREADS=1 OMP_NUM_THREADS=1 PYTHONPATH=. python benchmarks/bench_paraphrase.py [--pairs 2000]

Target (issue 4): >= 400 validations per second for the similarity part, batched,
on 2 CPU cores. Each precision runs with one torch thread and with every core
(``--threads``), side by side in one process: the paraphrase stage embeds with
every core (``paraphrase.threads: null``). Prints the machine's load average and
CPU time too: on a shared machine wall-clock rates move with the load; rates per
CPU-second much less.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("HF_HUB_OFFLINE", "1")

import torch  # noqa: E402

from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.language.embeddings import load_embedder  # noqa: E402
from ladev_lib.language.instructions import basic_instruction  # noqa: E402
from ladev_lib.language.paraphrase import offline_paraphrases  # noqa: E402
from ladev_lib.language.parser import InstructionParser  # noqa: E402
from ladev_lib.language.validator import ParaphraseValidator, resolve_precision  # noqa: E402

TASKS = [
    ("pick_up", "coke_can", None), ("pick_up", "011_banana", None), ("pick_up", "eggplant", None),
    ("move_near", "apple", "sponge"), ("move_near", "056_tennis_ball", "024_bowl"),
    ("put_on", "carrot", "plate"), ("put_on", "012_strawberry", "029_plate"),
    ("put_in", "eggplant", "basket"), ("put_in", "018_plum", "025_mug"),
]


def make_pairs(n: int) -> list[tuple[str, str]]:
    catalog = load_catalog()
    per_task = -(-n // len(TASKS))
    pairs: list[tuple[str, str]] = []
    for task, source, target in TASKS:
        original = basic_instruction(
            task, catalog.get(source).display_name, catalog.get(target).display_name if target else None
        )
        pairs += [(original, c) for c in offline_paraphrases(task, source, target, per_task, seed=7)]
    return pairs[:n]


def rate(n: int, seconds: float, cpu_seconds: float | None = None) -> str:
    text = f"{n / seconds:8.1f}/s wall ({n} in {seconds:.2f} s)"
    if cpu_seconds:
        text += f", {n / cpu_seconds:7.1f} per CPU-second"
    return text


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=2000)
    ap.add_argument("--batch-sizes", default="32,64,128")
    ap.add_argument("--precisions", default="fp32,bf16", help="fp32, bf16 (side by side)")
    ap.add_argument("--threads", default=f"1,{os.cpu_count() or 1}", help="torch threads to compare")
    args = ap.parse_args()

    print(f"torch threads {torch.get_num_threads()}, cpu count {os.cpu_count()}, "
          f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    t0 = time.perf_counter()
    embedder = load_embedder()
    print(f"model load: {time.perf_counter() - t0:.1f} s (once per process)")
    t0 = time.perf_counter()
    pairs = make_pairs(args.pairs)
    print(f"generator (offline paraphraser):     {rate(len(pairs), time.perf_counter() - t0)}")

    embedder.encode([c for _, c in pairs[:64]])  # warm-up
    print(f"{len(pairs)} pairs, {len({t for p in pairs for t in p})} distinct texts")
    for threads in dict.fromkeys(int(t) for t in args.threads.split(",")):
        for precision in args.precisions.split(","):
            for bs in (int(b) for b in args.batch_sizes.split(",")):
                embedder.batch_size = bs
                # a fresh embedding cache for every run
                validator = ParaphraseValidator(embedder, precision=precision, threads=threads)
                t0, c0 = time.perf_counter(), time.process_time()
                raw = validator.similarities(pairs)
                low = [p for p, s in zip(pairs, raw, strict=True) if s < validator.threshold]
                validator.canonical_similarities(low)
                wall, cpu = time.perf_counter() - t0, time.process_time() - c0
                print(f"similarity part, {precision}, {threads} thread(s), batch {bs:4d}: {rate(len(pairs), wall, cpu)}"
                      f"  ({len(low)} below the threshold re-compared with canonical names)")
    embedder.batch_size = 64

    parser = InstructionParser()
    t0 = time.perf_counter()
    for _, c in pairs:
        parser.parse(c)
    print(f"structural parse:                    {rate(len(pairs), time.perf_counter() - t0)}")
    validator = ParaphraseValidator(embedder, precision=resolve_precision("auto"), threads=os.cpu_count())
    t0, c0 = time.perf_counter(), time.process_time()
    verdicts = validator.validate_pairs(pairs)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"full validation ({validator.precision}, {os.cpu_count()} threads, both checks): {rate(len(pairs), wall, cpu)}; "
          f"{sum(v.valid for v in verdicts)}/{len(verdicts)} valid")


if __name__ == "__main__":
    main()
