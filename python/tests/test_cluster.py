import filecmp

import pytest

from garment_retarget import cluster, read_summary

dask_distributed = pytest.importorskip("dask.distributed")


def test_dask_cluster_writes_the_batch_bytes(manifest, batch_out, tmp_path):
    out = tmp_path / "cluster"
    result = cluster.run_cluster(str(manifest), str(out), "dask", workers=2, quiet=True)
    outcomes = {job["id"]: job for job in result["jobs"]}
    assert outcomes["dress"]["status"] == "certified"
    assert outcomes["broken"]["status"] == "bad_input"
    assert result["failed"] == 1
    for name in ("garment.obj", "garment.mtl"):
        if (batch_out / "dress" / name).exists():
            assert filecmp.cmp(out / "dress" / name, batch_out / "dress" / name, shallow=False)
    rows = {row["id"]: row for row in read_summary(out)}
    assert rows["dress"]["certificate"] == "certified"
    # A second run reuses the certified job.
    assert cluster.run_cluster(str(manifest), str(out), "dask", workers=1, quiet=True)["reused"] == 1


def test_cluster_command_line_reports_a_bad_manifest(tmp_path, capsys):
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "a", "garment": "g.obj"}\n')
    assert cluster.main([str(bad), "--out", str(tmp_path / "out"), "--engine", "dask"]) == 2
    assert "no \"avatar\"" in capsys.readouterr().err
