//! `method="direct"`: direct light only (the frame's shadow-mapped direct pass), no indirect.

use super::{options::common, DirectLight, FrameContext, Method, MethodInfo};
use crate::error::Result;

pub const INFO: MethodInfo = MethodInfo {
    name: "direct",
    summary: "direct light only (shadow-mapped), no indirect light",
    option_groups: &[&[common::SHADOW_SIZE, common::EMITTER_LIGHTS]],
    direct_light: DirectLight::ShadowMapped,
    indirect: false,
    extra_aovs: &[],
    ground_truth: false,
    area_emitters: false,
    configure: |_| Ok(Box::new(Direct)),
};

/// The frame's shadow-mapped direct pass is all of it (`shadow_size` is the frame script's).
struct Direct;

impl Method for Direct {
    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        ctx.skip("indirect", "method=\"direct\" computes direct light only");
        Ok(())
    }
}
