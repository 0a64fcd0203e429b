//! Hidden-depth sources: where a kernel looks when the first depth layer says a sample is
//! occluded (DESIGN.md data flow). A kernel consults its source only for such samples.
//!
//! The spine ships the trivial source; the later ones plug in here with their own module each:
//! dual depth by depth peeling (seed 000 §2.1), the rasterised stochastic depth map (seed 001 §3.1,
//! seed 000 §3.7/3.9), the ray-traced stochastic depth map (seed 002 §3.1–3.5) and direct ray
//! tracing of the sample columns (seed 000 §3.6/3.8).

/// Which hidden-depth source a technique uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HiddenDepth {
    /// Only the first depth layer: occluded samples use the thickness/halo model alone.
    #[default]
    None,
}

impl crate::settings::Technique {
    /// The hidden-depth source this technique consults.
    pub fn hidden_depth(self) -> HiddenDepth {
        match self {
            crate::settings::Technique::Vao => HiddenDepth::None,
        }
    }
}
