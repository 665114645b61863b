//! The strings of every choice option, each beside the enum it parses into
//! ([`ChoiceEnum`](super::options::ChoiceEnum)). The GPU-side enums live with their passes; the
//! options that select between code paths of a method, or that carry settings of their own,
//! get a tag enum here.

use crate::choice_names;
use crate::frame::uniforms::RsmFit;
use crate::passes::kmeans_centres::KmeansSpace;
use crate::passes::pathtrace::Strategy;
use crate::passes::vpl_sample::Sampling;
use crate::passes::vsgl2_reduce::Vsgl2Reduction;
use crate::passes::vsgl_gen::{Kernel, KernelFilter};
use crate::passes::vsgl_shading::{DiffuseMode, LambertLobe, LightingMode};

use super::metropolis::ChainSpace;

choice_names!(KernelFilter { Nodes => "nodes", Trilinear => "trilinear" });
choice_names!(Sampling { Stratified => "stratified", Random => "random", Metropolis => "metropolis" });
choice_names!(ChainSpace { World => "world", Rsm => "rsm" });
choice_names!(RsmFit { Scene => "scene", Cone => "cone" });
choice_names!(DiffuseMode { Papers => "papers", Accurate => "accurate", SgProduct => "sg_product" });
choice_names!(LambertLobe { ExactCompact => "exact_compact", Hemisphere => "hemisphere", Papers => "papers" });
choice_names!(LightingMode { Asg => "asg", Accurate => "accurate", Blend => "blend" });
choice_names!(Vsgl2Reduction { Auto => "auto", Subgroup => "subgroup", SharedMemory => "shared_memory" });
choice_names!(Strategy { Camera => "camera", Bidirectional => "bidirectional", Light => "light" });

choice_names!(
    /// `kernel=` (vsgl): a kernel rule of the filtered importance sampling, or k-means
    /// clustering in RSM texel coordinates or world positions.
    pub enum VsglKernel { Integral => "integral", Density => "density", Node => "node", Kmeans2d => "kmeans2d", Kmeans3d => "kmeans3d" }
);

impl VsglKernel {
    /// The sampled kernel rule, or none for k-means.
    pub fn sampled(self) -> Option<Kernel> {
        match self {
            VsglKernel::Integral => Some(Kernel::Integral),
            VsglKernel::Density => Some(Kernel::Density),
            VsglKernel::Node => Some(Kernel::Node),
            VsglKernel::Kmeans2d | VsglKernel::Kmeans3d => None,
        }
    }

    /// k-means' clustering space, or none for a sampled kernel.
    pub fn kmeans(self) -> Option<KmeansSpace> {
        match self {
            VsglKernel::Kmeans2d => Some(KmeansSpace::Texels),
            VsglKernel::Kmeans3d => Some(KmeansSpace::World),
            VsglKernel::Integral | VsglKernel::Density | VsglKernel::Node => None,
        }
    }
}

choice_names!(
    /// `visibility=`; the ISM settings are read with it (`VisibilityMode::from_options`).
    pub enum VisibilityChoice { None => "none", Ism => "ism", Raytrace => "raytrace" }
);
choice_names!(
    /// `importance=`; brsm's settings are read with it (`Importance::from_options`).
    pub enum ImportanceChoice { Rsm => "rsm", Brsm => "brsm" }
);
choice_names!(
    /// `denoise_form=`.
    pub enum DenoiseForm { Gather => "gather", Exchange => "exchange" }
);
choice_names!(
    /// `shadow_target=` (vsgl).
    pub enum ShadowTarget { Resampled => "resampled", Centre => "centre" }
);
choice_names!(
    /// `near_field=` (vsgl).
    pub enum NearField { Texels => "texels", Sg => "sg" }
);

#[cfg(test)]
mod tests {
    use super::super::options::ChoiceEnum;
    use super::*;

    fn round_trips<T: ChoiceEnum + std::fmt::Debug>() {
        assert_eq!(T::NAMES.len(), T::VALUES.len());
        for (name, value) in T::NAMES.iter().zip(T::VALUES) {
            assert_eq!(value.name(), *name);
            assert_eq!(T::from_name(name), Some(*value));
        }
        assert_eq!(T::from_name("no_such_choice"), None);
    }

    /// Every method configures with every value of each of its choice options: an option
    /// declared with a list its enum does not have would fail here with the error of
    /// `Options::choice` ("must be one of"). Some values need another option too (a papers'
    /// diffuse form needs lighting="asg"): those errors name that need, never the choice list.
    #[test]
    fn every_method_configures_with_every_value_of_its_choice_options() {
        use super::super::options::{OptionKind, OptionValue};
        use super::super::REGISTRY;
        let mut checked = 0;
        for method in REGISTRY {
            for spec in method.options() {
                let OptionKind::Choice(values) = spec.kind else { continue };
                for value in values {
                    let given = vec![(spec.name.to_string(), OptionValue::from(value.to_string()))];
                    let mut options = method.parse_options(&given).unwrap_or_else(|e| panic!("{} {}={value:?}: {e}", method.name, spec.name));
                    if let Err(e) = (method.configure)(&mut options) {
                        let text = e.to_string();
                        assert!(!text.contains("must be one of"), "{} {}={value:?}: {text}", method.name, spec.name);
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked >= 40, "only {checked} choice values checked");
    }

    /// Every name parses to its variant and back, and an unknown string to nothing.
    #[test]
    fn every_choice_round_trips() {
        round_trips::<VsglKernel>();
        round_trips::<KernelFilter>();
        round_trips::<Sampling>();
        round_trips::<ChainSpace>();
        round_trips::<RsmFit>();
        round_trips::<DiffuseMode>();
        round_trips::<LambertLobe>();
        round_trips::<LightingMode>();
        round_trips::<Vsgl2Reduction>();
        round_trips::<Strategy>();
        round_trips::<VisibilityChoice>();
        round_trips::<ImportanceChoice>();
        round_trips::<DenoiseForm>();
        round_trips::<ShadowTarget>();
        round_trips::<NearField>();
    }
}
