"""Where the LPV lookup should read: at the receiver, or moved along its normal. Each run is one
build: the offset was a literal in wgsl/passes/lpv_lookup.wgsl (0.5, 0 and 1 cell), and variant
B left the injected light out of the summed volume (lpv_propagate.rs). Prints, per scene, the
mean indirect diffuse light over the reference of the same RSM and the 4×4 block error at 8 and
32 iterations, 96², RSM 128² (lavapipe). Result: experiments/lavapipe/lpv/lookup_offset.txt.

    VSGL_SCENES=../shared/scenes .venv/bin/python experiments/lpv_lookup_offset.py LABEL
"""
import sys, numpy as np, vsgl
from vsgl.metrics import block_rmse
r = vsgl.Renderer(width=96, height=96)
out = []
for name in ["diffuse_cornell", "furnished_room", "cornell_box_original", "flight_helmet"]:
    scene = vsgl.scenes.builtin_scene(name) if name in vsgl.scenes.builtin_scene_names() else vsgl.scenes.corpus_scene(name).scene
    ref = r.render(scene, method="reference", rsm_size=128, aovs=["indirect_diffuse"]).aov("indirect_diffuse").astype(np.float64)
    row = [name]
    for it in [8, 32]:
        l = r.render(scene, method="lpv", rsm_size=128, lpv_iterations=it, aovs=["indirect_diffuse"]).aov("indirect_diffuse").astype(np.float64)
        row.append("it%d %.3f/%.3f" % (it, l.mean() / ref.mean(), block_rmse(l, ref, 4)))
    print(sys.argv[1], " ".join(row), flush=True)
