"""The SM clock through NVML (optional), the warm-up's clock thresholds, and time quartiles."""

from __future__ import annotations

import statistics
import time
from typing import Callable


def _quartiles(v: list[float]) -> tuple[float, float]:
    if len(v) < 2:
        return v[0], v[0]
    q = statistics.quantiles(v, n=4, method="inclusive")
    return q[0], q[2]


class _SmClock:
    """The SM clock in MHz through NVML (optional `nvidia-ml-py`): `read()` now, `max_mhz` the boost."""

    def __init__(self, read, max_mhz: int) -> None:
        self.read, self.max_mhz = read, max_mhz

    def warm(self, mhz: int) -> bool:
        return mhz >= CLOCK_WARM_FRACTION * self.max_mhz


#: A timed frame counts as warm when the SM clock read at least this fraction of its maximum
#: before and after it (docs/error.md, cold clocks: idle 345–360 MHz, boost 1980 on an H200).
CLOCK_WARM_FRACTION = 0.9
#: How long the warm-up may go on past `warmup_seconds` while the clock is still below that.
CLOCK_WARM_MAX_EXTRA_S = 5.0


def _clock_for(cpu: bool) -> _SmClock | None:
    """The SM clock to watch: none on a CPU adapter, which has no clock states to leave."""
    return None if cpu else _sm_clock_reader()


def _sm_clock_reader() -> _SmClock | None:
    """The SM clock of GPU 0 through NVML, or None."""
    try:
        import pynvml  # type: ignore[import-not-found]

        pynvml.nvmlInit()
        handle = pynvml.nvmlDeviceGetHandleByIndex(0)
        max_mhz = int(pynvml.nvmlDeviceGetMaxClockInfo(handle, pynvml.NVML_CLOCK_SM))
        return _SmClock(lambda: int(pynvml.nvmlDeviceGetClockInfo(handle, pynvml.NVML_CLOCK_SM)), max_mhz)
    except Exception:  # not installed, no NVIDIA driver, no device: clocks are not reported
        return None


def warm_up(render: Callable[[], object], seconds: float, sm_clock: _SmClock | None) -> int:
    """Sustained load before timing: `render()` back to back (nothing read back) for `seconds`,
    and where `sm_clock` reads the SM clock, on until it is warm (at most CLOCK_WARM_MAX_EXTRA_S
    more), so no frame is timed on a GPU that has not left its idle clock (docs/error.md, cold
    clocks). Returns the frames rendered."""
    frames = 0
    t_end = time.perf_counter() + seconds
    while time.perf_counter() < t_end or (
            sm_clock is not None and not sm_clock.warm(sm_clock.read()) and time.perf_counter() < t_end + CLOCK_WARM_MAX_EXTRA_S):
        render()
        frames += 1
    return frames
