//! The pass plan: what a frame needs, derived from the scene (cheap: one walk over the used
//! materials, redone every frame so an edited scene is re-planned) and the settings. It picks
//! the shader variants (WGSL `override` constants, `wgsl/common/plan.wgsl` and
//! `passes/material.wgsl`) with the unneeded work compiled out, and says in words what it
//! left out (`frame.skipped`). Settings-driven choices (which method's passes run) are made
//! by `renderer.rs` and reported the same way. Rules and their proofs: docs/frames.md,
//! "Pass plan"; every rule leaves the image unchanged beyond float rounding (tests/test_plan.py).

use crate::scene::Scene;

/// What the scene's materials need from the shaders. `ALL` is `plan="full"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShaderFeatures {
    /// Some used material samples a texture (else: untextured material variant).
    pub textures: bool,
    /// Some used material has a normal map (else: no tangent frames).
    pub normal_maps: bool,
    /// Some used material has R_s > 0 (else: no specular flux, lobes, GGX or SG–ASG terms).
    pub specular: bool,
}

impl ShaderFeatures {
    pub const ALL: Self = Self { textures: true, normal_maps: true, specular: true };

    /// The override constants of the passes that read only the specular switch.
    pub fn specular_flags(self) -> [(&'static str, bool); 1] {
        [("HAS_SPECULAR", self.specular)]
    }

    /// `name[variant,…]` for `frame.passes`: the pass name with what its variant leaves out.
    pub fn pass_name(self, pass: &str) -> String {
        let mut cut: Vec<&str> = Vec::new();
        if pass.ends_with("material") {
            if !self.textures {
                cut.push("untextured");
            } else if !self.normal_maps {
                cut.push("no_normal_maps");
            }
        }
        if !self.specular && SPECULAR_PASSES.contains(&pass) {
            cut.push("diffuse_only");
        }
        match (cut.is_empty(), pass.strip_suffix(']')) {
            (true, _) => pass.to_string(),
            (false, Some(open)) => format!("{open},{}]", cut.join(",")),
            (false, None) => format!("{pass}[{}]", cut.join(",")),
        }
    }
}

/// Passes with a `HAS_SPECULAR` variant.
const SPECULAR_PASSES: &[&str] = &[
    "direct", "rsm_flux", "vpl_sample", "vpl_sample[every_texel]", "vpl_shading", "vsgl_moments", "vsgl2_reduce",
    "vsgl_shading", "denoise", "vpl_shading[raytrace]", "vsgl_shading[raytrace]",
    "emitter_direct", "emitter_direct[raytrace]", "emitter_direct[ism]",
    "brsm_view_gbuffer", "brsm_view_moments", "brsm_importance",
];

/// A frame's scene-derived plan: the shader features and what they leave out, with reasons.
#[derive(Clone, Debug)]
pub struct Plan {
    pub features: ShaderFeatures,
    pub skipped: Vec<(String, String)>,
}

impl Plan {
    /// `full`: every feature on (`plan="full"`), nothing left out.
    pub fn new(scene: &Scene, full: bool) -> Self {
        if full {
            return Self { features: ShaderFeatures::ALL, skipped: Vec::new() };
        }
        let stats = scene.stats();
        let features = ShaderFeatures {
            textures: stats.has_textures,
            normal_maps: stats.has_normal_maps,
            specular: stats.has_specular,
        };
        let mut skipped = Vec::new();
        if !features.textures {
            skipped.push(("material_texture_fetch".into(), "no material in the scene uses a texture".into()));
        }
        if !features.normal_maps {
            skipped.push(("normal_map_tangent_frames".into(), "no material in the scene has a normal map".into()));
        }
        if !features.specular {
            skipped.push((
                "specular_lobes".into(),
                "no material has specular reflectance (metallic = 0 and KHR_materials_specular factor 0 \
                 everywhere): no specular flux, lobes, GGX or SG-ASG terms, no indirect_specular buffers"
                    .into(),
            ));
        }
        Self { features, skipped }
    }
}

#[cfg(test)]
mod tests {
    use super::SPECULAR_PASSES;
    use crate::shader_lib;

    /// The pass whose shader an entry of `frame.passes` names ("vpl_sample[every_texel]" →
    /// passes/vpl_sample.wgsl).
    fn shader_of(pass: &str) -> String {
        // The view's moments of bidirectional importance run the light's moment shader; the
        // emitter VSGLs' direct light runs the VSGL shading shader.
        let pass = pass.split('[').next().unwrap();
        let shader = match pass {
            "brsm_view_moments" => "vsgl_moments",
            "emitter_direct" => "vsgl_shading",
            other => other,
        };
        format!("passes/{shader}.wgsl")
    }

    /// `[diffuse_only]` is reported for exactly the passes whose shader reads HAS_SPECULAR, so
    /// `frame.passes` cannot claim a variant that does not exist or hide one that ran.
    #[test]
    fn diffuse_only_names_match_the_shaders_that_read_has_specular() {
        for pass in SPECULAR_PASSES {
            let src = shader_lib::compose(&shader_of(pass)).expect("pass shader composes");
            assert!(src.contains("if (HAS_SPECULAR"), "{pass} is named diffuse_only but its shader never reads HAS_SPECULAR");
        }
        // pathtrace includes vpl.wgsl but keeps one variant (docs/frames.md, "Pass plan").
        for path in shader_lib::paths().filter(|p| p.starts_with("passes/") && *p != "passes/pathtrace.wgsl") {
            let src = shader_lib::compose(path).expect("pass shader composes");
            // The subgroup reduction runs under its pass's name (vsgl2_reduce).
            let name = path.trim_start_matches("passes/").trim_end_matches(".wgsl").trim_end_matches("_subgroup");
            if src.contains("if (HAS_SPECULAR") {
                assert!(SPECULAR_PASSES.iter().any(|p| shader_of(p) == shader_of(name)), "{name} has a HAS_SPECULAR variant that frame.passes does not name");
            }
        }
    }
}
