// Spot-light shadow map: depth only, reverse-Z (1 at the near plane), one array layer per light.

struct ShadowView {
    view_proj: mat4x4f,
}

@group(0) @binding(0) var<uniform> shadow_view: ShadowView;

@vertex
fn vs_main(@location(0) position: vec3f) -> @builtin(position) vec4f {
    return shadow_view.view_proj * vec4f(position, 1.0);
}
