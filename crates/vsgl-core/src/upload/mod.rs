//! Scene → GPU buffers.
//!
//! Positions are uploaded relative to the scene's own anchor (the centre of its bounds),
//! computed in f64, so a scene 1e5 m from the world origin renders as precisely as one at the
//! origin, and a moving camera never re-uploads: each frame shifts the anchor-relative
//! vertices to its camera on the GPU (`FrameUniforms::view_origin` and the translation in
//! `view_proj`). The renderer reuses an upload while the scene instance and its
//! `geometry_version` are unchanged (`Renderer::uploaded_scene`, docs/frames.md
//! "Scene upload cache").

pub mod bvh;
pub mod convex;
pub mod emitters;
pub mod points;

use crate::error::{Error, Result};
use crate::gpu::buffers::{storage_pages_capacity, STORAGE_PAGES, STORAGE_PAGE_BYTES};
use crate::gpu::Gpu;
use crate::scene::{Scene, TextureUsage};
use glam::{DMat3, DVec3};
use wgpu::util::DeviceExt;

/// Per-vertex attributes for the material pass (storage buffer, 64 bytes).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VertexRaw {
    pub position: [f32; 3],
    pub _pad0: f32,
    pub normal: [f32; 3],
    pub _pad1: f32,
    pub tangent: [f32; 4],
    pub uv: [f32; 2],
    pub _pad2: [f32; 2],
}
const _: () = assert!(std::mem::size_of::<VertexRaw>() == 64);

/// Rasterised vertex: position relative to the upload anchor and the triangle id (16 bytes).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RasterVertex {
    pub position: [f32; 3],
    pub triangle: u32,
}
const _: () = assert!(std::mem::size_of::<RasterVertex>() == 16);

/// GPU twin of [`crate::scene::Material`] (64 bytes). Texture layers are −1 when absent.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialRaw {
    pub base_color: [f32; 4],
    pub metallic: f32,
    pub roughness: f32,
    pub normal_scale: f32,
    pub specular_factor: f32,
    pub base_color_layer: i32,
    pub metallic_roughness_layer: i32,
    pub normal_layer: i32,
    /// Layer of the emissive texture in the colour (sRGB) array.
    pub emissive_layer: i32,
    /// Emitted radiance L_e (linear RGB); the vec3 is paired with a scalar (WGSL alignment).
    pub emissive: [f32; 3],
    pub _pad1: f32,
    /// `KHR_texture_transform` of the base colour, metallic-roughness, normal and emissive
    /// references, two rows each: uv' = (row_u.xyz · (u, v, 1), row_v.xyz · (u, v, 1)); row_u.w
    /// is the mip-level shift ½·log2|det M| (the footprint's growth under M), row_v.w unused.
    pub base_color_uv: [[f32; 4]; 2],
    pub metallic_roughness_uv: [[f32; 4]; 2],
    pub normal_uv: [[f32; 4]; 2],
    pub emissive_uv: [[f32; 4]; 2],
}
const _: () = assert!(std::mem::size_of::<MaterialRaw>() == 192);

/// The GPU rows of a texture-coordinate transform (see [`MaterialRaw::base_color_uv`]).
fn uv_rows(t: &crate::scene::UvTransform) -> [[f32; 4]; 2] {
    let [u, v] = t.rows;
    let det = (f64::from(u[0]) * f64::from(v[1]) - f64::from(u[1]) * f64::from(v[0])).abs();
    let lod_shift = 0.5 * det.max(1e-30).log2();
    [[u[0], u[1], u[2], lod_shift as f32], [v[0], v[1], v[2], 0.0]]
}

/// Largest texture layer side. Textures are resampled into one array per colour space so the
/// material pass needs no bindless feature; 1024² keeps FlightHelmet/BoomBox detail at the
/// resolutions we render while bounding memory (4 MiB a layer before mips).
pub const TEXTURE_LAYER_MAX: u32 = 1024;

pub struct GpuScene {
    /// Three corners a triangle in scene order ([`RasterVertex`]): the rasteriser's vertex buffer
    /// and the ray tracers' triangle corners ([`GpuBvh`]).
    pub raster_vertices: wgpu::Buffer,
    pub raster_vertex_count: u32,
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    /// Per triangle: material index.
    pub triangle_materials: wgpu::Buffer,
    pub materials: wgpu::Buffer,
    pub color_textures: wgpu::TextureView,
    pub data_textures: wgpu::TextureView,
    pub texture_layer_size: u32,
    pub triangle_count: u32,
    /// World-space bounds diagonal, for scale-aware epsilons.
    pub extent: f64,
    /// World position every uploaded position is relative to: the centre of the scene bounds
    /// (the world origin for a scene without geometry). Uploaded coordinates are thus at most
    /// half the scene's diagonal, and f32 keeps them to ~3e-8 of its size wherever the scene is.
    pub anchor: DVec3,
    /// Half the sides of the scene bounds around [`Self::anchor`] (NaN without geometry): what a
    /// spot light's RSM is fitted to (`frame::uniforms::fitted_spot_view`).
    pub half_size: DVec3,
    /// The emissive triangles the path tracer samples as area lights ([`emitters`]; a 16-byte
    /// placeholder when none emits, then `emitter_count` is 0).
    pub emitters: wgpu::Buffer,
    pub emitter_count: u32,
    /// Their total power, π · Σ area · (L_r + L_g + L_b).
    pub emitter_power: f64,
    /// The same triangles for the emitter clusters of the real-time methods.
    emitter_triangles: Vec<emitters::EmitterTriangle>,
    /// Whether there are emitters and none faces any part of the scene's bounds
    /// ([`emitters::face_nothing`]): they light nothing.
    pub emitters_face_nothing: bool,
    /// The clusters last asked for, and the budget they were made for.
    emitter_lights: std::sync::Mutex<Option<(usize, std::sync::Arc<emitters::EmitterClusters>)>>,
    /// The ray tracers' BVH over these very triangles, built on first use and kept with the
    /// upload (a changed geometry re-uploads, and so rebuilds it).
    bvh: std::sync::Mutex<Option<std::sync::Arc<GpuBvh>>>,
    /// Whether the surfaces lie on their convex hull ([`convex::is_convex_shell`]), found on
    /// first use and kept with the upload like the BVH.
    convex_shell: std::sync::OnceLock<bool>,
    /// The scene as a point set for imperfect shadow maps (`points.rs`), generated on first use
    /// and kept with the upload like the BVH; regenerated only when another count is asked for.
    surface_points: std::sync::Mutex<Option<std::sync::Arc<GpuPoints>>>,
}

/// The scene's point set on the GPU: `count` vec4f rows relative to [`GpuScene::anchor`]
/// (a 16-byte placeholder when the scene has no area, then `count` is 0).
pub struct GpuPoints {
    pub buffer: wgpu::Buffer,
    pub count: u32,
    /// The count asked for (what the cache is keyed by).
    pub asked: u32,
}

/// A BVH on the GPU (layout in `wgsl/common/bvh.wgsl`). Its triangles' corners are
/// [`GpuScene::raster_vertices`], bound beside it.
pub struct GpuBvh {
    pub nodes: wgpu::Buffer,
    /// The scene triangle index of each leaf slot (u32, leaf order).
    pub triangle_ids: wgpu::Buffer,
    pub node_count: usize,
    pub depth: usize,
}

fn storage(gpu: &Gpu, label: &str, bytes: &[u8], extra: wgpu::BufferUsages) -> wgpu::Buffer {
    // wgpu rejects zero-sized bindings: pad empty arrays to one element.
    let padded;
    let contents = if bytes.is_empty() {
        padded = vec![0u8; 64];
        &padded[..]
    } else {
        bytes
    };
    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::STORAGE | extra,
    })
}

impl GpuScene {
    /// The BVH of the uploaded triangles, relative to [`Self::anchor`] like them (`scene` must
    /// be what the upload was made from), built now if no frame has needed it yet (then `true`).
    /// Whether no segment between two surface points of this upload can be blocked (every
    /// surface on the convex hull); computed once per upload.
    pub fn convex_shell(&self, scene: &Scene) -> bool {
        *self.convex_shell.get_or_init(|| convex::is_convex_shell(&bvh::scene_triangles(scene, self.anchor), self.extent))
    }

    /// The emissive triangles as at most `budget` lights ([`emitters::emitter_lights`]; at
    /// least one per normal direction that emits), made now unless the last frame of this
    /// upload asked for the same budget. Empty without emitters.
    /// `scene` must be what the upload was made from (its emissive textures are sampled).
    pub fn emitter_lights(&self, scene: &Scene, budget: usize) -> std::sync::Arc<emitters::EmitterClusters> {
        let mut cached = self.emitter_lights.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((b, lights)) = cached.as_ref().filter(|(b, _)| *b == budget) {
            debug_assert_eq!(*b, budget);
            return lights.clone();
        }
        // Off the emitting surface by a millionth of the scene, so the light's cube of views
        // does not meet its own triangles edge-on at the very apex.
        let lights = std::sync::Arc::new(emitters::emitter_lights(&self.emitter_triangles, &scene.textures, budget, self.anchor, 1e-6 * self.extent));
        *cached = Some((budget, lights.clone()));
        lights
    }

    pub fn bvh(&self, gpu: &Gpu, scene: &Scene) -> Result<(std::sync::Arc<GpuBvh>, bool)> {
        let mut cached = self.bvh.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(b) = cached.as_ref() {
            return Ok((b.clone(), false));
        }
        let triangles = bvh::scene_triangles(scene, self.anchor);
        if triangles.len() != self.triangle_count as usize {
            return Err(Error::invalid("scene", format!(
                "the BVH has {} triangles but the uploaded scene {}", triangles.len(), self.triangle_count
            )));
        }
        let started = std::time::Instant::now();
        let built = bvh::Bvh::build(&triangles);
        let id_bytes = built.triangle_id_bytes();
        // The frame that builds it says what it cost (CPU wall time, all threads of the build)
        // and how large it is per triangle (nodes and leaf-ordered triangle ids; the corners it
        // reads are the raster vertices the upload holds anyway).
        let build_ms = started.elapsed().as_secs_f64() * 1e3;
        let bytes = (id_bytes.len() + built.node_bytes().len()) as f64;
        crate::gpu::frame_log::note_setting("bvh_build_ms", build_ms.into());
        crate::gpu::frame_log::note_setting("bvh_bytes_per_triangle", (bytes / triangles.len().max(1) as f64).into());
        let max = gpu.limits.max_storage_buffer_binding_size as u64;
        // Nodes and corners are bound in pages (gpu::buffers::storage_pages), the ids whole.
        let paged = storage_pages_capacity(max);
        let (node_bytes, corner_bytes) = (built.node_bytes().len() as u64, self.raster_vertices.size());
        if id_bytes.len() as u64 > max || node_bytes > paged || corner_bytes > paged {
            return Err(Error::invalid("scene", format!(
                "{} triangles exceed this adapter's storage binding limits for the ray tracer: BVH nodes {node_bytes} bytes and triangle corners {corner_bytes} (each at most {paged}), triangle ids {} (at most {max})",
                triangles.len(),
                id_bytes.len()
            )));
        }
        let make = |label: &str, bytes: &[u8]| {
            gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents: bytes, usage: wgpu::BufferUsages::STORAGE })
        };
        let gpu_bvh = std::sync::Arc::new(GpuBvh {
            nodes: make("bvh_node_buffer", built.node_bytes()),
            triangle_ids: make("bvh_triangle_id_buffer", &id_bytes),
            node_count: built.nodes.len(),
            depth: built.depth,
        });
        *cached = Some(gpu_bvh.clone());
        Ok((gpu_bvh, true))
    }

    /// `count` points spread over the uploaded triangles by area (`points::surface_points`),
    /// relative to [`Self::anchor`], generated now unless an earlier frame of this upload asked
    /// for the same count (then `false`).
    pub fn surface_points(&self, gpu: &Gpu, scene: &Scene, count: u32) -> Result<(std::sync::Arc<GpuPoints>, bool)> {
        let mut cached = self.surface_points.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = cached.as_ref().filter(|p| p.asked == count) {
            return Ok((p.clone(), false));
        }
        let triangles = bvh::scene_triangles(scene, self.anchor);
        let rows = points::surface_points(&triangles, count);
        let bytes: &[u8] = bytemuck::cast_slice(&rows);
        if bytes.len() as u64 > gpu.limits.max_storage_buffer_binding_size as u64 {
            return Err(Error::invalid("ism_points", format!(
                "{count} points ({} bytes) exceed this adapter's storage binding limit of {} bytes", bytes.len(), gpu.limits.max_storage_buffer_binding_size
            )));
        }
        let points = std::sync::Arc::new(GpuPoints {
            buffer: storage(gpu, "scene_surface_point_buffer", bytes, wgpu::BufferUsages::empty()),
            count: rows.len() as u32,
            asked: count,
        });
        *cached = Some(points.clone());
        Ok((points, true))
    }


    pub fn upload(gpu: &Gpu, scene: &Scene) -> Result<Self> {
        let bounds = scene.bounds();
        let anchor = if bounds.is_empty() { DVec3::ZERO } else { bounds.center() };
        let mut raster = Vec::new();
        let mut verts = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut tri_mat: Vec<u32> = Vec::new();
        for (ni, node) in scene.nodes.iter().enumerate() {
            let Some(mi) = node.mesh else { continue };
            let Some(mesh) = scene.meshes.get(mi) else { continue };
            let world = scene.world_transform(ni);
            // Normals transform by the inverse transpose; a mirroring transform flips winding,
            // which does not matter because all surfaces are shaded double-sided.
            let normal_m = DMat3::from_mat4(world).inverse().transpose();
            let lin = DMat3::from_mat4(world);
            for prim in &mesh.primitives {
                let base = verts.len() as u32;
                for (k, p) in prim.positions.iter().enumerate() {
                    let wp = world.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)) - anchor;
                    let n = prim.normals.get(k).copied().unwrap_or([0.0, 1.0, 0.0]);
                    let wn = (normal_m * DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64)).normalize_or_zero();
                    let t = prim.tangents.get(k).copied().unwrap_or([1.0, 0.0, 0.0, 1.0]);
                    let wt = (lin * DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64)).normalize_or_zero();
                    verts.push(VertexRaw {
                        position: wp.as_vec3().to_array(),
                        _pad0: 0.0,
                        normal: wn.as_vec3().to_array(),
                        _pad1: 0.0,
                        tangent: [wt.x as f32, wt.y as f32, wt.z as f32, t[3]],
                        uv: prim.uvs.get(k).copied().unwrap_or([0.0, 0.0]),
                        _pad2: [0.0; 2],
                    });
                }
                for tri in prim.indices.chunks_exact(3) {
                    let t = tri_mat.len() as u32;
                    for &i in tri {
                        let v = verts.get((base + i) as usize).ok_or_else(|| {
                            Error::invalid("scene", format!("mesh {:?}: index {i} out of range", mesh.name))
                        })?;
                        raster.push(RasterVertex { position: v.position, triangle: t });
                        indices.push(base + i);
                    }
                    tri_mat.push(prim.material as u32);
                }
            }
        }
        let mut materials: Vec<MaterialRaw> = Vec::new();
        // Texture layers: one array per colour space, in first-use order.
        let mut color_layers: Vec<usize> = Vec::new();
        let mut data_layers: Vec<usize> = Vec::new();
        let mut layer = |tex: Option<usize>, want: TextureUsage| -> i32 {
            let Some(t) = tex else { return -1 };
            if t >= scene.textures.len() {
                return -1;
            }
            // The array a texture goes to follows its role in the material, so an image used
            // both as colour and as data gets one layer in each.
            let list = if want == TextureUsage::Color { &mut color_layers } else { &mut data_layers };
            match list.iter().position(|&x| x == t) {
                Some(i) => i as i32,
                None => {
                    list.push(t);
                    (list.len() - 1) as i32
                }
            }
        };
        for m in &scene.materials {
            materials.push(MaterialRaw {
                base_color: m.base_color_factor,
                metallic: m.metallic_factor.clamp(0.0, 1.0),
                roughness: m.roughness_factor.clamp(0.0, 1.0),
                normal_scale: m.normal_scale,
                specular_factor: m.specular_factor.clamp(0.0, 1.0),
                base_color_layer: layer(m.base_color_texture, TextureUsage::Color),
                metallic_roughness_layer: layer(m.metallic_roughness_texture, TextureUsage::Data),
                normal_layer: layer(m.normal_texture, TextureUsage::Data),
                emissive_layer: layer(m.emissive_texture, TextureUsage::Color),
                emissive: m.emissive,
                _pad1: 0.0,
                base_color_uv: uv_rows(&m.base_color_uv),
                metallic_roughness_uv: uv_rows(&m.metallic_roughness_uv),
                normal_uv: uv_rows(&m.normal_uv),
                emissive_uv: uv_rows(&m.emissive_uv),
            });
        }
        let max_side = color_layers
            .iter()
            .chain(&data_layers)
            .filter_map(|&t| scene.textures.get(t))
            .map(|t| t.width.max(t.height))
            .max()
            .unwrap_or(1);
        let layer_size = max_side.next_power_of_two().min(TEXTURE_LAYER_MAX).min(gpu.limits.max_texture_dimension_2d);
        let color_textures = texture_array(gpu, scene, &color_layers, layer_size, true, "scene_color_texture_array")?;
        let data_textures = texture_array(gpu, scene, &data_layers, layer_size, false, "scene_data_texture_array")?;

        let bytes = |n: usize, each: usize| (n * each) as u64;
        let max = gpu.limits.max_storage_buffer_binding_size as u64;
        // Vertices are bound in pages (gpu::buffers::storage_pages); indices and per-triangle
        // materials in one binding each.
        let vertex_capacity = storage_pages_capacity(max);
        let largest = [bytes(verts.len(), 64), bytes(raster.len(), 16)].into_iter().max().unwrap_or(0);
        if bytes(verts.len(), 64) > vertex_capacity || bytes(indices.len(), 4) > max || largest > gpu.limits.max_buffer_size {
            return Err(Error::invalid("scene", format!(
                "{} vertices and {} triangles exceed this adapter's buffer limits: vertices take {} bytes (at most {vertex_capacity}: {STORAGE_PAGES} bindings of {STORAGE_PAGE_BYTES} bytes where a binding holds {max}), indices {} (at most {max}, one binding), the largest buffer {largest} (at most {})",
                verts.len(),
                tri_mat.len(),
                bytes(verts.len(), 64),
                bytes(indices.len(), 4),
                gpu.limits.max_buffer_size
            )));
        }
        let extent = bounds.diagonal();
        // What the upload costs per triangle in geometry (raster vertices, shading vertices,
        // indices, per-triangle materials; textures apart), for the frame that uploads it.
        let geometry = bytes(raster.len(), 16) + bytes(verts.len(), 64) + bytes(indices.len(), 4) + bytes(tri_mat.len(), 4);
        crate::gpu::frame_log::note_setting("scene_bytes_per_triangle", (geometry as f64 / tri_mat.len().max(1) as f64).into());
        let emitter_table = emitters::emitter_table(&verts, &indices, &tri_mat, &scene.materials);
        Ok(Self {
            emitters: storage(gpu, "scene_emitter_buffer", bytemuck::cast_slice(&emitter_table.rows), wgpu::BufferUsages::empty()),
            emitter_count: emitter_table.rows.len() as u32,
            emitter_power: emitter_table.total_power,
            emitters_face_nothing: !bounds.is_empty()
                && emitters::face_nothing(&emitter_table.triangles, 0.5 * (bounds.max - bounds.min), 1e-6 * extent.max(f64::MIN_POSITIVE)),
            emitter_triangles: emitter_table.triangles,
            emitter_lights: Default::default(),
            anchor,
            half_size: if bounds.is_empty() { DVec3::NAN } else { 0.5 * (bounds.max - bounds.min) },
            raster_vertex_count: raster.len() as u32,
            raster_vertices: gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene_raster_vertex_buffer"),
                contents: if raster.is_empty() { &[0u8; 16] } else { bytemuck::cast_slice(&raster) },
                // STORAGE: the ray tracers read triangles' corners from it (upload/bvh.rs).
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            }),
            vertices: storage(gpu, "scene_vertex_buffer", bytemuck::cast_slice(&verts), wgpu::BufferUsages::empty()),
            indices: storage(gpu, "scene_index_buffer", bytemuck::cast_slice(&indices), wgpu::BufferUsages::empty()),
            triangle_materials: storage(gpu, "scene_triangle_material_buffer", bytemuck::cast_slice(&tri_mat), wgpu::BufferUsages::empty()),
            materials: storage(gpu, "scene_material_buffer", bytemuck::cast_slice(&materials), wgpu::BufferUsages::empty()),
            color_textures,
            data_textures,
            texture_layer_size: layer_size,
            triangle_count: tri_mat.len() as u32,
            extent: if extent.is_finite() && extent > 0.0 { extent } else { 1.0 },
            bvh: Default::default(),
            convex_shell: Default::default(),
            surface_points: Default::default(),
        })
    }
}

/// Resamples the listed textures into one mipmapped 2D array (mips by CPU box filtering).
fn texture_array(gpu: &Gpu, scene: &Scene, list: &[usize], size: u32, srgb: bool, label: &str) -> Result<wgpu::TextureView> {
    let layers = list.len().max(1) as u32;
    if layers > gpu.limits.max_texture_array_layers {
        return Err(Error::invalid("scene", format!(
            "{layers} textures exceed this adapter's limit of {} array layers", gpu.limits.max_texture_array_layers
        )));
    }
    let size = if list.is_empty() { 1 } else { size };
    let mips = 32 - size.leading_zeros();
    let format = if srgb { wgpu::TextureFormat::Rgba8UnormSrgb } else { wgpu::TextureFormat::Rgba8Unorm };
    let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: layers },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (layer, &t) in list.iter().enumerate() {
        let Some(src) = scene.textures.get(t) else { continue };
        let Some(img) = image::RgbaImage::from_raw(src.width, src.height, src.rgba8.clone()) else {
            return Err(Error::invalid("scene", format!("texture {:?}: pixel data does not match its size", src.name)));
        };
        let mut level = image::imageops::resize(&img, size, size, image::imageops::FilterType::Triangle);
        for mip in 0..mips {
            let s = (size >> mip).max(1);
            if mip > 0 {
                level = image::imageops::resize(&level, s, s, image::imageops::FilterType::Triangle);
            }
            gpu.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &tex,
                    mip_level: mip,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: layer as u32 },
                    aspect: wgpu::TextureAspect::All,
                },
                level.as_raw(),
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * s), rows_per_image: Some(s) },
                wgpu::Extent3d { width: s, height: s, depth_or_array_layers: 1 },
            );
        }
    }
    if list.is_empty() {
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo { texture: &tex, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect: wgpu::TextureAspect::All },
            &[255, 255, 255, 255],
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4), rows_per_image: Some(1) },
            wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
        );
    }
    Ok(tex.create_view(&wgpu::TextureViewDescriptor {
        label: Some(label),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    }))
}
