"""Runs a batch manifest on a distributed engine, one task per job.

    python -m garment_retarget.cluster MANIFEST --out DIR --engine dask|ray [--address ADDR]

Each task runs the job exactly as ``garment-retarget batch`` does (the same program, the
same arguments, the same temporary folder swapped into DIR/<id>), so the outputs are the
same bytes, and jobs with certified outputs for the same inputs and options are reused.
Without --address a local cluster of --workers processes is started; with it, the run
joins an existing cluster (Dask: the scheduler's tcp://host:8786; Ray: host:6379 or
ray://host:10001). Every worker needs this package and the manifest's inputs and DIR at
the same paths (a shared file system).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Callable, Iterator

from . import _core, program_path

ENGINES = ("dask", "ray")


def run_job(manifest: str, job_id: str, out: str, threads: int) -> dict:
    """One task: the job `job_id` of `manifest` into OUT/<id>, run by the package's program."""
    return _core.run_job(manifest, job_id, out, program_path(), threads)


def _dask_outcomes(manifest: str, ids: list[str], out: str, threads: int, workers: int,
                   address: str | None) -> Iterator[dict]:
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if address is None:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
    client = Client(address if address is not None else cluster)
    try:
        futures = [client.submit(run_job, manifest, job_id, out, threads, key=f"job-{job_id}", pure=False)
                   for job_id in ids]
        for future in as_completed(futures):
            yield future.result()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _ray_outcomes(manifest: str, ids: list[str], out: str, threads: int, workers: int,
                  address: str | None) -> Iterator[dict]:
    import ray

    if address is None:
        ray.init(num_cpus=workers * threads, include_dashboard=False, log_to_driver=False)
    else:
        ray.init(address=address, log_to_driver=False)
    try:
        task = ray.remote(num_cpus=threads, max_retries=0)(run_job)
        pending = [task.remote(manifest, job_id, out, threads) for job_id in ids]
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            yield ray.get(done[0])
    finally:
        ray.shutdown()


OUTCOMES: dict[str, Callable[..., Iterator[dict]]] = {"dask": _dask_outcomes, "ray": _ray_outcomes}


def _duration(seconds: float) -> str:
    seconds = round(seconds)
    return f"{seconds}s" if seconds < 60 else f"{seconds // 60}m{seconds % 60:02d}s"


def run_cluster(manifest: str, out: str, engine: str, address: str | None = None, workers: int = 1,
                threads_per_job: int = 0, quiet: bool = False) -> dict:
    """Runs every job of `manifest` on `engine` into `out`; writes OUT/summary.csv.

    Returns ``jobs`` (each job's outcome: id, status, exit_code, reused, seconds, error),
    ``failed`` (jobs not ending certified), ``reused`` and ``seconds`` (wall time).
    """
    if engine not in OUTCOMES:
        raise ValueError(f"engine must be one of {', '.join(ENGINES)}, not {engine!r}")
    manifest = os.path.abspath(manifest)
    out = os.path.abspath(out)
    ids = _core.manifest_ids(manifest)
    os.makedirs(out, exist_ok=True)
    _core.remove_interrupted_jobs(out)
    threads = threads_per_job or (_core.threads_per_job(workers) if address is None else 1)
    start = time.monotonic()
    outcomes: list[dict] = []
    failed = reused = 0
    for outcome in OUTCOMES[engine](manifest, ids, out, threads, workers, address):
        outcomes.append(outcome)
        reused += outcome["reused"]
        ok = outcome["reused"] or outcome["status"] in ("certified", "shape_changed")
        failed += not ok
        if not quiet:
            computed = len(outcomes) - reused
            left = len(ids) - len(outcomes)
            elapsed = time.monotonic() - start
            eta = _duration(elapsed / computed * left) if computed and left else ("0s" if not left else "?")
            how = "certified earlier, reused" if outcome["reused"] else f"{outcome['status']} in {outcome['seconds']:.1f} s"
            error = f" ({outcome['error']})" if outcome["error"] else ""
            print(f"{engine}: {outcome['id']}: {how}{error}; {len(outcomes)}/{len(ids)} done, "
                  f"{failed} failed, {left} left, ETA {eta}", file=sys.stderr, flush=True)
    _core.write_summary(manifest, out, [o["id"] for o in outcomes if o["reused"]])
    order = {job_id: i for i, job_id in enumerate(ids)}
    outcomes.sort(key=lambda o: order[o["id"]])
    return {"jobs": outcomes, "failed": failed, "reused": reused, "seconds": time.monotonic() - start}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m garment_retarget.cluster",
        description="Run a garment-retarget batch manifest on Dask or Ray, one task per job.")
    parser.add_argument("manifest", help="JSON Lines manifest, as for garment-retarget batch")
    parser.add_argument("--out", required=True, help="batch folder, on a file system every worker shares")
    parser.add_argument("--engine", choices=ENGINES, default="dask", help="distributed engine (default: dask)")
    parser.add_argument("--address", help="join this cluster instead of starting a local one")
    parser.add_argument("--workers", type=int, default=1, help="worker processes of the local cluster")
    parser.add_argument("--threads-per-job", type=int, default=0,
                        help="threads of each job (0: the local cores split between the workers; 1 on a "
                             "cluster given by --address)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args(argv)
    if args.workers < 1 or args.threads_per_job < 0:
        parser.error("--workers must be at least 1 and --threads-per-job at least 0")
    try:
        result = run_cluster(args.manifest, args.out, args.engine, args.address, args.workers,
                             args.threads_per_job, args.quiet)
    except (_core.InputError, _core.OutputError) as error:
        print(f"garment-retarget: error: {error}", file=sys.stderr)
        return 2 if isinstance(error, _core.InputError) else 5
    jobs = result["jobs"]
    print(f"{len(jobs)} jobs: {len(jobs) - result['reused'] - result['failed']} computed, {result['reused']} "
          f"reused, {result['failed']} failed in {result['seconds']:.1f} s; summary: "
          f"{os.path.join(os.path.abspath(args.out), 'summary.csv')}")
    return 0 if result["failed"] == 0 else 8


if __name__ == "__main__":
    sys.exit(main())
