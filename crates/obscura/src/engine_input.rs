//! Taking what an engine has: its hardware depth buffer and projection matrix, and its normals
//! if any, turned into the linear depth and view-space normals every AO pass reads
//! ([`FrameTextures`]) by compute passes (`shaders/engine_input/`): one when the engine gives
//! normals, two when they are reconstructed from the depth (which needs every neighbour's
//! linear depth first).
//!
//! ```text
//! engine depth (Depth32Float/…, NDC z) ─┐  projection⁻¹   ┌─> linear depth (R32Float)
//!                                        └────────────────┤
//! engine normals (view/world, or none) ───────────────────┴─> view-space normals (Rgba16Float)
//! ```
//!
//! Any projection wgpu can rasterise with works: perspective or orthographic, reversed-Z or not,
//! finite or infinite far plane ([`ScreenGeometry::from_projection`] reads the geometry from the
//! same matrix). The depth values must be NDC z in [0, 1], as wgpu (and Vulkan, D3D, Metal)
//! store them; an OpenGL-style matrix (`perspective_rh_gl`, z in [−1, 1]) is not one wgpu draws
//! with. Without normals they are reconstructed from the depth (see `normals.wgsl`).
//!
//! The depth (and normals) must cover the guard-banded framebuffer, `width + 2·guard_band` by
//! `height + 2·guard_band` pixels, rendered with a projection whose frustum covers it too: AO
//! samples near the image's edges read depth in the band, and without it they read nothing there.
//! An engine keeps its visible framing by widening the field of view with
//! [`crate::view::guard_banded_fov_y`] and using the framebuffer's aspect ratio, then shows the centre
//! `width × height` pixels (the AO output is already that size). A guard band of 0 works with the
//! engine's own projection unchanged, at the cost of darker or brighter AO near the edges.

use crate::bindings::{self, entry};
use crate::error::Error;
use crate::frame::{check_float_texture, check_texture};
use crate::gpu::Gpu;
use crate::pipeline::FrameTextures;
use crate::view::ScreenGeometry;
use glam::Mat4;
use wgpu::util::DeviceExt;

pub mod arrays;

/// How the engine's normals are stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NormalEncoding {
    /// The components as they are (a float format).
    #[default]
    Signed,
    /// `n * 0.5 + 0.5`, as in unorm targets (`Rgba8Unorm`, `Rgb10a2Unorm`).
    Biased,
}

/// The engine's normals, if it has them.
#[derive(Clone, Copy, Debug)]
pub enum EngineNormals<'a> {
    /// None: reconstructed from the depth buffer.
    Reconstruct,
    /// View-space normals (right-handed, camera looking down −Z), xyz of the texture.
    View {
        /// The engine's normal target over the framebuffer, any float or unorm format; need
        /// not be unit length (normalised, and turned to face the camera).
        texture: &'a wgpu::Texture,
        /// How the texture stores the components.
        encoding: NormalEncoding,
    },
    /// World-space normals with the view matrix (world to view) that turns them.
    World {
        /// The engine's normal target over the framebuffer, any float or unorm format.
        texture: &'a wgpu::Texture,
        /// How the texture stores the components.
        encoding: NormalEncoding,
        /// World to view space (the camera's view matrix); only its linear part turns the normals.
        view_from_world: Mat4,
    },
}

/// One frame as the engine has it. Every texture covers the guard-banded framebuffer
/// (`ScreenGeometry::full_width` × `full_height`), is single-sampled and has
/// `TEXTURE_BINDING` usage.
#[derive(Clone, Copy, Debug)]
pub struct EngineFrame<'a> {
    /// The hardware depth buffer: `Depth32Float`, `Depth24Plus`, `Depth24PlusStencil8`
    /// (its depth aspect), `Depth16Unorm`, or `R32Float` holding NDC z.
    pub depth: &'a wgpu::Texture,
    /// The projection the depth was rendered with (the one given to
    /// [`ScreenGeometry::from_projection`]).
    pub projection: Mat4,
    /// The engine's normals, or [`EngineNormals::Reconstruct`] to derive them from the depth.
    pub normals: EngineNormals<'a>,
}

/// The passes and the textures they write, for one screen geometry.
///
/// ```no_run
/// # fn frame(gpu: &obscura::Gpu, depth: &wgpu::Texture, projection: glam::Mat4)
/// #     -> Result<(), obscura::Error> {
/// use obscura::*;
/// // `projection` covers the 2048×1208 framebuffer: the game's 60° widened by
/// // guard_banded_fov_y(60f32.to_radians(), 1080, 64), aspect 2048 / 1208.
/// let screen = ScreenGeometry::from_projection(projection, 1920, 1080, 64)?;
/// let input = EngineInput::new(gpu, screen);
/// let ao = AmbientOcclusion::new(gpu, &AoSettings::default(), screen, SceneResources::default())?;
/// // Every frame, after the engine's depth prepass:
/// let mut encoder = gpu.device.create_command_encoder(&Default::default());
/// let frame = EngineFrame { depth, projection, normals: EngineNormals::Reconstruct };
/// let textures = input.encode(&mut encoder, &frame)?;
/// ao.encode(&mut encoder, textures, None)?;
/// gpu.queue.submit([encoder.finish()]);
/// // ao.output(): R32Float, the visible size, 1 = unoccluded.
/// # Ok(()) }
/// ```
pub struct EngineInput {
    gpu: Gpu,
    screen: ScreenGeometry,
    view: wgpu::Buffer,
    depth_layout: wgpu::BindGroupLayout,
    depth_pipeline: wgpu::ComputePipeline,
    /// Normals reconstructed from the linear depth (`normals.wgsl`'s `main`).
    reconstruct_layout: wgpu::BindGroupLayout,
    reconstruct_pipeline: wgpu::ComputePipeline,
    /// The engine's normals and depth in one pass (`main_fused`).
    fused_layout: wgpu::BindGroupLayout,
    /// Indexed by [`EngineInput::fused_pipeline_index`]: space × encoding.
    fused_pipelines: Vec<wgpu::ComputePipeline>,
    linear_depth: wgpu::Texture,
    normals: wgpu::Texture,
    /// `EngineDepth` and `EngineNormals` of the WGSL, written by each encode.
    depth_params: wgpu::Buffer,
    normal_params: wgpu::Buffer,
}

/// `EngineDepth` of depth.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct DepthParams {
    clip_to_view: [[f32; 4]; 4],
    far_clear: f32,
    _pad: [f32; 3],
}

const DEPTH_FORMATS: [wgpu::TextureFormat; 5] = [
    wgpu::TextureFormat::Depth32Float,
    wgpu::TextureFormat::Depth24Plus,
    wgpu::TextureFormat::Depth24PlusStencil8,
    wgpu::TextureFormat::Depth16Unorm,
    wgpu::TextureFormat::R32Float,
];

impl EngineInput {
    /// The passes for `screen` (e.g. from [`ScreenGeometry::from_projection`]).
    pub fn new(gpu: &Gpu, screen: ScreenGeometry) -> Self {
        // Pipelines an earlier constructor on this Gpu made are reused (gpu::memo).
        let _kept = gpu.keeping();
        let device = &gpu.device;
        let view = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine input view"),
            contents: bytemuck::bytes_of(&screen.uniform()),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let storage = entry::storage_texture;
        let depth_layout = bindings::layout(
            device,
            "engine depth",
            &[
                entry::uniform(0),
                entry::uniform(1),
                entry::texture(2),
                storage(3, wgpu::TextureFormat::R32Float),
            ],
        );
        let normal_format = crate::raster::gbuffer::NORMAL_FORMAT;
        let reconstruct_layout = bindings::layout(
            device,
            "engine normals reconstructed",
            &[
                entry::uniform(1),
                entry::texture(2),
                storage(4, normal_format),
            ],
        );
        let fused_layout = bindings::layout(
            device,
            "engine depth and normals",
            &[
                entry::uniform(0),
                entry::uniform(1),
                entry::texture(3),
                storage(4, normal_format),
                entry::uniform(5),
                entry::texture(6),
                storage(7, wgpu::TextureFormat::R32Float),
            ],
        );
        let pipeline = |label: &str,
                        layout: &wgpu::BindGroupLayout,
                        source: &str,
                        entry: &str,
                        constants: &[(&str, f64)]| {
            let module = crate::gpu::checked_module(
                device,
                label,
                &crate::shaders::with_common(
                    &[crate::shaders::VIEW, crate::shaders::ENGINE_LINEAR_DEPTH],
                    source,
                ),
            );
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &[Some(layout)],
                immediate_size: 0,
            });
            crate::gpu::entry_pipeline(
                device,
                label,
                &module,
                entry,
                constants,
                Some(&pipeline_layout),
            )
        };
        let orthographic = ("ORTHOGRAPHIC", f64::from(u8::from(screen.orthographic)));
        let depth_pipeline = pipeline(
            "engine depth",
            &depth_layout,
            crate::shaders::ENGINE_DEPTH,
            "main",
            &[],
        );
        let reconstruct_pipeline = pipeline(
            "engine normals reconstructed",
            &reconstruct_layout,
            crate::shaders::ENGINE_NORMALS,
            "main",
            &[orthographic],
        );
        let fused_pipelines = (0..4)
            .map(|i| {
                let (world, biased) = (i / 2, i % 2);
                pipeline(
                    "engine depth and normals",
                    &fused_layout,
                    crate::shaders::ENGINE_NORMALS,
                    "main_fused",
                    &[
                        ("WORLD", f64::from(world)),
                        ("BIASED", f64::from(biased)),
                        orthographic,
                    ],
                )
            })
            .collect();
        let uniform = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let target = |label, format| {
            crate::gpu::texture_2d(
                device,
                label,
                screen.full_width(),
                screen.full_height(),
                format,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        Self {
            gpu: gpu.clone(),
            screen,
            view,
            depth_layout,
            depth_pipeline,
            reconstruct_layout,
            reconstruct_pipeline,
            fused_layout,
            fused_pipelines,
            linear_depth: target("engine linear depth", wgpu::TextureFormat::R32Float),
            normals: target("engine normals", crate::raster::gbuffer::NORMAL_FORMAT),
            depth_params: uniform("engine depth params", std::mem::size_of::<DepthParams>()),
            normal_params: uniform("engine normals params", std::mem::size_of::<Mat4>()),
        }
    }

    /// The fused pipeline for the engine's normals (none for `Reconstruct`).
    fn fused_pipeline_index(normals: &EngineNormals) -> Option<usize> {
        let (world, encoding) = match normals {
            EngineNormals::Reconstruct => return None,
            EngineNormals::View { encoding, .. } => (0, *encoding),
            EngineNormals::World { encoding, .. } => (1, *encoding),
        };
        Some(2 * world + usize::from(encoding == NormalEncoding::Biased))
    }

    /// Record the passes for `frame`; the returned textures go to
    /// [`crate::AmbientOcclusion::encode`] in the same encoder. The frame's matrices are written
    /// to the queue (as `set_camera` does): one `encode` per submission. A texture of the wrong
    /// size, format, sample count or usage, or a projection that does not match the screen
    /// geometry, is an error naming it (nothing is recorded then).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &EngineFrame,
    ) -> Result<FrameTextures<'_>, Error> {
        let device = &self.gpu.device;
        check_texture(&self.screen, "engine depth", frame.depth, &DEPTH_FORMATS)?;
        let from_matrix = ScreenGeometry::from_projection(
            frame.projection,
            self.screen.width,
            self.screen.height,
            self.screen.guard_band,
        )?;
        let close = (from_matrix.tan_half_fov - self.screen.tan_half_fov)
            .abs()
            .max_element()
            <= 1e-4 * self.screen.tan_half_fov.max_element();
        if !close || from_matrix.orthographic != self.screen.orthographic {
            return Err(Error::Input(format!(
                "EngineFrame::projection describes {from_matrix:?}, but this EngineInput was made \
                 for {:?}: make a new EngineInput when the projection changes",
                self.screen
            )));
        }
        let normals_texture = match frame.normals {
            EngineNormals::Reconstruct => None,
            EngineNormals::View { texture, .. } | EngineNormals::World { texture, .. } => {
                Some(texture)
            }
        };
        if let Some(t) = normals_texture {
            check_float_texture(&self.screen, "engine normals", t)?;
        }
        let p = frame.projection;
        // Reversed-Z maps farther points to smaller depths: perspective when the constant term
        // of clip z is positive, orthographic when its z scale is.
        let reversed = if self.screen.orthographic {
            p.z_axis.z > 0.0
        } else {
            p.w_axis.z > 0.0
        };
        let params = DepthParams {
            clip_to_view: p.inverse().to_cols_array_2d(),
            far_clear: if reversed { 0.0 } else { 1.0 },
            _pad: [0.0; 3],
        };
        let queue = &self.gpu.queue;
        queue.write_buffer(&self.depth_params, 0, bytemuck::bytes_of(&params));
        let view_from_world = match frame.normals {
            EngineNormals::World {
                view_from_world, ..
            } => view_from_world,
            _ => Mat4::IDENTITY,
        };
        queue.write_buffer(
            &self.normal_params,
            0,
            bytemuck::cast_slice(&view_from_world.to_cols_array()),
        );
        let depth_in = frame.depth.create_view(&wgpu::TextureViewDescriptor {
            aspect: if frame.depth.format().has_depth_aspect() {
                wgpu::TextureAspect::DepthOnly
            } else {
                wgpu::TextureAspect::All
            },
            ..Default::default()
        });
        let linear = self.linear_depth.create_view(&Default::default());
        let normals_out = self.normals.create_view(&Default::default());
        let normals_in = normals_texture.map(|t| t.create_view(&Default::default()));
        let groups =
            crate::frame::workgroups_32x8(self.screen.full_width(), self.screen.full_height());
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("engine input"),
            timestamp_writes: None,
        });
        let texture = wgpu::BindingResource::TextureView;
        match (Self::fused_pipeline_index(&frame.normals), &normals_in) {
            (Some(index), Some(normals_in)) => {
                let group = bindings::group(
                    device,
                    "engine depth and normals",
                    &self.fused_layout,
                    &[
                        (0, self.normal_params.as_entire_binding()),
                        (1, self.view.as_entire_binding()),
                        (3, texture(normals_in)),
                        (4, texture(&normals_out)),
                        (5, self.depth_params.as_entire_binding()),
                        (6, texture(&depth_in)),
                        (7, texture(&linear)),
                    ],
                );
                pass.set_pipeline(&self.fused_pipelines[index]);
                pass.set_bind_group(0, &group, &[]);
                pass.dispatch_workgroups(groups.0, groups.1, groups.2);
            }
            _ => {
                let depth_group = bindings::group(
                    device,
                    "engine depth",
                    &self.depth_layout,
                    &[
                        (0, self.depth_params.as_entire_binding()),
                        (1, self.view.as_entire_binding()),
                        (2, texture(&depth_in)),
                        (3, texture(&linear)),
                    ],
                );
                let normals_group = bindings::group(
                    device,
                    "engine normals reconstructed",
                    &self.reconstruct_layout,
                    &[
                        (1, self.view.as_entire_binding()),
                        (2, texture(&linear)),
                        (4, texture(&normals_out)),
                    ],
                );
                pass.set_pipeline(&self.depth_pipeline);
                pass.set_bind_group(0, &depth_group, &[]);
                pass.dispatch_workgroups(groups.0, groups.1, groups.2);
                pass.set_pipeline(&self.reconstruct_pipeline);
                pass.set_bind_group(0, &normals_group, &[]);
                pass.dispatch_workgroups(groups.0, groups.1, groups.2);
            }
        }
        drop(pass);
        Ok(FrameTextures {
            depth: &self.linear_depth,
            normals: &self.normals,
            second_layer: None,
        })
    }

    /// The screen geometry these passes were made for.
    pub fn screen(&self) -> ScreenGeometry {
        self.screen
    }
}
