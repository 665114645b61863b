#!/usr/bin/env python3
"""How far is vsgl's path-traced ground truth (`method="pathtrace"`, default strategy "bidirectional") from Mitsuba 3's light tracer (`ptracer`) with the same materials, lights and camera?

An outside check of the truth the benchmark measures every method against (experiments/pathtracer_vs_mitsuba.md,
"Against Mitsuba 3's light tracer (`experiments/mitsuba_truth.py`)"). Not run in CI and
imported by no test: it needs Mitsuba 3 (``pip install mitsuba drjit``), which vsgl does not
depend on.

Both renderers get the same scene: vsgl's world-space triangles (``scene.triangles()``), its
per-vertex shading normals, its lights and one camera (the scene's own, or vsgl's default framing
of the scene's bounds, passed to both). Mitsuba gets vsgl's material model through two Python
plugins, registered by ``experiments/mitsuba_bridge.py`` (which also exports the scene and runs
Mitsuba's renders; this script compares and reports):

- ``vsgl_gltf`` (BSDF): Rd/π + Rs·D(h)·G2/(4|n·l||n·v|), Rd = base·(1 − metallic),
  Rs = mix(0.04·specular, base, metallic), GGX D with α = max(roughness², 1e-4), height-correlated
  Smith G2 = 1/(1 + Λ(l) + Λ(v)), no Fresnel; double-sided (the local frame is flipped to the
  side light arrives from). Sampled like vsgl's path tracer: the GGX lobe (visible normals,
  ``mi.MicrofacetDistribution``) with probability c_s = ΣRs/(ΣRd + ΣRs), else cosine; ``pdf`` is
  that mixture's. f is symmetric, so the light tracer's importance transport needs nothing more;
  with shading normals the integrator's own adjoint correction (Veach 1997, p. 155) applies.
- ``vsgl_spot`` (emitter): a point at ``position`` with intensity I·colour (cd) and the glTF smooth
  cone, t = clamp((cos θ − cos_outer)/max(cos_inner − cos_outer, 1e-4), 0, 1), attenuation t²;
  photons leave uniformly over the outer cone. Point lights are Mitsuba's ``point`` and
  directional lights its ``directional`` (same units: cd, lux).

Mitsuba gets lengths scaled so that the scene's bounds diagonal is 10 units (spot and point
intensities divided by the scale squared, so every radiance stays as it is; ``--mitsuba-units
world`` turns this off). Mitsuba 3.9's results depend on the length unit at both ends: at
coordinates ~1e3 (the millimetre Cornell box as it is) its camera-ray hit points were 0.06 mm
(median, 6e-5 of the scene) from an f64 intersection, which moved its direct light by up to 0.8%
in the spot's cone ramp (vsgl's matched an f64 evaluation within 2e-4 there); with a diagonal of
1 unit its ray offsets (ε·(1 + max|p|), an absolute floor) grow to ~1e-4 of the scene and its
caustics_ring indirect came out 0.8% brighter than with a diagonal of 100 or 1000 units (which
agree within 0.01%). At 10 units the direct light matches vsgl's within 8e-5 (rms) on every
scene here.

The camera is a pinhole with vsgl's vertical field of view and a ``box`` reconstruction filter, so
each Mitsuba pixel is the radiance averaged over the pixel's area, which is what vsgl's
bidirectional mode estimates for the indirect light. vsgl's ``direct`` AOV is the pixel centre's,
so the direct light is checked against a pixel-centre direct render in Mitsuba (deterministic:
the lights are points) and the full image is compared both as rendered (``image``: vsgl's centre
direct + area indirect against Mitsuba's area direct + area indirect) and like for like
(``image_c``: Mitsuba's centre direct + its area indirect).

Mitsuba's one-bounce light is ``ptracer`` with ``max_depth=3`` (light → x → y → eye, and the
direct paths) less ``max_depth=2`` (direct only) with the same seed, so the direct paths cancel
exactly; ``rr_depth`` is past both, so no Russian roulette. The light tracer alone does not
converge where the camera sees a near-mirror (light → x → mirror y → eye: the connection to the
eye goes through a lobe ~1e6 high and under a µsr wide, so such pixels are a few huge splats), so
paths whose eye-side vertex y lies on a material with roughness <= ``--camera-roughness`` (0.2)
are taken by camera paths instead (``mitsuba_camera_part``: a jittered ray finds y, y's BRDF is
sampled, x's direct light is reflected): the light tracer's connection to the eye returns 0 on
those materials, so every path is counted once. ``--camera-roughness -1`` gives the light tracer
alone. Mitsuba's own error is taken from the spread of two halves of its seeds (heavy-tailed
light, as on caustics_ring, makes that an underestimate); vsgl's from its ``stderr`` AOV.

Cross-checks (``--no-cross-check`` leaves them out): Mitsuba by camera paths for every path
(pixel-area averages, and pixel centres), against which vsgl's ``strategy="camera"`` (pixel
centres) is compared; and the share of Mitsuba's indirect light in pixels whose centre sees no
surface, which vsgl's pathtrace leaves at 0.

Usage (6–10 minutes on 2 CPU cores with lavapipe and Mitsuba's LLVM backend, which needs
libLLVM >= 16; 15 fails on Mitsuba 3.9's kernels):

    XDG_RUNTIME_DIR=/tmp python experiments/mitsuba_truth.py

writes ``truth.txt`` (the tables, with the command line at the top; ``--name`` renames it) under
``--out``, and with ``--save-images`` ``truth.npz`` with every image.
"""

from __future__ import annotations

import argparse
import pathlib
import shlex
import sys
import time

import numpy as np

import vsgl
from vsgl import metrics

# Mitsuba's side (experiments/ is on sys.path when this runs as a script).
from mitsuba_bridge import camera_of, load_mitsuba, mitsuba_camera_part, mitsuba_centre_direct, mitsuba_scene, render_mitsuba

BUILTIN = ("mirror_panel", "caustics_ring")
CORPUS = ("cornell_box_original", "cornell_box_mm", "lights_spot")
TEXTURED = ("flight_helmet", "boom_box")
DEFAULT_SCENES = BUILTIN + CORPUS
BLOCK = 4
# Acceptance on the caustic built-ins (the brief of this script).
ACCEPT_MEAN = 0.05
ACCEPT_BLOCK = 0.15
# Mitsuba's length unit: the scene's bounds diagonal is this many units (--mitsuba-units scene).
MITSUBA_DIAGONAL = 10.0


# --- Comparison ---------------------------------------------------------------------------------


def ratio(x, ref) -> float:
    r = float(np.mean(ref))
    return float(np.mean(x)) / r if r > 0.0 else float("nan")


def block_err(x, ref) -> float:
    """vsgl.metrics.block_rmse with 4×4 blocks (‖B(x) − B(ref)‖/‖B(ref)‖, B the 4×4 block means)."""
    if not np.any(ref):
        return float("nan")
    return metrics.block_rmse(np.asarray(x, np.float64), np.asarray(ref, np.float64), BLOCK)


def _block_counts(shape) -> np.ndarray:
    """Pixels per 4×4 block (edge blocks hold fewer), shaped like metrics.block_means' output."""
    heights = np.minimum(BLOCK, shape[0] - np.arange(0, shape[0], BLOCK))
    widths = np.minimum(BLOCK, shape[1] - np.arange(0, shape[1], BLOCK))
    return np.outer(heights, widths).reshape(len(heights), len(widths), *([1] * (len(shape) - 2)))


def vsgl_noise(x, stderr) -> tuple[float, float]:
    """vsgl's own relative error: per pixel sqrt(mean(stderr²))/rms(x), and that of the 4×4 block
    means (metrics.block_means: a block's stderr² averaged over it, over its pixel count, is the
    variance of its mean) relative to ‖B(x)‖."""
    x = np.asarray(x, np.float64)
    s2 = np.asarray(stderr, np.float64) ** 2
    rms = float(np.sqrt(np.mean(x**2)))
    if rms == 0.0:
        return float("nan"), float("nan")
    pixel = float(np.sqrt(np.mean(s2))) / rms
    var_b = metrics.block_means(s2, BLOCK) / _block_counts(s2.shape)
    block = float(np.sqrt(np.sum(var_b)) / np.sqrt(np.sum(metrics.block_means(x, BLOCK) ** 2)))
    return pixel, block


def seed_noise(a, b) -> tuple[float, float]:
    """The error of the mean m = (a + b)/2 of two seeds, from their difference: per pixel
    rms(a − b)/2 / rms(m), and of the 4×4 block means ‖B(a) − B(b)‖/2 / ‖B(m)‖."""
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    m = 0.5 * (a + b)
    rms = float(np.sqrt(np.mean(m**2)))
    if rms == 0.0:
        return float("nan"), float("nan")
    pixel = 0.5 * float(np.sqrt(np.mean((a - b) ** 2))) / rms
    ba, bb, bm = (metrics.block_means(v, BLOCK) for v in (a, b, m))
    block = 0.5 * float(np.sqrt(np.sum((ba - bb) ** 2)) / np.sqrt(np.sum(bm**2)))
    return pixel, block


def orientation(x, ref) -> str:
    """Which of the image, its left-right and up-down flips matches ``ref`` best (block error);
    a flip that matches as well as the image itself means the view is symmetric under it."""
    cands = {"as is": x, "flipped L-R": x[:, ::-1], "flipped U-D": x[::-1]}
    errs = {k: block_err(v, ref) for k, v in cands.items()}
    best = min(errs.values())
    ties = [k for k in ("flipped L-R", "flipped U-D") if errs[k] <= best + 1e-3]
    if errs["as is"] <= best + 1e-3:
        verdict = "as is" + (f" (the view is symmetric: {', '.join(ties)} matches as well)" if ties else "")
    else:
        verdict = "FLIPPED: " + min(errs, key=lambda k: errs[k])
    return verdict + " [" + ", ".join(f"{k} {v:.4f}" for k, v in errs.items()) + "]"


def mean_sigma(x, x_se2_sum, ref, ref_se2_sum) -> float:
    """Standard error of ratio(x, ref) from the two images' per-pixel variances (summed)."""
    n = np.asarray(x).size
    mx, mr = float(np.mean(x)), float(np.mean(ref))
    if mr <= 0.0 or mx <= 0.0:
        return float("nan")
    return (mx / mr) * float(np.sqrt(x_se2_sum / (n * mx) ** 2 + ref_se2_sum / (n * mr) ** 2))


def vsgl_area_direct(scene, cam, size: int, factor: int) -> np.ndarray:
    """vsgl's direct light averaged over each pixel's area: the pathtrace ``direct`` AOV (traced,
    deterministic, at the pixel centre) at factor× the resolution, averaged over factor×factor
    sub-pixels (their centres are a stratified grid over the pixel)."""
    r = vsgl.Renderer(width=size * factor, height=size * factor)
    f = r.render(scene, camera=cam, method="pathtrace", spp=1, seed=1, strategy="camera", aovs=["direct"])
    d = np.asarray(f.aov("direct"), np.float64)
    return d.reshape(size, factor, size, factor, 3).mean(axis=(1, 3))


def cross_checks(mi, dr, mscene, meshes, scene, cam, args, renderer) -> dict:
    """Each side against itself by another strategy: Mitsuba's camera paths for every path
    (every material camera-side; pixel-area averages, and pixel centres), and vsgl's
    strategy="camera" (pixel centres, no light tracing)."""
    size, spp, seeds = args.size, args.mitsuba_spp, range(101, 101 + args.mitsuba_seeds)
    out = {}
    for key, jitter in (("mts_cam_area", True), ("mts_cam_centre", False)):
        runs = [mitsuba_camera_part(mi, dr, mscene, meshes, size, spp, args.spp_per_pass, s, jitter=jitter)[1] for s in seeds]
        out[key] = np.mean(runs, axis=0)
        out[key + "_noise"] = seed_noise(np.mean(runs[0::2], axis=0), np.mean(runs[1::2], axis=0))
    f = renderer.render(scene, camera=cam, method="pathtrace", spp=args.spp, seed=args.seed, strategy="camera",
                        aovs=["indirect", "stderr"])
    out["vsgl_camera"] = np.asarray(f.aov("indirect"), np.float64)
    out["vsgl_camera_noise"] = vsgl_noise(out["vsgl_camera"], np.asarray(f.aov("stderr"), np.float64))
    return out


def load_scene(name: str):
    if name in vsgl.scenes.names():
        return vsgl.scenes.load(name), None
    if name in TEXTURED:
        return None, "textured (base colour, metallic-roughness and normal textures are not given to Mitsuba here): skipped"
    if name not in vsgl.scenes.corpus_names():
        raise SystemExit(f"--scenes: unknown scene {name!r}")
    if not vsgl.scenes.corpus_available(name):
        return None, f"its file is not under {vsgl.scenes.shared_scenes_dir()}: skipped"
    scene = vsgl.scenes.corpus_scene(name).scene
    if any(m["textures"] for m in scene.materials):
        return None, "textured: skipped"
    return scene, None


def drop_emission(scene) -> list[str]:
    """Emission lights nothing in vsgl; only the camera sees it. Mitsuba's emitters would light
    the scene, so emission is turned off in vsgl for the comparison (both sides without it)."""
    names = sorted({m["name"] for m in scene.materials if any(v > 0.0 for v in m["emissive"])})
    for n in names:
        scene.set_material(n, emissive=(0.0, 0.0, 0.0))
    return names


def compare_scene(mi, dr, name, scene, args, renderer) -> tuple[dict, dict]:
    size = args.size
    cam = camera_of(scene)
    t0 = time.perf_counter()
    f = renderer.render(scene, camera=cam, method="pathtrace", spp=args.spp, seed=args.seed,
                        aovs=["image", "indirect", "direct", "stderr", "depth"])
    t_vsgl = time.perf_counter() - t0
    v = {k: np.asarray(f.aov(k), np.float64) for k in ("image", "indirect", "direct", "stderr")}
    # Pixels whose centre sees no surface (depth 0): vsgl's camera strategy leaves them at 0; its
    # bidirectional default (since this comparison found the gap) takes their area's light.
    background = np.asarray(f.aov("depth"), np.float64).reshape(size, size) == 0.0
    v_area_direct = vsgl_area_direct(scene, cam, size, args.supersample)

    # The scene's diagonal is MITSUBA_DIAGONAL units in Mitsuba (see the module docstring).
    unit = float(np.linalg.norm(np.subtract(*scene.bounds))) / MITSUBA_DIAGONAL if args.mitsuba_units == "scene" else 1.0
    mscene, glossy, glossy_names, meshes = mitsuba_scene(mi, scene, cam, size, args.spp_per_pass, args.camera_roughness, unit)
    mc = mitsuba_centre_direct(mi, dr, mscene, size)
    t0 = time.perf_counter()
    m = render_mitsuba(mi, dr, mscene, glossy, size, args.mitsuba_spp, args.spp_per_pass, seeds=range(1, args.mitsuba_seeds + 1))
    t_mts = time.perf_counter() - t0
    mean = {k: np.mean(m[k], axis=0) for k in m}
    half = {k: (np.mean(m[k][0::2], axis=0), np.mean(m[k][1::2], axis=0)) for k in m}
    # m = (a + b)/2 for a, b the means of two halves of the seeds: E[((a − b)/2)²] = Var(m), so
    # the halves' spread is the error of the mean of all seeds as it stands.
    image_c = mc + mean["indirect"]
    # A scene without indirect light (a lone plane): vsgl's is 0, Mitsuba's the rounding of its
    # same-seed difference.
    no_indirect = not np.any(v["indirect"]) and abs(float(mean["indirect"].mean())) <= 1e-4 * float(mean["image"].mean())
    covered = ~background[..., None]
    x = cross_checks(mi, dr, mscene, meshes, scene, cam, args, renderer) if args.cross_check and not no_indirect else None
    nan2 = (float("nan"), float("nan"))
    row = {
        "scene": name, "strategy": f.settings.get("strategy", "?"), "unit": unit, "camera_side": glossy_names,
        "ind_v": float(v["indirect"].mean()), "ind_m": float(mean["indirect"].mean()),
        "ind_ratio": float("nan") if no_indirect else ratio(v["indirect"], mean["indirect"]),
        # Mitsuba's per-pixel variance of its mean from the two halves of its seeds: ((a − b)/2)².
        "ind_sigma": float("nan") if no_indirect else mean_sigma(
            v["indirect"], float(np.sum(v["stderr"] ** 2)), mean["indirect"],
            float(np.sum(((half["indirect"][0] - half["indirect"][1]) / 2.0) ** 2))),
        "ind_blk": float("nan") if no_indirect else block_err(v["indirect"], mean["indirect"]),
        "cam_share": float(mean["cam_indirect"].mean() / mean["indirect"].mean()) if not no_indirect else float("nan"),
        "img_ratio": ratio(v["image"], mean["image"]), "img_blk": block_err(v["image"], mean["image"]),
        "imgc_ratio": ratio(v["image"], image_c), "imgc_blk": block_err(v["image"], image_c),
        "dir_ratio": ratio(v["direct"], mc), "dir_blk": block_err(v["direct"], mc),
        "dir_maxrel": float(np.max(np.abs(v["direct"] - mc)) / max(float(np.max(mc)), 1e-30)),
        "orientation": orientation(v["direct"], mc) if np.any(mc) else "-",
        "adir_ratio": ratio(v_area_direct, mean["direct"]), "adir_blk": block_err(v_area_direct, mean["direct"]),
        "m_ac_ratio": ratio(mean["direct"], mc), "m_ac_blk": block_err(mean["direct"], mc),
        "bg_share": float("nan") if no_indirect else float((mean["indirect"] * ~covered).sum() / mean["indirect"].sum()),
        "bg_ratio": float("nan") if no_indirect else ratio(v["indirect"], mean["indirect"] * covered),
        "bg_blk": float("nan") if no_indirect else block_err(v["indirect"], mean["indirect"] * covered),
        "v_noise_ind": nan2 if no_indirect else vsgl_noise(v["indirect"], v["stderr"]),
        "v_noise_img": vsgl_noise(v["image"], v["stderr"]),
        "m_noise_ind": nan2 if no_indirect else seed_noise(*half["indirect"]),
        "m_noise_img": seed_noise(*half["image"]),
        "m_noise_adir": seed_noise(*half["direct"]),
        "t_vsgl": t_vsgl, "t_mts": t_mts,
    }
    if x is not None:
        row.update({
            "x_cam_ratio": ratio(x["mts_cam_area"], mean["indirect"]), "x_cam_blk": block_err(x["mts_cam_area"], mean["indirect"]),
            "x_cam_noise": x["mts_cam_area_noise"],
            "x_vcam_ratio": ratio(x["vsgl_camera"], x["mts_cam_centre"]), "x_vcam_blk": block_err(x["vsgl_camera"], x["mts_cam_centre"]),
            "x_vcam_noise": float(np.hypot(x["vsgl_camera_noise"][1], x["mts_cam_centre_noise"][1])),
            "x_bg_ratio": ratio(v["indirect"], x["mts_cam_area"] * covered), "x_bg_blk": block_err(v["indirect"], x["mts_cam_area"] * covered),
        })
    arrays = {f"{name}.vsgl.{k}": a for k, a in v.items()}
    arrays[f"{name}.vsgl.direct_area"] = v_area_direct
    arrays[f"{name}.mitsuba.direct_centre"] = mc
    for k in ("image", "indirect", "direct", "cam_indirect"):
        for i, a in enumerate(m[k]):
            arrays[f"{name}.mitsuba.{k}.seed{i + 1}"] = a
    return row, {k: a.astype(np.float32) for k, a in arrays.items()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(DEFAULT_SCENES), help="comma-separated (default: %(default)s)")
    ap.add_argument("--size", type=int, default=48, help="image side in pixels (default 48)")
    ap.add_argument("--spp", type=int, default=4096, help="vsgl pathtrace samples per pixel (default 4096)")
    ap.add_argument("--mitsuba-spp", type=int, default=32768,
                    help="Mitsuba samples per pixel per seed: ptracer light paths = spp × pixels, and as many camera paths (default 32768)")
    ap.add_argument("--mitsuba-seeds", type=int, default=2, help="independent Mitsuba seeds, averaged (even, >= 2: the spread of their two halves is Mitsuba's own error)")
    ap.add_argument("--spp-per-pass", type=int, default=1024, help="Mitsuba samples per pixel per wavefront pass (memory; default 1024)")
    ap.add_argument("--camera-roughness", type=float, default=0.2,
                    help="paths whose eye-side vertex is on a material this smooth (or smoother) are taken by camera paths, "
                         "the rest by the light tracer (default 0.2; -1: the light tracer takes every path)")
    ap.add_argument("--mitsuba-units", choices=("scene", "world"), default="scene",
                    help="lengths given to Mitsuba: scaled so the scene's bounds diagonal is 10 units (default), or as they are "
                         "(world); see the module docstring for why")
    ap.add_argument("--supersample", type=int, default=8, help="sub-pixels per side of vsgl's area-averaged direct check (default 8)")
    ap.add_argument("--no-cross-check", dest="cross_check", action="store_false",
                    help="leave out the cross-checks (Mitsuba camera paths for every path; vsgl strategy=\"camera\")")
    ap.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default llvm_ad_rgb; scalar_rgb works without LLVM, slowly)")
    ap.add_argument("--seed", type=int, default=1, help="vsgl seed (default 1)")
    ap.add_argument("--out", default="out/mitsuba/", help="output folder (default %(default)s)")
    ap.add_argument("--name", default="truth", help="output file name without extension (default %(default)s)")
    ap.add_argument("--save-images", action="store_true", help="also write NAME.npz with every image")
    args = ap.parse_args(argv)
    if args.mitsuba_seeds < 2 or args.mitsuba_seeds % 2:
        ap.error("--mitsuba-seeds: an even number >= 2 (two equal halves give Mitsuba's own error)")

    mi, dr = load_mitsuba(args.variant)
    out_dir = pathlib.Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    given = sys.argv[1:] if argv is None else list(argv)
    command = " ".join(["XDG_RUNTIME_DIR=/tmp python experiments/mitsuba_truth.py"] + [shlex.quote(a) for a in given])
    renderer = vsgl.Renderer(width=args.size, height=args.size)
    rows, notes, arrays = [], [], {}
    t_all = time.perf_counter()
    for name in [s.strip() for s in args.scenes.split(",") if s.strip()]:
        scene, why = load_scene(name)
        if scene is None:
            print(f"{name}: {why}", flush=True)
            notes.append(f"{name}: {why}")
            continue
        emissive = drop_emission(scene)
        if emissive:
            notes.append(f"{name}: emission of {', '.join(emissive)} set to 0 in vsgl (there it only shows to the camera and lights nothing; "
                         "in Mitsuba it would light the scene)")
        row, arr = compare_scene(mi, dr, name, scene, args, renderer)
        rows.append(row)
        arrays.update(arr)
        print(f"{name}: indirect vsgl/Mitsuba {row['ind_ratio']:.4f} blk4 {row['ind_blk']:.4f}; image {row['img_ratio']:.4f} "
              f"blk4 {row['img_blk']:.4f}; direct (centre) {row['dir_ratio']:.5f} blk4 {row['dir_blk']:.5f}; "
              f"vsgl {row['t_vsgl']:.1f} s, Mitsuba {row['t_mts']:.1f} s", flush=True)
    text = format_report(command, args, rows, notes, mi, time.perf_counter() - t_all)
    (out_dir / f"{args.name}.txt").write_text(text)
    if args.save_images:
        np.savez_compressed(out_dir / f"{args.name}.npz", **arrays)
    print(text)
    return 0


def _f(x, w=8, p=4):
    if isinstance(x, float) and not np.isfinite(x):
        return format("-", f">{w}")
    return format(x, f">{w}.{p}f")


def _pair(t):
    if not np.isfinite(t[0]):
        return format("-", ">16")
    return f"{t[0]:>8.4f}/{t[1]:<7.4f}"


def format_report(command, args, rows, notes, mi, wall) -> str:
    L = [f"# {command}", ""]
    split = (f"ptracer for paths whose eye-side vertex has roughness > {args.camera_roughness:g}, camera paths for the rest. "
             if args.camera_roughness >= 0.0 else "ptracer for every path. ")
    L.append(f"vsgl {vsgl.__version__} pathtrace (default strategy), {args.size}x{args.size}, {args.spp} spp, seed {args.seed}, lavapipe. "
             f"Mitsuba {mi.__version__} {args.variant}, {args.mitsuba_seeds} seeds x {args.mitsuba_spp} spp, box filter, no Russian roulette: "
             + split + f"Whole run {wall:.0f} s.")
    L.append(f"ratio = mean(vsgl)/mean(Mitsuba) over pixels and channels; blk4 = vsgl.metrics.block_rmse(vsgl, Mitsuba, 4). "
             f"Acceptance on {', '.join(BUILTIN)}: |ratio - 1| <= {ACCEPT_MEAN}, blk4 <= {ACCEPT_BLOCK}.")
    L.append("")
    L.append("## The gap")
    L.append("indirect: vsgl 'indirect' vs Mitsuba's one-bounce light (ptracer max_depth 3 - max_depth 2, same seed; + camera part). "
             "+-: the ratio's standard error from both renderers' own errors. cam: the camera part's share of Mitsuba's indirect.")
    L.append("image: vsgl 'image' (its direct is the pixel centre's) vs Mitsuba's (area-averaged direct + indirect); "
             "image_c: vs Mitsuba's centre direct + its indirect (like for like).")
    hdr = f"{'scene':<22}{'ind vsgl':>10}{'ind mts':>10}{'ratio':>8}{'+-':>8}{'blk4':>8}{'cam':>6} |{'image':>8}{'blk4':>8} |{'image_c':>8}{'blk4':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        L.append(f"{r['scene']:<22}{_f(r['ind_v'], 10, 5)}{_f(r['ind_m'], 10, 5)}{_f(r['ind_ratio'])}{_f(r['ind_sigma'])}{_f(r['ind_blk'])}{_f(r['cam_share'], 6, 2)} |"
                 f"{_f(r['img_ratio'])}{_f(r['img_blk'])} |{_f(r['imgc_ratio'])}{_f(r['imgc_blk'])}")
    L.append("")
    L.append("## Where the indirect gap sits (cross-checks)")
    L.append("bg: share of Mitsuba's indirect in pixels whose centre sees no surface; vsgl's strategy=\"camera\" leaves those pixels at 0, "
             "its bidirectional default takes the part of their area that covers a surface. excl bg: vsgl vs Mitsuba with those pixels zeroed in "
             "Mitsuba too. M cam/M: Mitsuba's camera paths for every path (area averages) vs the light-tracer-based result above (noise: the "
             "camera paths' own block error). v cam/M cam: vsgl strategy=\"camera\" vs Mitsuba's camera paths, both at pixel centres "
             "(noise: both block errors combined). excl bg (M cam): vsgl vs Mitsuba's camera paths with the background-centre pixels zeroed. "
             "Camera paths alone do not converge on caustics (mirror_panel, caustics_ring: see their noise); there the cross-checks say nothing.")
    hdr = (f"{'scene':<22}{'bg':>7} |{'excl bg':>8}{'blk4':>8} |{'M cam/M':>8}{'blk4':>8}{'noise':>8} |"
           f"{'v cam/M cam':>12}{'blk4':>8}{'noise':>8} |{'excl bg (M cam)':>16}{'blk4':>8}")
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        g = lambda k: r.get(k, float("nan"))  # noqa: E731
        L.append(f"{r['scene']:<22}{_f(g('bg_share'), 7)} |{_f(g('bg_ratio'))}{_f(g('bg_blk'))} |"
                 f"{_f(g('x_cam_ratio'))}{_f(g('x_cam_blk'))}{_f(g('x_cam_noise')[1] if 'x_cam_noise' in r else float('nan'))} |"
                 f"{_f(g('x_vcam_ratio'), 12)}{_f(g('x_vcam_blk'))}{_f(g('x_vcam_noise'))} |{_f(g('x_bg_ratio'), 16)}{_f(g('x_bg_blk'))}")
    L.append("")
    L.append("## Each renderer's own error (relative, per pixel / of the 4x4 block means) and time")
    L.append("vsgl: sqrt(mean(stderr^2))/rms, and the block means' stderr (block-averaged stderr^2 over the pixel count) over their norm; "
             "Mitsuba: from its seeds' spread. noise: sqrt(vsgl^2 + Mitsuba^2) of the block figures, the blk4 that noise alone gives.")
    hdr = f"{'scene':<22}{'vsgl ind':>16}{'mts ind':>16}{'noise':>8} |{'vsgl img':>16}{'mts img':>16}{'noise':>8} |{'vsgl s':>8}{'mts s':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        nb_i = float(np.hypot(r["v_noise_ind"][1], r["m_noise_ind"][1]))
        nb_m = float(np.hypot(r["v_noise_img"][1], r["m_noise_img"][1]))
        L.append(f"{r['scene']:<22}{_pair(r['v_noise_ind'])}{_pair(r['m_noise_ind'])}{_f(nb_i)} |"
                 f"{_pair(r['v_noise_img'])}{_pair(r['m_noise_img'])}{_f(nb_m)} |{r['t_vsgl']:>8.1f}{r['t_mts']:>8.1f}")
    L.append("")
    L.append("## Direct light (materials, lights, camera)")
    L.append("centre: vsgl 'direct' vs Mitsuba's deterministic pixel-centre direct light (maxrel = max|diff| / max(Mitsuba)). "
             f"area: vsgl's direct averaged over {args.supersample}x{args.supersample} sub-pixels vs Mitsuba's area-averaged direct "
             "(ptracer max_depth 2 + camera part; mts err its own block error). mts a/c: Mitsuba's area vs its centre direct "
             "(the sampling-position difference alone).")
    hdr = f"{'scene':<22}{'centre':>10}{'blk4':>10}{'maxrel':>10} |{'area':>8}{'blk4':>8}{'mts err':>9} |{'mts a/c':>8}{'blk4':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        L.append(f"{r['scene']:<22}{_f(r['dir_ratio'], 10, 6)}{_f(r['dir_blk'], 10, 6)}{_f(r['dir_maxrel'], 10, 6)} |"
                 f"{_f(r['adir_ratio'])}{_f(r['adir_blk'])}{_f(r['m_noise_adir'][1], 9)} |{_f(r['m_ac_ratio'])}{_f(r['m_ac_blk'])}")
    L.append("")
    L.append("## Checks")
    for r in rows:
        L.append(f"{r['scene']}: vsgl strategy {r['strategy']}; Mitsuba length unit {r['unit']:.4g}; camera-side materials {r['camera_side'] or 'none'}; "
                 f"orientation by the direct light (blk4 of vsgl's direct, and of its flips, vs Mitsuba's): {r['orientation']}")
    for r in rows:
        if r["scene"] in BUILTIN:
            ok_m = abs(r["ind_ratio"] - 1.0) <= ACCEPT_MEAN and abs(r["img_ratio"] - 1.0) <= ACCEPT_MEAN
            ok_b = r["ind_blk"] <= ACCEPT_BLOCK and r["img_blk"] <= ACCEPT_BLOCK
            L.append(f"{r['scene']}: acceptance (indirect and image) mean {'met' if ok_m else 'MISSED'}, block {'met' if ok_b else 'MISSED'}")
    if notes:
        L += ["", "## Notes"] + notes
    return "\n".join(L) + "\n"


if __name__ == "__main__":
    sys.exit(main())
