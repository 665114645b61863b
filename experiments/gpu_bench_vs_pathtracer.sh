#!/usr/bin/env bash
# The benchmark against the converged path tracer at GPU size (one device call, ~8 min; results under $OUT): at 960x540, for
# the built-in glossy_cornell, caustics_ring, cave_flashlight and the shared LightsSpot scene, the
# error of vsgl / vpl / vsgl2 at N up to 4096 against a converged ground truth — `pathtrace
# strategy="bidirectional"` (light tracing + camera paths by MIS) — with the ground truth's own
# error (`reference_rel_error`, which must be <= 1/3 of the best method's error) and the
# equal-time table (`equal_time` in bench.json). Also the cost of splitting num_lights
# over several lights (the RSM power pass) on LightsSpot (three spots).
# Prepare .gl/ and .whl/ and begin the device command with the device preamble (experiments/README.md, "Running a device script").
set -uo pipefail
OUT=${OUT:-out}; mkdir -p "$OUT"
export PYTHONUNBUFFERED=1
cd "$(dirname "$0")/.."
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.txt" 2>&1; cat "$OUT/gpu.txt"
scenes=glossy_cornell,caustics_ring,cave_flashlight
lights_spot=${VSGL_SCENES:-../shared/scenes}/LightsSpot/LightsSpot.gltf  # the corpus folder (docs/scenes.md)
[ -f "$lights_spot" ] && scenes="$scenes,$lights_spot"
timeout 480 python3 -m vsgl bench --scene "$scenes" --methods vsgl,vpl,vsgl2 --lights 256,1024,4096 \
  --size 960x540 --rsm-sizes 256 --seeds 3 --frames 10 --warmup-seconds 2 \
  --reference pathtrace --reference-strategy bidirectional --reference-spp 4096 \
  --no-progress --out "$OUT/bench_vs_pathtracer" 2>&1 | tail -80
# The ground truth's own convergence: stderr at 1024 vs 4096 spp should halve.
timeout 90 python3 - <<'PY' 2>&1 | tee "$OUT/pathtrace_convergence.txt"
import numpy as np, vsgl, time
r = vsgl.Renderer(width=960, height=540)
for name in ("glossy_cornell", "caustics_ring"):
    s = vsgl.scenes.load(name)
    for strategy in ("camera", "bidirectional"):
        for spp in (1024, 4096):
            t = time.perf_counter()
            f = r.render(s, method="pathtrace", spp=spp, strategy=strategy, seed=1)
            ind, se = f.aov("indirect").sum(-1), f.aov("stderr").sum(-1)
            lit = ind > 1e-3 * ind.max()
            print(name, strategy, spp, f"{time.perf_counter() - t:.2f} s", "median rel stderr", float(np.median(se[lit] / ind[lit])),
                  "rel error of the mean", float(np.sqrt((se**2).sum()) / ind.sum()))
PY
# Visibility and flicker (same call if time allows; else a second call): visibility timings and leak,
# then error, flicker and time on the animated built-ins.
timeout 240 python3 experiments/gpu_visibility_and_flicker.py --size 1920x1080 --frames 20 --warm-seconds 3 2>&1 | tail -30
timeout 200 python3 -m vsgl bench --scene cave_flashlight,glossy_cornell --methods vpl,vsgl,vsgl2 --K 1,2,4 --sequence 30 \
  --sampling stratified,metropolis \
  --size 960x540 --lights 1024 --rsm-sizes 256 --seeds 2 --frames 5 --no-progress --out "$OUT/bench_temporal" 2>&1 | tail -30
# A second call: kernels, the 2024 lighting and bidirectional importance against the
# bidirectional path tracer, N from 256 to 65536 (RSM grown with N as documented), equal time.
timeout 420 python3 -m vsgl bench --scene caustics_ring,glossy_cornell,cornell_box,mirror_panel --methods vsgl,vpl \
  --kernels integral,node --lighting asg,accurate --importance rsm,brsm --lights 256,1024,4096,16384,65536 \
  --size 960x540 --rsm-sizes 512 --seeds 3 --frames 5 --warmup-seconds 2 --visibility raytrace \
  --reference pathtrace --reference-strategy bidirectional --reference-spp 4096 \
  --no-progress --out "$OUT/bench_kernels_lighting_importance" 2>&1 | tail -60
# experiments/vsgl_vs_pathtracer.py at a GPU size (the same tables as experiments/vsgl_vs_pathtracer.md's lavapipe
# ones, 4×4-pixel blocks against the bidirectional path tracer, with and without shadow rays).
timeout 300 python3 experiments/vsgl_vs_pathtracer.py --size 256 --lights 256,1024,4096,16384,65536 --brsm \
  --cache "$OUT/pathtracer_truths" --out "$OUT/vsgl_vs_pathtracer_none.json" 2>&1 | tail -60
timeout 300 python3 experiments/vsgl_vs_pathtracer.py --size 256 --lights 256,1024,4096,16384 --visibility raytrace \
  --cache "$OUT/pathtracer_truths" --time-rounds 5 --out "$OUT/vsgl_vs_pathtracer_raytrace.json" 2>&1 | tail -60
echo "== lambert_lobe cost (experiments/lambert_lobe.md, Lambert lobes)"
timeout 120 python3 experiments/lambert_lobe_timing.py --size 512 --lights 1024,4096 --rounds 9 2>&1 | tail -12
