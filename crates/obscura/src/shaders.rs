//! WGSL sources. Shared helpers live once in `shaders/common/` and are prepended to the passes
//! that use them (WGSL has no `#include`; a prefix keeps line numbers of the pass readable).

pub const VIEW: &str = include_str!("../shaders/common/view.wgsl");
pub const BASIS: &str = include_str!("../shaders/common/basis.wgsl");
pub const MATERIAL: &str = include_str!("../shaders/common/material.wgsl");
pub const BVH: &str = include_str!("../shaders/common/bvh.wgsl");
pub const HASH: &str = include_str!("../shaders/common/hash.wgsl");

pub const GBUFFER: &str = include_str!("../shaders/gbuffer.wgsl");
pub const VAO: &str = include_str!("../shaders/vao.wgsl");
pub const VAO_SINGLE: &str = include_str!("../shaders/vao_single.wgsl");
pub const SVAO: &str = include_str!("../shaders/svao.wgsl");
pub const SVAO_PHASE1: &str = include_str!("../shaders/svao_phase1.wgsl");
pub const SVAO_PHASE2: &str = include_str!("../shaders/svao_phase2.wgsl");
pub const SVAO_INDIRECT: &str = include_str!("../shaders/svao_indirect.wgsl");
pub const HIDDEN_DEPTH_BUFFER: &str = include_str!("../shaders/hidden/depth_buffer.wgsl");
pub const HIDDEN_DUAL_DEPTH: &str = include_str!("../shaders/hidden/dual_depth.wgsl");
pub const DEPTH_PEEL: &str = include_str!("../shaders/depth_peel.wgsl");
pub const HIDDEN_COLUMN_RAYS: &str = include_str!("../shaders/hidden/column_rays.wgsl");
pub const HIDDEN_STOCHASTIC_DEPTH: &str = include_str!("../shaders/hidden/stochastic_depth.wgsl");
pub const STOCHASTIC_DEPTH: &str = include_str!("../shaders/stochastic_depth.wgsl");
pub const SD_RESET: &str = include_str!("../shaders/sd_reset.wgsl");
pub const SD_UNPACK: &str = include_str!("../shaders/sd_unpack.wgsl");
pub const BILATERAL_BLUR: &str = include_str!("../shaders/bilateral_blur.wgsl");
pub const RAY_QUERY: &str = include_str!("../shaders/ray_query.wgsl");
pub const REFERENCE: &str = include_str!("../shaders/reference.wgsl");

/// A pass's source with the shared helpers it names in front.
pub fn with_common(common: &[&str], pass: &str) -> String {
    let mut source = common.join("\n");
    source.push('\n');
    source.push_str(pass);
    source
}
