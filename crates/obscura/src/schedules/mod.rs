//! Schedules: which passes run an estimator over a hidden-depth source (the third axis of the
//! technique table). They own the sample loops (`shaders/schedules/`), for any estimator and
//! source that implement their contracts, and decide when the source prepares its data.

pub mod interleaved;
pub mod multiview;
pub mod single;
pub mod two_phase;

use crate::bindings::{self, GROUP_ESTIMATOR, GROUP_FRAME, GROUP_SCHEDULE, GROUP_SOURCE};
use crate::error::Error;
use crate::estimators::EstimatorPass;
use crate::frame::FrameInputs;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::sources::SourcePass;
use crate::technique::{Schedule, TechniqueRow};
use crate::view::ScreenGeometry;

pub(crate) use crate::sources::SourceGroup;

/// One compute pipeline of a schedule.
pub(crate) struct Stage {
    pub label: &'static str,
    /// The schedule's WGSL files, after frame, estimator and source.
    pub parts: Vec<&'static str>,
    pub source_group: SourceGroup,
    /// Group-3 layout entries (none: the stage binds no group 3).
    pub schedule_entries: Vec<wgpu::BindGroupLayoutEntry>,
    /// The stage's parts hold the source functions themselves (the interleaved schedule's
    /// first-layer lookup): the row's source WGSL is left out.
    pub own_source: bool,
    pub constants: Vec<(&'static str, f64)>,
    /// The most samples for which the stage's sample loop is written out sample by sample
    /// ([`write_out_sample_loop`]; 0: never), where the row allows it ([`writes_out_sample_loops`]).
    pub written_out_up_to: u32,
}

impl Stage {
    /// The source WGSL this stage is composed with: `source`, unless its parts hold their own.
    pub fn source_wgsl(&self, source: String) -> String {
        if self.own_source {
            String::new()
        } else {
            source
        }
    }
}

/// The AO pipelines of a schedule, in the order they run.
pub(crate) fn stages(schedule: Schedule) -> Vec<Stage> {
    match schedule {
        Schedule::Single => vec![single::stage()],
        Schedule::TwoPhase => two_phase::stages(true),
        Schedule::TwoPhaseDense => two_phase::stages(false),
        Schedule::Interleaved => vec![interleaved::stage()],
        // The camera's pass; the second view's pipeline is the schedule's own (multiview.rs).
        Schedule::Multiview => vec![single::stage()],
    }
}

/// What every estimator is composed after: the shared helpers it may call and the frame.
pub(crate) const ESTIMATOR_PRELUDE: [&str; 6] = [
    shaders::VIEW,
    shaders::BASIS,
    shaders::PATTERN,
    shaders::BENT,
    shaders::FRAME,
    shaders::FRAME_POINT,
];

/// The whole WGSL of an AO pipeline: binding names, shared helpers, frame, estimator, source,
/// schedule.
pub(crate) fn compose(estimator: &str, source: &str, schedule: &[&str]) -> String {
    let mut parts = ESTIMATOR_PRELUDE.to_vec();
    parts.extend([estimator, source]);
    parts.extend_from_slice(schedule);
    shaders::compose(&parts)
}

/// A stage's pipeline over the estimator and source it runs.
pub(crate) fn pipeline(
    device: &wgpu::Device,
    stage: &Stage,
    frame_layout: &wgpu::BindGroupLayout,
    estimator: &EstimatorPass,
    source: &SourcePass,
    schedule_layout: Option<&wgpu::BindGroupLayout>,
) -> wgpu::ComputePipeline {
    let source_layout = match stage.source_group {
        SourceGroup::Resolve => source.resolve_layout(),
        SourceGroup::Request => source.request_layout(),
    };
    let mut layouts = vec![
        (GROUP_FRAME, frame_layout),
        (GROUP_ESTIMATOR, &estimator.layout),
    ];
    layouts.extend(source_layout.map(|l| (GROUP_SOURCE, l)));
    layouts.extend(schedule_layout.map(|l| (GROUP_SCHEDULE, l)));
    let mut constants = estimator.constants.clone();
    constants.extend_from_slice(source.constants());
    constants.extend_from_slice(&stage.constants);
    let wgsl = write_out_sample_loop(
        &compose(
            estimator.wgsl,
            &stage.source_wgsl(source.wgsl(stage.source_group)),
            &stage.parts,
        ),
        &constants,
        stage.written_out_up_to,
    );
    bindings::compute_pipeline(
        device,
        stage.label,
        &wgsl,
        &constants,
        &bindings::by_group(&layouts),
    )
}

/// The sample loops of `wgsl` written out as one call per sample, for the SAMPLE_COUNT in
/// `constants` up to `up_to`: single.wgsl's and phase 1's (two_phase_1.wgsl), each a `for` over
/// `i` whose body is one call `NAME(p, i, …);` ([`SAMPLE_LOOP_HEAD`]). The driver unrolls WGSL's
/// loops as it sees fit, and NVIDIA's left the single pass's a loop for GTAO at any settings,
/// GTAO-VB with bent normals or at `high`, HBAO, HBAO+ and SSAO (their binary sizes:
/// tools/pipeline-stats). Written out, each sample's kernel entry, slice and direction are
/// constants and what a slice or a direction shares is made once: on an H100 (BENCHMARKS.md,
/// 2026-12-05) `gtao` 18 % faster (21 % at `high`), `hbao` 12 %, `gtao-vb` with bent normals 9 %
/// and at `high` 16 %, `gtao-vb-dual` 10 %; rows the driver had unrolled already within ±1.4 %.
/// Only NVIDIA's driver has timed it; a GPU with a smaller instruction cache may prefer loops.
fn write_out_sample_loop(wgsl: &str, constants: &[(&str, f64)], up_to: u32) -> String {
    let count = constants
        .iter()
        .find(|(name, _)| *name == "SAMPLE_COUNT")
        .map_or(0, |&(_, n)| n as u32);
    if count == 0 || count > up_to {
        return wgsl.to_owned();
    }
    let mut out = String::with_capacity(wgsl.len() + 2048);
    let mut rest = wgsl;
    while let Some(at) = rest.find(SAMPLE_LOOP_HEAD) {
        let after = &rest[at + SAMPLE_LOOP_HEAD.len()..];
        let body_end = after.find('\n').map_or(after.len(), |e| e + 1);
        let (body, tail) = after.split_at(body_end);
        let Some(tail) = tail.strip_prefix(SAMPLE_LOOP_TAIL) else {
            break;
        };
        out.push_str(&rest[..at]);
        for i in 0..count {
            out.push_str(&body.replacen("(p, i, ", &format!("(p, {i}u, "), 1));
        }
        rest = tail;
    }
    out.push_str(rest);
    out
}

/// How single.wgsl's and two_phase_1.wgsl's sample loops begin and end: [`write_out_sample_loop`]
/// finds them by this text (the tests check that it does).
const SAMPLE_LOOP_HEAD: &str = "    for (var i = 0u; i < SAMPLE_COUNT; i++) {\n";
const SAMPLE_LOOP_TAIL: &str = "    }\n";

/// What a schedule records one frame with: the device, the frame's inputs and group 0, and the
/// row's estimator and source.
#[derive(Clone, Copy)]
pub(crate) struct FrameContext<'a> {
    pub device: &'a wgpu::Device,
    pub frame: &'a FrameInputs<'a>,
    pub frame_group: &'a wgpu::BindGroup,
    /// The AO image and the bent normals `frame_group` writes (schedules that make their own
    /// group 0, as the multi-view one, bind them again).
    pub output: &'a wgpu::TextureView,
    pub bent: &'a wgpu::TextureView,
    /// The rays per pixel of a ray budget `frame_group` reads (a 1×1 stand-in without one).
    pub ray_grant: &'a wgpu::TextureView,
    pub estimator: &'a EstimatorPass,
    pub source: &'a SourcePass,
    /// The depth buffer `frame`'s first layer was rasterised into, where the caller drew the
    /// frame itself at this size ([`crate::Renderer`]); engines' frames have none.
    pub gbuffer_z: Option<&'a wgpu::Texture>,
    /// The triangle each pixel of `frame` shows + 1 (`R32Uint`, 0 = none), where the caller drew
    /// the frame itself at this size ([`crate::raster::gbuffer::GBuffer::visible_triangles`]).
    pub visible_triangles: Option<&'a wgpu::Texture>,
}

/// The groups every AO pass of a frame binds: frame, estimator, and the source's.
pub(crate) struct FrameGroups<'a> {
    pub frame: &'a wgpu::BindGroup,
    pub estimator: &'a wgpu::BindGroup,
    pub resolve: Option<&'a wgpu::BindGroup>,
    pub request: Option<&'a wgpu::BindGroup>,
}

impl FrameGroups<'_> {
    /// Sets groups 0–2 of a pass of `source_group`'s kind.
    pub fn set(&self, pass: &mut wgpu::ComputePass, source_group: SourceGroup) {
        pass.set_bind_group(GROUP_FRAME, self.frame, &[]);
        pass.set_bind_group(GROUP_ESTIMATOR, self.estimator, &[]);
        let source = match source_group {
            SourceGroup::Resolve => self.resolve,
            SourceGroup::Request => self.request,
        };
        if let Some(group) = source {
            pass.set_bind_group(GROUP_SOURCE, group, &[]);
        }
    }
}

/// What the single-pass and interleaved passes write per pixel besides (or instead of) the AO.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PixelOutputs {
    /// The estimator's debug image instead of its AO (pipeline constant `ESTIMATOR_DEBUG`).
    pub estimator_debug: bool,
    /// The bent normal next to the AO (`BENT_NORMALS`; single pass only).
    pub bent_normals: bool,
}

/// What a schedule beyond the row's estimator and source may need: the GPU, the settings, and
/// the scene's triangles (the multi-view schedule rasterises a second map from them).
pub(crate) struct ScheduleInputs<'a> {
    pub gpu: &'a crate::gpu::Gpu,
    pub settings: &'a crate::settings::AoSettings,
    pub scene: Option<&'a crate::raster::gpu_scene::GpuScene>,
}

/// Whether the single pass of `row` resolves its flagged samples after the others
/// (single.wgsl's DEFERRED_RESOLVE; measured in BENCHMARKS.md, "Flagged samples resolved last").
fn deferred_resolve(row: &TechniqueRow) -> bool {
    row.schedule.runs_single_pass()
        && row.estimator.defers_resolves()
        && row.source.costly_resolve()
}

#[cfg(test)]
thread_local! {
    /// Tests: `Some(false)` keeps every sample loop a loop.
    static WRITTEN_OUT: std::cell::Cell<Option<bool>> = const { std::cell::Cell::new(None) };
}

/// Whether `row`'s passes may have their sample loops written out ([`write_out_sample_loop`],
/// up to each stage's `written_out_up_to`): phase 1 of the two-phase schedules (first-layer
/// lookups only) always; the single pass where its loop body holds no costly resolve. A body
/// that resolves a stochastic depth map inline written out 8 to 32 times made those passes
/// slower on an H100 (`sd-hbao+` 27 %, `sd-gtao-vb` 55 %, `sd-hbao` 6.9 times: the code
/// outgrew the instruction cache), and with their resolves deferred to be written out they
/// were still 8–16 % slower than with the loop (BENCHMARKS.md), so they keep it; rows that defer
/// their resolves anyway (DEFERRED_RESOLVE: VAO and SSAO over the maps and column rays) resolve
/// after the written-out samples.
fn writes_out_sample_loops(row: &TechniqueRow) -> bool {
    #[cfg(test)]
    if WRITTEN_OUT.with(|u| u.get()) == Some(false) {
        return false;
    }
    match row.schedule {
        Schedule::Single | Schedule::Multiview => {
            !row.source.costly_resolve() || deferred_resolve(row)
        }
        Schedule::TwoPhase | Schedule::TwoPhaseDense => true,
        Schedule::Interleaved => false,
    }
}

#[cfg(test)]
thread_local! {
    /// Tests: `Some(true)` resolves each distinct depth once (`SD_DISTINCT`) for every row over
    /// the raster map, whatever the estimator; `Some(false)` for none, and no row stops at a
    /// settled depth (`SD_SETTLED_STOPS`).
    static DISTINCT_DEPTHS: std::cell::Cell<Option<bool>> = const { std::cell::Cell::new(None) };
}

/// Whether `row`'s samples that read the raster stochastic depth map make a value of each
/// distinct depth once (samples.wgsl's `SD_DISTINCT`, [`crate::technique::Estimator::resolves_distinct_depths`]).
fn distinct_depths(row: &TechniqueRow) -> bool {
    #[cfg(test)]
    if let Some(on) = DISTINCT_DEPTHS.with(|d| d.get()) {
        return row.needs().stochastic_depth_map && on;
    }
    row.needs().stochastic_depth_map && row.estimator.resolves_distinct_depths()
}

/// Whether `row`'s samples that read a map's depths nearest first stop at the first depth
/// behind which nothing can change their value (samples.wgsl's `SD_SETTLED_STOPS`,
/// [`crate::technique::Estimator::exact_hidden`]).
fn settled_stops(row: &TechniqueRow) -> bool {
    #[cfg(test)]
    if DISTINCT_DEPTHS.with(|d| d.get()) == Some(false) {
        return false;
    }
    row.source.maps_hidden_depth() && row.estimator.exact_hidden()
}

/// A schedule as an [`crate::AmbientOcclusion`] holds it.
pub(crate) enum SchedulePass {
    Single(single::Single),
    TwoPhase(two_phase::TwoPhase),
    Interleaved(interleaved::Interleaved),
    Multiview(Box<multiview::Multiview>),
}

impl SchedulePass {
    /// The passes of `row`'s schedule, writing `outputs` per pixel.
    pub fn new(
        row: &TechniqueRow,
        frame_layout: &wgpu::BindGroupLayout,
        estimator: &EstimatorPass,
        source: &SourcePass,
        screen: &ScreenGeometry,
        outputs: PixelOutputs,
        inputs: &ScheduleInputs,
    ) -> Result<Self, Error> {
        let device = &inputs.gpu.device;
        let (schedule, name) = (row.schedule, row.name);
        let mut stages = stages(schedule);
        for stage in &mut stages {
            if screen.orthographic {
                stage.constants.push(("ORTHOGRAPHIC", 1.0));
            }
            if outputs.estimator_debug {
                stage.constants.push(("ESTIMATOR_DEBUG", 1.0));
            }
            if outputs.bent_normals {
                stage.constants.push(("BENT_NORMALS", 1.0));
            }
            if row.estimator.late_first_layer_load(outputs.bent_normals) {
                stage.constants.push(("FIRST_LAYER_LOAD_LATE", 1.0));
            }
            if deferred_resolve(row) {
                stage.constants.push(("DEFERRED_RESOLVE", 1.0));
            }
            if distinct_depths(row) {
                stage.constants.push(("SD_DISTINCT", 1.0));
            }
            if settled_stops(row) {
                stage.constants.push(("SD_SETTLED_STOPS", 1.0));
            }
            if !writes_out_sample_loops(row) {
                stage.written_out_up_to = 0;
            }
        }
        Ok(match schedule {
            Schedule::Single => SchedulePass::Single(single::Single::new(
                device,
                name,
                &stages,
                frame_layout,
                estimator,
                source,
            )),
            Schedule::Interleaved => SchedulePass::Interleaved(interleaved::Interleaved::new(
                device,
                name,
                &stages,
                frame_layout,
                estimator,
                source,
                screen,
            )),
            Schedule::TwoPhase | Schedule::TwoPhaseDense => {
                SchedulePass::TwoPhase(two_phase::TwoPhase::new(
                    device,
                    schedule == Schedule::TwoPhase,
                    &stages,
                    frame_layout,
                    estimator,
                    source,
                    screen,
                )?)
            }
            Schedule::Multiview => {
                let scene = inputs.scene.ok_or_else(|| {
                    Error::Input(format!(
                        "technique '{name}' rasterises a second stochastic depth map: pass the \
                         scene's triangles (SceneResources::scene)"
                    ))
                })?;
                SchedulePass::Multiview(Box::new(multiview::Multiview::new(
                    inputs.gpu,
                    inputs.settings,
                    screen,
                    scene,
                    frame_layout,
                    estimator,
                    source,
                    &stages,
                    name,
                    outputs.estimator_debug,
                )?))
            }
        })
    }

    /// Records the AO passes into the frame's output, with the source prepared where the
    /// schedule needs it.
    pub fn encode(
        &self,
        ctx: &FrameContext,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        match self {
            SchedulePass::Single(s) => s.encode(ctx, encoder, profiler),
            SchedulePass::TwoPhase(s) => s.encode(ctx, encoder, profiler),
            SchedulePass::Interleaved(s) => s.encode(ctx, encoder, profiler),
            SchedulePass::Multiview(s) => s.encode(ctx, encoder, profiler),
        }
    }

    /// The camera of the coming frame (the multi-view schedule places its second view by it).
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &crate::view::FrameView) {
        if let SchedulePass::Multiview(m) = self {
            m.set_camera(queue, view);
        }
    }

    /// Two-phase: phase 1's per-pixel records (16 bytes each, the sample bit mask first).
    pub fn phase1_records(&self) -> Option<&wgpu::Buffer> {
        match self {
            SchedulePass::Single(_) | SchedulePass::Interleaved(_) | SchedulePass::Multiview(_) => {
                None
            }
            SchedulePass::TwoPhase(s) => Some(s.records()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{DISTINCT_DEPTHS, WRITTEN_OUT};
    use crate::pipeline::renderer::Renderer;
    use crate::raster::test_support::gpu;
    use crate::scene;
    use crate::settings::AoSettings;
    use crate::settings::{Preset, SdSelection};
    use crate::technique::Technique;

    /// Resolving each distinct depth of a map pixel once, nearest first, gives the same AO as
    /// resolving every stored sample in turn, for every estimator over the raster map (each
    /// combine keeps one of its arguments; GTAO-VB also stops at the first depth whose `hidden`
    /// is false, which holds its flag exact) and for the two-phase schedule, at
    /// S = 2 (which keeps the loop over the samples) and 4 and with missing-occlusion
    /// compensation; the `nearest` map, sorted by construction, with and without GTAO-VB's stop;
    /// and the maps hold a depth twice in many pixels, so the copies were there to skip.
    #[test]
    fn distinct_depths_change_no_pixel() {
        let gpu = gpu();
        let mut pixels_with_copies = 0;
        for name in ["stairs", "grass", "layers"] {
            let scene = scene::builtin(name).unwrap();
            let camera = scene.cameras[0].camera;
            for technique in [
                Technique::SdVao,
                Technique::SdSvao,
                Technique::SdGtaoVb,
                Technique::SdHbao,
                Technique::SdHbaoPlus,
                Technique::SdSsao,
            ] {
                for (samples, compensation, selection) in [
                    (4, 1.0, SdSelection::Stochastic),
                    (2, 1.0, SdSelection::Stochastic),
                    (4, 2.0, SdSelection::Stochastic),
                    (4, 1.0, SdSelection::Nearest),
                ] {
                    let mut settings = AoSettings::preset(technique, Preset::Medium);
                    settings.stochastic_depth.samples = samples;
                    settings.stochastic_depth.compensation = compensation;
                    settings.stochastic_depth.selection = selection;
                    let render = |on: bool| {
                        DISTINCT_DEPTHS.with(|d| d.set(Some(on)));
                        let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 8).unwrap();
                        r.render(&camera, None).unwrap();
                        DISTINCT_DEPTHS.with(|d| d.set(None));
                        (
                            r.read_ao().unwrap(),
                            r.read_stochastic_depth().unwrap().unwrap(),
                        )
                    };
                    let (each, map) = render(false);
                    let (distinct, _) = render(true);
                    let what = format!(
                        "{name} {technique} S = {samples}, compensation {compensation}, {selection:?}"
                    );
                    assert!(each == distinct, "{what}: distinct depths changed the AO");
                    pixels_with_copies += (0..map[0].len())
                        .filter(|&p| {
                            (0..map.len()).any(|a| {
                                (a + 1..map.len())
                                    .any(|b| map[a][p] > 0.0 && map[a][p] == map[b][p])
                            })
                        })
                        .count();
                }
            }
        }
        assert!(
            pixels_with_copies > 1000,
            "only {pixels_with_copies} map pixels hold a depth twice"
        );
    }

    /// single.wgsl and two_phase_1.wgsl hold the loops that write_out_sample_loop writes out
    /// (else nothing would be), and nothing else changes.
    #[test]
    fn the_sample_loops_are_found_and_written_out() {
        for (wgsl, call) in [
            (
                crate::shaders::SCHEDULE_SINGLE,
                "single_pass_sample(p, {}u, &r, &flagged);",
            ),
            (
                crate::shaders::SCHEDULE_TWO_PHASE_1,
                "phase_1_sample(p, {}u, &acc, &mask);",
            ),
        ] {
            let out = super::write_out_sample_loop(wgsl, &[("SAMPLE_COUNT", 3.0)], 3);
            assert_eq!(
                super::write_out_sample_loop(wgsl, &[("SAMPLE_COUNT", 3.0)], 2),
                wgsl
            );
            assert!(!out.contains(super::SAMPLE_LOOP_HEAD));
            for i in 0..4 {
                let written = out.contains(&call.replace("{}", &i.to_string()));
                assert_eq!(written, i < 3, "{call} for sample {i}");
            }
            // The loop's head, body and tail (3 lines) became three calls.
            assert_eq!(out.lines().count(), wgsl.lines().count(), "{call}");
        }
    }

    /// The single pass's sample loop written out sample by sample computes what the loop does,
    /// pixel for pixel, AO and bent normals alike, on every row that writes it out: the first
    /// layer, the second layer, a map with deferred resolves, the multi-view pass, at the
    /// presets' sample counts (8 to 32).
    #[test]
    fn the_written_out_sample_loop_changes_no_pixel() {
        let gpu = gpu();
        let scene = scene::builtin("stairs").unwrap();
        let camera = scene.cameras[0].camera;
        let mut written_out = 0;
        for technique in Technique::all() {
            let row = technique.row();
            if !super::writes_out_sample_loops(row) {
                continue;
            }
            written_out += 1;
            for preset in [Preset::Low, Preset::Medium, Preset::High] {
                let mut settings = AoSettings::preset(technique, preset);
                settings.bent_normals =
                    row.estimator.bent_normals() && row.schedule == super::Schedule::Single;
                let render = |written_out: bool| {
                    WRITTEN_OUT.with(|u| u.set(Some(written_out)));
                    let mut r = Renderer::new(&gpu, &scene, &settings, 64, 48, 8).unwrap();
                    r.render(&camera, None).unwrap();
                    WRITTEN_OUT.with(|u| u.set(None));
                    (r.read_ao().unwrap(), r.read_bent_normals().unwrap())
                };
                let (looped, written) = (render(false), render(true));
                assert!(
                    looped == written,
                    "{technique} at {preset:?}: the written-out loop changed the image"
                );
            }
        }
        assert!(
            written_out >= 8,
            "only {written_out} rows write their loop out"
        );
    }
}
