// vsgl:include-only — storage arrays that may outgrow one binding (the scene's vertices, the
// BVH's nodes and triangle corners: common/scene_vertices.wgsl, common/bvh.wgsl) are bound as
// four pages of one buffer, STORAGE_PAGE_BYTES = 2^27 bytes each
// (crates/vsgl-core/src/gpu/buffers.rs). STORAGE_PAGED is set only where one of them spans more
// than a page: without it every read is of page 0, with no test of the index. (A page test in
// every BVH node and corner read made lavapipe's traversal 1.7–2× slower even when every index
// was in page 0.)
override STORAGE_PAGED: bool = false;
