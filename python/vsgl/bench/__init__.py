"""Error against run time: ``python -m vsgl bench`` and ``vsgl.bench.run(...)``.

Sweeps methods × light counts × RSM sizes × VSGL kernels (× K with ``--K``, × the SG lighting forms of
vsgl and vsgl2 with ``--lighting asg,accurate,blend``, × any other method option with ``-O NAME=V1,V2``,
for the methods that take it) over scenes at one resolution. For each
configuration it reports GPU time per pass and in total (median, interquartile range and
extremes over frames rendered back to back after a warm-up of ``--warmup-seconds`` of sustained
rendering, so the GPU leaves its idle clock; from timestamp queries; the SM clock before and
after the timed frames where ``nvidia-ml-py`` is installed), and the error of the ``indirect`` AOV and of the full
image against the scene's reference (``reference`` by default, computed once per scene, view
and settings, and cached on disk), as the mean and spread over seeds for stochastic methods.
Writes a terminal table, ``bench.csv``, ``bench.json`` and, with matplotlib, ``error_vs_time.png``,
``error_vs_lights.png`` and ``bias_noise_vs_lights.png``. On a CPU adapter only ratios inside one report mean anything.

Error you can trust (docs/error.md): the reference reports its own error
(``reference_rel_error``: from its stderr for ``pathtrace``, from the difference to one at half
the RSM side for ``reference``), and a row whose error is not at least 3× that is flagged
"reference too noisy". Stochastic methods get ``bias`` and ``noise`` apart and
``relmse_indirect_debiased`` (the MSE less the reference's variance) with a 90% interval, and
``equal_time`` names, per scene and time budget, the method with the lowest debiased error and
by how much it beats the runner-up.

Called with no sizes on a CPU adapter (lavapipe), the defaults scale down so the run takes about
two minutes, and the report and stderr say which.

With ``--plans auto,full`` every configuration also runs with the pass plan forced to
``"full"`` (nothing left out), and the report gives the pruned/full time ratio per configuration
(``plan_ratios``) next to both errors, which must agree: pruning never changes the image.

With ``--importance rsm,brsm`` every vpl and vsgl configuration also runs with bidirectional RSM
importance (``importance="brsm"``, its rows marked ``brsm``), so the sweep compares the two
sampling densities at equal light counts and, through ``equal_time``, at equal time;
``--importance-interleave K`` sets the brsm rows' ``importance_interleave``. Every ``--sampling``
combines with it (Metropolis chains then follow the re-weighted density).
"""

from __future__ import annotations

import sys
import types
from typing import Any

from . import cli, output, reference, report, sweep, timing
from .cli import _ints, _option_axis, _strs, main
from .output import CSV_COLUMNS, _plots, write
from .reference import (
    MIN_RSM,
    RSM_REFERENCE_ORDER,
    _reference,
    _reference_key,
    _reference_progress,
    _ReferenceRender,
    _rsm_reference_error,
    _scene_reference,
)
from .report import (
    TRUST_FACTOR,
    Report,
    Row,
    _brief,
    _equal_time,
    _equal_time_line,
    _interval,
    _kernel_label,
    _label,
    _method_label,
    _num,
    _plan_ratios,
    table,
)
from .sweep import (
    CORPUS_DEFAULT_SCENES,
    CPU_DEFAULTS,
    GPU_DEFAULTS,
    METROPOLIS_BURN_IN,
    SAMPLINGS,
    _makes_indirect,
    _stochastic,
    _takes,
    SWEPT_ELSEWHERE,
    _lit_scene,
    _option_combinations,
    _progress,
    _resolve_defaults,
    _scene,
    _sequence_changes,
    _sequence_frames,
    _sequence_truth,
    _shown,
    _trust,
    default_scenes,
    run,
)
from .timing import CLOCK_WARM_FRACTION, CLOCK_WARM_MAX_EXTRA_S, _clock_for, _quartiles, _sm_clock_reader, _SmClock

_UNSET = object()


class _Package(types.ModuleType):
    """Setting a name on ``vsgl.bench`` (``monkeypatch.setattr(bench, "_clock_for", ...)``) also
    sets it in the modules of the package that hold the same object, so it takes effect where the
    code reads it, as it did when bench was one module."""

    def __setattr__(self, name: str, value: Any) -> None:
        old = self.__dict__.get(name, _UNSET)
        super().__setattr__(name, value)
        if old is _UNSET:
            return
        for module in (cli, output, reference, report, sweep, timing):
            if module.__dict__.get(name, _UNSET) is old:
                setattr(module, name, value)


sys.modules[__name__].__class__ = _Package
