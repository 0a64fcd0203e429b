//! Hidden-depth sources: where a kernel looks when the first depth layer says a sample is
//! occluded (DESIGN.md data flow). A kernel consults its source only for such samples.
//!
//! In WGSL a source is one file of `shaders/hidden/` defining `sample_free_length` for the VAO
//! kernel. There are four so far: the first depth layer only, dual depth by depth peeling (seed
//! 000 §2.1), direct ray tracing of the sample columns (seed 000 §3.6) and the rasterised
//! stochastic depth map (seed 001 §3.1, seed 000 §3.7/3.9). Still to come: the ray-traced
//! stochastic depth map (seed 002 §3.1–3.5).

/// Which hidden-depth source a technique uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HiddenDepth {
    /// Only the first depth layer: occluded samples use the thickness/halo model alone
    /// (`shaders/hidden/depth_buffer.wgsl`).
    #[default]
    None,
    /// Occluded samples also read a second depth layer from depth peeling
    /// (`shaders/hidden/dual_depth.wgsl`, seed 000 §2.1).
    DualDepth,
    /// Occluded (and off-screen) samples trace their camera ray through the scene's BVH
    /// (`shaders/hidden/column_rays.wgsl`, seed 000 §3.6).
    ColumnRays,
    /// Occluded samples also read every sample of the stratified stochastic depth map at the
    /// sample's pixel (`shaders/hidden/stochastic_depth.wgsl`, seed 000 §3.7, seed 001 §3.1).
    StochasticDepth,
}

impl crate::settings::Technique {
    /// The hidden-depth source this technique consults.
    pub fn hidden_depth(self) -> HiddenDepth {
        match self {
            crate::settings::Technique::Vao => HiddenDepth::None,
            crate::settings::Technique::VaoDual => HiddenDepth::DualDepth,
            crate::settings::Technique::RtVao
            | crate::settings::Technique::RtSvao
            | crate::settings::Technique::RtSvaoDense => HiddenDepth::ColumnRays,
            crate::settings::Technique::SdVao | crate::settings::Technique::SdSvao => {
                HiddenDepth::StochasticDepth
            }
        }
    }
}
