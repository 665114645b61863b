//! Imperfect shadow maps (compute, `visibility="ism"`): splats the scene's point set into one
//! small octahedral depth map per virtual light with atomics, then fills holes by pull-push
//! (`wgsl/passes/ism.wgsl`). The shading passes read the maps (`wgsl/common/ism_lookup.wgsl`).

use crate::error::Result;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::ism::WORKGROUP;
/// Most maps one dispatch covers (the y dimension of a dispatch is at most 65535 workgroups).
const MAPS_PER_DISPATCH: u32 = 65535;

/// Where the maps live in their storage buffer: per map, level 0 (`size`²) and `pull_levels`
/// coarser levels, each a quarter of the last.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IsmLayout {
    pub size: u32,
    pub pull_levels: u32,
}

impl IsmLayout {
    /// `pull_levels` is cut so the coarsest level keeps at least 2² texels.
    pub fn new(size: u32, pull_levels: u32) -> Self {
        let most = size.max(2).ilog2().saturating_sub(1);
        Self { size, pull_levels: pull_levels.min(most) }
    }

    /// Word offset of each level within a map, and the words of one map.
    pub fn level_offsets(&self) -> (Vec<u32>, u32) {
        let mut offsets = Vec::new();
        let mut total = 0;
        for level in 0..=self.pull_levels {
            offsets.push(total);
            let side = self.size >> level;
            total += side * side;
        }
        (offsets, total)
    }

    pub fn words_per_map(&self) -> u32 {
        self.level_offsets().1
    }

    pub fn bytes_per_map(&self) -> u64 {
        self.words_per_map() as u64 * 4
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct IsmBuildParamsRaw {
    map_size: u32,
    words_per_map: u32,
    first_map: u32,
    map_count: u32,
    point_count: u32,
    points_per_map: u32,
    point_stride: u32,
    light_record_words: u32,
    fine_offset: u32,
    coarse_offset: u32,
    coarse_size: u32,
    _pad: u32,
}
const _: () = assert!(std::mem::size_of::<IsmBuildParamsRaw>() == 48);

/// What one build reads: the lights (records of `record_words` u32 words, position first), the
/// scene's points, and how many of them each map splats.
pub struct IsmSources<'a> {
    pub frame: &'a wgpu::Buffer,
    pub points: &'a wgpu::Buffer,
    pub point_count: u32,
    pub points_per_map: u32,
    pub lights: &'a wgpu::Buffer,
    pub light_count: u32,
    pub record_words: u32,
}

pub struct IsmPass {
    splat: wgpu::ComputePipeline,
    pull: wgpu::ComputePipeline,
    push: wgpu::ComputePipeline,
}

impl IsmPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/ism.wgsl")?;
        Ok(Self {
            splat: gpu.compute_pipeline("ism_splat_pipeline", &module, "splat"),
            pull: gpu.compute_pipeline("ism_pull_pipeline", &module, "pull"),
            push: gpu.compute_pipeline("ism_push_pipeline", &module, "push"),
        })
    }

    /// Builds the maps of lights 0 … light_count − 1 into `atlas` (which must hold them and be
    /// zero: empty texels are key 0).
    pub fn record(&self, rec: &mut Recorder<'_>, atlas: &wgpu::Buffer, layout: IsmLayout, src: &IsmSources<'_>) {
        let (offsets, words_per_map) = layout.level_offsets();
        let per_map = src.points_per_map.min(src.point_count);
        if src.light_count == 0 || per_map == 0 {
            return;
        }
        let base = IsmBuildParamsRaw {
            map_size: layout.size,
            words_per_map,
            first_map: 0,
            map_count: 0,
            point_count: src.point_count,
            points_per_map: per_map,
            point_stride: (src.point_count / per_map).max(1),
            light_record_words: src.record_words,
            fine_offset: 0,
            coarse_offset: 0,
            coarse_size: 0,
            _pad: 0,
        };
        let mut first = 0;
        while first < src.light_count {
            let maps = (src.light_count - first).min(MAPS_PER_DISPATCH);
            let chunk = IsmBuildParamsRaw { first_map: first, map_count: maps, ..base };
            let uniform = rec.uniform("ism_splat_params_uniform_buffer", &chunk);
            rec.compute(
                "ism_splat",
                &self.splat,
                &[&[atlas.as_entire_binding(), uniform.as_entire_binding(), src.frame.as_entire_binding(), src.points.as_entire_binding(), src.lights.as_entire_binding()]],
                (groups(per_map, WORKGROUP), maps, 1),
            );
            // Pull: level l → l + 1, finest first.
            for level in 0..layout.pull_levels as usize {
                let coarse_size = layout.size >> (level + 1);
                let params = IsmBuildParamsRaw { fine_offset: offsets[level], coarse_offset: offsets[level + 1], coarse_size, ..chunk };
                let uniform = rec.uniform("ism_pull_params_uniform_buffer", &params);
                rec.compute("ism_pull", &self.pull, &[&[atlas.as_entire_binding(), uniform.as_entire_binding()]], (groups(coarse_size * coarse_size, WORKGROUP), maps, 1));
            }
            // Push: level l + 1 → l into the texels no point reached, coarsest first.
            for level in (0..layout.pull_levels as usize).rev() {
                let coarse_size = layout.size >> (level + 1);
                let fine_size = 2 * coarse_size;
                let params = IsmBuildParamsRaw { fine_offset: offsets[level], coarse_offset: offsets[level + 1], coarse_size, ..chunk };
                let uniform = rec.uniform("ism_push_params_uniform_buffer", &params);
                rec.compute("ism_push", &self.push, &[&[atlas.as_entire_binding(), uniform.as_entire_binding()]], (groups(fine_size * fine_size, WORKGROUP), maps, 1));
            }
            first += maps;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_counts_the_pyramid_and_keeps_the_coarsest_level_at_least_two_wide() {
        let l = IsmLayout::new(64, 3);
        assert_eq!(l.level_offsets(), (vec![0, 4096, 5120, 5376], 5440));
        assert_eq!(IsmLayout::new(8, 5).pull_levels, 2);
        assert_eq!(IsmLayout::new(8, 5).words_per_map(), 64 + 16 + 4);
    }
}
