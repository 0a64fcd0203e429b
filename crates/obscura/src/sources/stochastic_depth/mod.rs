//! Hidden-depth source "stochastic depth". The stratified stochastic depth map (seed 001 §3.1,
//! Alg. 1; `shaders/sources/stochastic_depth/map.wgsl`): S depths per pixel in a storage buffer,
//! in which every hidden fragment is kept in ⌊αS + ξ⌋ of the S samples of its pixel, nearest
//! first, all samples at the pixel centre as the paper places them. Optionally limited to the
//! pixels of an SD-request mask (seed 000 §3.9): a full-screen pass copies the mask into the
//! stencil (`reset.wgsl`, `reset.rs`) and the scene is drawn with the stencil test, or
//! ([`SdMask::Depth`]) the reset writes the far plane where the mask is not set and the depth test
//! alone rejects those pixels, or ([`SdMask::Discard`]) the map's fragment shader reads the mask
//! itself.
//!
//! The map writes no depth, so its fragments are depth- and stencil-tested before they are shaded
//! (where the device has wgpu's `SHADER_EARLY_DEPTH_TEST`): the reset writes per pixel the depth
//! a fragment must lie behind to be hidden, and the stencil. Any S of
//! [`crate::settings::SD_SAMPLE_COUNTS`] runs on any adapter (no multisampled target). Like the
//! G-buffer it draws only the scene's chunks in view ([`crate::raster::chunks`]). With
//! `rasterizer = "compute"`, or `"auto"` (the default) on a GPU that binds their buffers
//! ([`resolve_rasterizer`]), compute passes make its fragments instead (`compute_raster.rs`),
//! and the hardware draws only what they leave to it.
//! The AO passes read the map through `read.wgsl` (the source contract).
//!
//! By default the map has its own guard band (`stochastic_depth.guard_band`, 512 px at 1080p;
//! ours, after the ray-traced map's of seed 002 §3.5): it is rasterised with the same camera over a frame that
//! many pixels wider on every side ([`FrameView::widened`]), keeping every layer in the band,
//! where there is no first layer, so that samples off the framebuffer read it
//! (`read.wgsl`'s `guard_band_lookup`) instead of the framebuffer's edge, which otherwise
//! makes the map's edge the least steady part of it in motion (issue 62). `0` turns it off.

mod compute_raster;
mod reset;

use crate::bindings::{entry, SOURCE_SD_MAPS, SOURCE_SD_NEAR};
use crate::error::Error;
use crate::gpu::PassProfiler;
use crate::raster::gbuffer::{
    behind_first_layer_entries, scene_layout, scene_resources, visibility_draws, CameraUniform,
    ScenePipeline,
};
use crate::raster::gpu_scene::GpuScene;
use crate::raster::triangle_cull::{CullList, TriangleCull};
use crate::settings::{
    SdMask, SdRasterizer, SdSelection, StochasticDepthSettings, SD_SAMPLE_COUNTS,
};
use crate::shaders;
use crate::view::FrameView;
use reset::{ResetScope, SdReset};
use std::sync::atomic::{AtomicU32, Ordering};
use wgpu::util::DeviceExt;

/// How the S depth samples per pixel are laid out. One map of S since the map is a storage
/// buffer; the ray-traced map reports its N slots the same way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SdLayout {
    /// Number of maps, each with its own seed (1).
    pub maps: u32,
    /// Depth samples per pixel in each map.
    pub samples_per_map: u32,
}

impl SdLayout {
    /// S, the depth samples per pixel over all maps.
    pub fn samples(&self) -> u32 {
        self.maps * self.samples_per_map
    }

    /// The layout of `samples` per pixel: one map, for every count of
    /// [`crate::settings::SD_SAMPLE_COUNTS`].
    pub fn plan(samples: u32) -> Option<Self> {
        SD_SAMPLE_COUNTS.contains(&samples).then_some(Self {
            maps: 1,
            samples_per_map: samples,
        })
    }
}

/// The depth format of the map's early-test target. Where its reset writes that depth: 24 bits,
/// with the stencil of SD-SVAO where the map is stenciled (both formats every WebGPU device
/// has). The map pass tests 24-bit depth faster than 32-bit float: on an H200 at 1080p its
/// `sd_map` took 1.064 → 1.019 ms with the depth mask and 1.368 → 1.235 with the stencil (16 bits,
/// depth mask: 1.055; BENCHMARKS.md, issue 16). The reset moves its depth two steps towards the
/// camera (reset.wgsl, SD_CULL_QUANTUM), so no rounding rejects a fragment the shader would keep.
/// A whole map tested against the G-buffer's depth buffer (`gbuffer_z`) takes that buffer's
/// `Depth32Float`, which its pipelines must match: a 24-bit reset there measured slower (map
/// 1.708 ms after a 0.160 ms reset, against 1.701 with no reset).
fn cull_format(stenciled: bool, gbuffer_z: bool) -> wgpu::TextureFormat {
    if stenciled {
        wgpu::TextureFormat::Depth24PlusStencil8
    } else if gbuffer_z {
        wgpu::TextureFormat::Depth32Float
    } else {
        wgpu::TextureFormat::Depth24Plus
    }
}

#[cfg(test)]
thread_local! {
    /// Tests: maps made on this thread always test against their reset's depth, never the
    /// G-buffer's (the twin of [`StochasticDepthMap::render`] given a `gbuffer_z`).
    pub(crate) static RESET_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Tests: frames whose map was tested against the G-buffer's depth on this thread.
    pub(crate) static GBUFFER_Z_FRAMES: std::cell::Cell<u32> = const { std::cell::Cell::new(0) };
}

/// Whether the map's fragments are tested before they are shaded (wgpu feature
/// `SHADER_EARLY_DEPTH_TEST`, requested by [`crate::Gpu`] where the adapter has it). Without it
/// the map is the same, only slower: every fragment is shaded and decides for itself.
pub fn early_tests_available(device: &wgpu::Device) -> bool {
    device
        .features()
        .contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST)
}

/// The mask table of `map.wgsl` for `samples` bits: S + 2 offsets (index of
/// the first mask with R bits, R = 0..=S, then 2^S), then all 2^S masks sorted by popcount (seed
/// 001 §3.1: "all possible subsets of R_i samples out of the total of S samples").
pub fn mask_table(samples: u32) -> Vec<u32> {
    let mut masks: Vec<u32> = (0..1u32 << samples).collect();
    masks.sort_by_key(|m| (m.count_ones(), *m));
    let mut table: Vec<u32> = (0..=samples + 1)
        .map(|r| masks.iter().take_while(|m| m.count_ones() < r).count() as u32)
        .collect();
    table.extend(masks);
    table
}

/// The WGSL that binds a map of `layout` for reading (the source group: `sd_near` is bound by
/// samples.wgsl) and its `sd_load`, for `read.wgsl` and the multi-view lookup. The map's
/// `SdRaster` is bound a second time for its width (`sd_map_params[1].z`, the band included).
/// `band`: the map's own guard band in pixels ([`StochasticDepthMap::band`]); 0 compiles none
/// of the band's code in.
pub(crate) fn bindings_wgsl(layout: SdLayout, band: u32) -> String {
    format!(
        "// Generated by src/sources/stochastic_depth/mod.rs.
const SD_MAPS: u32 = 1u;
const SD_SAMPLES: u32 = {samples}u;
@group(GROUP_SOURCE) @binding(SOURCE_SD_MAPS) var<storage, read> sd_map_depths: array<f32>;
@group(GROUP_SOURCE) @binding(SOURCE_SD_MAPS + 1u) var<uniform> sd_map_params: array<vec4<u32>, 2>;
// The map's own guard band in pixels: it reaches this far beyond the framebuffer on every side.
const SD_GUARD: i32 = {band};
const SD_HAS_GUARD_BAND: bool = {has_band};
// The cell of framebuffer pixel `pixel` (the band's pixels lie outside the framebuffer) in a
// map `width` cells wide, its band included.
fn sd_cell_in(pixel: vec2<i32>, width: u32) -> u32 {{
    let t = pixel + vec2<i32>(SD_GUARD);
    return u32(t.y) * width + u32(t.x);
}}
fn sd_load(map: u32, pixel: vec2<i32>, s: u32) -> f32 {{
    return sd_map_depths[sd_cell_in(pixel, sd_map_params[1].z) * SD_SAMPLES + s];
}}
// The request mask's cell of `pixel` (the frame's map: the framebuffer and its band).
fn sd_request_cell(pixel: vec2<i32>) -> u32 {{
    return sd_cell_in(pixel, view.full_size.x + 2u * u32(SD_GUARD));
}}
// Whether the map's band holds `pixel`, one off the framebuffer (none without a band: such a
// sample reads the framebuffer's edge).
fn sd_guard_covers(pixel: vec2<i32>) -> bool {{
    let t = pixel + vec2<i32>(SD_GUARD);
    return SD_HAS_GUARD_BAND && all(t >= vec2<i32>(0))
        && all(t < vec2<i32>(view.full_size) + 2 * SD_GUARD);
}}
",
        samples = layout.samples(),
        has_band = band > 0,
    )
}

/// Source-group layout entries of a reader of a map (any S: the bindings are the same).
pub(crate) fn read_layout_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        entry::uniform(SOURCE_SD_NEAR),
        entry::storage(SOURCE_SD_MAPS, true),
        entry::uniform(SOURCE_SD_MAPS + 1),
    ]
}

/// What the device allows for the map, for `obscura info` and messages.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SdCapabilities {
    /// Where the map lives.
    pub format: String,
    /// `stochastic_depth.samples` values accepted.
    pub sample_counts: Vec<u32>,
    /// The map's fragments are depth- and stencil-tested before shading.
    pub early_tests: bool,
    /// `--sd-rasterizer compute` runs here (the device binds enough storage buffers per stage).
    pub compute_rasterizer: bool,
}

impl SdCapabilities {
    /// What `device` allows.
    pub fn of(device: &wgpu::Device) -> Self {
        Self {
            format: "storage buffer, S f32 per pixel".to_string(),
            sample_counts: SD_SAMPLE_COUNTS.to_vec(),
            early_tests: early_tests_available(device),
            compute_rasterizer: compute_raster::available(device, true),
        }
    }
}

/// The rasteriser `wanted` resolves to on `adapter` for a map limited to requested pixels
/// (`requested`) or not: `Auto` becomes `Compute` where the passes can be bound and the adapter is
/// not a CPU, else `Hardware` (see [`SdRasterizer::Auto`] for why); the others stay as they are
/// (an explicit `Compute` the device cannot bind is refused when the map is made).
pub fn resolve_rasterizer(
    adapter: &wgpu::Adapter,
    device: &wgpu::Device,
    wanted: SdRasterizer,
    requested: bool,
) -> SdRasterizer {
    match wanted {
        SdRasterizer::Auto
            if adapter.get_info().device_type != wgpu::DeviceType::Cpu
                && compute_raster::available(device, requested) =>
        {
            SdRasterizer::Compute
        }
        SdRasterizer::Auto => SdRasterizer::Hardware,
        other => other,
    }
}

/// The map pass's bindings after the scene's (from binding 6 on; stages and type): the first
/// layer and `SdRaster`, the mask table, the map, and the request mask where the map is limited
/// to it. The compute rasteriser binds the same, visible to compute.
fn map_bindings(requested: bool) -> Vec<(wgpu::ShaderStages, wgpu::BindingType)> {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    let storage = |read_only| wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let mut bindings = behind_first_layer_entries();
    bindings.extend([(fragment, storage(true)), (fragment, storage(false))]);
    if requested {
        bindings.push((fragment, storage(true)));
    }
    bindings
}

/// `SdRaster` of map.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SdRaster {
    near: f32,
    alpha: f32,
    separation: f32,
    seed: u32,
    samples: u32,
    /// Non-zero: keep every layer, the first visible one included (the multi-view schedule's
    /// second map, which has no depth buffer of its own view).
    all_layers: u32,
    /// The map's width in pixels, its band included.
    width: u32,
    /// Its own guard band in pixels on every side.
    band: u32,
    /// The framebuffer's size (the first layer's), the band left out.
    first_size: [u32; 2],
    _pad: [u32; 2],
}

/// One stochastic depth map (S samples per pixel) for a framebuffer size, with its raster
/// pipelines.
pub struct StochasticDepthMap {
    samples: u32,
    settings: StochasticDepthSettings,
    separation: f32,
    /// The framebuffer it covers, guard band included.
    size: (u32, u32),
    /// Its own guard band beyond that, pixels on every side
    /// (`stochastic_depth.guard_band`).
    band: u32,
    scene: GpuScene,
    /// S depths per pixel, pixel-major, reversed-Z (near / linear depth), 0 = empty.
    depths: wgpu::Buffer,
    /// The depth (and stencil) the map's fragments are tested against, written by the reset.
    cull: wgpu::TextureView,
    /// `SdRaster`; its first member `near` is what readers bind.
    params: wgpu::Buffer,
    /// The near plane of the last frame, for [`StochasticDepthMap::read_layers`].
    near: AtomicU32,
    camera: wgpu::Buffer,
    lut: wgpu::Buffer,
    /// Back faces culled / kept / alpha-tested (`visibility_draws`' groups).
    pipelines: [wgpu::RenderPipeline; 3],
    /// Empties the map before each frame and writes the depth (and stencil) it is tested against.
    reset: SdReset,
    /// Limited to an SD-request mask ([`StochasticDepthMap::render`]).
    requested: bool,
    /// Keep every layer ([`StochasticDepthMap::keeping_every_layer`]).
    all_layers: bool,
    /// May be tested against the G-buffer's own depth buffer instead of its reset's
    /// ([`StochasticDepthMap::render`]): the whole map, no band of its own, early tests and a
    /// separation.
    gbuffer_z_usable: bool,
    /// Timing name of the raster (`sd_map`; the reset's is its own).
    timing_name: &'static str,
    /// The triangles of the coming frame's draws (the scene's chunks in view,
    /// [`visibility_draws`]) that may cover a pixel centre.
    triangle_cull: TriangleCull,
    /// With `rasterizer = "compute"`: the passes that rasterise the map in compute; the
    /// hardware then draws only the triangles they leave to it.
    compute: Option<compute_raster::ComputeRaster>,
}

impl StochasticDepthMap {
    /// A map for a `width`×`height` framebuffer (guard band included), and its own band of
    /// `band` pixels beyond it (`stochastic_depth.guard_band`, resolved by
    /// [`StochasticDepthSettings::guard_band_for`]). `separation`: how far
    /// behind the first layer a fragment must lie to count as hidden. `requested`: rasterise only
    /// where an SD-request mask is set ([`StochasticDepthMap::render`]), by stencil, depth or
    /// discard.
    pub fn new(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        settings: &StochasticDepthSettings,
        separation: f32,
        (width, height, band): (u32, u32, u32),
        scene: &GpuScene,
        requested: Option<SdMask>,
    ) -> Result<Self, Error> {
        // Rasterised in compute, the hardware draws only the triangles the compute passes leave
        // to it, untested: their shaders decide for themselves (the first layer, the request
        // mask), and no reset pass writes a depth or a stencil for so few fragments.
        let rasterizer =
            resolve_rasterizer(adapter, device, settings.rasterizer, requested.is_some());
        let compute_raster = rasterizer == SdRasterizer::Compute;
        let stenciled = requested == Some(SdMask::Stencil) && !compute_raster;
        let layout = SdLayout::plan(settings.samples).ok_or_else(|| {
            crate::error::SettingsError::Invalid {
                field: "stochastic_depth.samples",
                value: settings.samples.to_string(),
                rule: "must be 1, 2, 4, 8 or 16".into(),
            }
        })?;
        // `AoSettings::validate` checked α already; this guards direct use of the map.
        let alpha = settings.alpha();
        if !(alpha > 0.0 && alpha <= 1.0) {
            return Err(crate::error::SettingsError::Invalid {
                field: "stochastic_depth.alpha",
                value: alpha.to_string(),
                rule: "must be in (0, 1], e.g. 0.2".into(),
            }
            .into());
        }
        let samples = layout.samples();
        let (map_width, map_height) = (width + 2 * band, height + 2 * band);
        // Whole 16-byte words for the clear (gpu::zero_fill).
        let bytes = crate::gpu::zero_fill::zero_fill_size(
            u64::from(map_width) * u64::from(map_height) * u64::from(samples) * 4,
        );
        let max = device.limits().max_storage_buffer_binding_size;
        if bytes > max {
            return Err(crate::error::SettingsError::Unsupported {
                field: "stochastic_depth.samples",
                value: samples.to_string(),
                adapter: adapter.get_info().name,
                reason: format!(
                    "the map of {map_width}×{map_height} px × {samples} samples needs {bytes} bytes in one storage buffer and this device allows {max}; use fewer samples, a smaller size or a narrower --sd-map-guard-band"
                ),
            }
            .into());
        }
        let depths = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stochastic depth map"),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        // The G-buffer's depth buffer holds the first layer's own depth: tested against it (no
        // writes, `Less`), the first layer's fragments fail, and those behind it pass early; the
        // shader drops what lies within `separation` behind (as it does with the reset's
        // depth). Only a fragment the rasteriser puts at the first layer's own depth while its
        // linear depth lies more than `separation` behind would be lost: that takes a separation
        // within the depth's rounding (about 1e-7 of the depth), and a separation of 0 keeps
        // the reset.
        let gbuffer_z_usable = !compute_raster
            && requested.is_none()
            && band == 0
            && separation > 0.0
            && early_tests_available(device);
        #[cfg(test)]
        let gbuffer_z_usable = gbuffer_z_usable && !RESET_ONLY.with(|r| r.get());
        let format = cull_format(stenciled, gbuffer_z_usable);
        let cull = crate::gpu::texture_2d(
            device,
            "stochastic depth cull",
            map_width,
            map_height,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        )
        .create_view(&Default::default());
        // Whether the map has a band (without one its shaders read the first layer as before)
        // and keeps the nearest layers (the stochastic map's shaders are then as they were).
        let mut map_source = format!(
            "const SD_MAP_BAND: bool = {};\nconst SD_NEAREST: bool = {};\n{}",
            band > 0,
            settings.selection == SdSelection::Nearest,
            shaders::with_common(
                &[
                    shaders::MATERIAL,
                    shaders::HASH,
                    shaders::VERTEX_NORMAL,
                    shaders::GBUFFER,
                ],
                shaders::STOCHASTIC_DEPTH_MAP,
            )
        );
        if !early_tests_available(device) {
            // The attribute needs the feature; without it the shaders decide alone (map.wgsl).
            map_source = map_source.replace("@early_depth_test(force)", "");
        }
        let compute = compute_raster.then(|| {
            compute_raster::ComputeRaster::new(
                adapter,
                device,
                &format!("{map_source}\n{}", shaders::GBUFFER_RESOLVE),
                &scene.draw_ordered(),
                (map_width, map_height),
                &map_bindings(requested.is_some()),
                requested.is_some(),
            )
        });
        let compute = compute.transpose()?;
        let source = format!("{map_source}\n{}", shaders::STOCHASTIC_DEPTH_RESET);
        let module = crate::gpu::checked_module(device, "stochastic depth", &source);
        // Stenciled: shade only where the reset wrote this frame's stencil value.
        let stencil_test = if stenciled {
            let face = wgpu::StencilFaceState {
                compare: wgpu::CompareFunction::Equal,
                ..Default::default()
            };
            wgpu::StencilState {
                front: face,
                back: face,
                read_mask: 0xff,
                write_mask: 0,
            }
        } else {
            Default::default()
        };
        // With `--sd-mask depth` or `stencil` and early tests, the fixed-function test alone
        // keeps unrequested pixels from the shader (tests/it/stochastic_depth.rs holds the map
        // empty there); otherwise the shader reads the mask as well (for the stenciled map that
        // read cost 0.5 % of its pass on an H200, BENCHMARKS.md).
        let mask_in_tests = !compute_raster
            && matches!(requested, Some(SdMask::Depth | SdMask::Stencil))
            && early_tests_available(device);
        let [plain, masked] = if requested.is_some() && !mask_in_tests {
            [
                "fs_stochastic_depth_requested",
                "fs_stochastic_depth_masked_requested",
            ]
        } else {
            ["fs_stochastic_depth", "fs_stochastic_depth_masked"]
        };
        // One layout for the three pipelines (the lean ones bind less than they are given).
        let layout = scene_layout(device, &map_bindings(requested.is_some()));
        // The G-buffer's three groups: back faces culled, double-sided, alpha-tested (drawn
        // double-sided, as the G-buffer draws them).
        let pipelines = [
            (Some(wgpu::Face::Back), "vs_depth", plain),
            (None, "vs_depth", plain),
            (None, "vs_main", masked),
        ]
        .map(|(cull_mode, vertex, fragment)| {
            ScenePipeline {
                layout: Some(&layout),
                module: &module,
                cull_mode,
                // Reversed Z: behind the reset's depth is less.
                depth_stencil: wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(if compute_raster {
                        wgpu::CompareFunction::Always
                    } else {
                        wgpu::CompareFunction::Less
                    }),
                    stencil: stencil_test.clone(),
                    bias: Default::default(),
                },
                multisample: Default::default(),
                vertex,
                fragment,
                targets: &[],
            }
            .create(device)
        });
        let scope = match requested {
            _ if compute_raster => ResetScope::All,
            Some(SdMask::Stencil) => ResetScope::Stenciled,
            Some(SdMask::Depth) => ResetScope::RequestedByDepth,
            Some(SdMask::Discard) | None => ResetScope::All,
        };
        let reset = SdReset::new(device, &module, format, scope);
        Ok(Self {
            samples,
            settings: *settings,
            separation,
            size: (width, height),
            band,
            // Triangles in chunk order, as the G-buffer draws them (its chunks index it).
            scene: scene.draw_ordered(),
            depths,
            cull,
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sd raster params"),
                size: std::mem::size_of::<SdRaster>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            near: AtomicU32::new(0),
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sd camera"),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            lut: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sd mask table"),
                contents: bytemuck::cast_slice(&mask_table(samples)),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            pipelines,
            reset,
            requested: requested.is_some(),
            all_layers: false,
            gbuffer_z_usable,
            timing_name: "sd_map",
            triangle_cull: TriangleCull::new(device, &scene.draw_ordered(), "sd_cull", None),
            compute,
        })
    }

    /// This map storing every layer, the first visible one included: no first layer is skipped
    /// (the multi-view schedule's second view, seed 001 §3.4). The `first_layer` given to
    /// [`StochasticDepthMap::render`] is then not read.
    pub fn keeping_every_layer(mut self) -> Self {
        self.all_layers = true;
        self
    }

    /// This map timed as `clear`, `reset`, `cull` and `map` instead of `sd_clear`, `sd_reset`,
    /// `sd_cull` and `sd_map`.
    pub fn timed_as(
        mut self,
        clear: &'static str,
        reset: &'static str,
        cull: &'static str,
        map: &'static str,
    ) -> Self {
        self.reset.clear_name = clear;
        self.reset.name = reset;
        self.triangle_cull.name = cull;
        self.timing_name = map;
        self
    }

    /// How its S samples per pixel are laid out.
    pub fn layout(&self) -> SdLayout {
        SdLayout {
            maps: 1,
            samples_per_map: self.samples,
        }
    }

    /// The framebuffer size the map covers.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Its own guard band beyond the framebuffer, pixels on every side.
    pub fn band(&self) -> u32 {
        self.band
    }

    /// Its size in pixels, the band included (the request mask's size too).
    pub fn map_size(&self) -> (u32, u32) {
        (self.size.0 + 2 * self.band, self.size.1 + 2 * self.band)
    }

    /// For each framebuffer pixel (row-major), the index of its cell in the map.
    pub fn cell_of_pixels(&self) -> impl Iterator<Item = usize> + '_ {
        let (w, h) = (self.size.0 as usize, self.size.1 as usize);
        let (band, map_width) = (self.band as usize, self.map_size().0 as usize);
        (0..w * h).map(move |p| (p / w + band) * map_width + p % w + band)
    }

    /// The camera of the coming frame; `frame` (0: none) changes the seed of the coverage masks
    /// per frame under temporal accumulation.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView, frame: u32) {
        // The map's own band: the same camera over a wider frame, every pixel in its place.
        let view = &view.widened(self.band);
        queue.write_buffer(
            &self.camera,
            0,
            bytemuck::bytes_of(&CameraUniform::new(view)),
        );
        let raster = SdRaster {
            near: view.near,
            alpha: self.settings.alpha(),
            separation: self.separation,
            // Frames (under temporal accumulation) draw independent masks.
            seed: crate::hash::pcg_hash(self.settings.seed ^ frame.wrapping_mul(0x85eb_ca6b)),
            samples: self.samples,
            all_layers: u32::from(self.all_layers),
            width: self.map_size().0,
            band: self.band,
            first_size: [self.size.0, self.size.1],
            _pad: [0; 2],
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&raster));
        // The G-buffer's draws (its groups: back faces culled, double-sided, alpha-tested), one
        // pipeline of this map each; the compute rasteriser culls for itself.
        if self.compute.is_none() {
            self.triangle_cull
                .prepare(queue, view, visibility_draws(&self.scene, view), false);
        }
        self.near.store(view.near.to_bits(), Ordering::Relaxed);
    }

    /// Rasterise the map behind `first_layer` (the G-buffer's linear depth). With `request` (a
    /// map made with `requested`), only the pixels whose u32 in it is non-zero; the map is then
    /// empty elsewhere. `gbuffer_z`: the depth buffer the first layer was rasterised into
    /// (reversed-Z `Depth32Float` of the framebuffer's size, drawn with this frame's camera), if
    /// the caller has one; a whole map without a band of its own is then tested against it
    /// instead of a depth its reset writes (the same map: fragments the G-buffer's depth lets
    /// through but the reset's would not lie within `separation` behind the first layer, and the
    /// shader drops them). Timings: `sd_clear` (emptying the map), `sd_reset` (the depth, and
    /// for a stenciled map the stencil, its fragments are tested against; not run when tested
    /// against `gbuffer_z`) and `sd_map`.
    pub fn render(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        first_layer: &wgpu::TextureView,
        gbuffer_z: Option<&wgpu::Texture>,
        request: Option<&wgpu::Buffer>,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        assert_eq!(
            self.requested,
            request.is_some(),
            "a map limited to requested pixels is rendered with its request mask, and only it"
        );
        let mut extra = vec![
            wgpu::BindingResource::TextureView(first_layer),
            self.params.as_entire_binding(),
            self.lut.as_entire_binding(),
            self.depths.as_entire_binding(),
        ];
        extra.extend(request.map(|r| r.as_entire_binding()));
        let resources = scene_resources(&self.camera, &self.scene, extra);
        if let Some(compute) = &self.compute {
            self.render_in_compute(device, encoder, compute, &resources, profiler);
            return;
        }
        let gbuffer_z = gbuffer_z
            .filter(|z| {
                self.gbuffer_z_usable
                    && !self.all_layers
                    && z.format() == wgpu::TextureFormat::Depth32Float
                    && z.sample_count() == 1
                    && (z.width(), z.height()) == self.size
            })
            .map(|z| z.create_view(&Default::default()));
        // A map keeping every layer tests against nothing: its pass clears the depth to 1.
        let stencil_value = self.reset.encode(
            device,
            encoder,
            &self.depths,
            (!self.all_layers && gbuffer_z.is_none()).then_some(&self.cull),
            &resources,
            profiler.as_deref_mut(),
        );
        let bind_group = crate::gpu::bind_group(
            device,
            "stochastic depth",
            &self.pipelines[0].get_bind_group_layout(0),
            &resources,
        );
        let bind_groups = [bind_group.clone(), bind_group.clone(), bind_group];
        self.triangle_cull.encode(encoder, profiler.as_deref_mut());
        let map_name = self.timing_name;
        let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(map_name));
        let load = if self.all_layers {
            wgpu::LoadOp::Clear(1.0)
        } else {
            wgpu::LoadOp::Load
        };
        #[cfg(test)]
        if gbuffer_z.is_some() {
            GBUFFER_Z_FRAMES.with(|f| f.set(f.get() + 1));
        }
        let target = gbuffer_z.as_ref().unwrap_or(&self.cull);
        let mut pass = begin(encoder, target, load, timestamp_writes);
        pass.set_stencil_reference(stencil_value);
        if let Some(p) = profiler.as_deref_mut() {
            p.begin_fragments(&mut pass, map_name);
        }
        self.triangle_cull
            .record(&mut pass, &self.pipelines, &bind_groups, CullList::All);
        if let Some(p) = profiler.as_deref() {
            p.end_fragments(&mut pass);
        }
    }

    /// [`StochasticDepthMap::render`] with `rasterizer = "compute"`: the map emptied, the compute
    /// passes (`sd_bin`, `sd_tiles`), then the triangles they left to the hardware (`sd_map`),
    /// drawn without depth tests (over the target as it is: nothing reads it).
    fn render_in_compute(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        compute: &compute_raster::ComputeRaster,
        resources: &[wgpu::BindingResource],
        mut profiler: Option<&mut PassProfiler>,
    ) {
        self.reset.encode(
            device,
            encoder,
            &self.depths,
            None,
            resources,
            profiler.as_deref_mut(),
        );
        compute.encode(device, encoder, resources, profiler.as_deref_mut());
        let bind_group = crate::gpu::bind_group(
            device,
            "stochastic depth",
            &self.pipelines[0].get_bind_group_layout(0),
            resources,
        );
        let timestamp_writes = profiler
            .as_deref_mut()
            .map(|p| p.render_pass(self.timing_name));
        // Its pipelines neither test (`Always`) nor write depth, so the target's contents do
        // not matter: loaded, not cleared. Why: the clear alone cost 0.12-0.14 ms a frame on an
        // H200 at 1080p (the pass with nothing left to draw, BENCHMARKS.md 2026-12-05).
        let mut pass = begin(encoder, &self.cull, wgpu::LoadOp::Load, timestamp_writes);
        if let Some(p) = profiler.as_deref_mut() {
            p.begin_fragments(&mut pass, self.timing_name);
        }
        compute.record_left(&mut pass, &self.pipelines, &bind_group);
        if let Some(p) = profiler.as_deref() {
            p.end_fragments(&mut pass);
        }
    }

    /// With `rasterizer = "compute"`, the compute passes' counters of the last frame (items,
    /// records, triangles left to the hardware, records or item runs that did not fit,
    /// fragments shaded by the bin and the tile pass).
    #[cfg(test)]
    pub(crate) fn compute_counts(&self, gpu: &crate::gpu::Gpu) -> Option<[u32; 6]> {
        self.compute.as_ref().map(|c| c.read_counts(gpu).unwrap())
    }

    /// What a reader binds in the source group, matching [`bindings_wgsl`] and
    /// [`read_layout_entries`].
    pub(crate) fn read_resources(&self) -> Vec<(u32, wgpu::BindingResource<'_>)> {
        vec![
            (SOURCE_SD_NEAR, self.params.as_entire_binding()),
            (SOURCE_SD_MAPS, self.depths.as_entire_binding()),
            (SOURCE_SD_MAPS + 1, self.params.as_entire_binding()),
        ]
    }

    /// Every sample layer of the last map rendered, as linear depth (0 = empty), framebuffer-sized
    /// (its own band left out) and row-major: `layers[s]` is sample `s`. Waits for the GPU.
    pub fn read_layers(&self, gpu: &crate::gpu::Gpu) -> Result<Vec<Vec<f32>>, Error> {
        let near = f32::from_bits(self.near.load(Ordering::Relaxed));
        let bytes = crate::gpu::read_buffer_copy(gpu, &self.depths)?;
        let values: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes);
        let s = self.samples as usize;
        Ok((0..s)
            .map(|k| {
                self.cell_of_pixels()
                    .map(|cell| values[cell * s + k])
                    .map(|v| if v > 0.0 { near / v } else { 0.0 })
                    .collect()
            })
            .collect())
    }
}

/// A render pass on the map's depth(-stencil) target: depth loaded as `depth` says, the stencil
/// kept.
pub(crate) fn begin<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &wgpu::TextureView,
    depth: wgpu::LoadOp<f32>,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    fn keep<V>() -> wgpu::Operations<V> {
        wgpu::Operations {
            load: wgpu::LoadOp::Load,
            store: wgpu::StoreOp::Store,
        }
    }
    let stencil = target.texture().format().has_stencil_aspect().then(keep);
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("stochastic depth"),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: target,
            depth_ops: Some(wgpu::Operations {
                load: depth,
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: stencil,
        }),
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::renderer::Renderer;
    use crate::raster::test_support::{gpu, moved};
    use crate::scene;
    use crate::settings::AoSettings;
    use crate::technique::Technique;

    /// The whole map tested against the G-buffer's depth buffer holds the same depths as its
    /// twin tested against its reset's, on every built-in scene and camera, frame after frame
    /// (a frame of another view in between), for S = 1, 4 and 16 and both selections; so do
    /// the AO images. A map with its own band keeps its reset.
    #[test]
    fn the_gbuffer_depth_gives_the_reset_depths_map() {
        let gpu = gpu();
        let mut cases = vec![];
        for (samples, selection) in [
            (4, SdSelection::Stochastic),
            (1, SdSelection::Stochastic),
            (16, SdSelection::Stochastic),
            (4, SdSelection::Nearest),
        ] {
            let mut s = AoSettings {
                technique: Technique::SdVao,
                ..AoSettings::default()
            };
            s.stochastic_depth.samples = samples;
            s.stochastic_depth.selection = selection;
            // The whole map, no band of its own (a banded map keeps its reset, below).
            s.stochastic_depth.guard_band = Some(0);
            cases.push(s);
        }
        let mut non_empty = 0;
        for name in scene::builtin_names() {
            let scene = scene::builtin(name).unwrap();
            for named in &scene.cameras {
                let camera = named.camera;
                let moved = moved(&scene, &camera);
                for settings in &cases {
                    let frames = |reset_only: bool| {
                        RESET_ONLY.with(|r| r.set(reset_only));
                        let mut r = Renderer::new(&gpu, &scene, settings, 96, 64, 8).unwrap();
                        let before = GBUFFER_Z_FRAMES.with(|f| f.get());
                        let frames: Vec<_> = [&camera, &moved, &camera]
                            .iter()
                            .map(|&camera| {
                                r.render(camera, None).unwrap();
                                let map = r.read_stochastic_depth_as_written().unwrap().unwrap();
                                (map, r.read_ao().unwrap())
                            })
                            .collect();
                        // (The map is made at the first frame.)
                        RESET_ONLY.with(|r| r.set(false));
                        let used = GBUFFER_Z_FRAMES.with(|f| f.get()) - before;
                        (frames, used)
                    };
                    let (z, used) = frames(false);
                    let (reset, reset_used) = frames(true);
                    let what = format!(
                        "{name} {}, S = {}, {:?}",
                        named.name,
                        settings.stochastic_depth.samples,
                        settings.stochastic_depth.selection
                    );
                    assert_eq!(
                        (used, reset_used),
                        (3, 0),
                        "{what}: frames on the G-buffer's z"
                    );
                    for (f, (a, b)) in z.iter().zip(&reset).enumerate() {
                        non_empty += usize::from(a.0.iter().flatten().any(|&d| d > 0.0));
                        assert!(
                            a == b,
                            "{what}, frame {f}: the G-buffer's z changed the map"
                        );
                    }
                }
            }
        }
        assert!(non_empty > 0, "every map was empty");
        // Far away, where the reset's 24-bit steps are coarse (the near plane is 1e-5 of the
        // scene's diagonal: about 0.2 world units a step at depth 1000 here), a layer 0.1 behind
        // the first is kept as the G-buffer's 32-bit depth keeps it: the steps of margin the
        // reset adds let through every fragment the shader would keep.
        let mut far = scene::Scene {
            name: "far layers".into(),
            materials: vec![scene::Material::default()],
            ..Default::default()
        };
        for d in [1000.0f32, 1000.1] {
            let base = far.positions.len() as u32;
            far.positions.extend([
                glam::Vec3::new(-10.0 * d, -10.0 * d, -d),
                glam::Vec3::new(10.0 * d, -10.0 * d, -d),
                glam::Vec3::new(0.0, 10.0 * d, -d),
            ]);
            far.uvs.extend([glam::Vec2::ZERO; 3]);
            far.triangles.push([base, base + 1, base + 2]);
            far.triangle_materials.push(0);
        }
        let eye = scene::Camera::new(glam::Vec3::ZERO, glam::Vec3::NEG_Z, 90.0).unwrap();
        let map = |reset_only: bool| {
            // (Set while the map is made, at the first frame.)
            RESET_ONLY.with(|r| r.set(reset_only));
            let mut r = Renderer::new(&gpu, &far, &cases[0], 64, 64, 0).unwrap();
            r.render(&eye, None).unwrap();
            RESET_ONLY.with(|r| r.set(false));
            r.read_stochastic_depth_as_written().unwrap().unwrap()
        };
        let (z, reset) = (map(false), map(true));
        let stored = reset.iter().flatten().filter(|&&d| d > 0.0).count();
        assert!(stored > 64 * 64, "the far map stored {stored} depths");
        assert!(
            z == reset,
            "far away, the 24-bit reset's map differs from the G-buffer's"
        );
        // Its own band: the reset, always.
        let mut s = AoSettings {
            technique: Technique::SdVao,
            ..AoSettings::default()
        };
        s.stochastic_depth.guard_band = Some(4);
        let scene = scene::builtin("stairs").unwrap();
        let mut r = Renderer::new(&gpu, &scene, &s, 96, 64, 8).unwrap();
        let before = GBUFFER_Z_FRAMES.with(|f| f.get());
        r.render(&scene.cameras[0].camera, None).unwrap();
        assert_eq!(GBUFFER_Z_FRAMES.with(|f| f.get()), before, "a banded map");
    }

    #[test]
    fn mask_table_lists_every_subset_by_popcount() {
        for s in SD_SAMPLE_COUNTS {
            let t = mask_table(s);
            let (offsets, masks) = t.split_at(s as usize + 2);
            assert_eq!(masks.len(), 1 << s);
            let mut sorted = masks.to_vec();
            sorted.sort();
            assert_eq!(sorted, (0..1u32 << s).collect::<Vec<_>>());
            for r in 0..=s {
                let range = offsets[r as usize] as usize..offsets[r as usize + 1] as usize;
                // C(S, R) masks, each with R bits.
                let binomial = (0..r).fold(1u64, |c, i| c * u64::from(s - i) / u64::from(i + 1));
                assert_eq!(range.len() as u64, binomial, "S={s} R={r}");
                assert!(masks[range].iter().all(|m| m.count_ones() == r));
            }
        }
    }

    #[test]
    fn every_sample_count_is_one_map() {
        for s in SD_SAMPLE_COUNTS {
            assert_eq!(
                SdLayout::plan(s),
                Some(SdLayout {
                    maps: 1,
                    samples_per_map: s
                })
            );
        }
        assert_eq!(SdLayout::plan(3), None);
        assert_eq!(SdLayout::plan(32), None);
    }
}
