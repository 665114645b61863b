// vsgl:include-only — the including shader includes common/frame.wgsl (VertexRaw) and declares
//   the scene's vertices as four storage arrays of VertexRaw, vertices, vertices_1, vertices_2
//   and vertices_3: the pages of one buffer (STORAGE_PAGE_BYTES = 2^27 bytes each,
//   crates/vsgl-core/src/gpu/buffers.rs), so a scene may hold more vertices than one binding
//   does (2^21 of 64 bytes). Pages past the scene's end bind the first again; without
//   STORAGE_PAGED (common/storage_pages.wgsl) every index is in page 0.
#include "common/storage_pages.wgsl"

const VERTEX_PAGE_SHIFT: u32 = 21u;

// Vertex i of the scene (the numbering of `indices`).
fn scene_vertex(i: u32) -> VertexRaw {
    if (!STORAGE_PAGED || i < (1u << VERTEX_PAGE_SHIFT)) {
        return vertices[i];
    }
    let j = i & ((1u << VERTEX_PAGE_SHIFT) - 1u);
    switch (i >> VERTEX_PAGE_SHIFT) {
        case 1u: {
            return vertices_1[j];
        }
        case 2u: {
            return vertices_2[j];
        }
        default: {
            return vertices_3[j];
        }
    }
}
