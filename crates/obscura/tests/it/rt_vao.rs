//! RT-VAO (seed 000 §3.6): the `vao` kernel whose occluded samples trace their camera ray through
//! the BVH on the GPU. It must equal the `vao` ground-truth model and remove the halo.

use crate::common::*;
use obscura::bvh::Bvh;
use obscura::estimators::vao;
use obscura::metrics::{summarize, Image};
use obscura::reference::ground_truth::{render_reference, ReferenceSettings, Tracer};
use obscura::scene::{self, Scene};
use obscura::{AoSettings, Renderer, Technique};

/// Raw (unblurred) AO of `technique`, the ground truth, the G-buffer's visible depth, and which
/// pixels may legitimately differ: a sample within 1e-3 px of a pixel edge, or a pixel or one of
/// its samples' pixels whose first surface the rasteriser and a ray see differently (an edge
/// within the rasteriser's sub-pixel precision).
fn render(
    scene: &Scene,
    technique: Technique,
    w: u32,
    h: u32,
    band: u32,
) -> (Vec<f32>, Vec<f32>, Vec<f32>, Vec<bool>) {
    let gpu = gpu();
    let mut settings = AoSettings {
        technique,
        ..Default::default()
    };
    settings.blur.enabled = false;
    let mut r = Renderer::new(&gpu, scene, &settings, w, h, band).unwrap();
    r.render(&scene.cameras[0].camera, None).unwrap();
    let ao = r.read_ao().unwrap();
    let view = *r.view().unwrap();
    let g = r.read_gbuffer().unwrap();
    let bvh = Bvh::build(scene);
    let reference = render_reference(scene, &bvh, view, &ReferenceSettings::default(), &|_| {});
    let oracle = obscura::reference::cpu_vao::cpu_vao(&g, &view.screen(), &settings.vao);
    let tracer = Tracer::new(scene, &bvh, view);
    let screen = view.screen();
    // Framebuffer pixels whose first surface differs between the rasteriser and a ray (silhouette
    // edges within the rasteriser's sub-pixel precision, or the neighbouring triangle).
    let (fw, fh) = (screen.full_width(), screen.full_height());
    let mismatch: Vec<bool> = (0..fh)
        .flat_map(|y| (0..fw).map(move |x| glam::UVec2::new(x, y)))
        .map(|p| {
            let i = (p.y * fw + p.x) as usize;
            match tracer.first_surface(&tracer.camera_ray(p.as_vec2() + 0.5)) {
                None => g.depth[i] > 0.0,
                Some(s) => {
                    (s.depth - g.depth[i]).abs() > 1e-4 * s.depth
                        || (view.view_matrix().transform_vector3(s.normal) - g.normals[i]).length()
                            > 1e-2
                }
            }
        })
        .collect();
    let kernel = vao::kernel(&settings.vao);
    let exempt = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .enumerate()
        .map(|(i, (x, y))| {
            let px = glam::UVec2::new(x + band, y + band);
            let z = g.depth_at(px);
            if oracle.ambiguous[i] || mismatch[(px.y * fw + px.x) as usize] {
                return true;
            }
            if z <= 0.0 {
                return false;
            }
            // Any sample reading a mismatched pixel.
            let pos = screen.pixel_to_view(px.as_vec2() + 0.5, z);
            let frame = vao::PixelFrame::new(pos, g.normals[(px.y * fw + px.x) as usize], x, y);
            kernel
                .iter()
                .filter_map(|&k| frame.column(k, &settings.vao, &screen))
                .any(|c| {
                    let (p, _) = vao::snap(c.px, &screen);
                    mismatch[(p.y * fw + p.x) as usize]
                })
        })
        .collect();
    (ao, reference, g.visible_depth(band), exempt)
}

#[test]
fn rt_vao_equals_the_vao_ground_truth() {
    for name in ["stairs", "colonnade", "layers"] {
        let scene = scene::builtin(name).unwrap();
        let (ao, reference, _, exempt) = render(&scene, Technique::RtVao, 160, 96, 16);
        let (mut worst, mut exempted) = (0.0f32, 0);
        for (i, (&a, &r)) in ao.iter().zip(&reference).enumerate() {
            let diff = (a - r).abs();
            if diff > 1.0 / 255.0 {
                assert!(exempt[i], "{name}: pixel {i}: rt-vao {a} vs reference {r}");
                exempted += 1;
            } else {
                worst = worst.max(diff);
            }
        }
        println!("{name}: max |rt-vao - reference| {worst:.2e}, {exempted} exempt pixels differ");
        assert!(
            exempted * 100 <= ao.len(),
            "{name}: {exempted} pixels differ"
        );
    }
}

#[test]
fn rt_vao_removes_the_halo() {
    let scene = scene::builtin("stairs").unwrap();
    let (w, h) = (160, 96);
    let halo = |technique| {
        let (ao, reference, depth, _) = render(&scene, technique, w, h, 16);
        let img = |d: &[f32]| Image::new(w as usize, h as usize, d.to_vec().leak()).unwrap();
        summarize(&img(&ao), &img(&reference), &img(&depth), 4, 0.1).unwrap()
    };
    let (vao, rt) = (halo(Technique::Vao), halo(Technique::RtVao));
    println!(
        "bright halo: vao {:.4}, rt-vao {:.6}",
        vao.halo_bright, rt.halo_bright
    );
    assert!(vao.halo_bright > 0.01);
    assert!(
        rt.halo_bright * 10.0 <= vao.halo_bright,
        "vao {vao:?} rt-vao {rt:?}"
    );
}

#[test]
fn ray_traced_techniques_need_the_scene() {
    let gpu = gpu();
    let settings = AoSettings {
        technique: Technique::RtVao,
        ..Default::default()
    };
    let screen = obscura::ScreenGeometry {
        width: 32,
        height: 32,
        guard_band: 0,
        tan_half_fov: glam::Vec2::ONE,
        orthographic: false,
    };
    let err =
        obscura::AmbientOcclusion::new(&gpu, &settings, screen, obscura::SceneResources::default())
            .err()
            .unwrap();
    // The error names what is missing and where it goes.
    assert!(
        err.to_string().contains("triangles") && err.to_string().contains("SceneResources"),
        "{err}"
    );
}

#[test]
fn rt_vao_equals_vao_on_a_height_field() {
    // Nothing is hidden: tracing finds no surface the depth buffer lacks.
    let mut scene = height_field();
    let mut cam = camera(glam::Vec3::new(0.0, 7.0, 0.0), glam::Vec3::ZERO, 30.0);
    cam.up = glam::Vec3::NEG_Z;
    scene.cameras.push(obscura::scene::NamedCamera {
        name: "top".into(),
        camera: cam,
    });
    let (vao, _, _, _) = render(&scene, Technique::Vao, 96, 64, 32);
    let (rt, _, _, _) = render(&scene, Technique::RtVao, 96, 64, 32);
    let worst = max_abs_diff(&vao, &rt);
    assert!(worst <= 1e-5, "max |vao - rt-vao| {worst}");
}

#[test]
fn renderers_sharing_a_bvh_cache_build_it_once_and_render_the_same() {
    // compare, path, bench and the viewer make one renderer per technique through one cache.
    let gpu = gpu();
    let scene = scene::builtin("stairs").unwrap();
    let camera = scene.cameras[0].camera;
    let cache = obscura::bvh::BvhCache::new();
    let render = |technique: Technique, cache: Option<&obscura::bvh::BvhCache>| {
        let settings = AoSettings {
            technique,
            ..Default::default()
        };
        let mut r = match cache {
            Some(c) => Renderer::with_bvh_cache(&gpu, &scene, &settings, 80, 48, 8, c),
            None => Renderer::new(&gpu, &scene, &settings, 80, 48, 8),
        }
        .unwrap();
        r.render(&camera, None).unwrap();
        r.read_ao().unwrap()
    };
    let rt_vao = render(Technique::RtVao, Some(&cache));
    // A technique without rays leaves the cache alone.
    render(Technique::Vao, Some(&cache));
    let rt_svao = render(Technique::RtSvao, Some(&cache));
    assert_eq!(cache.builds(), 1);
    assert_eq!(rt_vao, render(Technique::RtVao, None));
    assert_eq!(rt_svao, render(Technique::RtSvao, None));
}
