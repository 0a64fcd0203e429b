//! Estimators: what turns depth samples into occlusion (the first axis of the technique table).
//!
//! An estimator is a WGSL file in `shaders/estimators/` implementing the estimator contract
//! (docs/ARCHITECTURE.md: per-pixel setup, samples, the value of one sample against one depth, how
//! values of several depths combine, "needs hidden depth?", the accumulated state and the finish)
//! plus a Rust module here that makes its parameters (bind group 1) and pipeline constants. The
//! schedules own the loops; the sources consult the estimator for each depth they find.

pub mod gtao;
pub mod gtao_vb;
pub mod hbao;
pub mod hbao_plus;
pub mod pyramid_hbao;
pub mod sao;
pub mod ssao;
pub mod vao;

use crate::bindings::{self, entry, ESTIMATOR_PARAMS, ESTIMATOR_TABLE};
use crate::settings::AoSettings;
use crate::technique::Estimator;
use wgpu::util::DeviceExt;

/// An estimator as a pipeline sees it: its shader, its `override` constants and group 1.
pub(crate) struct EstimatorPass {
    pub wgsl: &'static str,
    pub constants: Vec<(&'static str, f64)>,
    pub layout: wgpu::BindGroupLayout,
    pub group: wgpu::BindGroup,
}

impl EstimatorPass {
    /// The estimator of a technique row with its settings; `max_radius_px` caps its radius on
    /// screen (0: no cap; [`AoSettings::max_radius_px`], which the ground truth leaves out).
    pub fn for_row(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        estimator: Estimator,
        settings: &AoSettings,
        max_radius_px: f32,
    ) -> Self {
        let (wgsl, names) = wgsl(estimator);
        let (params, values) = params(estimator, settings);
        let mut constants: Vec<_> = names.iter().copied().zip(values).collect();
        // common/view.wgsl's cap, set only where there is one (0 is the shader's default).
        if max_radius_px > 0.0 {
            constants.push(("MAX_RADIUS_PX", f64::from(max_radius_px)));
        }
        let name = estimator.name();
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(name),
            contents: &params,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let table = table(estimator).map(|texels| {
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
        let layout = bindings::layout(device, name, &layout_entries(estimator));
        let mut resources = vec![(ESTIMATOR_PARAMS, buffer.as_entire_binding())];
        if let Some(view) = &table {
            resources.push((ESTIMATOR_TABLE, wgpu::BindingResource::TextureView(view)));
        }
        let group = bindings::group(device, name, &layout, &resources);
        Self {
            wgsl,
            constants,
            layout,
            group,
        }
    }
}

/// Group 1 of `estimator`: its uniform parameters, and the table of those that read one.
pub(crate) fn layout_entries(estimator: Estimator) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![entry::uniform(ESTIMATOR_PARAMS)];
    if table(estimator).is_some() {
        entries.push(entry::texture(ESTIMATOR_TABLE));
    }
    entries
}

/// The texels (`Rg32Float`, one row) of the table `estimator` reads at `ESTIMATOR_TABLE`, if any.
fn table(estimator: Estimator) -> Option<Vec<[f32; 2]>> {
    match estimator {
        Estimator::GtaoVb => Some(gtao_vb::sector_direction_table()),
        _ => None,
    }
}

/// The estimator's uniform bytes and its `override` constants' values (in the order of its
/// `CONSTANTS`, `SAMPLE_COUNT` first) under `settings`.
fn params(estimator: Estimator, settings: &AoSettings) -> (Vec<u8>, Vec<f64>) {
    match estimator {
        Estimator::Vao => vao::params(&settings.vao),
        Estimator::Hbao => hbao::params(&settings.hbao),
        Estimator::HbaoPlus => hbao_plus::params(&settings.hbao_plus),
        Estimator::Gtao => gtao::params(&settings.gtao),
        Estimator::Sao => sao::params(&settings.sao, &settings.pyramid),
        Estimator::Ssao => ssao::params(&settings.ssao, settings.stochastic_depth.query),
        Estimator::PyramidHbao => pyramid_hbao::params(&settings.pyramid_hbao, &settings.pyramid),
        Estimator::GtaoVb => gtao_vb::params(&settings.gtao_vb, &settings.stochastic_depth),
    }
}

/// Samples per pixel of `estimator` under `settings`: its `SAMPLE_COUNT` constant, the bits of a
/// two-phase schedule's mask it uses (e.g. to normalise `render --debug-out`'s `samples.png`).
pub fn samples_per_pixel(estimator: Estimator, settings: &AoSettings) -> u32 {
    params(estimator, settings).1[0] as u32
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

/// [`bayer_pattern`] for the 16 pixels of the 4×4 tile, indexed x % 4 + 4 (y % 4), as the
/// estimators' uniform tables hold it (xy rotation, z jitter).
pub(crate) fn bayer_table(period: f32) -> [[f32; 4]; 16] {
    std::array::from_fn(|i| {
        let (c, s, jitter) = bayer_pattern(i as u32 % 4, i as u32 / 4, period);
        [c, s, jitter, 0.0]
    })
}

/// An estimator's WGSL and the names of its pipeline constants (also for composing shaders without
/// a device: the shader validation test).
pub(crate) fn wgsl(estimator: Estimator) -> (&'static str, &'static [&'static str]) {
    match estimator {
        Estimator::Vao => (vao::WGSL, vao::CONSTANTS),
        Estimator::Hbao => (hbao::WGSL, hbao::CONSTANTS),
        Estimator::HbaoPlus => (hbao_plus::WGSL, hbao_plus::CONSTANTS),
        Estimator::Gtao => (gtao::WGSL, gtao::CONSTANTS),
        Estimator::Sao => (sao::WGSL, sao::CONSTANTS),
        Estimator::Ssao => (ssao::WGSL, ssao::CONSTANTS),
        Estimator::PyramidHbao => (pyramid_hbao::WGSL, pyramid_hbao::CONSTANTS),
        Estimator::GtaoVb => (gtao_vb::WGSL, gtao_vb::CONSTANTS),
    }
}
