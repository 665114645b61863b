//! `method="direct"`: direct light only (the frame's shadow-mapped direct pass), no indirect.

use super::{options::common, DirectLight, FrameContext, Method, MethodInfo, OptionSpec, Options};
use crate::error::Result;
use crate::gpu::Gpu;

pub const INFO: MethodInfo = MethodInfo {
    name: "direct",
    summary: "direct light only (shadow-mapped), no indirect light",
    options: OPTIONS,
    direct_light: DirectLight::ShadowMapped,
    indirect: false,
    extra_aovs: &[],
    configure: |o| Ok(Box::new(Direct { options: o.clone() })),
};

const OPTIONS: &[OptionSpec] = &[common::SHADOW_SIZE];

struct Direct {
    options: Options,
}

impl Method for Direct {
    fn record(&self, ctx: &mut FrameContext<'_>) -> Result<()> {
        ctx.skip("indirect", "method=\"direct\" computes direct light only");
        Ok(())
    }

    fn settings(&self, _gpu: &Gpu) -> Result<Vec<(String, String)>> {
        Ok(self.options.rows())
    }
}
