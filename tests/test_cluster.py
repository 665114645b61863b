"""bench on a Ray cluster: a local cluster started here (2 CPUs, a custom "vsgl_gpu" resource
standing in for GPUs) runs a 2 scenes × 2 methods × 2 N sweep whose report equals the local
sweep's except for the timing columns; an interrupted sweep resumes with only what is missing;
and the errors a user can act on."""

from __future__ import annotations

import socket
import sys

import pytest

from vsgl import bench
from vsgl.bench.cluster import same_rows_but_timing

ray = pytest.importorskip("ray", reason="the cluster extra (pip install 'vsgl[cluster]') is not installed")

SWEEP = dict(scenes=("cornell_box", "diffuse_cornell"), methods=("vpl", "vsgl"), lights=(16, 32), size=(24, 16),
             rsm_sizes=(32,), seeds=(0, 1), frames=2, warmup=0, reference_rsm=32, progress=False)
RESOURCE = "vsgl_gpu"


class _Interrupted(Exception):
    pass


@pytest.fixture(scope="module")
def local_cluster():
    ray.init(num_cpus=2, resources={RESOURCE: 2}, logging_level="ERROR", log_to_driver=False, include_dashboard=False)
    yield "auto"
    ray.shutdown()


@pytest.fixture(scope="module")
def local_report():
    return bench.run(**SWEEP)


@pytest.mark.gpu
@pytest.mark.slow
def test_a_cluster_sweep_reports_what_the_local_sweep_does(local_cluster, local_report, tmp_path):
    report = bench.run(cluster=local_cluster, cluster_gpu_resource=RESOURCE, out=tmp_path, **SWEEP)
    assert len(report.rows) == 2 * 2 * 2
    assert same_rows_but_timing(local_report, report) == []
    assert report.reference_rel_error == local_report.reference_rel_error
    assert report.cluster["ran"] == 8 and report.cluster["resumed"] == 0
    assert all(r.adapter for r in report.rows) and all(r.adapter is None for r in local_report.rows)
    assert "adapter" in (tmp_path / "bench.csv").read_text().splitlines()[0].split(",")
    # The comparison can fail: one changed error is found.
    report.rows[3].rmse_indirect *= 1.0001
    assert len(same_rows_but_timing(local_report, report)) == 1


@pytest.mark.gpu
@pytest.mark.slow
def test_an_interrupted_sweep_reruns_only_what_is_missing(local_cluster, local_report, tmp_path):
    def stop_after_three(done, total):
        if done >= 3:
            raise _Interrupted()

    with pytest.raises(_Interrupted):
        bench.run(cluster=local_cluster, cluster_gpu_resource=RESOURCE, out=tmp_path, _on_cluster_result=stop_after_three, **SWEEP)
    stored = sorted(p.name for p in (tmp_path / "cluster").glob("config-*.pkl"))
    assert len(stored) == 3 and not list((tmp_path / "cluster").glob("*.tmp"))
    resumed = bench.run(cluster=local_cluster, cluster_gpu_resource=RESOURCE, out=tmp_path, **SWEEP)
    assert resumed.cluster["resumed"] == 3 and resumed.cluster["ran"] == 5
    assert same_rows_but_timing(local_report, resumed) == []
    again = bench.run(cluster=local_cluster, cluster_gpu_resource=RESOURCE, out=tmp_path, **SWEEP)
    assert again.cluster["ran"] == 0 and again.cluster["resumed"] == 8


def test_cluster_errors_name_what_to_do(tmp_path, monkeypatch):
    with pytest.raises(ValueError, match="needs --out"):
        bench.run(cluster="auto", out=None, **SWEEP)
    with pytest.raises(ValueError, match="expected auto, local or HOST:PORT"):
        bench.run(cluster="nowhere", out=tmp_path, **SWEEP)
    # A port nobody listens on: the address named, with the wait.
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    from vsgl.bench.cluster import connect

    with pytest.raises(ConnectionError, match=rf"cluster 127\.0\.0\.1:{port}: no answer within 2 s"):
        connect(f"127.0.0.1:{port}", timeout_s=2)
    # The extra missing: its name.
    monkeypatch.setitem(sys.modules, "ray", None)
    with pytest.raises(ImportError, match=r"pip install 'vsgl\[cluster\]'"):
        bench.run(cluster="auto", out=tmp_path, **SWEEP)


@pytest.mark.gpu
@pytest.mark.slow
def test_a_resource_the_cluster_lacks_is_named(local_cluster, tmp_path):
    with pytest.raises(ValueError, match="no 'GPU' resource"):
        bench.run(cluster=local_cluster, out=tmp_path, **SWEEP)
