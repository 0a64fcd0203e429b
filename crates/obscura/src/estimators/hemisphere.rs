//! The hemisphere estimator (`shaders/estimators/hemisphere.wgsl`): cosine-weighted rays within
//! the world radius R from each visible pixel, the model of `reference --model hemisphere` and of
//! offline renderers' AO, with the ground truth's rays (`shaders/common/hemisphere.wgsl`). Its
//! sources answer whether a ray is blocked: marched in screen space over the first depth layer
//! with a thickness (`screen rays`), or traced through the scene's BVH (`bvh rays`, `rtao`).
//! Each frame of temporal accumulation draws a new set of rays, so the accumulated image
//! converges to the ground truth.

use crate::knob::{Kind, Knob, Widget};
use serde::{Deserialize, Serialize};

/// Hemisphere AO parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HemisphereSettings {
    /// Radius R in world units: surfaces farther along a ray do not occlude it.
    pub radius: f32,
    /// Rays per pixel each frame, 1 to 32 (one bit each in the two-phase mask).
    pub rays: u32,
    /// Weight a blocked ray by W(t) = max(0, 1 − t/R) rather than 1 (the ground truth's
    /// `--falloff`).
    pub falloff: bool,
    /// Screen rays: points tested along each ray.
    pub steps: u32,
    /// Phase 1 of two-phase BVH rays (`rtao-two-phase`): the longest image on screen, in
    /// pixels, of a ray phase 1 walks to prove it free or blocked; a longer one goes to the BVH
    /// unwalked.
    pub proof_pixels: u32,
    /// Screen rays: the thickness assumed behind every depth sample, world units (a ray point
    /// farther behind the first surface than this passes behind it).
    pub thickness: f32,
    /// Rays a frame at most, given to the pixels whose accumulated AO is least certain (no
    /// history first, then the largest variance); 0: every pixel casts `rays` rays. Needs
    /// temporal accumulation (a pixel without rays keeps its history).
    pub ray_budget: u32,
    /// GPU milliseconds a frame after the G-buffer: the frame loops (`view`, `path`, `bench`'s
    /// warm-up, `compare`) set the ray budget each frame from the last frame's GPU timings
    /// (`TimeBudget`, filter/ray_budget.rs); 0: off. Needs temporal accumulation and timestamp queries.
    pub time_budget: f32,
}

impl Default for HemisphereSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            // One ray a frame: `rtao` with it met both of docs/lab's targets on an H100 at
            // Sponza 1080p (one frame MAE 0.031 at 0.90 ms after the G-buffer; 0.017 after 16
            // still frames), where 4 rays took 3.1 ms (docs/lab/2026-12-06-hemisphere.md).
            rays: 1,
            falloff: false,
            steps: 8,
            proof_pixels: 256,
            // GTAO-VB's and VAO's default thickness, the same physical assumption.
            thickness: 0.25,
            ray_budget: 0,
            time_budget: 0.0,
        }
    }
}

impl HemisphereSettings {
    /// Every field's knob: range, unit, flag, help, widget (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new(
            "hemisphere.radius",
            "--hemisphere-radius",
            "Hemisphere AO radius R in world units: farther surfaces do not occlude.",
            Kind::POSITIVE,
        )
        .length()
        .doc("radius R: a ray is blocked by surfaces within R of the shading point")
        .widget(Widget::RADIUS),
        Knob::new(
            "hemisphere.rays",
            "--hemisphere-rays",
            "Hemisphere rays per pixel each frame.",
            Kind::int(1, 32),
        )
        .note("one bit per ray")
        .doc("cosine-weighted rays per pixel each frame (a new set every frame with --temporal)")
        .widget(Widget::Range),
        Knob::new(
            "hemisphere.falloff",
            "--hemisphere-falloff",
            "Weight a ray blocked at distance t by 1 - t/R (reference --falloff).",
            Kind::Switch { flag_sets: true },
        )
        .doc("weight a ray blocked at t by W(t) = max(0, 1 − t/R), as `reference --falloff`")
        .widget(Widget::Checkbox),
        Knob::new(
            "hemisphere.steps",
            "--hemisphere-steps",
            "Screen rays: points tested along each ray.",
            Kind::int(1, 64),
        )
        .doc("screen rays: points tested along each ray, evenly spaced with a per-pixel jitter")
        .widget(Widget::Range),
        Knob::new(
            "hemisphere.proof_pixels",
            "--proof-pixels",
            "rtao-two-phase: the longest image on screen (pixels) of a ray phase 1 walks to prove \
             it free or blocked; longer rays go to the BVH unwalked.",
            Kind::int(0, 4096),
        )
        .units("px")
        .doc(
            "`rtao-two-phase`: the longest image on screen of a ray that phase 1 walks, pixel by \
             pixel, to prove it free or blocked; a longer ray goes to the BVH unwalked (0: every \
             ray does)",
        ),
        Knob::new(
            "hemisphere.thickness",
            "--hemisphere-thickness",
            "Screen rays: thickness behind every depth sample, world units.",
            Kind::POSITIVE,
        )
        .length()
        .doc("screen rays: the thickness assumed behind every depth sample (a ray passes behind it)"),
        Knob::new(
            "hemisphere.ray_budget",
            "--ray-budget",
            "Hemisphere rays a frame at most, to the pixels with the least history or the most \
             variance first (needs --temporal); 0: no budget.",
            Kind::int(0, 1 << 30),
        )
        .units("rays")
        .doc(
            "rays a frame at most, given first to the pixels with no history, then to those whose \
             accumulated AO has the largest variance; 0: every pixel casts `rays` (needs \
             `temporal.enabled`)",
        ),
        Knob::new(
            "hemisphere.time_budget",
            "--time-budget",
            "Milliseconds a frame for the hemisphere rays: the ray budget follows the GPU timings \
             (view, path, bench; needs --temporal and timestamp queries); 0: off.",
            Kind::POSITIVE.or_zero("off"),
        )
        .units("ms")
        .doc(
            "GPU milliseconds a frame after the G-buffer (the budget's passes, the sources, the \
             AO pass, the filters): frame loops set the ray budget from the last frame's \
             timings (needs `temporal.enabled`)",
        )
        .widget(Widget::Slider {
            min: 0.0,
            max: 4.0,
            log: false,
        }),
    ];

    /// Whether a ray budget or a time budget is asked for.
    pub fn budgeted(&self) -> bool {
        self.ray_budget > 0 || self.time_budget > 0.0
    }
}

/// The estimator's WGSL (the estimator contract, docs/ARCHITECTURE.md): the shared rays and the
/// screen-space estimators' accessors, then the estimator.
pub(crate) const WGSL: &str = concat!(
    include_str!("../../shaders/common/hash.wgsl"),
    include_str!("../../shaders/estimators/screen_space.wgsl"),
    include_str!("../../shaders/common/hemisphere.wgsl"),
    include_str!("../../shaders/estimators/hemisphere.wgsl"),
    include_str!("../../shaders/estimators/no_bent_sample.wgsl"),
    include_str!("../../shaders/estimators/no_depth_interval.wgsl"),
    include_str!("../../shaders/estimators/no_bent_normal.wgsl"),
);

/// Its `override` constants: the rays per pixel; whether a ray budget grants them per pixel.
pub(crate) const CONSTANTS: &[&str] = &["SAMPLE_COUNT", "RAY_BUDGET"];

/// GPU mirror of `HemisphereParams` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct HemisphereParams {
    radius: f32,
    thickness: f32,
    falloff: u32,
    steps: u32,
    proof_pixels: u32,
    _pad: [u32; 3],
}

/// The estimator as the technique table runs it (`EstimatorCaps::module`).
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: WGSL,
    constants: CONSTANTS,
    knobs: HemisphereSettings::KNOBS,
    params: |section, inputs| params(&super::section(section), inputs.ray_budget),
    table: None,
};

/// The parameter block (group 1) and the values of [`CONSTANTS`] for `settings`; `ray_budget`:
/// the AO pass reads each pixel's rays from the budget's grant (a budget asked for, with the
/// temporal accumulation it needs running).
pub(crate) fn params(s: &HemisphereSettings, ray_budget: bool) -> (Vec<u8>, Vec<f64>) {
    let params = HemisphereParams {
        radius: s.radius,
        thickness: s.thickness,
        falloff: u32::from(s.falloff),
        steps: s.steps,
        proof_pixels: s.proof_pixels,
        _pad: [0; 3],
    };
    (
        bytemuck::bytes_of(&params).to_vec(),
        vec![f64::from(s.rays), f64::from(u8::from(ray_budget))],
    )
}
