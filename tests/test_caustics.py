"""The mirror-panel caustic: glossy VSGLs must put a near-mirror's reflected light where it
goes, against the bidirectional path tracer (light tracing + camera paths, an independent
estimator with its own error), not spread it over the wall as glow.

The built-in `mirror_panel` throws a narrow spot off a 45° polished panel (roughness 0.02) onto a
diffuse wall. The truth's patch on the wall holds ~94% of the wall's indirect light; the rest of
the wall is lit only by the floor's faint bounce. Measured on lavapipe (48×27, RSM 64, interleave
1; patch / rest-of-wall energy over the truth's): N = 1024 0.962 / 1.22, N = 4096 0.973 / 0.93,
N = 16384 0.979 / 0.92. VPLs at N = 1024 (RSM 256) put 0.20 of it there: their razor-sharp lobes
miss most pixels. The bounds below allow the path tracer's error on the patch (0.1%) and the
SG approximation's share, and fail for a lobe pointing the wrong way or spread over the wall."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl


@pytest.fixture(scope="module")
def truth(make_renderer):
    r = make_renderer(48, 27)
    f = r.render(vsgl.scenes.mirror_panel(), method="pathtrace", strategy="bidirectional", spp=512, aovs=["indirect", "stderr", "normal"])
    indirect = f.aov("indirect").astype(np.float64).sum(axis=-1)
    wall = f.aov("normal")[..., 2] > 0.99  # the wall faces +z; floor and panel do not
    patch = wall & (indirect > 0.25 * indirect[wall].max())
    own = np.sqrt((f.aov("stderr").astype(np.float64)[patch] ** 2).sum()) / indirect[patch].sum()
    assert own < 0.01, f"the path tracer's own error on the patch is {own:.3f}"
    return indirect, patch, wall & ~patch


@pytest.mark.parametrize("num_lights", [1024, 4096])
def test_the_mirror_panels_caustic_lands_where_the_path_tracer_puts_it(make_renderer, truth, num_lights):
    indirect, patch, rest_of_wall = truth
    r = make_renderer(48, 27)
    f = r.render(vsgl.scenes.mirror_panel(), method="vsgl", num_lights=num_lights, rsm_size=64, interleave=1, denoise=False, aovs=["indirect"])
    x = f.aov("indirect").astype(np.float64).sum(axis=-1)
    assert np.all(np.isfinite(x))
    on_patch = x[patch].sum() / indirect[patch].sum()
    glow = x[rest_of_wall].sum() / indirect[rest_of_wall].sum()
    assert abs(on_patch - 1) < 0.08, f"VSGLs put {on_patch:.3f}× the truth's light on the mirror's patch"
    assert 0.5 < glow < 2.0, f"the wall around the patch gets {glow:.2f}× the truth (glow)"
