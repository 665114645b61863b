//! Reading a frame's AOVs back: only the buffers the asked-for AOVs are made from, converted
//! from the GPU's vec4f per pixel to (H, W, C) floats.

use super::options::RenderOptions;
use crate::error::Result;
use crate::frame::{GBuffer, IndirectTargets};
use crate::gpu::Gpu;
use crate::methods::MethodInfo;
use std::collections::HashMap;

/// The frame's targets that AOVs are made from.
pub(super) struct AovSources<'a> {
    pub direct: &'a wgpu::Buffer,
    pub indirect: &'a IndirectTargets,
    pub gbuffer: &'a GBuffer,
    pub stderr: Option<&'a wgpu::Buffer>,
    /// Whether the scene has specular materials (else the specular target is a placeholder).
    pub specular: bool,
}

pub(super) type Aovs = Vec<(String, usize, Vec<f32>)>;

fn rgb(v: &[f32]) -> Vec<f32> {
    v.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
}

/// The AOVs `opts` asks for (all the method makes when it names none), in `AOV_NAMES` order.
pub(super) fn read_aovs(gpu: &Gpu, opts: &RenderOptions, info: &MethodInfo, src: &AovSources<'_>, pixels: usize) -> Result<Aovs> {
    let wants = |names: &[&str]| names.iter().any(|n| opts.wants_aov(info, n));
    let specular_wanted = wants(&["image", "indirect", "indirect_specular"]);
    let sources: Vec<(&str, &wgpu::Buffer)> = [
        ("direct", src.direct, wants(&["image", "direct"])),
        ("indirect_diffuse", &src.indirect.diffuse, wants(&["image", "indirect", "indirect_diffuse"])),
        ("indirect_specular", &src.indirect.specular, src.specular && specular_wanted),
        ("albedo", &src.gbuffer.base_color, wants(&["albedo"])),
        ("normal", &src.gbuffer.normal, wants(&["normal"])),
        ("depth", &src.gbuffer.position, wants(&["depth"])),
    ]
    .into_iter()
    .chain(src.stderr.map(|b| ("stderr", b, wants(&["stderr"]))))
    .filter(|(_, _, wanted)| *wanted)
    .map(|(name, buffer, _)| (name, buffer))
    .collect();
    let buffers: Vec<&wgpu::Buffer> = sources.iter().map(|(_, b)| *b).collect();
    let read = if buffers.is_empty() { Vec::new() } else { gpu.read_buffers(&buffers)? };
    let mut raw: HashMap<&str, Vec<f32>> =
        sources.iter().zip(read).map(|((name, _), bytes)| (*name, bytemuck::cast_slice::<u8, f32>(&bytes).to_vec())).collect();

    let mut take_rgb = |name: &str| raw.remove(name).map(|v| rgb(&v));
    let direct = take_rgb("direct");
    let ind_d = take_rgb("indirect_diffuse");
    // Without specular materials the specular target is a placeholder: zero by definition
    // (made whenever the specular part is wanted, with or without the diffuse readback).
    let ind_s = take_rgb("indirect_specular").or_else(|| specular_wanted.then(|| vec![0.0; pixels * 3]));
    let albedo = take_rgb("albedo");
    let normal = take_rgb("normal");
    let stderr = take_rgb("stderr");
    // View depth; 0 where no surface was hit (never Inf, see docs/rendering.md).
    let depth = raw.remove("depth").map(|p| p.chunks_exact(4).map(|p| if p[3] > 0.0 { p[3] } else { 0.0 }).collect::<Vec<f32>>());
    let sum = |a: &[f32], b: &[f32]| -> Vec<f32> { a.iter().zip(b).map(|(x, y)| x + y).collect() };
    let indirect_sum = match (&ind_d, &ind_s) {
        (Some(d), Some(s)) => Some(sum(d, s)),
        _ => None,
    };
    // Without indirect light the image is the direct AOV: moved, not copied, unless both are
    // asked for.
    let (image, direct) = match (&direct, &indirect_sum) {
        _ if !info.indirect && opts.wants_aov(info, "direct") => (direct.clone(), direct),
        _ if !info.indirect => (direct, None),
        (Some(d), Some(i)) => (Some(sum(d, i)), direct),
        _ => (None, direct),
    };
    let made: [(&str, usize, Option<Vec<f32>>); 9] = [
        ("image", 3, image),
        ("indirect", 3, indirect_sum),
        ("indirect_diffuse", 3, ind_d),
        ("indirect_specular", 3, ind_s),
        ("direct", 3, direct),
        ("albedo", 3, albedo),
        ("normal", 3, normal),
        ("depth", 1, depth),
        ("stderr", 3, stderr),
    ];
    Ok(made
        .into_iter()
        .filter(|(name, _, _)| opts.wants_aov(info, name))
        .filter_map(|(name, c, data)| data.map(|d| (name.to_string(), c, d)))
        .collect())
}
