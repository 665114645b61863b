"""The error-against-run-time benchmark and its metrics."""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import vsgl
from vsgl import bench, metrics


def test_metrics_match_their_definitions():
    rng = np.random.default_rng(3)
    ref = rng.random((5, 7, 3))
    x = ref + rng.normal(0, 0.1, ref.shape)
    assert metrics.rmse(x, ref) == pytest.approx(math.sqrt(np.sum((x - ref) ** 2) / x.size))
    eps = 1e-2 * np.mean(ref**2)
    assert metrics.relmse(x, ref) == pytest.approx(np.mean((x - ref) ** 2 / (ref**2 + eps)))
    assert metrics.relmse(x, ref, eps=0.5) == pytest.approx(np.mean((x - ref) ** 2 / (ref**2 + 0.5)))
    assert metrics.rmse(ref, ref) == 0.0
    # A known case by hand: errors 0, 3, 4 → RMSE sqrt(25/3).
    assert metrics.rmse(np.array([1.0, 5.0, 6.0]), np.array([1.0, 2.0, 2.0])) == pytest.approx(math.sqrt(25 / 3))
    with pytest.raises(ValueError, match="shape"):
        metrics.rmse(np.zeros(3), np.zeros(4))


def test_small_sweep_writes_files_and_has_sane_numbers(tmp_path, renderer):
    report = bench.run(
        scenes=["cornell_box"],
        methods=["vpl", "vsgl", "reference"],
        lights=[8, 512],
        size=(48, 32),
        rsm_sizes=[64],
        seeds=(0, 1, 2, 3),
        frames=2,
        reference_rsm=64,
        out=tmp_path,
        progress=False,
    )
    for name in ("bench.csv", "bench.json", "bench.txt", "error_vs_time.png", "error_vs_lights.png", "bias_noise_vs_lights.png"):
        assert (tmp_path / name).is_file(), name
    rows = list(csv.DictReader(open(tmp_path / "bench.csv")))
    assert len(rows) == len(report.rows) == 5
    data = json.loads((tmp_path / "bench.json").read_text())
    assert data["adapter"]["name"] and data["size"] == [48, 32]
    for r in report.rows:
        for value in (r.rmse_indirect, r.rmse_image, r.relmse_indirect, r.relmse_image, r.total_ms_median):
            assert math.isfinite(value) and value >= 0
        assert r.total_ms_min <= r.total_ms_median <= r.total_ms_max
    by = {(r.method, r.num_lights): r for r in report.rows}
    # The reference against itself (same RSM, same view) has zero error.
    assert by[("reference", None)].rmse_indirect == 0.0
    # ... so it is marked and does not compete at equal time (it would win every budget).
    assert "the reference itself" in by[("reference", None)].notes
    assert report.equal_time and all(e["best"]["method"] != "reference" for e in report.equal_time)
    # VPL error falls as N grows.
    assert by[("vpl", 512)].rmse_indirect < by[("vpl", 8)].rmse_indirect
    text = bench.table(report)
    assert "llvmpipe" in text or report.adapter["name"] in text
    if report.adapter["device_type"] == "Cpu":
        assert "only ratios" in text
    # The reference is cached on disk and reused.
    assert list((tmp_path / "cache").glob("reference-*.npz"))


def test_cli_help_documents_every_flag():
    out = subprocess.run([sys.executable, "-m", "vsgl", "bench", "--help"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0
    for flag in ("--scene", "--methods", "--lights", "--size", "--rsm-sizes", "--kernels", "--lighting", "--seeds", "--reference", "--plans", "--out"):
        assert flag in out.stdout, flag


def test_bad_arguments_are_rejected(tmp_path):
    with pytest.raises(ValueError, match="methods"):
        bench.run(methods=["photon"], size=(8, 8), out=None, progress=False)
    with pytest.raises(ValueError, match="reference"):
        bench.run(reference="oracle", size=(8, 8), out=None, progress=False)
    # A seed count where the seeds are asked for (a TypeError from len() before).
    for seeds in (2, "01", (0, 1.5)):
        with pytest.raises(ValueError, match=r"seeds: expected a list of integer seeds, e\.g\. \(0, 1\)"):
            bench.run(seeds=seeds, size=(8, 8), out=None, progress=False)


def test_pruned_and_full_plans_are_timed_side_by_side_with_equal_error(tmp_path, renderer):
    """The leave-out benchmark: on the diffuse-only box the pruned plan's image error
    equals the full plan's (pruning is output-neutral), and the ratio of their times is reported."""
    report = bench.run(
        scenes=["diffuse_cornell"], methods=["vsgl", "vpl"], lights=[32], size=(32, 24), rsm_sizes=[32],
        seeds=(0,), frames=2, warmup=1, reference_rsm=32, plans=("auto", "full"), out=tmp_path, progress=False,
    )
    assert [r.plan for r in report.rows] == ["auto", "full", "auto", "full"]
    assert len(report.plan_ratios) == 2
    for p in report.plan_ratios:
        assert p["rmse_image_auto"] == pytest.approx(p["rmse_image_full"], rel=1e-5, abs=1e-9)
        assert math.isfinite(p["ratio"]) and p["ratio"] > 0
    assert "pruned/full time" in bench.table(report)
    assert json.loads((tmp_path / "bench.json").read_text())["plan_ratios"]
    with pytest.raises(ValueError, match="plans"):
        bench.run(plans=("some",), size=(8, 8), out=None, progress=False)


def test_timings_report_quartiles_and_the_warm_up(tmp_path, renderer):
    report = bench.run(
        scenes=["cornell_box"], methods=["vsgl2"], size=(32, 24), rsm_sizes=[32], seeds=(0,), frames=5,
        reference_rsm=32, out=tmp_path, progress=False, warmup_seconds=0.5,
    )
    (r,) = report.rows
    assert r.total_ms_min <= r.total_ms_q1 <= r.total_ms_median <= r.total_ms_q3 <= r.total_ms_max
    for name, (q1, q3) in r.passes_iqr_ms.items():
        assert q1 <= r.passes_ms[name] <= q3, name
    cpu = renderer.adapter["device_type"] == "Cpu"
    # A CPU adapter has no clock to warm; a GPU gets the asked-for sustained load, and says so.
    assert report.warmup_seconds == (0.0 if cpu else 0.5)
    assert (r.warmup_frames == 0) == cpu
    text = (tmp_path / "bench.txt").read_text()
    assert "IQR" in text and "sustained rendering" in text
    assert "total_ms_q1" in (tmp_path / "bench.csv").read_text()
    with pytest.raises(ValueError, match="warmup_seconds"):
        bench.run(warmup_seconds=-1.0, size=(8, 8), out=None, progress=False)


def test_rows_carry_the_references_own_error_and_flag_a_too_noisy_reference(tmp_path, renderer):
    """A 1-spp path-traced reference (its stderr is as large as its image)
    flags every row "reference too noisy"; a 256-spp one does not flag the rows whose error is
    far above its own (direct light only, which misses all indirect light: relative error 1)."""
    common = dict(scenes=["cornell_box"], methods=["direct", "vpl"], lights=[8], size=(48, 32), rsm_sizes=[32],
                  seeds=(0, 1), frames=1, warmup=0, reference="pathtrace", progress=False)
    noisy = bench.run(reference_spp=1, out=tmp_path / "noisy", **common)
    good = bench.run(reference_spp=256, out=tmp_path / "good", **common)
    assert noisy.reference_rel_error["cornell_box"] > 0.3
    assert good.reference_rel_error["cornell_box"] < 0.3 * noisy.reference_rel_error["cornell_box"]
    for r in noisy.rows:
        assert r.reference_too_noisy and "reference too noisy" in r.notes, r
    direct = next(r for r in good.rows if r.method == "direct")
    assert direct.rel_rmse_indirect == pytest.approx(1.0)
    assert not direct.reference_too_noisy and direct.notes == []
    data = json.loads((tmp_path / "good" / "bench.json").read_text())
    assert data["reference_rel_error"]["cornell_box"] == good.reference_rel_error["cornell_box"]
    for row in data["rows"]:
        for key in ("reference_rel_error", "bias", "noise", "relmse_indirect_debiased", "relmse_indirect_debiased_interval", "reference_too_noisy"):
            assert key in row, key
        lo, hi = row["relmse_indirect_debiased_interval"]
        assert lo <= row["relmse_indirect_debiased"] <= hi
    vpl = next(r for r in good.rows if r.method == "vpl")
    assert vpl.noise > 0 and vpl.bias >= 0
    assert direct.noise == 0.0
    csv_rows = list(csv.DictReader(open(tmp_path / "noisy" / "bench.csv")))
    assert all(r["reference_too_noisy"] == "True" and "reference too noisy" in r["notes"] for r in csv_rows)
    text = bench.table(noisy)
    assert "its own error" in text and "reference too noisy" in text


def test_equal_time_names_a_winner_per_scene_and_the_rsm_reference_reports_its_error(tmp_path, renderer):
    """Every scene gets equal-time entries (the best row within each
    budget, and its margin over another method with an interval); the every-texel reference's
    own error comes from one at another RSM size, and the reference's cost counts every batch."""
    report = bench.run(
        scenes=["cornell_box", "diffuse_cornell"], methods=["vpl", "vsgl2"], lights=[8, 64], size=(32, 24), rsm_sizes=[32],
        seeds=(0, 1), frames=1, warmup=0, reference_rsm=64, out=tmp_path, progress=False,
    )
    scenes = {e["scene"] for e in report.equal_time}
    assert scenes == {"cornell_box", "diffuse_cornell"}
    for scene in scenes:
        entries = [e for e in report.equal_time if e["scene"] == scene]
        assert len(entries) == len({r.total_ms_median for r in report.rows if r.scene == scene})
        last = entries[-1]  # the largest budget holds every row
        rows = [r for r in report.rows if r.scene == scene]
        assert last["best"]["relmse_indirect_debiased"] == min(r.relmse_indirect_debiased for r in rows)
        assert last["runner_up"]["method"] != last["best"]["method"]
        c = last["runner_up_vs_best"]
        assert c["difference"] >= 0 and c["difference_interval"][0] <= c["difference"] <= c["difference_interval"][1]
        # The 64² reference against a 32² one: a small but nonzero error.
        assert 0 < report.reference_rel_error[scene] < 0.5
        assert report.reference_batches[scene] >= 2 and report.reference_ms[scene] > 0
    assert "equal time cornell_box" in bench.table(report)
    assert json.loads((tmp_path / "bench.json").read_text())["equal_time"]


def test_cpu_defaults_scale_down_only_what_is_not_given():
    given = {k: None for k in bench.GPU_DEFAULTS}
    used, scaled = bench._resolve_defaults(given, cpu=True)
    assert used == bench.CPU_DEFAULTS
    # Only what differs from the GPU defaults is reported as scaled; the reference shrinks most.
    assert scaled and all(bench.CPU_DEFAULTS[k] != bench.GPU_DEFAULTS[k] for k in scaled)
    assert scaled["reference_rsm"] < bench.GPU_DEFAULTS["reference_rsm"]
    used, scaled = bench._resolve_defaults(dict(given, size=(300, 200)), cpu=True)
    assert used["size"] == (300, 200) and "size" not in scaled
    used, scaled = bench._resolve_defaults(given, cpu=False)
    assert used == bench.GPU_DEFAULTS and scaled == {}


def test_the_reference_shows_its_progress_and_counts_every_batch(make_renderer):
    """On a CPU adapter the reference submits small batches, reports progress
    between them, and the bench's cost of it counts them all (wall time over every batch)."""
    renderer = make_renderer(48, 32)
    if renderer.adapter["device_type"] != "Cpu":
        pytest.skip("the small batches are a CPU adapter's (a GPU batches 2^31 evaluations)")
    seen = []
    ref = bench._reference(renderer, vsgl.scenes.cornell_box(), (48, 32), "reference", {"rsm_size": 128}, None, lambda *a: seen.append(a))
    assert len(seen) >= 1 and seen[-1][1] == 128 * 128 and seen[-1][2] == "texels"
    assert [d for d, _, _ in seen] == sorted(d for d, _, _ in seen)
    assert ref.batches == len(seen) + 1
    assert ref.wall_ms > 0


@pytest.mark.gpu
def test_bench_lights_scenes_from_the_shell(tmp_path, capsys):
    """--no-scene-lights and --light (any type) light every scene of the sweep; a bad --light
    is a usage error naming it."""
    out = tmp_path / "lit"
    argv = ["--scene", "cornell_box", "--methods", "vpl", "--lights", "16", "--size", "24x16", "--rsm-sizes", "32", "--seeds", "1",
            "--frames", "1", "--warmup-seconds", "0", "--reference-rsm", "32", "--no-progress", "--out", str(out),
            "--no-scene-lights", "--light", "point position=0,1,0 intensity=3", "--light", "directional direction=0.3,-1,-0.2 intensity=2"]
    assert bench.main(argv) == 0
    data = json.loads((out / "bench.json").read_text())
    row = data["rows"][0]
    assert row["method"] == "vpl" and math.isfinite(row["rmse_indirect"])
    frame_lights = bench._scene("cornell_box")
    assert len(frame_lights.lights) == 1, "the built-in scene itself is untouched"
    with pytest.raises(SystemExit) as e:
        bench.main(argv[:-4] + ["--light", "lamp"])
    assert e.value.code == 2 and "--light" in capsys.readouterr().err


def test_sequence_reports_flicker_next_to_error_and_time(tmp_path, renderer):
    """`--sequence N` renders N frames of a moving light per configuration
    (cave_flashlight: its sweep) and reports metrics.flicker of indirect against the
    reference's frames: 0 for the reference itself, > 0 for the approximations, and vsgl below
    vpl at equal N; `--K` sweeps vsgl's kernel mass (lavapipe, 32×32, 8 frames: vpl 1.76,
    vsgl K=1 1.50, K=2 1.25, K=4 1.11, vsgl2 1.01)."""
    with pytest.raises(ValueError, match="sequence: expected 0"):
        bench.run(sequence=1, size=(8, 8), out=None, progress=False)
    with pytest.raises(ValueError, match=r"Ks: K: must be finite and > 0"):
        bench.run(Ks=(0.0,), size=(8, 8), out=None, progress=False)
    report = bench.run(scenes=["cave_flashlight"], methods=["reference", "vpl", "vsgl", "vsgl2"], lights=[32], size=(32, 32),
                       rsm_sizes=[64], reference_rsm=64, seeds=(0,), frames=1, warmup=0, sequence=4, Ks=(1.0, 4.0),
                       out=tmp_path, progress=False)
    flick = {(r.method, r.K): r.flicker_indirect for r in report.rows}
    assert flick[("reference", None)] == 0.0
    assert flick[("vsgl2", None)] > 0.0 and flick[("vsgl", 1.0)] < flick[("vpl", None)], flick
    # --K sweeps vsgl's kernel mass: larger K, less flicker here (the sweep is smooth).
    assert flick[("vsgl", 4.0)] < flick[("vsgl", 1.0)], flick
    assert "integral K=4" in bench.table(report)
    assert "animation over 4 s" in report.sequence_motion["cave_flashlight"]
    assert "flicker" in bench.table(report)
    rows = list(csv.DictReader(open(tmp_path / "bench.csv")))
    assert float(rows[0]["flicker_indirect"]) == 0.0 and {r["K"] for r in rows} == {"", "1.0", "4.0"}
    assert json.loads((tmp_path / "bench.json").read_text())["sequence"] == 4


@pytest.mark.gpu
def test_bench_shadows_every_virtual_light_and_the_reference_with_visibility(tmp_path):
    """--visibility raytrace: the methods cast shadow rays and the every-texel reference too,
    so a method agreeing with the reference has no visibility error to hide."""
    report = bench.run(scenes=["cornell_box"], methods=["vpl", "reference"], lights=[64], size=(24, 16), rsm_sizes=[32], seeds=(0,),
                       frames=1, warmup_seconds=0, reference_rsm=32, visibility="raytrace", out=tmp_path, progress=False)
    assert report.visibility == "raytrace" and report.reference_settings["visibility"] == "raytrace"
    by = {r.method: r for r in report.rows}
    # The reference against itself with the same visibility: zero error.
    assert by["reference"].rmse_indirect == 0.0
    assert "visibility raytrace" in bench.table(report)
    assert json.loads((tmp_path / "bench.json").read_text())["visibility"] == "raytrace"
    with pytest.raises(ValueError, match="visibility"):
        bench.run(scenes=["cornell_box"], methods=["vpl"], visibility="shadows", progress=False)


def test_lighting_sweeps_the_sg_lighting_forms_of_vsgl_and_vsgl2(tmp_path, renderer):
    """--lighting asg,accurate: one row per form for vsgl and vsgl2 (not for
    vpl), named in the table and the CSV; the two forms differ on a glossy scene."""
    report = bench.run(
        scenes=["glossy_cornell"], methods=["vpl", "vsgl", "vsgl2"], lights=[32], size=(24, 16), rsm_sizes=[32],
        seeds=(0,), frames=1, warmup=0, reference_rsm=32, lightings=("asg", "accurate"), out=tmp_path, progress=False,
    )
    assert [(r.method, r.lighting) for r in report.rows] == [
        ("vpl", None), ("vsgl", "asg"), ("vsgl", "accurate"), ("vsgl2", "asg"), ("vsgl2", "accurate")]
    table = bench.table(report)
    for label in ("vsgl:asg", "vsgl:accurate", "vsgl2:asg", "vsgl2:accurate"):
        assert label in table, label
    by = {(r.method, r.lighting): r.rmse_indirect for r in report.rows}
    assert by[("vsgl2", "asg")] != by[("vsgl2", "accurate")]
    assert "lighting" in (tmp_path / "bench.csv").read_text().splitlines()[0].split(",")
    with pytest.raises(ValueError, match="lightings"):
        bench.run(lightings=("exact",), size=(8, 8), out=None, progress=False)


@pytest.mark.gpu
def test_option_sweeps_any_method_option_for_the_methods_that_take_it(tmp_path):
    """-O NAME=V1,V2 sweeps an option that has no axis of its own (here lambert_lobe, which
    vsgl and vsgl2 take and vpl does not): one row per value for the methods that take it, the
    value in the table, the CSV and the JSON, and the values render differently (the papers'
    lobe delivers 1/1.101 of the hemisphere one's diffuse light). Options with their own axis,
    options no swept method takes, and empty value lists are refused by name."""
    out = tmp_path / "b"
    done = subprocess.run([sys.executable, "-m", "vsgl", "bench", "--scene", "diffuse_cornell", "--methods", "vpl,vsgl,vsgl2", "--lights", "32",
                           "--size", "24x16", "--rsm-sizes", "32", "--seeds", "1", "--frames", "1", "--warmup", "0", "--reference-rsm", "32",
                           "-O", "lambert_lobe=papers,hemisphere", "--no-progress", "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    for label in ("vsgl(lambert_lobe=papers)", "vsgl(lambert_lobe=hemisphere)", "vsgl2(lambert_lobe=papers)", "vsgl2(lambert_lobe=hemisphere)"):
        assert label in done.stdout, label
    rows = list(csv.DictReader((out / "bench.csv").open()))
    assert [(r["method"], r["options"]) for r in rows] == [
        ("vpl", ""), ("vsgl", "lambert_lobe=papers"), ("vsgl", "lambert_lobe=hemisphere"),
        ("vsgl2", "lambert_lobe=papers"), ("vsgl2", "lambert_lobe=hemisphere")]
    saved = json.loads((out / "bench.json").read_text())["rows"]
    assert [r["options"] for r in saved] == [None, {"lambert_lobe": "papers"}, {"lambert_lobe": "hemisphere"},
                                             {"lambert_lobe": "papers"}, {"lambert_lobe": "hemisphere"}]
    err = {(r["method"], r["options"]): float(r["rmse_indirect"]) for r in rows}
    assert err[("vsgl", "lambert_lobe=papers")] != err[("vsgl", "lambert_lobe=hemisphere")]
    for bad, match in (({"kernel": ("node",)}, "--kernels"), ({"photon_count": (1,)}, "none of the methods"), ({"lambert_lobe": ()}, "non-empty")):
        with pytest.raises(ValueError, match=match):
            bench.run(methods=["vsgl"], options=bad, size=(8, 8), out=None, progress=False)
    # A value the option refuses is named before anything is rendered: the scene below does not
    # exist, so a check that came only with the first render would report the scene instead.
    with pytest.raises(vsgl.ArgumentError, match="lambert_lobe: must be one of"):
        bench.run(scenes=["no_such_scene"], methods=["vsgl"], options={"lambert_lobe": ("papers", "sphere")}, size=(8, 8), out=None, progress=False)
    refused = subprocess.run([sys.executable, "-m", "vsgl", "bench", "-O", "lambert_lobe"], capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and "NAME=V1,V2" in refused.stderr, refused.stderr


@pytest.mark.gpu
def test_bench_compares_rsm_and_brsm_importance(tmp_path):
    """--importance rsm,brsm: each vpl and vsgl configuration runs with both sampling densities
    (rows marked in the table, CSV and JSON); methods that sample nothing run once."""
    with pytest.raises(ValueError, match="importances: expected"):
        bench.run(importances=("bidirectional",), size=(8, 8), out=None, progress=False)
    report = bench.run(scenes=["cornell_box"], methods=["vpl", "vsgl", "reference"], lights=[64], size=(24, 16), rsm_sizes=[32], seeds=(0, 1),
                       frames=1, warmup_seconds=0, reference_rsm=32, importances=("rsm", "brsm"), out=tmp_path, progress=False)
    got = sorted((r.method, r.importance) for r in report.rows)
    assert got == [("reference", None), ("vpl", "brsm"), ("vpl", "rsm"), ("vsgl", "brsm"), ("vsgl", "rsm")]
    by = {(r.method, r.importance): r for r in report.rows}
    assert "brsm_importance" in by[("vpl", "brsm")].passes_ms or not by[("vpl", "rsm")].passes_ms
    assert "brsm_importance" not in by[("vpl", "rsm")].passes_ms
    for key in [("vpl", "brsm"), ("vsgl", "brsm")]:
        assert by[key].rel_rmse_indirect is not None and np.isfinite(by[key].rel_rmse_indirect)
    assert " brsm" in bench.table(report)
    rows = list(csv.DictReader(open(tmp_path / "bench.csv")))
    assert {r["importance"] for r in rows} == {"", "rsm", "brsm"}
    assert {r["importance"] for r in json.loads((tmp_path / "bench.json").read_text())["rows"]} == {None, "rsm", "brsm"}


@pytest.mark.gpu
def test_bench_runs_brsm_with_metropolis_and_an_importance_interleave():
    """brsm and metropolis combine (the chains follow the re-weighted density), so the sweep no
    longer skips the pair; --importance-interleave sets the brsm rows' importance_interleave."""
    with pytest.raises(ValueError, match=r"importance_interleave: .*must be in 1\.\.=16"):
        bench.run(importance_interleave=0, size=(8, 8), out=None, progress=False)
    report = bench.run(scenes=["cornell_box"], methods=["vpl"], lights=[32], size=(16, 16), rsm_sizes=[32], seeds=(0,), frames=1, warmup_seconds=0,
                       reference_rsm=32, importances=("rsm", "brsm"), samplings=("stratified", "metropolis"), importance_interleave=2, out=None, progress=False)
    assert sorted((r.importance, r.sampling) for r in report.rows) == [("brsm", "metropolis"), ("brsm", "stratified"), ("rsm", "metropolis"), ("rsm", "stratified")]
    for r in report.rows:
        assert r.rel_rmse_indirect is not None and np.isfinite(r.rel_rmse_indirect)
    brsm = next(r for r in report.rows if r.importance == "brsm")
    assert "brsm_importance_filter" in brsm.passes_ms or not brsm.passes_ms


@pytest.mark.gpu
def test_sampling_sweep_reports_error_flicker_and_time_for_warp_and_metropolis(tmp_path):
    """`--sampling stratified,metropolis`: a row per sampling with its own time, error and flicker
    (the cornell box's slid spot; docs/methods/metropolis.md, "Metropolis–Hastings sampling", has the
    table). Metropolis rows take each seed's frame from fresh chains stepped
    METROPOLIS_BURN_IN frames first."""
    with pytest.raises(ValueError, match="samplings: expected values from stratified, random, metropolis"):
        bench.run(samplings=("warp",), size=(8, 8), out=None, progress=False)
    report = bench.run(scenes=["cornell_box"], methods=["vsgl"], lights=[32], size=(32, 32), rsm_sizes=[64], reference_rsm=64,
                       seeds=(0, 1), frames=1, warmup=0, sequence=6, samplings=("stratified", "metropolis"), out=tmp_path, progress=False)
    by = {r.sampling: r for r in report.rows}
    assert set(by) == {"stratified", "metropolis"}
    for r in by.values():
        assert r.total_ms_median > 0 and r.rel_rmse_indirect > 0 and r.flicker_indirect > 0
    # Measured on lavapipe (8 frames): 0.132 stratified, 0.087 metropolis.
    assert by["metropolis"].flicker_indirect < by["stratified"].flicker_indirect
    text = bench.table(report)
    assert "sampling" in text and "metropolis" in text and "vsgl[integral metropolis]" in text
    rows = list(csv.DictReader(open(tmp_path / "bench.csv")))
    assert {r["sampling"] for r in rows} == {"stratified", "metropolis"}


class _FakeClock(bench._SmClock):
    """An SM clock that idles at 360 MHz and reaches its 1980 MHz boost after `warm_after` reads."""

    def __init__(self, warm_after: int | None) -> None:
        self.reads = 0

        def read() -> int:
            self.reads += 1
            return 1980 if warm_after is not None and self.reads > warm_after else 360

        super().__init__(read, 1980)


@pytest.mark.gpu
def test_warm_up_waits_for_the_clock_and_cold_rows_are_flagged_and_out_of_equal_time(tmp_path, monkeypatch):
    """Warm-up goes on while the SM clock is below 90% of its boost; a row whose clock was still
    cold before or after its timed frames says so and does not compete for equal time (an H200
    sweep with 0.3 s of warm-up timed rows at 360–900 MHz, 2–7x slower than their warm twins)."""
    monkeypatch.setattr(bench, "CLOCK_WARM_MAX_EXTRA_S", 1.0)
    common = dict(scenes=["cornell_box"], methods=["vpl", "vsgl"], lights=[16], size=(24, 16), rsm_sizes=[32], seeds=(0, 1),
                  frames=1, reference_rsm=32, progress=False, warmup_seconds=0.0)
    warming = _FakeClock(warm_after=3)
    monkeypatch.setattr(bench, "_clock_for", lambda cpu: warming)
    report = bench.run(**common, out=tmp_path / "warm")
    first = report.rows[0]
    assert first.warmup_frames >= 3  # rendered while the clock read cold, none were asked for
    assert all(not any(n.startswith("clock cold") for n in r.notes) for r in report.rows)
    assert report.equal_time and all(e["best"] is not None for e in report.equal_time)

    monkeypatch.setattr(bench, "_clock_for", lambda cpu: _FakeClock(warm_after=None))
    report = bench.run(**common, out=tmp_path / "cold")
    assert all(any(n.startswith("clock cold (360-360 of 1980 MHz)") for n in r.notes) for r in report.rows), [r.notes for r in report.rows]
    assert all(e["best"] is None for e in report.equal_time), report.equal_time
    assert "clock cold" in (tmp_path / "cold" / "bench.txt").read_text()
