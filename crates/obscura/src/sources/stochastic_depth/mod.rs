//! Hidden-depth source "stochastic depth". The stratified stochastic depth map (seed 001 §3.1,
//! Alg. 1; `shaders/sources/stochastic_depth/map.wgsl`):
//! a multisampled depth target in which every hidden fragment is kept in ⌊αS + ξ⌋ of the S
//! samples of its pixel, nearest first. Optionally limited to the pixels of an SD-request mask
//! (seed 000 §3.9): a full-screen pass copies the mask into the stencil
//! (`reset.wgsl`, `reset.rs`) and the scene is drawn with the stencil test, or
//! ([`SdMask::Discard`]) the map's fragment shader reads the mask and discards.
//!
//! S samples per pixel need a target with S samples. When the adapter cannot rasterise S samples
//! into one target, S is made of several 4× or 8× maps with independent seeds ([`SdLayout`]).
//! The AO passes read the map through `read.wgsl` (the source contract); `unpack.rs` reads it back.

mod reset;
mod unpack;

use crate::bindings::{entry, SOURCE_SD_MAPS, SOURCE_SD_NEAR};
use crate::gpu::PassProfiler;
use crate::raster::gbuffer::{
    draw_scene, scene_resources, whole_ranges, CameraUniform, ScenePipeline,
};
use crate::raster::gpu_scene::GpuScene;
use crate::settings::{SdMask, StochasticDepthSettings};
use crate::view::FrameView;
use crate::{shaders, Error};
use reset::{ResetScope, SdReset};
use wgpu::util::DeviceExt;

/// Samples per map we rasterise in one target; larger counts are stacked (the mask table of 2^S
/// entries stays small).
const MAP_SAMPLE_COUNTS: [u32; 4] = [1, 2, 4, 8];
/// At most this many stacked maps (S = 16 from 4× maps).
const MAX_MAPS: u32 = 4;

/// How S depth samples per pixel are laid out: `maps` targets of `samples_per_map` each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SdLayout {
    /// Number of stacked map targets, each with its own seed (1 to 4).
    pub maps: u32,
    /// Depth samples per pixel in each target: the multisample count (1, 2, 4 or 8).
    pub samples_per_map: u32,
}

impl SdLayout {
    /// S, the depth samples per pixel over all maps.
    pub fn samples(&self) -> u32 {
        self.maps * self.samples_per_map
    }

    /// The layout of `samples` per pixel given the sample counts one target supports: one target
    /// when it can, else the fewest stacked 4×/8× targets.
    pub fn plan(samples: u32, supported: &[u32]) -> Option<Self> {
        if MAP_SAMPLE_COUNTS.contains(&samples) && supported.contains(&samples) {
            return Some(Self {
                maps: 1,
                samples_per_map: samples,
            });
        }
        [8, 4]
            .into_iter()
            .filter(|m| supported.contains(m) && *m < samples && samples.is_multiple_of(*m))
            .map(|m| Self {
                maps: samples / m,
                samples_per_map: m,
            })
            .find(|l| l.maps <= MAX_MAPS)
    }

    /// Every layout `supported` allows, for messages: "1, 4, 8 (2 maps of 4), …".
    pub fn describe_supported(supported: &[u32]) -> String {
        crate::settings::SD_SAMPLE_COUNTS
            .iter()
            .filter_map(|&s| Self::plan(s, supported))
            .map(|l| match l.maps {
                1 => l.samples().to_string(),
                n => format!("{} ({n} maps of {})", l.samples(), l.samples_per_map),
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The map's depth-stencil format: reversed-Z depth in 32-bit float keeps positions to float
/// precision (24-bit fixed point would not, at reversed-Z's small values), with the stencil of
/// SD-SVAO. Both techniques use it, so `sd-svao` reads the values `sd-vao` reads.
pub const SD_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32FloatStencil8;

/// Whether this device can make the map at all (wgpu feature `DEPTH32FLOAT_STENCIL8`, requested
/// by [`crate::Gpu`] where the adapter has it).
pub fn sd_format_available(device: &wgpu::Device) -> bool {
    device
        .features()
        .contains(wgpu::Features::DEPTH32FLOAT_STENCIL8)
}

/// Samples per pixel one map of [`SD_FORMAT`] can have on this adapter (WebGPU guarantees 1
/// and 4; more need the adapter-specific format features, which [`crate::Gpu`] requests).
pub fn map_sample_counts(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Vec<u32> {
    if !sd_format_available(device) {
        return Vec::new();
    }
    if !device
        .features()
        .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
    {
        return vec![1, 4];
    }
    let flags = adapter.get_texture_format_features(SD_FORMAT).flags;
    MAP_SAMPLE_COUNTS
        .into_iter()
        .filter(|&n| flags.sample_count_supported(n))
        .collect()
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

/// The WGSL that binds a layout's maps for reading (the source group from `SOURCE_SD_MAPS` on) and
/// `sd_load`, for `read.wgsl` and `unpack.wgsl`.
pub(crate) fn bindings_wgsl(layout: SdLayout) -> String {
    let (ty, index) = if layout.samples_per_map == 1 {
        ("texture_depth_2d", "0u")
    } else {
        ("texture_depth_multisampled_2d", "s")
    };
    let mut src = format!(
        "// Generated by src/sources/stochastic_depth/mod.rs.\nconst SD_MAPS: u32 = {}u;\nconst SD_SAMPLES: u32 = {}u;\n",
        layout.maps, layout.samples_per_map
    );
    for m in 0..layout.maps {
        src += &format!(
            "@group(GROUP_SOURCE) @binding(SOURCE_SD_MAPS + {m}u) var sd_map_{m}: {ty};\n"
        );
    }
    src += "fn sd_load(map: u32, pixel: vec2<u32>, s: u32) -> f32 {\n    switch map {\n";
    for m in 1..layout.maps {
        src +=
            &format!("        case {m}u: {{ return textureLoad(sd_map_{m}, pixel, {index}); }}\n");
    }
    src += &format!(
        "        default: {{ return textureLoad(sd_map_0, pixel, {index}); }}\n    }}\n}}\n"
    );
    src
}

/// Source-group layout entries of a reader of maps laid out as `layout`.
pub(crate) fn read_layout_entries(layout: SdLayout) -> Vec<wgpu::BindGroupLayoutEntry> {
    std::iter::once(entry::uniform(SOURCE_SD_NEAR))
        .chain(
            (0..layout.maps)
                .map(|m| entry::depth_texture(SOURCE_SD_MAPS + m, layout.samples_per_map > 1)),
        )
        .collect()
}

/// What the adapter allows for the map, for `obscura info` and messages.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SdCapabilities {
    /// [`SD_FORMAT`], or "unavailable" on this device.
    pub format: String,
    /// Samples per pixel one map target can have.
    pub map_sample_counts: Vec<u32>,
    /// `stochastic_depth.samples` values accepted (larger ones as stacked maps).
    pub sample_counts: Vec<u32>,
    /// The same with their layouts: e.g. "1, 4, 8 (2 maps of 4), 16 (4 maps of 4)".
    pub layouts: String,
}

impl SdCapabilities {
    /// What `adapter` and `device` allow: the map's format and the sample counts and layouts.
    pub fn of(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Self {
        let per_map = map_sample_counts(adapter, device);
        Self {
            format: if sd_format_available(device) {
                format!("{SD_FORMAT:?}")
            } else {
                "unavailable".to_string()
            },
            sample_counts: crate::settings::SD_SAMPLE_COUNTS
                .into_iter()
                .filter(|&s| SdLayout::plan(s, &per_map).is_some())
                .collect(),
            layouts: SdLayout::describe_supported(&per_map),
            map_sample_counts: per_map,
        }
    }
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
    _pad: [u32; 2],
}

/// One stochastic depth map (S samples per pixel, possibly several stacked targets) for a
/// framebuffer size, with its raster pipelines.
pub struct StochasticDepthMap {
    layout: SdLayout,
    settings: StochasticDepthSettings,
    separation: f32,
    scene: GpuScene,
    maps: Vec<wgpu::Texture>,
    /// Per map: the view rendered into, and the depth-only view readers sample.
    targets: Vec<wgpu::TextureView>,
    read_views: Vec<wgpu::TextureView>,
    /// `SdRaster` per map (the seeds differ); its first member `near` is what readers bind.
    params: Vec<wgpu::Buffer>,
    camera: wgpu::Buffer,
    lut: wgpu::Buffer,
    /// Back faces culled / kept.
    pipelines: [wgpu::RenderPipeline; 2],
    /// Empties the map (or its requested pixels) before each frame, and writes the stencil.
    reset: SdReset,
    /// The fragment shader reads the request mask itself ([`SdMask::Discard`]).
    discards: bool,
    /// Keep every layer ([`StochasticDepthMap::keeping_every_layer`]).
    all_layers: bool,
    /// Timing name of the raster (`sd_map`; the reset's is its own).
    timing_name: &'static str,
}

impl StochasticDepthMap {
    /// Targets for a `width`×`height` framebuffer (guard band included). `separation`: how far
    /// behind the first layer a fragment must lie to count as hidden. `requested`: rasterise only
    /// where an SD-request mask is set ([`StochasticDepthMap::render`]), by stencil or discard.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        settings: &StochasticDepthSettings,
        separation: f32,
        (width, height): (u32, u32),
        scene: &GpuScene,
        requested: Option<SdMask>,
    ) -> Result<Self, Error> {
        let stenciled = requested == Some(SdMask::Stencil);
        let format = SD_FORMAT;
        if !sd_format_available(device) {
            return Err(Error::Input(format!(
                "adapter '{}' has no {format:?} depth-stencil format (wgpu feature DEPTH32FLOAT_STENCIL8), which the stochastic depth map needs: use another adapter or a technique without a stochastic depth map ({})",
                adapter.get_info().name,
                crate::technique::names_where(|r| !r.needs().stochastic_depth_map)
            )));
        }
        let supported = map_sample_counts(adapter, device);
        let layout = SdLayout::plan(settings.samples, &supported).ok_or_else(|| {
            crate::SettingsError::Unsupported {
                field: "stochastic_depth.samples",
                value: settings.samples.to_string(),
                adapter: adapter.get_info().name,
                reason: format!(
                    "{format:?} multisamples {supported:?} per target here; use one of {}",
                    SdLayout::describe_supported(&supported)
                ),
            }
        })?;
        // `AoSettings::validate` checked α already; this guards direct use of the map.
        let alpha = settings.alpha();
        if !(alpha > 0.0 && alpha <= 1.0) {
            return Err(crate::SettingsError::Invalid {
                field: "stochastic_depth.alpha",
                value: alpha.to_string(),
                rule: "must be in (0, 1], e.g. 0.2",
            }
            .into());
        }
        let maps: Vec<wgpu::Texture> = (0..layout.maps)
            .map(|m| {
                device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(&format!("stochastic depth map {m}")),
                    size: wgpu::Extent3d {
                        width,
                        height,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: layout.samples_per_map,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
            })
            .collect();
        let params = (0..layout.maps)
            .map(|_| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("sd raster params"),
                    size: std::mem::size_of::<SdRaster>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let source = shaders::with_common(
            &[
                shaders::MATERIAL,
                shaders::HASH,
                shaders::VERTEX_NORMAL,
                shaders::GBUFFER,
            ],
            shaders::STOCHASTIC_DEPTH_MAP,
        );
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("stochastic depth"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let multisample = wgpu::MultisampleState {
            count: layout.samples_per_map,
            ..Default::default()
        };
        // Stenciled: draw only where the reset wrote this frame's stencil value.
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
        let pipelines = [Some(wgpu::Face::Back), None].map(|cull_mode| {
            ScenePipeline {
                layout: None,
                module: &module,
                cull_mode,
                depth_stencil: wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: stencil_test.clone(),
                    bias: Default::default(),
                },
                multisample,
                vertex: "vs_main",
                fragment: if requested == Some(SdMask::Discard) {
                    "fs_stochastic_depth_requested"
                } else {
                    "fs_stochastic_depth"
                },
                targets: &[],
            }
            .create(device)
        });
        let scope = match requested {
            None => ResetScope::All,
            Some(mask) => ResetScope::Requested {
                stencil: mask == SdMask::Stencil,
            },
        };
        let reset = SdReset::new(device, format, multisample, (width, height), scope);
        Ok(Self {
            layout,
            settings: *settings,
            separation,
            scene: scene.clone(),
            targets: maps
                .iter()
                .map(|m| m.create_view(&Default::default()))
                .collect(),
            read_views: maps
                .iter()
                .map(|m| {
                    m.create_view(&wgpu::TextureViewDescriptor {
                        aspect: wgpu::TextureAspect::DepthOnly,
                        ..Default::default()
                    })
                })
                .collect(),
            maps,
            params,
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sd camera"),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            lut: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sd mask table"),
                contents: bytemuck::cast_slice(&mask_table(layout.samples_per_map)),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            pipelines,
            reset,
            discards: requested == Some(SdMask::Discard),
            all_layers: false,
            timing_name: "sd_map",
        })
    }

    /// This map storing every layer, the first visible one included: no first layer is skipped
    /// (the multi-view schedule's second view, seed 001 §3.4). The `first_layer` given to
    /// [`StochasticDepthMap::render`] is then not read.
    pub fn keeping_every_layer(mut self) -> Self {
        self.all_layers = true;
        self
    }

    /// This map timed as `reset` and `map` instead of `sd_reset` and `sd_map`.
    pub fn timed_as(mut self, reset: &'static str, map: &'static str) -> Self {
        self.reset.name = reset;
        self.timing_name = map;
        self
    }

    /// How its S samples per pixel are laid out over stacked targets.
    pub fn layout(&self) -> SdLayout {
        self.layout
    }

    /// The framebuffer size the map covers.
    pub fn size(&self) -> (u32, u32) {
        (self.maps[0].width(), self.maps[0].height())
    }

    /// The camera of the coming frame; `frame` (0: none) changes the seed of the coverage masks
    /// per frame under temporal accumulation.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView, frame: u32) {
        queue.write_buffer(
            &self.camera,
            0,
            bytemuck::bytes_of(&CameraUniform::new(view)),
        );
        for (m, buffer) in self.params.iter().enumerate() {
            let raster = SdRaster {
                near: view.near,
                alpha: self.settings.alpha(),
                separation: self.separation,
                // Stacked maps: independent seeds; frames (under temporal accumulation) too.
                seed: crate::hash::pcg_hash(
                    self.settings.seed
                        ^ (m as u32).wrapping_mul(0x9e37_79b9)
                        ^ frame.wrapping_mul(0x85eb_ca6b),
                ),
                samples: self.layout.samples_per_map,
                all_layers: u32::from(self.all_layers),
                _pad: [0; 2],
            };
            queue.write_buffer(buffer, 0, bytemuck::bytes_of(&raster));
        }
    }

    /// Rasterise the map behind `first_layer` (the G-buffer's linear depth). With `request` (a
    /// map made with `requested`), only the pixels whose u32 in it is non-zero; the map is then
    /// defined only there (elsewhere it holds what earlier frames left). Timings: `sd_reset`
    /// (emptying the map, and for a stenciled map the copy of the request mask into the stencil)
    /// and `sd_map`, summed over stacked maps.
    pub fn render(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        first_layer: &wgpu::TextureView,
        request: Option<&wgpu::Buffer>,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        let stencil_value = self.reset.next_frame();
        for (target, params) in self.targets.iter().zip(&self.params) {
            self.reset.encode(
                device,
                encoder,
                target,
                request,
                stencil_value,
                profiler.as_deref_mut(),
            );
            let mut extra = vec![
                wgpu::BindingResource::TextureView(first_layer),
                params.as_entire_binding(),
                self.lut.as_entire_binding(),
            ];
            if self.discards {
                extra.extend(request.map(|r| r.as_entire_binding()));
            }
            let resources = scene_resources(&self.camera, &self.scene, extra);
            let bind_groups = self.pipelines.each_ref().map(|p| {
                crate::gpu::bind_group(
                    device,
                    "stochastic depth",
                    &p.get_bind_group_layout(0),
                    &resources,
                )
            });
            let map_name = self.timing_name;
            let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(map_name));
            let mut pass = begin(encoder, target, timestamp_writes);
            pass.set_stencil_reference(stencil_value);
            if let Some(p) = profiler.as_deref_mut() {
                p.begin_fragments(&mut pass, map_name);
            }
            draw_scene(
                &mut pass,
                &self.pipelines,
                &bind_groups,
                &whole_ranges(self.scene.cull_ranges()),
            );
            if let Some(p) = profiler.as_deref() {
                p.end_fragments(&mut pass);
            }
        }
    }

    /// What a reader binds in the source group: the uniform whose first float is `near`, then one
    /// depth-only view per map, matching [`bindings_wgsl`] and [`read_layout_entries`].
    pub(crate) fn read_resources(&self) -> Vec<(u32, wgpu::BindingResource<'_>)> {
        std::iter::once((SOURCE_SD_NEAR, self.params[0].as_entire_binding()))
            .chain(
                self.read_views
                    .iter()
                    .zip(SOURCE_SD_MAPS..)
                    .map(|(v, b)| (b, wgpu::BindingResource::TextureView(v))),
            )
            .collect()
    }
}

/// A render pass on one map's depth-stencil target, keeping what earlier passes wrote (the map
/// is emptied by [`SdReset`], not by a clear).
pub(crate) fn begin<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &wgpu::TextureView,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    fn keep<V>() -> wgpu::Operations<V> {
        wgpu::Operations {
            load: wgpu::LoadOp::Load,
            store: wgpu::StoreOp::Store,
        }
    }
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("stochastic depth"),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: target,
            depth_ops: Some(keep()),
            stencil_ops: Some(keep()),
        }),
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_table_lists_every_subset_by_popcount() {
        for s in MAP_SAMPLE_COUNTS {
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
    fn layouts_stack_only_where_one_target_cannot() {
        let lavapipe = [1, 4];
        let plan = |s, sup: &[u32]| SdLayout::plan(s, sup).map(|l| (l.maps, l.samples_per_map));
        assert_eq!(plan(4, &lavapipe), Some((1, 4)));
        assert_eq!(plan(8, &lavapipe), Some((2, 4)));
        assert_eq!(plan(16, &lavapipe), Some((4, 4)));
        assert_eq!(plan(2, &lavapipe), None);
        assert_eq!(plan(1, &lavapipe), Some((1, 1)));
        let full = [1, 2, 4, 8];
        assert_eq!(plan(8, &full), Some((1, 8)));
        assert_eq!(plan(16, &full), Some((2, 8)));
        assert_eq!(plan(2, &full), Some((1, 2)));
        assert_eq!(plan(3, &full), None);
        assert_eq!(
            SdLayout::describe_supported(&lavapipe),
            "1, 4, 8 (2 maps of 4), 16 (4 maps of 4)"
        );
    }
}
