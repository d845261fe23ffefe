import filecmp
import importlib.util

import pytest

from garment_retarget import cluster, read_summary

dask_distributed = pytest.importorskip("dask.distributed")

# Dask is in python/requirements-test.txt, so CI runs its test; Ray's runs where it is installed.
ENGINES = [
    "dask",
    pytest.param("ray", marks=pytest.mark.skipif(importlib.util.find_spec("ray") is None, reason="ray not installed")),
]


@pytest.mark.parametrize("engine", ENGINES)
def test_cluster_writes_the_batch_bytes(engine, manifest, batch_out, tmp_path):
    out = tmp_path / "cluster"
    result = cluster.run_cluster(str(manifest), str(out), engine, workers=2, quiet=True)
    outcomes = {job["id"]: job for job in result["jobs"]}
    assert outcomes["dress"]["status"] == "certified"
    assert outcomes["broken"]["status"] == "bad_input"
    assert result["failed"] == 1
    for name in ("garment.obj", "garment.mtl", "certificate.json"):
        assert filecmp.cmp(out / "dress" / name, batch_out / "dress" / name, shallow=False)
    rows = {row["id"]: row for row in read_summary(out)}
    assert rows["dress"]["certificate"] == "certified"
    # A second run reuses the certified job.
    assert cluster.run_cluster(str(manifest), str(out), engine, workers=1, quiet=True)["reused"] == 1


def test_cluster_command_line_reports_a_bad_manifest(tmp_path, capsys):
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "a", "garment": "g.obj"}\n')
    assert cluster.main([str(bad), "--out", str(tmp_path / "out"), "--engine", "dask"]) == 2
    assert "no \"avatar\"" in capsys.readouterr().err


def test_dask_joins_a_running_cluster(manifest, batch_out, tmp_path):
    with dask_distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                       dashboard_address=None) as running:
        out = tmp_path / "joined"
        result = cluster.run_cluster(str(manifest), str(out), "dask", address=running.scheduler_address,
                                     quiet=True)
    assert {job["id"]: job["status"] for job in result["jobs"]} == {"dress": "certified", "broken": "bad_input"}
    assert filecmp.cmp(out / "dress" / "garment.obj", batch_out / "dress" / "garment.obj", shallow=False)
