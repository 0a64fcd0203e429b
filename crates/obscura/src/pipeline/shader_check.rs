//! Every technique row's AO pipelines composed and validated without a GPU (naga), as vello's
//! build step checks its shader permutations: a broken combination of estimator, source and
//! schedule fails here even if no lavapipe test renders it. Each resource a shader declares must
//! be in the explicit layout the pipeline is built with, with the same kind of binding, and every
//! pipeline constant must exist.
//!
//! Also a stub estimator (`STUB`, this file only) run through every source and schedule: the
//! contracts accept a new estimator with no edit to sources or schedules.

use crate::bindings::{self, entry, GROUP_ESTIMATOR, GROUP_FRAME, GROUP_SCHEDULE, GROUP_SOURCE};
use crate::schedules::{self, SourceGroup};
use crate::sources::{self, stochastic_depth::SdLayout};
use crate::technique::{Schedule, Source, TABLE};

/// A minimal estimator implementing the contract: eight samples on a ring of 2 px, each
/// occluded (value 0) when its depth is nearer than the pixel's. Not a technique; it only shows
/// what a new estimator has to provide.
const STUB: &str = r#"
struct StubParams { radius_px: f32, _pad0: f32, _pad1: f32, _pad2: f32 }
@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: StubParams;
override SAMPLE_COUNT: u32 = 8u;
struct EstimatorPixel { pixel: vec2<u32>, depth: f32, valid: bool }
struct EstimatorSample { px: vec2<f32>, on: bool }
alias EstimatorValue = f32;
struct EstimatorAccum { open: f32, count: f32, _pad: f32 }
struct Occluder { value: f32, hidden: bool }
fn estimator_pixel(id: vec2<u32>) -> EstimatorPixel {
    let pixel = id + vec2<u32>(view.guard_band);
    let z = textureLoad(depth_tex, pixel, 0).r;
    return EstimatorPixel(pixel, z, !is_background(z));
}
fn estimator_pixel_valid(p: EstimatorPixel) -> bool { return p.valid; }
fn estimator_shading_pixel(p: EstimatorPixel) -> vec2<u32> { return p.pixel; }
fn estimator_sample(p: EstimatorPixel, i: u32) -> EstimatorSample {
    let a = 6.2831853 * f32(i) / f32(SAMPLE_COUNT);
    return EstimatorSample(vec2<f32>(p.pixel) + 0.5 + params.radius_px * vec2<f32>(cos(a), sin(a)), true);
}
fn estimator_sample_active(s: EstimatorSample) -> bool { return s.on; }
fn estimator_sample_px(p: EstimatorPixel, s: EstimatorSample) -> vec2<f32> { return s.px; }
fn estimator_unoccluded(p: EstimatorPixel, s: EstimatorSample) -> f32 { return 1.0; }
fn estimator_occluder(p: EstimatorPixel, s: EstimatorSample, pos: vec3<f32>) -> Occluder {
    let occluded = -pos.z < p.depth;
    return Occluder(select(1.0, 0.0, occluded), occluded);
}
fn estimator_occluder_at(p: EstimatorPixel, s: EstimatorSample, px: vec2<f32>, z: f32) -> Occluder {
    return estimator_occluder(p, s, pixel_to_view(view, px, z));
}
fn estimator_combine(a: f32, b: f32) -> f32 { return min(a, b); }
fn estimator_compensate(p: EstimatorPixel, s: EstimatorSample, v: f32, factor: f32) -> f32 { return v; }
fn estimator_bent_sample(p: EstimatorPixel, s: EstimatorSample, v: f32) -> vec3<f32> { return vec3<f32>(0.0); }
fn estimator_depth_interval(p: EstimatorPixel, s: EstimatorSample, px: vec2<f32>) -> vec2<f32> { return vec2<f32>(0.0, 3.0e38); }
fn estimator_bent_normal(p: EstimatorPixel, acc: EstimatorAccum, v: vec3<f32>, o: vec3<f32>) -> vec3<f32> { return vec3<f32>(0.0); }
fn estimator_accum_init() -> EstimatorAccum { return EstimatorAccum(0.0, 0.0, 0.0); }
fn estimator_accum_sample(acc: EstimatorAccum, s: EstimatorSample) -> EstimatorAccum {
    return EstimatorAccum(acc.open, acc.count + 1.0, 0.0);
}
fn estimator_accum_value(acc: EstimatorAccum, s: EstimatorSample, value: f32) -> EstimatorAccum {
    return EstimatorAccum(acc.open + value, acc.count, 0.0);
}
fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 { return select(1.0, acc.open / acc.count, acc.count > 0.0); }
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 { return acc.count; }
"#;

/// Parse and validate `source`; then hold every global its entry point uses to `layouts` (per
/// group) and check `constants` are overrides of the module.
fn check(
    label: &str,
    source: &str,
    layouts: &[(u32, Vec<wgpu::BindGroupLayoutEntry>)],
    constants: &[&str],
) {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
    assert_eq!(module.entry_points.len(), 1, "{label}: one entry point");
    let used = info.get_entry_point(0);
    for (handle, global) in module.global_variables.iter() {
        // Only what the entry point uses must be bound (as wgpu requires).
        let Some(binding) = global.binding.as_ref().filter(|_| !used[handle].is_empty()) else {
            continue;
        };
        let name = global.name.as_deref().unwrap_or("?");
        let entry = layouts
            .iter()
            .filter(|(group, _)| *group == binding.group)
            .flat_map(|(_, entries)| entries)
            .find(|e| e.binding == binding.binding)
            .unwrap_or_else(|| {
                panic!(
                    "{label}: `{name}` at group {} binding {} is in no layout",
                    binding.group, binding.binding
                )
            });
        let kind_matches = match (global.space, entry.ty) {
            (naga::AddressSpace::Uniform, wgpu::BindingType::Buffer { ty, .. }) => {
                ty == wgpu::BufferBindingType::Uniform
            }
            (
                naga::AddressSpace::Storage { access },
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only },
                    ..
                },
            ) => read_only != access.contains(naga::StorageAccess::STORE),
            (
                naga::AddressSpace::Handle,
                wgpu::BindingType::Texture { .. } | wgpu::BindingType::StorageTexture { .. },
            ) => true,
            _ => false,
        };
        assert!(
            kind_matches,
            "{label}: `{name}` ({:?}) does not match its layout entry {:?}",
            global.space, entry.ty
        );
    }
    // The two-phase schedule stores the estimator's state as three 32-bit words after the mask
    // (16-byte records, `PIXEL_BYTES` in src/schedules/two_phase.rs).
    // Single-pass estimators may keep more (HBAO's and GTAO's running horizons).
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("type layouts");
    let two_phase = module
        .types
        .iter()
        .any(|(_, ty)| ty.name.as_deref() == Some("TwoPhasePixel"));
    for (handle, ty) in module.types.iter() {
        match ty.name.as_deref() {
            Some("EstimatorAccum") if two_phase => {
                assert_eq!(
                    layouter[handle].size, 12,
                    "{label}: EstimatorAccum is three words"
                )
            }
            Some("TwoPhasePixel") => {
                assert_eq!(
                    layouter[handle].size, 16,
                    "{label}: TwoPhasePixel is 16 bytes"
                )
            }
            _ => {}
        }
    }
    for constant in constants {
        assert!(
            module
                .overrides
                .iter()
                .any(|(_, o)| o.name.as_deref() == Some(constant)),
            "{label}: no override `{constant}`"
        );
    }
}

fn frame_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        entry::uniform(bindings::FRAME_VIEW),
        entry::texture(bindings::FRAME_DEPTH),
        entry::texture(bindings::FRAME_NORMALS),
        entry::storage_texture_r32f(bindings::FRAME_AO_OUT),
        entry::storage_texture_rgba16f(bindings::FRAME_BENT_OUT),
        entry::texture_uint(bindings::FRAME_RAY_GRANT),
    ]
}

/// The stochastic depth layouts to compose a source with (one dummy for the other sources).
fn sd_layouts(source: Source) -> Vec<SdLayout> {
    let all: &[u32] = if source.needs().stochastic_depth_map {
        &crate::settings::SD_SAMPLE_COUNTS
    } else {
        &[1]
    };
    all.iter().filter_map(|&s| SdLayout::plan(s)).collect()
}

/// One pipeline of a schedule, composed and checked against the layouts it is built with.
fn check_stage(
    label: &str,
    (estimator, constants): (&str, &[&str]),
    estimator_entries: &[wgpu::BindGroupLayoutEntry],
    source: Source,
    sd: SdLayout,
    stage: schedules::Stage,
) {
    let wgsl = schedules::compose(
        estimator,
        &stage.source_wgsl(sources::wgsl(
            source,
            sd,
            sources::ray_stochastic_depth::RayMapLayout {
                divisor: 4,
                guard: 32,
            },
            stage.source_group,
        )),
        &stage.parts,
    );
    let source_entries = match stage.source_group {
        SourceGroup::Resolve => sources::resolve_entries(source),
        SourceGroup::Request => sources::request_entries(source),
    };
    let mut all_constants = constants.to_vec();
    all_constants.extend(stage.constants.iter().map(|(n, _)| *n));
    // The radius cap (EstimatorPass::for_row) goes to every stage an estimator is in.
    all_constants.push("MAX_RADIUS_PX");
    check(
        &format!("{label} / {source:?} ({sd:?}) / {}", stage.label),
        &wgsl,
        &[
            (GROUP_FRAME, frame_entries()),
            (GROUP_ESTIMATOR, estimator_entries.to_vec()),
            (GROUP_SOURCE, source_entries),
            (GROUP_SCHEDULE, stage.schedule_entries),
        ],
        &all_constants,
    );
}

/// Every pipeline of `estimator` × `source` × every schedule that can run it (the two-phase ones
/// only an order-independent estimator over a source that serves no levels).
fn check_all_schedules(
    label: &str,
    estimator: (&str, &[&str]),
    estimator_entries: &[wgpu::BindGroupLayoutEntry],
    source: Source,
    order_independent: bool,
) {
    for sd in sd_layouts(source) {
        for schedule in [
            Schedule::Single,
            Schedule::TwoPhase,
            Schedule::TwoPhaseDense,
            Schedule::Interleaved,
        ] {
            if (schedule.two_phase() && !order_independent) || !schedule.supports_source(source) {
                continue;
            }
            for stage in schedules::stages(schedule) {
                check_stage(label, estimator, estimator_entries, source, sd, stage);
            }
        }
    }
}

/// An estimator's WGSL and the names of its pipeline constants.
fn wgsl(estimator: crate::technique::Estimator) -> (&'static str, &'static [&'static str]) {
    let module = estimator.caps().module;
    (module.wgsl, module.constants)
}

#[test]
fn every_row_composes_and_validates() {
    for row in TABLE {
        for sd in sd_layouts(row.source) {
            for stage in schedules::stages(row.schedule) {
                let estimator = wgsl(row.estimator);
                let entries = crate::estimators::layout_entries(row.estimator.caps().module);
                check_stage(row.name, estimator, &entries, row.source, sd, stage);
            }
        }
    }
    let (indirect, entries) = schedules::two_phase::indirect_stage();
    check("two-phase indirect", &indirect, &[(0, entries)], &[]);
}

#[test]
fn every_estimator_runs_over_every_source_it_supports() {
    let mut pairs = 0;
    for estimator in TABLE.iter().map(|r| r.estimator) {
        for source in Source::all().filter(|s| s.supports(estimator)) {
            check_all_schedules(
                estimator.name(),
                wgsl(estimator),
                &crate::estimators::layout_entries(estimator.caps().module),
                source,
                estimator.order_independent(),
            );
            pairs += 1;
        }
    }
    println!("{pairs} (estimator, source) pairs checked, an estimator once per row");
}

#[test]
fn a_new_estimator_needs_no_source_or_schedule_edit() {
    // Every source that answers for any estimator reading the depth layers: not those that read
    // one estimator's own model (column rays, the hemisphere's rays) nor the pyramid's levels.
    let open = Source::all().filter(|s| s.caps().only_for.is_none() && !s.caps().serves_levels);
    let mut sources = 0;
    for source in open {
        sources += 1;
        let entries = [entry::uniform(bindings::ESTIMATOR_PARAMS)];
        check_all_schedules(
            "stub estimator",
            (STUB, &["SAMPLE_COUNT"]),
            &entries,
            source,
            true,
        );
    }
    println!("the stub over {sources} sources");
}

#[test]
fn a_broken_combination_fails_the_check() {
    // The check itself can fail: a source without the contract's functions, and a shader whose
    // binding is not in its layout.
    let estimator = crate::estimators::vao::MODULE.wgsl;
    let stage = schedules::single::stage();
    let missing = schedules::compose(estimator, "", &stage.parts);
    assert!(std::panic::catch_unwind(|| check("missing source", &missing, &[], &[])).is_err());
    let wgsl = schedules::compose(estimator, crate::shaders::SOURCE_FIRST_LAYER, &stage.parts);
    let no_frame = std::panic::catch_unwind(|| {
        check(
            "no frame layout",
            &wgsl,
            &[(GROUP_ESTIMATOR, vec![entry::uniform(0)])],
            &[],
        )
    });
    assert!(no_frame.is_err());
}
