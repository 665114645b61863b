"""A plane lighting itself near a light: CornellBoxOriginal (../shared/scenes) with a point light
0.19 m below its ceiling, seen by the default camera from above the box's open front, so the top
of the thin ceiling quad fills the top third of the image. `vsgl` (unshadowed, the papers' setting)
against the every-texel `reference` of the same RSM (docs/methods/vsgl.md, "The cluster's tangent
plane"). The reference puts no indirect light on the ceiling (every texel that could light it is
coplanar with it or below it); the papers' diffuse form without the tangent-plane fade
(`plane_fade=False`, the default before 2026-11-29) put about half of the image's indirect light
there, lighting the back of the lit ceiling.

    .venv/bin/python experiments/near_light_self_lighting.py [--size 96] [--scene PATH]"""

from __future__ import annotations

import argparse
import pathlib

import vsgl

DEFAULT_SCENE = pathlib.Path(__file__).resolve().parents[2] / "shared/scenes/CornellBoxOriginal/CornellBoxOriginal.glb"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=96)
    p.add_argument("--scene", type=pathlib.Path, default=DEFAULT_SCENE)
    a = p.parse_args()
    if not a.scene.exists():
        p.error(f"--scene: {a.scene} not found (CornellBoxOriginal.glb from ../shared/scenes)")
    scene = vsgl.Scene.load(str(a.scene))
    scene.add_light(vsgl.PointLight(position=(-0.01, 1.8, 0.2), intensity=3.0))
    r = vsgl.Renderer(a.size, a.size)
    ref = r.render(scene, method="reference", rsm_size=128, aovs=["indirect", "normal"])
    # The ceiling's top side: up-facing (shading normals face the camera) in the image's top third.
    normal = ref.aov("normal")
    ceiling = normal[..., 1] > 0.99
    ceiling[a.size // 3:] = False
    truth = ref.aov("indirect").astype(float)
    print(f"reference: indirect mean {truth.mean():.4g}, share on the ceiling {truth[ceiling].sum() / truth.sum():.3f}")
    for label, kw in (("default (the papers' diffuse form with the fade)", {}),
                      ("the papers' form without the fade (plane_fade=False)", dict(lighting="asg", plane_fade=False)),
                      ("diffuse=accurate (the clamped cosine, always faded)", dict(diffuse="accurate")),
                      ("kernel=node", dict(kernel="node")), ("kernel=node, plane_fade=False", dict(kernel="node", lighting="asg", plane_fade=False)),
                      ("lighting=blend (its diffuse is the faded clamped cosine)", dict(lighting="blend"))):
        f = r.render(scene, method="vsgl", rsm_size=128, interleave=1, denoise=False, aovs=["indirect"], **kw)
        img = f.aov("indirect").astype(float)
        print(f"vsgl {label}: mean {img.mean() / truth.mean():.2f}x the reference's, share on the ceiling {img[ceiling].sum() / img.sum():.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
