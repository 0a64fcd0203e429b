//! Our own frame: a loaded scene rasterised into a G-buffer, then [`AmbientOcclusion`].

use super::{AmbientOcclusion, FrameTextures, OwnGBuffer};
use crate::bvh::{gpu::GpuBvh, BvhCache};
use crate::error::{Error, SettingsError};
use crate::gpu::{read_texture_f32, read_texture_f32_async, FrameTimings, Gpu, PassProfiler};
use crate::raster::GBufferImage;
use crate::raster::{gbuffer::GBuffer, gpu_scene::GpuScene};
use crate::scene::{Camera, Scene};
use crate::settings::AoSettings;
use crate::sources::SceneResources;
use crate::view::FrameView;
use glam::Vec3;

/// A warning where the technique's AO radius (world units, as the papers and engines take it:
/// metres for glTF files) is far off the scene's extent: below 1/300 of its bounding box's
/// diagonal, as for a scene modelled in centimetres or millimetres (then the AO only darkens
/// thin creases; a 3.6 m room in centimetres with HBAO+'s 1 is at 1/358), or above the whole
/// diagonal (then every surface occludes every other). The built-in scenes and the shared real
/// scenes, in metres, lie between 1/110 (Sibenik's 53 m) and 1/3.5 (the Cornell box) at the
/// defaults; a scene in metres wider than 150 m is warned about too, harmlessly.
pub fn radius_scale_warning(settings: &AoSettings, scene: &Scene) -> Option<String> {
    let diagonal = scene.bounds().diagonal();
    let radius = settings.radius();
    if scene.triangles.is_empty() || !(diagonal > 0.0 && diagonal.is_finite()) {
        return None;
    }
    let (name, field) = (&scene.name, settings.radius_field());
    if radius * 300.0 < diagonal {
        Some(format!(
            "the AO radius {field} = {radius} is {:.3} % of scene '{name}''s extent ({diagonal:.0} \
             units corner to corner): if the scene is in centimetres or millimetres, the AO will \
             only darken thin creases; set {field} in the scene's units (e.g. {} for {radius} m \
             in centimetres), or convert every length of the settings with AoSettings::scaled \
             (the command line's --units cm)",
            100.0 * radius / diagonal,
            radius * 100.0,
        ))
    } else if radius > diagonal {
        Some(format!(
            "the AO radius {field} = {radius} is larger than scene '{name}' ({diagonal:.3} units \
             corner to corner): every surface occludes every other; set {field} in the scene's \
             units (e.g. {:.3}, a tenth of its extent)",
            diagonal * 0.1,
        ))
    } else {
        None
    }
}

/// Renders AO images of one scene at one size. Owns what it uses (a [`Gpu`] is a cheap handle on
/// a shared device), so a viewer or a game loop can keep it.
pub struct Renderer {
    gpu: Gpu,
    scene: GpuScene,
    /// The scene's BVH, for techniques that trace rays.
    bvh: Option<GpuBvh>,
    near: f32,
    width: u32,
    height: u32,
    guard_band: u32,
    settings: AoSettings,
    gbuffer: GBuffer,
    ao: Option<AmbientOcclusion>,
    view: Option<FrameView>,
}

impl Renderer {
    /// Upload `scene` and allocate targets for a visible `width`×`height` plus `guard_band`.
    /// Builds the scene's BVH when the technique traces rays; to build it once for several
    /// renderers of one scene, use [`Renderer::with_bvh_cache`].
    pub fn new(
        gpu: &Gpu,
        scene: &Scene,
        settings: &AoSettings,
        width: u32,
        height: u32,
        guard_band: u32,
    ) -> Result<Self, Error> {
        Self::with_bvh_cache(
            gpu,
            scene,
            settings,
            width,
            height,
            guard_band,
            &BvhCache::new(),
        )
    }

    /// [`Renderer::new`] taking the scene's BVH from `bvh` (built there on first use): renderers
    /// of several techniques, or made again after a settings change, then share one build.
    pub fn with_bvh_cache(
        gpu: &Gpu,
        scene: &Scene,
        settings: &AoSettings,
        width: u32,
        height: u32,
        guard_band: u32,
        bvh: &BvhCache,
    ) -> Result<Self, Error> {
        // Pipelines an earlier constructor on this Gpu made are reused (gpu::memo).
        let _kept = gpu.keeping();
        settings.validate()?;
        gpu.check_backend()?;
        if let Some(warning) = scene
            .check_extent()
            .map_err(|e| Error::Input(e.to_string()))?
        {
            log::warn!("{warning}");
        }
        if let Some(warning) = radius_scale_warning(settings, scene) {
            log::warn!("{warning}");
        }
        if width == 0 || height == 0 {
            return Err(Error::Input(format!(
                "image size {width}x{height} is empty: use e.g. --size 1280x720"
            )));
        }
        let (fw, fh) = (
            u64::from(width) + 2 * u64::from(guard_band),
            u64::from(height) + 2 * u64::from(guard_band),
        );
        let max = u64::from(gpu.summary.max_texture_dimension_2d);
        if fw > max || fh > max {
            return Err(Error::Input(format!(
                "image size {width}x{height} with a {guard_band} px guard band needs a {fw}x{fh} \
                 framebuffer, over this adapter's limit of {max}x{max} ('{}'): use a smaller --size or --guard-band",
                gpu.summary.name
            )));
        }
        let limits = gpu.device.limits();
        let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, scene, &limits)?;
        let near = crate::view::near_plane(scene);
        let needs = settings.technique.needs();
        let peel = needs.second_layer.then_some(settings.peel_separation);
        let keep_triangles = settings.technique.row().proves_rays_blocked();
        let gbuffer = GBuffer::new(
            &gpu.device,
            (fw as u32, fh as u32),
            peel,
            keep_triangles,
            &gpu_scene,
        )
        .map_err(|e| sized(e.into(), gpu, settings, (width, height), guard_band))?;
        let bvh = needs
            .bvh
            .then(|| GpuBvh::new(&gpu.device, &bvh.get(scene), scene))
            .transpose()?;
        gpu.check_errors()?;
        // The rasteriser named, so that `settings()` says which one `auto` chose (for the
        // larger need, a map limited to requested pixels: one setting for every row).
        let mut settings = *settings;
        settings.stochastic_depth.rasterizer = crate::sources::stochastic_depth::resolve_rasterizer(
            &gpu.adapter,
            &gpu.device,
            settings.stochastic_depth.rasterizer,
            true,
        );
        Ok(Self {
            gpu: gpu.clone(),
            bvh,
            scene: gpu_scene,
            near,
            width,
            height,
            guard_band,
            settings,
            gbuffer,
            ao: None,
            view: None,
        })
    }

    /// Renders one frame of a frame loop (`render --frames`, `path`, `bench`'s warm-up, the
    /// viewer, Python's `render(frames=)`). Under a time budget (`hemisphere.time_budget`) the
    /// frame is timed with GPU timestamps and the next frame's ray budget follows its time
    /// ([`crate::TimeBudget`]); its timings are returned then, else `None`. A time budget on an
    /// adapter without timestamp queries is an error naming the field and the fix.
    pub fn render_frame(&mut self, camera: &Camera) -> Result<Option<FrameTimings>, Error> {
        let settings = &self.settings;
        if !(settings.hemisphere.time_budget > 0.0 && settings.ray_budget_active()) {
            self.render(camera, None)?;
            return Ok(None);
        }
        let gpu = self.gpu.clone();
        let mut profiler = PassProfiler::new(&gpu, 1).map_err(|e| {
            Error::Settings(SettingsError::Unsupported {
                field: "hemisphere.time_budget",
                value: settings.hemisphere.time_budget.to_string(),
                adapter: gpu.summary.name.clone(),
                reason: format!(
                    "it follows the GPU's timestamps ({e}): use hemisphere.ray_budget (rays a \
                     frame, --ray-budget) instead"
                ),
            })
        })?;
        self.render(camera, Some(&mut profiler))?;
        let timings = profiler.read(&gpu)?.pop().unwrap_or_default();
        if let Some(ao) = &self.ao {
            ao.follow_time_budget(&timings)?;
        }
        Ok(Some(timings))
    }

    /// Record and submit one frame seen from `camera`.
    pub fn render(
        &mut self,
        camera: &Camera,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let view = FrameView::new(*camera, self.width, self.height, self.guard_band, self.near);
        if self.ao.as_ref().map(|ao| ao.screen()) != Some(view.screen()) {
            self.ao = Some(
                AmbientOcclusion::new(
                    &self.gpu,
                    &self.settings,
                    view.screen(),
                    self.scene_resources(),
                )
                .map_err(|e| {
                    let size = (self.width, self.height);
                    sized(e, &self.gpu, &self.settings, size, self.guard_band)
                })?,
            );
            self.gpu.check_errors()?;
        }
        let ao = self.ao.as_ref().expect("created above");
        ao.set_camera(&self.gpu.queue, &view);
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        self.gbuffer.render(
            device,
            &self.gpu.queue,
            &mut encoder,
            &self.scene,
            &view,
            profiler.as_deref_mut(),
        );
        ao.encode_with_gbuffer(
            &mut encoder,
            self.frame_textures(),
            OwnGBuffer {
                z: Some(self.gbuffer.z_buffer()),
                visible_triangles: self.gbuffer.visible_triangles(),
            },
            profiler.as_deref_mut(),
        )?;
        if let Some(p) = profiler {
            p.end_frame(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
        self.view = Some(view);
        self.gpu.check_errors()?;
        Ok(())
    }

    /// What the technique's row needs of the scene, for [`AmbientOcclusion`].
    fn scene_resources(&self) -> SceneResources<'_> {
        let needs = self.settings.technique.needs();
        SceneResources {
            scene: needs.triangles.then_some(&self.scene),
            bvh: self.bvh.as_ref(),
        }
    }

    /// The G-buffer's textures as the AO passes read them.
    fn frame_textures(&self) -> FrameTextures<'_> {
        FrameTextures {
            depth: &self.gbuffer.depth,
            normals: &self.gbuffer.normals,
            second_layer: self.gbuffer.second_layer(),
        }
    }

    /// The raster stochastic depth map of the last frame, if its technique has one.
    #[cfg(test)]
    pub(crate) fn stochastic_depth_map(
        &self,
    ) -> Option<&crate::sources::stochastic_depth::StochasticDepthMap> {
        self.ao.as_ref()?.source.stochastic_depth()
    }

    fn last_ao(&self) -> Result<&AmbientOcclusion, Error> {
        self.ao
            .as_ref()
            .ok_or_else(|| Error::Input("nothing rendered yet: call render() first".into()))
    }

    /// The settings this renderer was made with, `stochastic_depth.rasterizer` resolved
    /// (`auto` is reported as the rasteriser it chose on this device).
    pub fn settings(&self) -> &AoSettings {
        &self.settings
    }

    /// The guard band in pixels on every side of the visible image.
    pub fn guard_band(&self) -> u32 {
        self.guard_band
    }

    /// The G-buffer of the last frame as textures, for a viewer's display pass (no read-back):
    /// linear depth (`R32Float`, 0 = background) and view-space normals (`Rgba16Float`), both over
    /// the whole framebuffer, guard band included.
    pub fn gbuffer_textures(&self) -> (&wgpu::Texture, &wgpu::Texture) {
        (&self.gbuffer.depth, &self.gbuffer.normals)
    }

    /// Record the base-colour pass of the last frame's view into `encoder` and return its target
    /// (framebuffer-sized `Rgba8UnormSrgb`, white where nothing is): [`Self::read_albedo`]
    /// without the read-back, for a viewer's composite.
    pub fn encode_albedo(&self, encoder: &mut wgpu::CommandEncoder) -> &wgpu::Texture {
        self.gbuffer
            .render_albedo(&self.gpu.device, encoder, &self.scene);
        &self.gbuffer.albedo
    }

    /// The last frame's view (camera, sizes, projection).
    pub fn view(&self) -> Option<&FrameView> {
        self.view.as_ref()
    }

    /// Final AO of the visible image, row-major.
    pub fn read_ao(&self) -> Result<Vec<f32>, Error> {
        pollster::block_on(self.read_ao_async())
    }

    /// [`Self::read_ao`] without blocking (the only way in a browser).
    pub async fn read_ao_async(&self) -> Result<Vec<f32>, Error> {
        Ok(read_texture_f32_async(&self.gpu, self.last_ao()?.output(), 1).await?)
    }

    /// Rays of the last frame whose BVH traversal overflowed its stack (0 without rays).
    pub fn read_stack_overflows(&self) -> Result<u32, Error> {
        self.last_ao()?.read_stack_overflows()
    }

    /// Two-phase techniques: the per-pixel masks of samples that needed rays (last frame).
    pub fn read_sample_masks(&self) -> Result<Option<Vec<u32>>, Error> {
        self.last_ao()?.read_sample_masks()
    }

    /// The AO passes of the last frame (their settings, screen and read-backs).
    pub fn ambient_occlusion(&self) -> Option<&AmbientOcclusion> {
        self.ao.as_ref()
    }

    /// `sd-vao`, `sd-svao` (and the ray-traced map's rows, one layer per reservoir slot): every
    /// sample layer of the last frame's stochastic depth map
    /// (framebuffer-sized, linear depth, 0 = empty; layer `m · samples_per_map + s` is sample `s`
    /// of map `m`).
    pub fn read_stochastic_depth(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        self.last_ao()?.read_stochastic_depth()
    }

    /// [`AmbientOcclusion::read_stochastic_depth_as_written`] of the last frame.
    pub fn read_stochastic_depth_as_written(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        self.last_ao()?.read_stochastic_depth_as_written()
    }

    /// `ray-sd-vao`, `ray-sd-vao-full`: the hits each pixel's ray handled in the last frame (see
    /// [`AmbientOcclusion::read_ray_sd_hits`]).
    pub fn read_ray_sd_hits(&self) -> Result<Option<Vec<u32>>, Error> {
        self.last_ao()?.read_ray_sd_hits()
    }

    /// [`AmbientOcclusion::read_sd_intervals`] of the last frame.
    pub fn read_sd_intervals(&self) -> Result<Option<Vec<Option<[f32; 2]>>>, Error> {
        self.last_ao()?.read_sd_intervals()
    }

    /// `sd-svao`: the last frame's SD-request mask (framebuffer-sized, non-zero = requested).
    pub fn read_sd_requests(&self) -> Result<Option<Vec<u32>>, Error> {
        self.last_ao()?.read_sd_requests()
    }

    /// The ray-traced map's size in texels and guard band in texels (see
    /// [`AmbientOcclusion::ray_sd_map_size`]) of the last frame's technique.
    pub fn ray_sd_map_size(
        &self,
    ) -> Result<Option<crate::sources::ray_stochastic_depth::RaySdMapSize>, Error> {
        Ok(self.last_ao()?.ray_sd_map_size())
    }

    /// The size and band of the last frame's SD-request mask (see
    /// [`AmbientOcclusion::sd_request_map_size`]).
    pub fn sd_request_map_size(
        &self,
    ) -> Result<Option<crate::sources::ray_stochastic_depth::RaySdMapSize>, Error> {
        Ok(self.last_ao()?.sd_request_map_size())
    }

    /// Two-phase stochastic depth: the last frame's SD-request mask as phase 1 wrote it (see
    /// [`AmbientOcclusion::read_sd_request_texels`]; the ray-traced map's guard band included).
    pub fn read_sd_request_texels(&self) -> Result<Option<Vec<u32>>, Error> {
        self.last_ao()?.read_sd_request_texels()
    }

    /// `sao`, `pyramid-hbao`: the last frame's depth pyramid, levels 1 … L − 1 (see
    /// [`AmbientOcclusion::read_depth_pyramid`]).
    pub fn read_depth_pyramid(&self) -> Result<Option<Vec<Vec<f32>>>, Error> {
        self.last_ao()?.read_depth_pyramid()
    }

    /// The estimator's debug image of the last frame's view and G-buffer, row-major over the
    /// visible image ([`crate::technique::TechniqueRow::estimator_debug_image`] says what it
    /// shows); None for rows without one. Builds the pipelines it needs each call: for tools.
    pub fn read_estimator_debug(&self) -> Result<Option<Vec<f32>>, Error> {
        let view = self
            .view
            .ok_or_else(|| Error::Input("nothing rendered yet: call render() first".into()))?;
        if self
            .settings
            .technique
            .row()
            .estimator_debug_image()
            .is_none()
        {
            return Ok(None);
        }
        let needs = self.settings.technique.needs();
        let resources = SceneResources {
            scene: needs.triangles.then_some(&self.scene),
            bvh: self.bvh.as_ref(),
        };
        // At full resolution: the debug image shows the estimator's own quantities per pixel.
        let settings = AoSettings {
            resolution: crate::settings::Resolution::Full,
            ..self.settings
        };
        let ao = AmbientOcclusion::build(&self.gpu, &settings, view.screen(), resources, true)?;
        ao.set_camera(&self.gpu.queue, &view);
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        ao.encode(
            &mut encoder,
            FrameTextures {
                depth: &self.gbuffer.depth,
                normals: &self.gbuffer.normals,
                second_layer: self.gbuffer.second_layer(),
            },
            None,
        )?;
        self.gpu.queue.submit([encoder.finish()]);
        Ok(Some(read_texture_f32(&self.gpu, ao.raw_output(), 1)?))
    }

    /// `bent_normals`: the last frame's bent normals, row-major over the visible image (see
    /// [`AmbientOcclusion::bent_normals`] for the encoding); None without `bent_normals`.
    pub fn read_bent_normals(&self) -> Result<Option<Vec<[f32; 4]>>, Error> {
        self.last_ao()?.read_bent_normals()
    }

    /// The filtered AO before the upsample at half resolution (the half-size image; with
    /// `resolution = "full"` the same as [`Self::read_ao`]).
    pub fn read_work_ao(&self) -> Result<Vec<f32>, Error> {
        Ok(read_texture_f32(
            &self.gpu,
            self.last_ao()?.work_output(),
            1,
        )?)
    }

    /// The kernel's AO before the blur (at half resolution: the half-size image, see
    /// [`AmbientOcclusion::work_screen`]).
    pub fn read_raw_ao(&self) -> Result<Vec<f32>, Error> {
        Ok(read_texture_f32(
            &self.gpu,
            self.last_ao()?.raw_output(),
            1,
        )?)
    }

    /// The second depth layer of the whole framebuffer (`vao-dual` only), row-major.
    pub fn read_second_layer(&self) -> Result<Option<Vec<f32>>, Error> {
        match self.gbuffer.second_layer() {
            Some(t) => Ok(Some(read_texture_f32(&self.gpu, t, 1)?)),
            None => Ok(None),
        }
    }

    /// Its G-buffer (tests).
    #[cfg(test)]
    pub(crate) fn gbuffer(&self) -> &crate::raster::gbuffer::GBuffer {
        &self.gbuffer
    }

    /// Depth and normals of the whole framebuffer.
    pub fn read_gbuffer(&self) -> Result<GBufferImage, Error> {
        pollster::block_on(self.read_gbuffer_async())
    }

    /// [`Self::read_gbuffer`] without blocking (the only way in a browser).
    pub async fn read_gbuffer_async(&self) -> Result<GBufferImage, Error> {
        let depth = read_texture_f32_async(&self.gpu, &self.gbuffer.depth, 1).await?;
        let bytes =
            crate::gpu::read_texture_bytes_async(&self.gpu, &self.gbuffer.normals, 8).await?;
        let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
        let normals = halves
            .chunks_exact(4)
            .map(|c| Vec3::new(c[0].to_f32(), c[1].to_f32(), c[2].to_f32()))
            .collect();
        Ok(GBufferImage {
            width: self.gbuffer.depth.width(),
            height: self.gbuffer.depth.height(),
            depth,
            normals,
        })
    }

    /// Base colour (sRGB-encoded RGBA8) of the visible image of the last frame (rendered now, by
    /// its own pass: the frame itself does not write it).
    pub fn read_albedo(&self) -> Result<Vec<[u8; 4]>, Error> {
        pollster::block_on(self.read_albedo_async())
    }

    /// [`Self::read_albedo`] without blocking (the only way in a browser).
    pub async fn read_albedo_async(&self) -> Result<Vec<[u8; 4]>, Error> {
        self.last_ao()?;
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        self.gbuffer
            .render_albedo(&self.gpu.device, &mut encoder, &self.scene);
        self.gpu.queue.submit([encoder.finish()]);
        let full = crate::gpu::read_texture_bytes_async(&self.gpu, &self.gbuffer.albedo, 4).await?;
        let fw = self.gbuffer.albedo.width() as usize;
        let g = self.guard_band as usize;
        let mut out = Vec::with_capacity((self.width * self.height) as usize);
        for y in 0..self.height as usize {
            let row = (y + g) * fw + g;
            out.extend(
                full[row * 4..(row + self.width as usize) * 4]
                    .chunks_exact(4)
                    .map(|c| [c[0], c[1], c[2], c[3]]),
            );
        }
        Ok(out)
    }
}

/// A buffer too large for the device ([`crate::gpu::GpuError::BufferTooLarge`]) as one message
/// that also names the image size and the technique, and what to change; other errors as they
/// are.
fn sized(
    e: Error,
    gpu: &Gpu,
    settings: &AoSettings,
    (width, height): (u32, u32),
    guard_band: u32,
) -> Error {
    match e {
        Error::Gpu(e @ crate::gpu::GpuError::BufferTooLarge { .. }) => Error::Input(format!(
            "image size {width}x{height} (with its {guard_band} px guard band) with technique \
             '{}' on '{}': {e}: use a smaller --size, or another technique",
            settings.technique.name(),
            gpu.summary.name
        )),
        e => e,
    }
}

#[cfg(test)]
mod tests {
    use super::radius_scale_warning;
    use crate::scene;
    use crate::settings::AoSettings;
    use crate::technique::Technique;

    /// The built-in scenes (metres) at every technique's default radius draw no warning; the
    /// same scene in centimetres or at a hundredth of its size does, naming the technique's
    /// radius field (a real settings path).
    #[test]
    fn a_radius_far_off_the_scenes_scale_is_warned_about() {
        let paths = AoSettings::field_paths();
        for name in scene::builtin_names() {
            let metres = scene::builtin(name).unwrap();
            for technique in Technique::all() {
                let settings = AoSettings {
                    technique,
                    ..AoSettings::default()
                };
                assert_eq!(
                    radius_scale_warning(&settings, &metres),
                    None,
                    "{name} {technique:?}"
                );
                let field = settings.radius_field();
                assert!(paths.iter().any(|p| p == field), "{field}");
                for (scale, says) in [(100.0, "centimetres"), (0.01, "larger than")] {
                    let mut scaled = metres.clone();
                    scaled.positions.iter_mut().for_each(|p| *p *= scale);
                    let warning = radius_scale_warning(&settings, &scaled)
                        .unwrap_or_else(|| panic!("{name} ×{scale} {technique:?}: no warning"));
                    assert!(
                        warning.contains(field) && warning.contains(says),
                        "{warning}"
                    );
                }
            }
        }
    }
}
