"""`python -m vsgl stability`: the f32-vs-f64 stability suite of every WGSL math function.

The suite itself (bounds, grids) is asserted in Rust (crates/vsgl-core/tests/stability.rs); here:
the CLI runs on the current adapter, exits 0 and prints a table with every function and family;
the Python API returns well-formed rows; and the pass/fail logic can fail — on the real GPU with
bounds scaled down, and on synthetic rows.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

import vsgl
from vsgl import stability

# Every function of wgsl/common/{math,sg,ggx,vsgl,vsgl_tangent_plane}.wgsl that has an oracle twin.
FUNCTIONS = [
    "expm1_over_x", "expm1", "mulsign", "erf", "safe_normalize", "orthonormal_basis",
    "sg_evaluate", "sg_integral", "sg_integral_approx", "sg_product", "sg_product_integral",
    "sg_mean_cosine", "sg_tangent_second_moment", "sg_cosine_variance", "sg_clamped_cosine_integral",
    "sg_toksvig_mean_direction", "sg_from_toksvig_mean_direction", "lambert_lobe_sg",
    "ggx_ndf_sg_sharpness", "ggx_lobe_sg", "asg_evaluate", "ggx_lobe_asg", "sg_asg_product_integral",
    "sg_asg_product_integral_over_asg_integral", "vsgl_lobe_from_moments", "vsgl_position_from_moments",
    "vsgl_incoming_radiance", "vsgl_diffuse", "vsgl_diffuse_approx", "vsgl_diffuse_accurate",
    "vsgl_diffuse_sg_product", "vsgl_specular", "ggx_alpha_from_roughness", "ggx_d", "ggx_smith_lambda",
    "ggx_smith_g2", "ggx_brdf_over_rs", "lambert_brdf_over_rd", "vsgl_specular_accurate",
    "vsgl_position_seen_from", "vsgl_incoming_radiance_seen", "vsgl_specular_receiver_from",
    "vsgl_specular_with_receiver", "vsgl_specular_blend", "vsgl_specular_filtered", "vsgl_specular_blend_with_receiver",
    "vsgl_tangent_plane_from_moments", "vsgl_tangent_plane_fade",
]


@pytest.fixture(scope="module")
def rows() -> list[dict]:
    try:
        return stability.run()
    except vsgl.NoAdapterError as e:
        if os.environ.get("CI"):
            pytest.fail(f"CI has no GPU adapter: {e}")
        pytest.skip(f"no GPU adapter: {e}")


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    return subprocess.run([sys.executable, "-m", "vsgl", "stability", *args], capture_output=True, text=True, env=env, timeout=600)


@pytest.mark.gpu
def test_cli_passes_and_prints_every_function_and_family(rows: list[dict]) -> None:
    proc = _cli()
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    out = proc.stdout
    header = out.splitlines()[0]
    for column in stability.COLUMNS:
        assert column in header, header
    for name in FUNCTIONS:
        assert f"{name}." in out, f"{name} missing from the table"
    for r in rows:
        assert r["family"] in out, r["family"]
    assert "FAIL" not in out
    assert f"{len(rows)} of {len(rows)} rows pass" in out


@pytest.mark.gpu
def test_rows_are_well_formed_and_pass(rows: list[dict]) -> None:
    keys = {"function", "family", "cases", "max_rel_error", "bound", "worst_ratio", "nonfinite", "passed", "worst_case"}
    assert rows and all(set(r) == keys for r in rows)
    assert {r["function"].split(".")[0] for r in rows} == set(FUNCTIONS)
    for r in rows:
        assert r["cases"] > 0
        assert r["nonfinite"] == 0, r
        assert r["passed"] and r["worst_ratio"] <= 1.0, r
        assert r["max_rel_error"] <= r["bound"] or r["max_rel_error"] == 0.0, r
    assert stability.exit_code(rows) == 0


@pytest.mark.gpu
def test_suite_fails_when_bounds_are_too_tight(rows: list[dict]) -> None:
    # Real GPU errors against bounds / 1000: most rows must fail, and the CLI must exit non-zero.
    tight = stability.run(bound_scale=1e-3)
    failed = [r for r in tight if not r["passed"]]
    assert len(failed) * 2 > len(tight), f"only {len(failed)} of {len(tight)} rows fail at bounds / 1000"
    assert stability.exit_code(tight) == 1
    proc = _cli("--bound-scale", "1e-3")
    assert proc.returncode == 1, proc.stdout[-2000:] + proc.stderr[-2000:]
    assert "FAIL" in proc.stdout


def _row(**overrides: object) -> dict:
    row = {
        "function": "sg_evaluate.value", "family": "synthetic", "cases": 1, "max_rel_error": 1e-7,
        "bound": 1e-6, "worst_ratio": 0.1, "nonfinite": 0, "passed": True, "worst_case": "",
    }
    row.update(overrides)
    return row


def test_pass_fail_logic_on_synthetic_rows(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    assert stability.exit_code([_row()]) == 0
    assert stability.exit_code([_row(), _row(passed=False, worst_ratio=3.0)]) == 1
    assert stability.exit_code([_row(nonfinite=2)]) == 1, "a NaN/Inf count fails even if 'passed' were set"
    assert stability.exit_code([]) == 1, "an empty table is not a pass"
    table = stability.format_table([_row(), _row(function="erf.value", passed=False)])
    assert "FAIL" in table and "pass" in table and "erf.value" in table
    # main() returns non-zero when any row fails, whatever the suite returned
    monkeypatch.setattr(stability, "run", lambda adapter=None, bound_scale=1.0: [_row(), _row(passed=False, worst_ratio=9.0)])
    assert stability.main([]) == 1
    assert "FAIL" in capsys.readouterr().out
    monkeypatch.setattr(stability, "run", lambda adapter=None, bound_scale=1.0: [_row()])
    assert stability.main([]) == 0


def test_bad_arguments() -> None:
    with pytest.raises(ValueError, match="bound_scale"):
        vsgl._vsgl.stability_suite(None, -1.0)
    assert stability.main(["--bound-scale", "0"]) == 2
    with pytest.raises(vsgl.NoAdapterError):
        stability.run(adapter="no-such-adapter-name-xyz")
