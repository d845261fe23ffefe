#!/usr/bin/env python3
"""Throughput of catalogue runs: every pairing of the shared garments and avatars run by the
local batch and by the cluster engines, with 1 and 2 workers; then each run again, when every
job is reused, which leaves the per-job cost of the runner itself.

    PYTHONPATH=build/python python bench/batch_throughput.py --out /tmp/throughput \\
        [--engines dask ray] [--workers 1 2]

Prints a table (jobs per minute, seconds, per-job time of the all-reused rerun) and checks
that every run wrote the same garment.obj bytes as the first. With --overhead N it then
times each runner on manifests of 1 and of N jobs whose certified results already exist
(the bundled scene, copied): the difference over N - 1 is the runner's cost per job, with
the start-up (a local cluster's included) taken out.
"""

from __future__ import annotations

import argparse
import filecmp
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT.parent / "shared" / "data"


def write_pairings_manifest(path: Path) -> int:
    """Every garment of ../shared/data on every avatar, with the skeletons, skin weights and
    no-fit lists they have; returns the number of jobs."""
    lines = []
    for garment in sorted((DATA / "garments").iterdir()):
        for avatar in sorted((DATA / "avatars").iterdir()):
            job = {"id": f"{garment.name}_{avatar.name}", "garment": str(garment / "garment.obj"),
                   "avatar": str(avatar / "avatar.obj")}
            if (garment / "skeleton.obj").exists() and (avatar / "skeleton.obj").exists():
                job["source_skeleton"] = str(garment / "skeleton.obj")
                job["target_skeleton"] = str(avatar / "skeleton.obj")
                if (avatar / "skin.txt").exists():
                    job["skin_weights"] = str(avatar / "skin.txt")
            if (garment / "no-fit.txt").exists():
                job["no_fit"] = str(garment / "no-fit.txt")
            if garment.name == "skirt":
                job["skirt"] = True
            lines.append(json.dumps(job))
    path.write_text("\n".join(lines) + "\n")
    return len(lines)


def measure_overhead(out: Path, runners: dict[str, list[str]], jobs: int) -> None:
    """Per-job cost of each runner on jobs that are all reused (see the module's text)."""
    import shutil

    scene = ROOT / "tools" / "scenes" / "dress_form"
    job = {"garment": str(scene / "garment.obj"), "avatar": str(scene / "avatar.obj"),
           "no_fit": str(scene / "no-fit.txt"), "quality": "fast"}
    manifests = {}
    for count in (1, jobs):
        manifests[count] = out / f"reused-{count}.jsonl"
        manifests[count].write_text("".join(json.dumps({"id": f"dress{i}", **job}) + "\n" for i in range(count)))
    results = out / "reused"
    subprocess.run(runners["local"] + [str(manifests[1]), "--out", str(results)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for i in range(1, jobs):
        if not (results / f"dress{i}").exists():
            shutil.copytree(results / "dress0", results / f"dress{i}")
    for name, command in runners.items():
        one, _ = timed(command + [str(manifests[1]), "--out", str(results)])
        many, code = timed(command + [str(manifests[jobs]), "--out", str(results)])
        print(f"{name:6} all reused: 1 job {one:6.2f} s, {jobs} jobs {many:6.2f} s (exit {code}): "
              f"{(many - one) / (jobs - 1) * 1000:7.1f} ms per job", flush=True)


def timed(command: list[str]) -> tuple[float, int]:
    start = time.monotonic()
    completed = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start, completed.returncode


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--engines", nargs="*", default=["dask", "ray"])
    parser.add_argument("--workers", nargs="*", type=int, default=[1, 2])
    parser.add_argument("--overhead", type=int, default=0, metavar="N",
                        help="also time each runner on 1 and N reused jobs")
    parser.add_argument("--skip-throughput", action="store_true")
    args = parser.parse_args()
    import garment_retarget

    args.out.mkdir(parents=True, exist_ok=True)
    manifest = args.out / "pairings.jsonl"
    jobs = write_pairings_manifest(manifest)
    runners = {"local": [garment_retarget.program_path(), "batch", "--quiet"]}
    for engine in args.engines:
        runners[engine] = [sys.executable, "-m", "garment_retarget.cluster", "--engine", engine, "--quiet"]
    rows, reference = [], None
    for name, command in ({} if args.skip_throughput else runners).items():
        for workers in args.workers:
            out = args.out / f"{name}-{workers}"
            run = command + [str(manifest), "--out", str(out), "--workers", str(workers)]
            seconds, code = timed(run)
            rerun_seconds, rerun_code = timed(run)
            summary = (out / "summary.csv").read_text().splitlines()[1:]
            job_seconds = sum(float(line.split(",")[4]) for line in summary)
            same = True
            for line in summary:
                job_id = line.split(",")[0]
                if reference is None:
                    continue
                same &= filecmp.cmp(out / job_id / "garment.obj", reference / job_id / "garment.obj", shallow=False)
            reference = reference or out
            rows.append((name, workers, code, seconds, 60.0 * jobs / seconds, job_seconds, rerun_code,
                         rerun_seconds / jobs, same))
            print(f"{name:6} workers {workers}: exit {code}, {seconds:7.1f} s, {60.0 * jobs / seconds:5.2f} jobs/min, "
                  f"jobs' own time {job_seconds:6.1f} s; all reused: exit {rerun_code}, "
                  f"{rerun_seconds / jobs:6.3f} s per job; garment.obj same bytes: {same}", flush=True)
    if args.overhead > 1:
        measure_overhead(args.out, runners, args.overhead)
    return 0 if all(row[2] in (0, 8) and row[8] for row in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
