// Leave-out switches (override constants) that the frame's pass plan sets
// (crates/vsgl-core/src/plan.rs; docs/frames.md, "Pass plan"). Each defaults to the full
// computation; `false` compiles the work out where the scene provably does not need it, so
// the image is unchanged beyond float rounding.

// HAS_SPECULAR = false: no material reflects specularly (metallic = 0 and a zero
// KHR_materials_specular factor everywhere, so R_s = 0): no specular flux, no specular lobes,
// no GGX / SG–ASG evaluation, and the indirect_specular targets are not allocated.
override HAS_SPECULAR: bool = true;
