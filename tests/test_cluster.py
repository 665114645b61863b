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
    with pytest.raises(ValueError, match="no 'gpu_node' resource to schedule tasks on .*CPU"):
        bench.run(cluster=local_cluster, cluster_gpu_resource="gpu_node", out=tmp_path, **SWEEP)


@pytest.mark.gpu
@pytest.mark.slow
def test_a_cluster_without_gpus_runs_on_cpu_adapters_and_says_so(local_cluster, local_report, tmp_path):
    # The default resource, GPU, on a cluster that has none (this one): a CPU a task.
    report = bench.run(cluster=local_cluster, out=tmp_path, **SWEEP)
    assert "offers no GPU" in report.note
    assert same_rows_but_timing(local_report, report) == []


def test_a_task_opens_the_gpu_ray_assigned_it_by_bus_id():
    from vsgl.bench.cluster import assigned_adapter, nvidia_bus_ids

    smi = "0, 00000000:17:00.0\n1, 00000000:2A:00.0\n"
    bus = nvidia_bus_ids(smi)
    assert bus == {"0": "00000000:17:00.0", "1": "00000000:2A:00.0"}
    assert assigned_adapter(None, [1], bus) == "pci:00000000:2A:00.0"  # not GPU 0, whatever CUDA_VISIBLE_DEVICES says
    assert assigned_adapter("H200", [1], bus) == "H200"  # the sweep's own choice wins
    assert assigned_adapter(None, [], bus) is None  # no GPU assigned: the best adapter there is
    with pytest.raises(RuntimeError, match="GPU 3 assigned by Ray has no PCI bus id"):
        assigned_adapter(None, [3], bus)


def test_renderer_takes_a_pci_bus_id_and_names_the_adapters_it_saw():
    import vsgl

    seen = vsgl.adapters()
    assert all({"pci_bus_id", "limits"} <= set(a) for a in seen)
    assert all(a["limits"]["max_storage_binding_bytes"] > 0 and a["limits"]["max_texture_side"] >= 2048 for a in seen)
    with pytest.raises(vsgl.NoAdapterError, match=r'no adapter at PCI bus id "0000:ff:1f\.7"; adapters seen: .+'):
        vsgl.Renderer(8, 8, adapter="pci:0000:ff:1f.7")
    with_bus = [a for a in seen if a["pci_bus_id"]]
    if with_bus:  # a GPU machine: its own bus id opens it, in NVML's spelling too
        bus = with_bus[0]["pci_bus_id"]
        assert vsgl.Renderer(8, 8, adapter=f"pci:{bus}").adapter["name"] == with_bus[0]["name"]
