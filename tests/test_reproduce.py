"""`python -m vsgl reproduce`: the papers' tables beside ours, with the ratios that compare across
hardware and the error column the papers lack (tiny settings: this checks the command, not the
numbers)."""

from __future__ import annotations

import re

import pytest

from vsgl import reproduce


@pytest.mark.gpu
def test_reproduce_prints_every_table_with_the_papers_numbers_ratios_and_errors(capsys):
    assert reproduce.main(["--size", "32x18", "--rsm", "32", "--frames", "1"]) == 0
    out = capsys.readouterr().out
    # The papers' own figures, beside ours.
    for figure in ("15.150", "4.440", "0.816", "11.091", "0.492 ms", "1984 kB"):
        assert figure in out, figure
    for title in ("2015 paper, Table 1", "2016 paper, Table 1", "2015 poster, Table 1"):
        assert title in out, title
    # Ratios that compare across hardware: paper and ours, each a positive number.
    ratios = [float(x) for x in re.findall(r"ours ([0-9.]+)x", out)]
    assert len(ratios) >= 3 and all(r > 0 for r in ratios), out
    assert re.search(r"kmeans3d\s+total over FIS: paper 9\.34x \(Table 2: 16\.78x\), ours [0-9.]+x, \d+ dispatches", out), out
    # The error column the papers lack, for every configuration.
    errors = re.findall(r"(?:VPLs|BRSM|VSGL|LPV) ([0-9.]+) / ([0-9.]+)", out) + re.findall(r"diffuse ([0-9.]+), block ([0-9.]+)", out)
    assert len(errors) >= 3 + 3 + 2, out
    if "CPU adapter" in out:
        # No absolute time of ours on a CPU adapter.
        assert "(cpu)" in out and not re.search(r"ours\s+[0-9]+\.[0-9]{3}\b", out), out


def test_reproduce_refuses_an_unknown_table():
    with pytest.raises(SystemExit):
        reproduce.main(["--tables", "tok17"])


@pytest.mark.gpu
def test_reproduce_warms_the_clock_as_the_bench_does_and_says_when_it_stayed_cold(capsys, monkeypatch):
    from vsgl import bench

    from test_bench import _FakeClock

    monkeypatch.setattr(bench, "CLOCK_WARM_MAX_EXTRA_S", 0.3)
    args = ["--tables", "poster", "--size", "24x16", "--rsm", "32", "--frames", "1"]
    # A clock that is warm after a few reads: the warm-up renders until then, so the timed
    # frames' clocks read warm and nothing is said.
    monkeypatch.setattr(bench, "_clock_for", lambda cpu: _FakeClock(warm_after=4))
    assert reproduce.main(args) == 0
    assert "ran cold" not in capsys.readouterr().err
    # A clock that never warms: the table is still printed, and says so.
    monkeypatch.setattr(bench, "_clock_for", lambda cpu: _FakeClock(warm_after=None))
    assert reproduce.main(args) == 0
    assert "SM clock 360-360 of 1980 MHz" in capsys.readouterr().err
