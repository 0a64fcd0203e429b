//! Estimators: what turns depth samples into occlusion (the first axis of the technique table).
//!
//! An estimator is a WGSL file in `shaders/estimators/` implementing the estimator contract
//! (docs/ARCHITECTURE.md: per-pixel setup, samples, the value of one sample against one depth, how
//! values of several depths combine, "needs hidden depth?", the accumulated state and the finish)
//! plus a Rust module here that holds everything else of it: its settings struct and their knobs,
//! its parameter packing (bind group 1) and pipeline constants, as one [`EstimatorModule`], and its
//! CPU mirror (`cpu_<name>`, the kernel as plain Rust that the tests hold the GPU to; what the
//! mirrors share is in [`mirror`]). The schedules own the loops; the sources consult the estimator
//! for each depth they find. Nothing here knows the technique table or the settings of the whole.

/// The registry of estimators, one entry each: its module, its `Estimator` variant, its settings
/// struct and what it is (with a paper section). `registry!(then)` hands the list to the macro
/// `then`: the module declarations below, the `Estimator` enum (technique.rs) and `AoSettings`'
/// fields and defaults (settings/mod.rs). Adding an estimator: its module, its entry here, its
/// caps literal and rows in technique.rs, its test (docs/ARCHITECTURE.md, "Adding a technique").
macro_rules! registry {
    ($then:ident) => {
        $then! {
            vao: Vao(VaoSettings) = "Volumetric AO, seed 000 §3.1–3.5.",
            hbao: Hbao(HbaoSettings) = "Horizon-based AO, seed 001 §3.2 Algorithm 2, seed 004 §2.2.1.",
            hbao_plus: HbaoPlus(HbaoPlusSettings) = "NVIDIA-style per-sample horizon AO, the seed \
                authors' baseline (seed 000 §2.1, docs/AUTHORS_CODE.md §1.7).",
            gtao: Gtao(GtaoSettings) = "Ground-truth-based AO (Jimenez et al. 2016), the baseline \
                of seed 003.",
            ssao: Ssao(SsaoSettings) = "SSAO as seed 001 §3.2 extends it: Alchemy AO (McGuire et \
                al. 2011).",
            sao: Sao(SaoSettings) = "Scalable Ambient Obscurance (McGuire et al. 2012), seed 004 \
                §2.2.2.",
            pyramid_hbao: PyramidHbao(PyramidHbaoSettings) = "Pyramid HBAO, seed 004 §3.",
            gtao_vb: GtaoVb(GtaoVbSettings) = "GTAO with a visibility bitmask of 32 sectors per \
                slice (seed 003).",
            hemisphere: Hemisphere(HemisphereSettings) = "Hemisphere AO: cosine-weighted rays \
                within R, the ground truth's model (src/reference/ground_truth.rs).",
            // A stub with the knobs of a real one, to test that an entry alone gives an estimator
            // its flags, checks, presets, viewer widgets and docs rows (settings/tests.rs).
            #[cfg(test)]
            stub: Stub(StubSettings) = "A test stub (settings/tests.rs).",
        }
    };
}
pub(crate) use registry;

/// The registry's modules.
macro_rules! declare_modules {
    ($($(#[$attr:meta])* $name:ident: $variant:ident($settings:ident) = $doc:literal,)*) => {
        $($(#[$attr])* pub mod $name;)*
    };
}
registry!(declare_modules);

// Not an estimator (no registry entry): the helpers the estimators' CPU mirrors share.
pub mod mirror;

use crate::bindings::{self, entry, ESTIMATOR_PARAMS, ESTIMATOR_TABLE};
use crate::knob::{Knob, Value};
use wgpu::util::DeviceExt;

/// One estimator, described once in its module (`estimators/<name>.rs`, `MODULE`): its WGSL and
/// pipeline constants, its settings' knobs, how its parameter block is packed and the table it
/// reads, if any. The technique table points at it (`EstimatorCaps::module`).
#[derive(Clone, Copy, Debug)]
pub struct EstimatorModule {
    /// Its WGSL (the estimator contract, docs/ARCHITECTURE.md).
    pub wgsl: &'static str,
    /// The names of its `override` constants, `SAMPLE_COUNT` first.
    pub constants: &'static [&'static str],
    /// Its settings section's knobs (`VaoSettings::KNOBS`).
    pub knobs: &'static [Knob],
    /// Its uniform bytes and its constants' values from its settings section (serde form, as a
    /// settings file holds it) and what its source decides.
    pub params: PackParams,
    /// The texels (`Rg32Float`, one row) of the table it reads at `ESTIMATOR_TABLE`, if any.
    pub table: Option<fn() -> Vec<[f32; 2]>>,
}

/// How an estimator packs its parameters: its uniform bytes and its constants' values (in the
/// order of its `constants`) from its settings section and its source's inputs.
pub type PackParams = fn(&Value, &SourceInputs) -> (Vec<u8>, Vec<f64>);

/// What an estimator's parameters take from its hidden-depth source's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SourceInputs {
    /// The stochastic depth map is read where the first surface does not occlude even if no
    /// deeper surface can (`stochastic_depth.query = "first-layer"`).
    pub literal_query: bool,
    /// The stochastic samples' missing-occlusion compensation (`stochastic_depth.compensation`).
    pub compensation: f32,
    /// The depth pyramid's levels L (`pyramid.levels`).
    pub pyramid_levels: u32,
    /// The depth pyramid's factor K (`pyramid.factor`).
    pub pyramid_factor: u32,
    /// A ray budget grants each pixel its rays this frame (the frame group's `FRAME_RAY_GRANT`,
    /// from temporal accumulation's history: `AoSettings::ray_budget_active`).
    pub ray_budget: bool,
}

impl SourceInputs {
    /// Whether GTAO-VB's samples skip the hidden depth where every sector a deeper surface could
    /// mark is marked already (gtao_vb.wgsl): with the default query, and only without
    /// compensation, which widens a stochastic sample's run beyond the sectors the test counts on.
    pub fn exact_query(&self) -> bool {
        !self.literal_query && self.compensation == 1.0
    }
}

/// An estimator's settings section in its struct (the section comes from valid settings).
pub(crate) fn section<T: serde::de::DeserializeOwned>(section: &Value) -> T {
    section
        .clone()
        .try_into()
        .expect("an estimator's settings section reads back")
}

/// An estimator as a pipeline sees it: its shader, its `override` constants and group 1.
pub(crate) struct EstimatorPass {
    pub wgsl: &'static str,
    pub constants: Vec<(&'static str, f64)>,
    pub layout: wgpu::BindGroupLayout,
    pub group: wgpu::BindGroup,
}

impl EstimatorPass {
    /// Estimator `module` (labelled `name`) with its settings section and its source's inputs;
    /// `max_radius_px` caps its radius on screen (0: no cap; `AoSettings::max_radius_px`, which
    /// the ground truth leaves out).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        (name, module): (&str, &EstimatorModule),
        (section, inputs): (&Value, &SourceInputs),
        max_radius_px: f32,
    ) -> Self {
        let (params, values) = (module.params)(section, inputs);
        let mut constants: Vec<_> = module.constants.iter().copied().zip(values).collect();
        // common/view.wgsl's cap, set only where there is one (0 is the shader's default).
        if max_radius_px > 0.0 {
            constants.push(("MAX_RADIUS_PX", f64::from(max_radius_px)));
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(name),
            contents: &params,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let table = module.table.map(|table| {
            let texels = table();
            let texture = device.create_texture_with_data(
                queue,
                &wgpu::TextureDescriptor {
                    label: Some(name),
                    size: wgpu::Extent3d {
                        width: texels.len() as u32,
                        height: 1,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: wgpu::TextureFormat::Rg32Float,
                    usage: wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                },
                wgpu::util::TextureDataOrder::LayerMajor,
                bytemuck::cast_slice(&texels),
            );
            texture.create_view(&Default::default())
        });
        let layout = bindings::layout(device, name, &layout_entries(module));
        let mut resources = vec![(ESTIMATOR_PARAMS, buffer.as_entire_binding())];
        if let Some(view) = &table {
            resources.push((ESTIMATOR_TABLE, wgpu::BindingResource::TextureView(view)));
        }
        let group = bindings::group(device, name, &layout, &resources);
        Self {
            wgsl: module.wgsl,
            constants,
            layout,
            group,
        }
    }
}

/// Group 1 of an estimator: its uniform parameters, and the table of those that read one.
pub(crate) fn layout_entries(module: &EstimatorModule) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![entry::uniform(ESTIMATOR_PARAMS)];
    if module.table.is_some() {
        entries.push(entry::texture(ESTIMATOR_TABLE));
    }
    entries
}

/// Pixel (x, y)'s rotation and jitter for screen-space estimators (HBAO, HBAO+, GTAO, GTAO-VB): (cos, sin) of
/// `period`·B/16 with B the 4×4 Bayer value of (x % 4, y % 4) (the pattern VAO rotates by), and a
/// jitter in [0, 1) from the transposed matrix, (B(y % 4, x % 4) + 0.5)/16, so angle and jitter
/// do not repeat together; the blur's 4-pixel radius averages both.
pub fn bayer_pattern(x: u32, y: u32, period: f32) -> (f32, f32, f32) {
    let (i, j) = ((x % 4) as usize, (y % 4) as usize);
    let angle = period * vao::BAYER_4X4[i + 4 * j] as f32 / 16.0;
    let jitter = (vao::BAYER_4X4[j + 4 * i] as f32 + 0.5) / 16.0;
    (angle.cos(), angle.sin(), jitter)
}

/// Level `level`'s size in texels of the depth pyramid over a `full` framebuffer with factor K =
/// `factor`: ⌈full / K^level⌉ per axis. Here, below the sources, because both the source that
/// builds the levels (`sources::depth_pyramid`) and the pyramid estimators' mirrors
/// ([`mirror::Levels`]) need it.
pub fn pyramid_level_size(full: (u32, u32), factor: u32, level: u32) -> (u32, u32) {
    let scale = factor.pow(level);
    (full.0.div_ceil(scale), full.1.div_ceil(scale))
}

/// [`bayer_pattern`] for the 16 pixels of the 4×4 tile, indexed x % 4 + 4 (y % 4), as the
/// estimators' uniform tables hold it (xy rotation, z jitter).
pub(crate) fn bayer_table(period: f32) -> [[f32; 4]; 16] {
    std::array::from_fn(|i| {
        let (c, s, jitter) = bayer_pattern(i as u32 % 4, i as u32 / 4, period);
        [c, s, jitter, 0.0]
    })
}
