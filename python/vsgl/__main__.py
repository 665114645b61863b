"""Command line: ``python -m vsgl render|animate|view|methods|bench|stability|adapters``."""

from __future__ import annotations

import argparse
import math
import os
import sys
import time


def _render(args: argparse.Namespace) -> int:
    import numpy as np

    import vsgl
    from vsgl.lightspec import describe_lights

    try:
        scene = _load_scene(args.scene)
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.no_scene_lights:
        scene.lights = []
    for light in args.light:
        scene.add_light(light)
    width, height = args.size
    t0 = time.perf_counter()
    renderer = vsgl.Renderer(width=width, height=height, adapter=args.adapter)
    t1 = time.perf_counter()
    # Pass each flag only to a method that takes it (the registry says which).
    flags = dict(shadow_size=args.shadow_size, num_lights=args.lights, seed=args.seed, rsm_size=args.rsm_size,
                 kernel=args.kernel, interleave=args.interleave, spp=args.spp, visibility=args.visibility, strategy=args.strategy,
                 importance=args.importance)
    takes = vsgl.method_options(args.method)
    options = {k: v for k, v in flags.items() if k in takes and v is not None}
    # --option NAME=VALUE reaches every option of the method; the library names a wrong one.
    options.update(args.option)
    progress = _progress_line(args.method)
    frame = renderer.render(scene, method=args.method, plan=args.plan, progress=progress, **options)
    if progress is not None and progress.shown:  # type: ignore[attr-defined]
        print(file=sys.stderr)
    t2 = time.perf_counter()
    frame.save(args.output, exposure=args.exposure)
    image = frame.image
    print(f"scene     {scene!r}")
    lo, hi = scene.bounds
    print(f"lights    {describe_lights(scene)}; scene bounds {tuple(round(x, 3) for x in lo)} to {tuple(round(x, 3) for x in hi)} (--light positions are in these units)")
    print(f"adapter   {renderer.adapter['name']} ({renderer.adapter['device_type']})")
    print(f"method    {args.method}, {width}x{height}")
    for warning in frame.warnings:
        print(f"warning   {warning}")
        if warning.startswith("the scene has no light"):
            # The library's hint names the API; from the shell the light comes from --light.
            # The example is a headlight: at the scene's camera, or where the default camera
            # stands (renderer::default_camera: in front (+Z) of and above the bounds' centre),
            # so it lights what the image shows; its intensity gives ~10 W/m² at that distance.
            lo, hi = scene.bounds
            centre = [(a + b) / 2 for a, b in zip(lo, hi)]
            if scene.cameras:
                eye = list(scene.cameras[0].eye)
            else:
                radius = max(0.5 * math.dist(lo, hi), 1e-3)
                eye = [c + d * radius / math.sin(math.radians(22.5)) for c, d in zip(centre, (0.0, 0.6 / math.hypot(0.6, 1.0), 1.0 / math.hypot(0.6, 1.0)))]
            distance = max(math.dist(eye, centre), 1e-3)
            print(f'hint      light it from here with --light, e.g. --light "point position={",".join(f"{x:.4g}" for x in eye)} '
                  f'intensity={10 * distance * distance:.3g}" (a light at the camera; see render --help)')
    if args.explain:
        print("passes    " + ", ".join(frame.passes))
        for name, why in frame.skipped.items():
            print(f"skipped   {name}: {why}")
        features = ", ".join(scene.stats["features"]) or "none"
        print(f"features  {features}")
        mib = sum(frame.memory_bytes.values()) / 2**20
        print(f"memory    {mib:.2f} MiB in frame buffers and targets (scene upload excluded)")
    clock = frame.timings_clock
    print(f"timings   ({clock}{'; CPU adapter: compare only ratios' if renderer.adapter['device_type'] == 'Cpu' else ''})")
    for name, ms in frame.timings_ms.items():
        print(f"  {name:<12} {ms:9.3f} ms")
    print(f"wall      device+pipelines {1e3 * (t1 - t0):.1f} ms, render+readback {1e3 * (t2 - t1):.1f} ms")
    finite = bool(np.isfinite(image).all())
    print(f"image     mean radiance {float(image.mean()):.6g}, max {float(image.max()):.6g}, finite: {finite}")
    # An estimate from the RSM (it takes rsm_size, is no ground truth, makes indirect light) is
    # compared with the every-texel reference of the same light.
    info = vsgl.method_info(args.method)
    estimates_rsm = "rsm_size" in vsgl.method_options(args.method) and not info["ground_truth"] and "indirect" in info["aovs"]
    if estimates_rsm and not args.no_error:
        t3 = time.perf_counter()
        # The reference can take a minute on a CPU adapter: show how far it is (on a terminal).
        ref_progress = _progress_line("reference (for the error; --no-error skips it)")
        # With the method's visibility, so the error is the method's and not the shadows'.
        visibility = args.visibility or "none"
        ref = renderer.render(scene, method="reference", rsm_size=args.reference_rsm, shadow_size=args.shadow_size, visibility=visibility, progress=ref_progress)
        if ref_progress is not None and ref_progress.shown:  # type: ignore[attr-defined]
            print(file=sys.stderr)
        t4 = time.perf_counter()
        for aov in ("indirect", "image"):
            a, b = frame.aov(aov).astype(np.float64), ref.aov(aov).astype(np.float64)
            rmse = float(np.sqrt(np.mean((a - b) ** 2)))
            rel = rmse / max(float(np.sqrt(np.mean(b**2))), 1e-30)
            print(f"error     {aov:<9} RMSE {rmse:.6g} (relative {rel:.4f}) vs reference ({args.reference_rsm}² RSM, visibility {visibility}, {1e3 * (t4 - t3):.0f} ms)")
    elif args.no_error:
        print("error     not measured (--no-error)")
    else:
        print("error     n/a for this method (error is measured for vpl, vsgl and vsgl2 against reference)")
    print(f"wrote     {args.output}")
    return 0 if finite else 1


def _option(text: str) -> tuple[str, object]:
    """NAME=VALUE of --option, the value as int, float, bool or text (in that order)."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE (e.g. importance_interleave=2), got {text!r}")
    from vsgl.lightspec import option_value

    return name.strip(), option_value(value)


def _load_scene(name: str):
    import vsgl

    if name in vsgl.scenes.names():
        return vsgl.scenes.load(name)
    if name in vsgl.scenes.corpus_names():
        return vsgl.scenes.corpus_scene(name).scene
    if os.path.exists(name):
        return vsgl.Scene.load(name)
    raise ValueError(
        f"scene {name!r} is neither a file, a built-in scene ({', '.join(vsgl.scenes.names())}) "
        f"nor a corpus scene ({', '.join(vsgl.scenes.corpus_names())})"
    )


def _animate(args: argparse.Namespace) -> int:
    import vsgl
    from vsgl import video

    methods = [m.strip() for m in (args.compare or args.method).split(",") if m.strip()]
    # Fail on the output kind and the optional packages before the scene or the GPU is touched.
    video.output_kind(args.output)
    scene = _load_scene(args.scene)
    if not scene.animations:
        print(f"warning: {args.scene} has no animations: every frame shows the same pose", file=sys.stderr)
    width, height = args.size
    renderer = vsgl.Renderer(width=width, height=height, adapter=args.adapter)
    options = dict(num_lights=args.lights, rsm_size=args.rsm_size, seed=args.seed, K=args.K,
                   interleave=args.interleave, spp=args.spp)
    t0 = time.perf_counter()
    result = video.animate(renderer, scene, methods, frames=args.frames, fps=args.fps, output=args.output,
                           options=options, progress=video.main_progress)
    seconds = time.perf_counter() - t0
    w, h = result["size"]
    print(f"scene     {scene!r}")
    for a in scene.animations:
        print(f"animation {a['name']}: {a['duration']:.3g} s, {a['channels']} channel(s)")
    print(f"adapter   {renderer.adapter['name']} ({renderer.adapter['device_type']})")
    print(f"frames    {result['frames']} at {args.fps:g} fps ({result['frames'] / args.fps:.3g} s), {w}x{h}, {result['label']}")
    print(f"wall      {seconds:.2f} s ({1e3 * seconds / max(1, result['frames'] * len(methods)):.1f} ms a frame and method)")
    where = args.output if len(result["files"]) == 1 else f"{args.output} ({len(result['files'])} PNG files)"
    print(f"wrote     {where}")
    return 0


def _adapters(_: argparse.Namespace) -> int:
    import vsgl

    found = vsgl.adapters()
    if not found:
        print("no adapters; on Debian/Ubuntu: apt-get install mesa-vulkan-drivers libvulkan1")
        return 1
    for a in found:
        print(f"{a['name']}  [{a['device_type']}, {a['backend']}, timestamps={a['timestamps']}]  {a['driver']}")
    return 0


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT, got {text!r}") from None
    return w, h


def _light(text: str):
    from vsgl.lightspec import parse_light

    try:
        return parse_light(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _methods(args: argparse.Namespace) -> int:
    import vsgl

    for name in vsgl.METHODS:
        print(vsgl.describe_method(name))
    return 0


def _progress_line(method: str):
    """A `progress` callback that keeps one line on stderr up to date for long renders (shown
    only on a terminal, so logs and pipes stay clean); Ctrl-C stops the render between batches."""
    if not sys.stderr.isatty():
        return None

    def show(done: int, total: int, unit: str) -> None:
        show.shown = True  # type: ignore[attr-defined]
        print(f"\r{method}: {done}/{total} {unit} ({100.0 * done / max(total, 1):.0f}%), Ctrl-C stops", end="", file=sys.stderr, flush=True)

    show.shown = False  # type: ignore[attr-defined]
    return show


def _view(args: argparse.Namespace) -> int:
    import vsgl
    from vsgl.window_view import view

    scene = _load_scene(args.scene)  # a bad name or path: main() prints the error, status 2
    for light in args.light:
        scene.add_light(light)
    methods = args.compare.split(",") if args.compare else [args.method]
    options: dict = {}
    for name, value in (("num_lights", args.lights), ("rsm_size", args.rsm_size), ("interleave", args.interleave)):
        if value is not None and any(name in vsgl.method_options(m) for m in methods):
            options[name] = value
    options.update(args.option)
    renderer = vsgl.Renderer(width=args.size[0], height=args.size[1], adapter=args.adapter)
    try:
        result = view(scene, methods[0], compare=methods if len(methods) > 1 else None, renderer=renderer,
                      size=args.size, ui=not args.no_ui, vsync=not args.no_vsync, frames=args.frames,
                      screenshot=args.screenshot, seed=args.seed, **options)
    except vsgl.WindowUnavailableError as e:
        print(f"error: {e}", file=sys.stderr)
        return 3
    if result["median_frame_ms"] is not None:
        print(f"frames    {result['frames']}, median {result['median_frame_ms']:.2f} ms a frame (render, compose, panel, present)")
    if result["screenshot"]:
        print(f"screenshot {result['screenshot']}")
    return 0


def main(argv: list[str] | None = None) -> int:
    import vsgl

    parser = argparse.ArgumentParser(prog="python -m vsgl", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    render = sub.add_parser("render", help="render a scene to an image and print timings")
    render.add_argument("scene", nargs="?", default="cornell_box", help="built-in or corpus scene name, or .gltf/.glb path (default: cornell_box)")
    render.add_argument("-o", "--output", default="out.png", help="output image, .png or .npy (default: out.png)")
    render.add_argument("--size", type=_size, default=(320, 180), help="WIDTHxHEIGHT (default: 320x180)")
    render.add_argument("--method", default="vsgl", choices=list(vsgl.METHODS), help="the method (default: vsgl); `python -m vsgl methods` describes each")
    render.add_argument("--lights", type=int, default=None, help="VPLs or VSGLs in all, split over the lights by reflected power (default: the method's: vsgl 1024, vpl 256)")
    render.add_argument("--light", action="append", default=[], type=_light, metavar="SPEC",
                        help='add a light (repeatable): "spot position=X,Y,Z direction=X,Y,Z intensity=W [color=R,G,B] '
                             '[inner_cone_deg=D] [outer_cone_deg=D]", "point position=X,Y,Z intensity=W [color=R,G,B]" '
                             'or "directional direction=X,Y,Z intensity=LUX [color=R,G,B]" (intensities in W/sr, lux)')
    render.add_argument("--no-scene-lights", action="store_true", help="drop the scene's own lights (then light it with --light)")
    render.add_argument("--rsm-size", type=int, default=None, help="RSM side, power of two; any 32..4096 for vsgl2 (default: 256; reference 1024)")
    render.add_argument("--kernel", default="integral", choices=["integral", "density", "node"],
                        help="VSGL kernel size rule (default: integral; node: quadtree nodes read exactly, converging to VPLs as --lights reaches the RSM's texel count)")
    render.add_argument("--interleave", type=int, default=None,
                        help="interleaving tile side of vsgl and vpl (default: the method's, 8 for vsgl, 1 for vpl)")
    render.add_argument("--seed", type=int, default=0, help="sampling seed (default: 0)")
    render.add_argument("--spp", type=int, default=64, help="samples per pixel of pathtrace (default: 64)")
    render.add_argument("--strategy", default=None, choices=["camera", "bidirectional", "light"],
                        help="paths of pathtrace: camera (pixel centres; default), bidirectional (light tracing + camera paths by MIS, per pixel area: caustics) or light")
    render.add_argument("--visibility", default=None, choices=["none", "raytrace"],
                        help="visibility of virtual lights in vpl, vsgl, vsgl2 and reference: none (unshadowed; default) or raytrace (shadow rays through the BVH)")
    render.add_argument("--importance", default=None, choices=["rsm", "brsm"],
                        help="RSM sampling density of vpl and vsgl: rsm (reflected power; default) or brsm (bidirectional: importance to the camera's view)")
    render.add_argument("-O", "--option", action="append", default=[], type=_option, metavar="NAME=VALUE",
                        help="any option of the method (repeatable), e.g. -O importance_interleave=2 -O lambert_lobe=papers "
                             "-O denoise=false; values are read as int, float, true/false or text; "
                             "`python -m vsgl methods` lists each method's options")
    render.add_argument("--reference-rsm", type=int, default=128, help="RSM side of the reference the error is measured against (default: 128; the library default 1024 takes minutes on a CPU adapter)")
    render.add_argument("--no-error", action="store_true", help="skip rendering the reference and the error report")
    render.add_argument("--shadow-size", type=int, default=1024, help="shadow map side (default: 1024)")
    render.add_argument("--plan", default="auto", choices=["auto", "full"], help="leave out unneeded passes (auto) or run all (full)")
    render.add_argument("--exposure", type=float, default=1.0, help="PNG exposure multiplier (default: 1)")
    render.add_argument("--adapter", default=None, help="adapter name substring (default: best, or $VSGL_ADAPTER)")
    render.add_argument("--explain", action="store_true", help="print the pass plan and what was left out, with reasons")
    render.set_defaults(run=_render)

    animate = sub.add_parser("animate", help="render a scene's animation to .mp4, .gif or a folder of PNGs")
    animate.add_argument("scene", nargs="?", default="cave_flashlight", help="built-in scene name or .gltf/.glb path (default: cave_flashlight)")
    animate.add_argument("-o", "--output", default="frames/", help="a folder ending with '/' (PNGs), .gif or .mp4 (the last two: pip install vsgl[video]) (default: frames/)")
    animate.add_argument("--method", default="vsgl", choices=list(vsgl.METHODS), help="the method (default: vsgl)")
    animate.add_argument("--compare", default=None, metavar="M1,M2,...", help="tile several methods left to right, e.g. vpl,vsgl,reference")
    animate.add_argument("--frames", type=int, default=120, help="number of frames (default: 120)")
    animate.add_argument("--fps", type=float, default=30.0, help="frames per second; frame k shows time k/fps (default: 30)")
    animate.add_argument("--size", type=_size, default=(320, 180), help="WIDTHxHEIGHT of each tile (default: 320x180)")
    animate.add_argument("--lights", type=int, default=None, help="VPLs or VSGLs in all (default: the method's: vsgl 1024, vpl 256)")
    animate.add_argument("--rsm-size", type=int, default=None, help="RSM side (default: the method's)")
    animate.add_argument("--K", type=float, default=None, help="vsgl kernel mass K (default: 1)")
    animate.add_argument("--interleave", type=int, default=None, help="interleaving tile side of vsgl and vpl (default: the method's)")
    animate.add_argument("--seed", type=int, default=0, help="sampling seed, the same every frame (default: 0)")
    animate.add_argument("--spp", type=int, default=None, help="samples per pixel of pathtrace (default: 64)")
    animate.add_argument("--adapter", default=None, help="adapter name substring (default: best, or $VSGL_ADAPTER)")
    animate.set_defaults(run=_animate)

    view_cmd = sub.add_parser("view", help="a desktop window: move the camera and the lights, change the method and its options live")
    view_cmd.add_argument("scene", nargs="?", default="cornell_box", help="built-in or corpus scene name, or .gltf/.glb path (default: cornell_box)")
    view_cmd.add_argument("--method", default="vsgl", choices=list(vsgl.METHODS), help="the method (default: vsgl)")
    view_cmd.add_argument("--compare", default=None, metavar="M1,M2", help="two methods side by side with a movable divider, e.g. vpl,vsgl")
    view_cmd.add_argument("--size", type=_size, default=(960, 540), help="WIDTHxHEIGHT of the window in logical pixels (default: 960x540)")
    view_cmd.add_argument("--lights", type=int, default=None, help="VPLs or VSGLs in all (default: the method's)")
    view_cmd.add_argument("--rsm-size", type=int, default=None, help="RSM side (default: the method's)")
    view_cmd.add_argument("--interleave", type=int, default=None, help="interleaving tile side (default: the method's)")
    view_cmd.add_argument("--light", action="append", default=[], type=_light, metavar="SPEC", help="add a light (repeatable), as in render --help")
    view_cmd.add_argument("--seed", type=int, default=0, help="sampling seed (default: 0)")
    view_cmd.add_argument("-O", "--option", action="append", default=[], type=_option, metavar="NAME=VALUE", help="any option of the method (repeatable)")
    view_cmd.add_argument("--frames", type=int, default=None, help="render this many frames, then close (headless runs; default: until the window is closed)")
    view_cmd.add_argument("--screenshot", default=None, metavar="PNG", help="save the last frame presented there when the window closes")
    view_cmd.add_argument("--no-ui", action="store_true", help="no settings panel or status line over the frame")
    view_cmd.add_argument("--no-vsync", action="store_true", help="present without waiting for the display's refresh (frame-rate measurements)")
    view_cmd.add_argument("--adapter", default=None, help="adapter name substring (default: best, or $VSGL_ADAPTER)")
    view_cmd.set_defaults(run=_view)

    methods = sub.add_parser("methods", help="list the methods and the options each takes")
    methods.set_defaults(run=_methods)

    adapters = sub.add_parser("adapters", help="list the adapters wgpu sees")
    adapters.set_defaults(run=_adapters)

    # `bench` has its own parser (vsgl.bench.main); it is listed here for --help.
    sub.add_parser("bench", help="error against run time: sweep methods and settings, write CSV/JSON/plots", add_help=False)

    # `stability` has its own parser (vsgl.stability.main); it is listed here for --help.
    sub.add_parser("stability", help="the numerical stability suite: every WGSL math function in f32 against its f64 oracle", add_help=False)

    # `reproduce` has its own parser (vsgl.reproduce.main); it is listed here for --help.
    sub.add_parser("reproduce", help="the papers' tables (pass times, k-means against FIS, LPV against one VSGL) next to ours, with error", add_help=False)

    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["reproduce"]:
        from vsgl import reproduce as reproduce_module

        return reproduce_module.main(argv[1:])
    if argv[:1] == ["stability"]:
        from vsgl import stability as stability_module

        return stability_module.main(argv[1:])
    if argv[:1] == ["bench"]:
        from vsgl import bench as bench_module

        try:
            return bench_module.main(argv[1:])
        except ValueError as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
