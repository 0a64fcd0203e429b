//! Ground-truth AO computed from the triangles (never from a depth buffer), on the CPU with the
//! SAH BVH of [`crate::bvh`], one rayon task per image row.
//!
//! Two models:
//! - [`ReferenceModel::Vao`]: the quantity VAO estimates with nothing hidden (seed 000 §3.6,
//!   Fig. 6; docs/AUTHORS_CODE.md §1.6). The same kernel, rotation pattern, R/τ/exponent as the
//!   `vao` technique, but each sample's occluder is every surface the camera ray through the
//!   sample's pixel crosses, not only the first: the sample's visibility is the minimum of the
//!   per-hit visibilities. Heights are measured exactly as the kernel measures them, so on a scene
//!   with a single depth layer the technique and this reference agree.
//! - [`ReferenceModel::VaoMean`]: the `vao` model averaged over all 16 rotations of the 4×4
//!   pattern: what a VAO technique converges to when its pattern turns every frame (temporal
//!   accumulation, issue 13), free of the pattern's per-pixel noise. 16 times the `vao` model's
//!   rays.
//! - [`ReferenceModel::Hemisphere`]: classic AO, the fraction of cosine-weighted rays from the
//!   surface point (geometric normal, small offset) that hit nothing within R (optionally with the
//!   linear falloff W(t) = max(0, 1 − t/R)), `spp` rays per pixel (1024 by default, as Pyramid
//!   HBAO's Blender reference, seed 004 §4), stratified by a Hammersley set with a seeded
//!   per-pixel Cranley–Patterson rotation.

use crate::bvh::{Bvh, HitAction, Ray};
use crate::estimators::vao::{column_visibility, kernel, Accumulator, Column, PixelFrame};
use crate::scene::Scene;
use crate::settings::VaoSettings;
use crate::view::FrameView;
use glam::{Mat4, UVec2, Vec2, Vec3};
use rayon::prelude::*;
use std::f32::consts::TAU;
use std::fmt;
use std::str::FromStr;

/// Which quantity a ground-truth image holds (the module documentation describes both).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ReferenceModel {
    /// `vao`: the VAO kernel with every surface along each sample's camera ray as occluder
    /// (seed 000 §3.6): what the `vao` techniques estimate with nothing hidden.
    Vao,
    /// `vao-mean`: the `vao` model averaged over the 16 rotations of its 4×4 pattern (the
    /// pattern's noise averaged out, as temporal accumulation averages it).
    VaoMean,
    /// `hemisphere`: the fraction of cosine-weighted rays from the surface that hit nothing
    /// within R.
    Hemisphere,
}

impl ReferenceModel {
    /// Its name on the command line and in reports (`vao`, `hemisphere`).
    pub fn name(self) -> &'static str {
        match self {
            ReferenceModel::Vao => "vao",
            ReferenceModel::VaoMean => "vao-mean",
            ReferenceModel::Hemisphere => "hemisphere",
        }
    }
}

impl fmt::Display for ReferenceModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ReferenceModel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "vao" => Ok(ReferenceModel::Vao),
            "vao-mean" => Ok(ReferenceModel::VaoMean),
            "hemisphere" => Ok(ReferenceModel::Hemisphere),
            _ => Err(format!(
                "unknown reference model '{s}': use vao, vao-mean or hemisphere"
            )),
        }
    }
}

/// Everything a reference image depends on (also the cache key's content).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceSettings {
    /// Which quantity to compute.
    pub model: ReferenceModel,
    /// The VAO parameters: the `vao` model's kernel; `radius` is also the hemisphere's R.
    pub vao: VaoSettings,
    /// Hemisphere rays per pixel.
    pub spp: u32,
    /// Hemisphere: weight hits by W(t) = max(0, 1 − t/R) instead of counting them fully.
    pub falloff: bool,
    /// Seed of the hemisphere's per-pixel rotations.
    pub seed: u64,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        Self {
            model: ReferenceModel::Vao,
            vao: VaoSettings::default(),
            spp: 1024,
            falloff: false,
            seed: 0,
        }
    }
}

impl ReferenceSettings {
    /// Rejects `spp` 0 and VAO parameters [`crate::AoSettings::validate`] rejects, with a message
    /// naming the value.
    pub fn validate(&self) -> Result<(), String> {
        if self.spp == 0 {
            return Err(
                "--spp 0: the hemisphere reference needs at least 1 ray per pixel (default 1024)"
                    .into(),
            );
        }
        let s = crate::settings::AoSettings {
            vao: self.vao,
            ..Default::default()
        };
        s.validate().map_err(|e| e.to_string())
    }

    /// Rays per pixel as reports state them: `spp` for the hemisphere model, `None` for the
    /// vao models (which trace every sample column exactly).
    pub fn reported_spp(&self) -> Option<u32> {
        (self.model == ReferenceModel::Hemisphere).then_some(self.spp)
    }

    /// Rays traced per visible pixel with geometry (for rays/s figures).
    pub fn rays_per_pixel(&self) -> u64 {
        match self.model {
            ReferenceModel::Vao => 1 + u64::from(self.vao.samples),
            ReferenceModel::VaoMean => 1 + 16 * u64::from(self.vao.samples),
            ReferenceModel::Hemisphere => 1 + u64::from(self.spp),
        }
    }
}

/// The camera and the BVH, everything a ray needs.
pub struct Tracer<'a> {
    /// The scene the BVH was built from.
    pub scene: &'a Scene,
    /// The BVH over `scene`.
    pub bvh: &'a Bvh,
    /// The camera, image size and guard band of the frame.
    pub view: FrameView,
    camera_to_world: Mat4,
}

/// The first surface along a camera ray.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// Linear view depth (= the ray parameter for camera rays built by [`Tracer::camera_ray`]).
    pub depth: f32,
    /// The hit point, world space.
    pub world: Vec3,
    /// The normal AO is computed around ([`Scene::surface_normal`]: the face normal, or the shading
    /// normal where the scene uses them) on the ray origin's side, world space.
    pub normal: Vec3,
}

impl<'a> Tracer<'a> {
    /// A tracer for `view` of `scene` through `bvh` (built from `scene`).
    pub fn new(scene: &'a Scene, bvh: &'a Bvh, view: FrameView) -> Self {
        Self {
            scene,
            bvh,
            view,
            camera_to_world: view.view_matrix().inverse(),
        }
    }

    /// The camera ray through framebuffer pixel coordinates `px`, with `dir` scaled so that the
    /// ray parameter equals linear view depth.
    pub fn camera_ray(&self, px: Vec2) -> Ray {
        let dir = self.view.screen().pixel_to_view(px, 1.0);
        Ray::new(
            self.view.camera.eye,
            self.camera_to_world.transform_vector3(dir),
        )
    }

    /// Closest surface along `ray` beyond the near plane.
    pub fn first_surface(&self, ray: &Ray) -> Option<Surface> {
        let hit = self
            .bvh
            .closest_hit(self.scene, ray, self.view.near, f32::INFINITY)?;
        let normal = self
            .scene
            .surface_normal(hit.triangle, hit.u, hit.v, -ray.dir);
        Some(Surface {
            depth: hit.t,
            world: ray.at(hit.t),
            normal,
        })
    }

    fn to_view(&self, p: Vec3) -> Vec3 {
        self.view.view_matrix().transform_point3(p)
    }

    fn to_view_dir(&self, d: Vec3) -> Vec3 {
        self.view.view_matrix().transform_vector3(d)
    }
}

/// `vao` model AO of one visible pixel (`x`, `y`) whose first surface is `surface`.
pub fn vao_ao_at(t: &Tracer, surface: &Surface, x: u32, y: u32, s: &VaoSettings) -> f32 {
    vao_ao_at_counted(t, surface, x, y, s, 0).0
}

/// [`vao_ao_at`] with the pattern turned by `pattern_offset` entries (as the GPU turns it per
/// frame), and the number of sample rays it traced.
fn vao_ao_at_counted(
    t: &Tracer,
    surface: &Surface,
    x: u32,
    y: u32,
    s: &VaoSettings,
    pattern_offset: u32,
) -> (f32, u64) {
    let mut traced = 0;
    let screen = t.view.screen();
    let pixel = UVec2::new(x, y) + screen.guard_band;
    let pos = t.to_view(surface.world);
    // The pattern entry this pixel uses, as the (x % 4, y % 4) that names it.
    let entry = (x % 4 + 4 * (y % 4) + pattern_offset) % 16;
    let frame = PixelFrame::new(pos, t.to_view_dir(surface.normal), entry % 4, entry / 4);
    let mut acc = Accumulator::default();
    for k in kernel(s) {
        let Some(column) = frame.column(k, s, &screen) else {
            continue;
        };
        // Unlike the depth-buffer kernel, samples beyond the framebuffer are traced too.
        let sample_pixel = column.px.floor();
        let free = if sample_pixel == pixel.as_vec2() {
            column.start - column.end
        } else {
            traced += 1;
            min_visibility_along(t, &frame, &column, sample_pixel + 0.5, s)
        };
        acc.add(&column, free);
    }
    (acc.finish(s), traced)
}

/// Minimum per-hit visibility of `column` over every surface along the camera ray through `px`.
fn min_visibility_along(
    t: &Tracer,
    frame: &PixelFrame,
    column: &Column,
    px: Vec2,
    s: &VaoSettings,
) -> f32 {
    let full = column.start - column.end;
    let ray = t.camera_ray(px);
    // Along this ray the view-space point is `t · dir_view`, so the kernel's height is affine in
    // the ray parameter: height(t) = a + b·t. Only heights in (end, halo end) can lower the
    // visibility; elsewhere it is full. That bounds the interval to trace.
    let dir_view = t.view.screen().pixel_to_view(px, 1.0);
    let a = frame.height(column, Vec3::ZERO);
    let b = frame.height_slope(dir_view);
    let halo_end = (1.0 + s.thickness) * s.radius + full;
    let (mut t_min, mut t_max) = (t.view.near, f32::INFINITY);
    if b.abs() > 1e-12 {
        let (t0, t1) = ((column.end - a) / b, (halo_end - a) / b);
        t_min = t_min.max(t0.min(t1));
        t_max = t0.max(t1);
    }
    if t_min.partial_cmp(&t_max) != Some(std::cmp::Ordering::Less) {
        return full;
    }
    let mut visibility = full;
    t.bvh.for_each_hit(t.scene, &ray, t_min, t_max, |hit| {
        let height = a + b * hit.t;
        visibility = visibility.min(column_visibility(s, height, column.start, column.end));
        if visibility <= 0.0 {
            HitAction::Stop
        } else {
            HitAction::Continue
        }
    });
    visibility
}

/// Hammersley point `i` of `n` (stratified in both dimensions).
fn hammersley(i: u32, n: u32) -> Vec2 {
    Vec2::new(
        (i as f32 + 0.5) / n as f32,
        crate::estimators::vao::van_der_corput(i),
    )
}

pub use crate::hash::pcg_hash;

/// Per-pixel Cranley–Patterson rotation in [0,1)² from the seed and the pixel.
pub fn pixel_rotation_2d(seed: u64, x: u32, y: u32) -> Vec2 {
    let h1 = pcg_hash((seed as u32) ^ pcg_hash(x.wrapping_add(pcg_hash(y))));
    let h2 = pcg_hash(h1);
    Vec2::new((h1 >> 8) as f32, (h2 >> 8) as f32) / (1u32 << 24) as f32
}

/// How the hemisphere model samples one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HemisphereRays {
    /// Rays longer than this do not occlude.
    pub radius: f32,
    /// Rays for the point (the Hammersley set's size).
    pub spp: u32,
    /// Weight hits by W(t) = max(0, 1 − t/R).
    pub falloff: bool,
    /// Cranley–Patterson rotation of the Hammersley set, in [0,1)².
    pub rotation: Vec2,
}

/// Hemisphere AO at world point `p` with geometric normal `n`: the fraction of `rays.spp`
/// cosine-weighted rays unoccluded within `rays.radius` (with falloff: 1 − mean W(t)).
pub fn hemisphere_ao_at(scene: &Scene, bvh: &Bvh, p: Vec3, n: Vec3, rays: &HemisphereRays) -> f32 {
    let HemisphereRays {
        radius,
        spp,
        falloff,
        rotation,
    } = *rays;
    let n = n.normalize();
    let (tangent, bitangent) = crate::estimators::vao::orthonormal_basis(n);
    // Offset along the normal against self-intersection, relative to R (and to the magnitude of
    // the position, where f32 spacing grows).
    let origin = p + n * (1e-4 * radius).max(1e-6 * p.abs().max_element());
    let mut occlusion = 0.0f64;
    for i in 0..spp {
        let u = (hammersley(i, spp) + rotation).fract();
        // Cosine-weighted: a uniform point on the unit disc lifted to the hemisphere (Malley).
        let (r, phi) = (u.x.sqrt(), TAU * u.y);
        let local = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt());
        let dir = tangent * local.x + bitangent * local.y + n * local.z;
        let ray = Ray::new(origin, dir);
        if falloff {
            if let Some(hit) = bvh.closest_hit(scene, &ray, 0.0, radius) {
                occlusion += f64::from((1.0 - hit.t / radius).max(0.0));
            }
        } else if bvh.any_hit(scene, &ray, 0.0, radius) {
            occlusion += 1.0;
        }
    }
    (1.0 - occlusion / f64::from(spp)) as f32
}

/// The reference image of the visible `view.width × view.height` (row-major, 1 = unoccluded,
/// background 1). `progress(rows_done)` is called from worker threads as rows finish.
pub fn render_reference(
    scene: &Scene,
    bvh: &Bvh,
    view: FrameView,
    settings: &ReferenceSettings,
    progress: &(dyn Fn(u32) + Sync),
) -> Vec<f32> {
    render_reference_counted(scene, bvh, view, settings, progress).0
}

/// [`render_reference`] that also returns how many rays it traced (primary rays, plus one per
/// hemisphere ray or per traced VAO sample column).
pub fn render_reference_counted(
    scene: &Scene,
    bvh: &Bvh,
    view: FrameView,
    settings: &ReferenceSettings,
    progress: &(dyn Fn(u32) + Sync),
) -> (Vec<f32>, u64) {
    let tracer = Tracer::new(scene, bvh, view);
    let done = std::sync::atomic::AtomicU32::new(0);
    let rays = std::sync::atomic::AtomicU64::new(0);
    let count = |n: u64| {
        rays.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    };
    let (w, h) = (view.width, view.height);
    let image = (0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            let row: Vec<f32> = (0..w)
                .map(|x| {
                    let px = (UVec2::new(x, y) + view.guard_band).as_vec2() + 0.5;
                    count(1);
                    let Some(surface) = tracer.first_surface(&tracer.camera_ray(px)) else {
                        return 1.0;
                    };
                    match settings.model {
                        ReferenceModel::Vao => {
                            let (ao, traced) =
                                vao_ao_at_counted(&tracer, &surface, x, y, &settings.vao, 0);
                            count(traced);
                            ao
                        }
                        ReferenceModel::VaoMean => {
                            let mut sum = 0.0;
                            for offset in 0..16 {
                                let (ao, traced) = vao_ao_at_counted(
                                    &tracer,
                                    &surface,
                                    x,
                                    y,
                                    &settings.vao,
                                    offset,
                                );
                                count(traced);
                                sum += ao;
                            }
                            sum / 16.0
                        }
                        ReferenceModel::Hemisphere => {
                            count(u64::from(settings.spp));
                            hemisphere_ao_at(
                                scene,
                                bvh,
                                surface.world,
                                surface.normal,
                                &HemisphereRays {
                                    radius: settings.vao.radius,
                                    spp: settings.spp,
                                    falloff: settings.falloff,
                                    rotation: pixel_rotation_2d(settings.seed, x, y),
                                },
                            )
                        }
                    }
                })
                .collect();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            row
        })
        .collect();
    (image, rays.into_inner())
}
