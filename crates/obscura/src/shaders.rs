//! WGSL sources and how they are composed. WGSL has no `#include`: a pass is the binding names of
//! [`crate::bindings`], then the shared helpers it needs (`shaders/common/`), then its axis files
//! joined in one string (module-scope declarations may come in any order). Estimators keep their
//! own WGSL in their module (`src/estimators/`). `wesl` was evaluated
//! instead and not adopted; docs/ARCHITECTURE.md says why.

pub const VIEW: &str = include_str!("../shaders/common/view.wgsl");
pub const BASIS: &str = include_str!("../shaders/common/basis.wgsl");
pub const PATTERN: &str = include_str!("../shaders/common/pattern.wgsl");
pub const MATERIAL: &str = include_str!("../shaders/common/material.wgsl");
pub const BVH: &str = include_str!("../shaders/common/bvh.wgsl");
pub const HASH: &str = include_str!("../shaders/common/hash.wgsl");
pub const HEMISPHERE: &str = include_str!("../shaders/common/hemisphere.wgsl");
pub const VISIBILITY_VARIANCE: &str = include_str!("../shaders/common/visibility_variance.wgsl");
pub const VERTEX_NORMAL: &str = include_str!("../shaders/common/vertex_normal.wgsl");

pub const FRAME: &str = include_str!("../shaders/frame/frame.wgsl");
pub const FRAME_POINT: &str = include_str!("../shaders/frame/point.wgsl");
pub const BENT: &str = include_str!("../shaders/common/bent.wgsl");

pub const SOURCE_FIRST_LAYER: &str = include_str!("../shaders/sources/first_layer.wgsl");
pub const SOURCE_DUAL_DEPTH: &str = include_str!("../shaders/sources/dual_depth.wgsl");
pub const SOURCE_RAY_CAMERA: &str = include_str!("../shaders/sources/ray_camera.wgsl");
pub const SOURCE_SCREEN_RAYS: &str = include_str!("../shaders/sources/screen_rays.wgsl");
pub const SCREEN_RAYS_FIRST: &str = include_str!("../shaders/sources/screen_rays_first.wgsl");
pub const SCREEN_RAYS_DUAL: &str = include_str!("../shaders/sources/screen_rays_dual.wgsl");
pub const SCREEN_RAYS_STOCHASTIC: &str =
    include_str!("../shaders/sources/screen_rays_stochastic.wgsl");
pub const SOURCE_BVH_RAYS: &str = include_str!("../shaders/sources/bvh_rays.wgsl");
pub const SOURCE_BVH_RAYS_PROOF: &str = include_str!("../shaders/sources/bvh_rays_proof.wgsl");
pub const SOURCE_BVH_RAYS_NO_PROOF: &str =
    include_str!("../shaders/sources/bvh_rays_no_proof.wgsl");
pub const SOURCE_COLUMN_TRACE: &str = include_str!("../shaders/sources/column_trace.wgsl");
pub const SOURCE_COLUMN_RAYS: &str = include_str!("../shaders/sources/column_rays.wgsl");
pub const SOURCE_DEPTH_PYRAMID: &str = include_str!("../shaders/sources/depth_pyramid.wgsl");
pub const DEPTH_PYRAMID_BUILD: &str = include_str!("../shaders/sources/depth_pyramid/build.wgsl");
pub const SOURCE_ALL_LAYERS: &str = include_str!("../shaders/sources/all_layers.wgsl");
pub const SOURCE_STOCHASTIC_DEPTH: &str =
    include_str!("../shaders/sources/stochastic_depth/read.wgsl");
pub const STOCHASTIC_DEPTH_SAMPLES: &str =
    include_str!("../shaders/sources/stochastic_depth/samples.wgsl");
pub const RAY_SD_COLLECT: &str =
    include_str!("../shaders/sources/ray_stochastic_depth/collect.wgsl");
pub const RAY_SD_COLLECT_ALL: &str =
    include_str!("../shaders/sources/ray_stochastic_depth/collect_all.wgsl");
pub const RAY_SD_COLLECT_REQUESTED: &str =
    include_str!("../shaders/sources/ray_stochastic_depth/collect_requested.wgsl");
pub const RAY_SD_REQUEST: &str =
    include_str!("../shaders/sources/ray_stochastic_depth/request.wgsl");
pub const STOCHASTIC_DEPTH_REQUEST: &str =
    include_str!("../shaders/sources/stochastic_depth/request.wgsl");
pub const STOCHASTIC_DEPTH_MAP: &str = include_str!("../shaders/sources/stochastic_depth/map.wgsl");
pub const STOCHASTIC_DEPTH_COMPUTE_RASTER: &str =
    include_str!("../shaders/sources/stochastic_depth/compute_raster.wgsl");
pub const STOCHASTIC_DEPTH_RESET: &str =
    include_str!("../shaders/sources/stochastic_depth/reset.wgsl");

pub const SCHEDULE_SINGLE: &str = include_str!("../shaders/schedules/single.wgsl");
pub const SCHEDULE_SINGLE_MAIN: &str = include_str!("../shaders/schedules/single_main.wgsl");
pub const SCHEDULE_INTERLEAVED: &str = include_str!("../shaders/schedules/interleaved.wgsl");
pub const SCHEDULE_INTERLEAVED_SPLIT: &str =
    include_str!("../shaders/schedules/interleaved_split.wgsl");
pub const SCHEDULE_TWO_PHASE: &str = include_str!("../shaders/schedules/two_phase.wgsl");
pub const SCHEDULE_TWO_PHASE_1: &str = include_str!("../shaders/schedules/two_phase_1.wgsl");
pub const SCHEDULE_TWO_PHASE_2: &str = include_str!("../shaders/schedules/two_phase_2.wgsl");
pub const MULTIVIEW_POINT: &str = include_str!("../shaders/schedules/multiview/point.wgsl");
pub const MULTIVIEW_LOOKUP: &str = include_str!("../shaders/schedules/multiview/lookup.wgsl");
pub const MULTIVIEW_MAIN: &str = include_str!("../shaders/schedules/multiview/main.wgsl");
pub const SCHEDULE_TWO_PHASE_INDIRECT: &str =
    include_str!("../shaders/schedules/two_phase_indirect.wgsl");
pub const SCHEDULE_WORK_LIST: &str = include_str!("../shaders/schedules/work_list.wgsl");

pub const GBUFFER: &str = include_str!("../shaders/raster/gbuffer.wgsl");
pub const TRIANGLE_CULL: &str = include_str!("../shaders/raster/triangle_cull.wgsl");
pub const OCCLUSION_PYRAMID_LAYOUT: &str = include_str!("../shaders/common/occlusion_pyramid.wgsl");
pub const OCCLUSION_PYRAMID: &str = include_str!("../shaders/raster/occlusion_pyramid.wgsl");
pub const GBUFFER_RESOLVE: &str = include_str!("../shaders/raster/gbuffer_resolve.wgsl");
pub const GBUFFER_RESOLVE_MAIN: &str = include_str!("../shaders/raster/gbuffer_resolve_main.wgsl");
pub const VISIBILITY_TARGET_LOAD: &str =
    include_str!("../shaders/raster/visibility_target_load.wgsl");
pub const VISIBILITY_WORDS_LOAD: &str =
    include_str!("../shaders/raster/visibility_words_load.wgsl");
pub const VISIBILITY_WORDS_STORE: &str =
    include_str!("../shaders/raster/visibility_words_store.wgsl");
pub const VISIBILITY_WORDS_INDEX: &str =
    include_str!("../shaders/raster/visibility_words_index.wgsl");
pub const GBUFFER_VISIBILITY_ATOMIC: &str =
    include_str!("../shaders/raster/gbuffer_visibility_atomic.wgsl");
pub const DEPTH_PEEL: &str = include_str!("../shaders/raster/depth_peel.wgsl");
pub const DEPTH_PEEL_RESOLVE: &str = include_str!("../shaders/raster/depth_peel_resolve.wgsl");
pub const ATROUS: &str = include_str!("../shaders/filter/atrous.wgsl");
pub const BILATERAL_BLUR: &str = include_str!("../shaders/filter/bilateral_blur.wgsl");
pub const RAY_BUDGET: &str = include_str!("../shaders/filter/ray_budget.wgsl");
pub const TEMPORAL_ACCUMULATION: &str =
    include_str!("../shaders/filter/temporal_accumulation.wgsl");
pub const HALF_DOWNSAMPLE: &str = include_str!("../shaders/filter/half_resolution/downsample.wgsl");
pub const HALF_UPSAMPLE: &str = include_str!("../shaders/filter/half_resolution/upsample.wgsl");
pub const RAY_QUERY: &str = include_str!("../shaders/bvh/ray_query.wgsl");
pub const REFERENCE: &str = include_str!("../shaders/reference/reference.wgsl");
pub const ENGINE_LINEAR_DEPTH: &str = include_str!("../shaders/engine_input/linear_depth.wgsl");
pub const ENGINE_DEPTH: &str = include_str!("../shaders/engine_input/depth.wgsl");
pub const ENGINE_NORMALS: &str = include_str!("../shaders/engine_input/normals.wgsl");

/// A pass's source with the shared helpers it names in front (raster and utility passes, which
/// use no binding names).
pub fn with_common(common: &[&str], pass: &str) -> String {
    let mut source = common.join("\n");
    source.push('\n');
    source.push_str(pass);
    source
}

/// An AO pass: the binding names, then `parts` in order.
pub fn compose(parts: &[&str]) -> String {
    let mut source = crate::bindings::wgsl_constants();
    for part in parts {
        source.push_str(part);
        source.push('\n');
    }
    source
}
