//! The GPU BVH traversal (shaders/common/bvh.wgsl) against the CPU oracle, hit for hit.

use crate::common::*;
use glam::{Vec2, Vec3};
use obscura::bvh::gpu::{trace_batch, GpuBvh, QueryMode, QueryRay};
use obscura::bvh::{Bvh, Ray};
use obscura::raster::gpu_scene::GpuScene;
use obscura::scene::{self, Material, Scene};

/// Deterministic rays from each camera (or the bounds' corners) into the scene bounds.
fn rays_for(scene: &Scene, n: u32) -> Vec<QueryRay> {
    let b = scene.bounds();
    let mut eyes: Vec<Vec3> = scene.cameras.iter().map(|c| c.camera.eye).collect();
    if eyes.is_empty() {
        eyes.push(b.max + (b.max - b.min) * 0.5);
    }
    (0..n)
        .map(|i| {
            let f = |k: u32| ((i.wrapping_mul(7919) + k * 104_729) % 1000) as f32 / 1000.0;
            let eye = eyes[i as usize % eyes.len()];
            let target = b.min + (b.max - b.min) * Vec3::new(f(1), f(2), f(3));
            let (t_min, t_max) = if i % 3 == 0 {
                (0.0, f32::MAX)
            } else {
                (0.2 + f(4), 0.6 + 2.0 * f(5))
            };
            QueryRay {
                origin: eye.to_array(),
                t_min,
                dir: (target - eye).to_array(),
                t_max,
            }
        })
        .collect()
}

fn compare(scene: &Scene, rays: &[QueryRay]) -> (usize, usize) {
    let gpu = gpu();
    let bvh = Bvh::build(scene);
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, scene, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &bvh, scene).unwrap();
    let closest = trace_batch(&gpu, &gpu_scene, &gpu_bvh, rays, QueryMode::ClosestHit).unwrap();
    let all = trace_batch(&gpu, &gpu_scene, &gpu_bvh, rays, QueryMode::AllHits).unwrap();
    gpu.finish().unwrap();
    let (mut hits, mut edge_cases) = (0, 0);
    for (i, q) in rays.iter().enumerate() {
        let ray = Ray::new(Vec3::from(q.origin), Vec3::from(q.dir));
        let cpu_all = bvh.all_hits(scene, &ray, q.t_min, q.t_max);
        let (g, a) = (&closest[i], &all[i]);
        assert_eq!(g.stack_overflow, 0, "ray {i}: stack overflow");
        // A ray exactly through a shared edge or vertex: the CPU decides in f64, the GPU counts
        // both sides; such rays may differ by the triangles sharing that edge only.
        let on_edge = cpu_all
            .iter()
            .any(|h| h.u.min(h.v).min(1.0 - h.u - h.v).abs() < 1e-6);
        match bvh.closest_hit(scene, &ray, q.t_min, q.t_max) {
            None => assert!(g.t < 0.0 || on_edge, "ray {i}: GPU hit {g:?}, CPU none"),
            Some(c) => {
                hits += 1;
                assert!(g.t >= 0.0, "ray {i}: CPU hit {c:?}, GPU none");
                assert!(
                    (g.t - c.t).abs() <= 1e-5 * c.t.abs().max(1.0),
                    "ray {i}: t {} vs {}",
                    g.t,
                    c.t
                );
                if g.triangle != c.triangle {
                    // Ties: the GPU's triangle must be one the CPU hits at the same distance.
                    assert!(cpu_all
                        .iter()
                        .any(|h| h.triangle == g.triangle
                            && (h.t - c.t).abs() <= 1e-5 * c.t.max(1.0)));
                }
            }
        }
        let mut gpu_set: Vec<u32> = a.triangles[..(a.hit_count as usize).min(16)].to_vec();
        let mut cpu_set: Vec<u32> = cpu_all.iter().map(|h| h.triangle).collect();
        gpu_set.sort();
        cpu_set.sort();
        if a.hit_count as usize <= 16 && gpu_set != cpu_set {
            assert!(
                on_edge || a.hit_count as usize > cpu_set.len(),
                "ray {i}: GPU {gpu_set:?} vs CPU {cpu_set:?}"
            );
            edge_cases += 1;
        }
    }
    (hits, edge_cases)
}

#[test]
fn gpu_traversal_matches_cpu_on_builtin_scenes() {
    for name in ["stairs", "colonnade", "grass", "tower"] {
        let scene = scene::builtin(name).unwrap();
        let rays = rays_for(&scene, 2000);
        let (hits, edges) = compare(&scene, &rays);
        println!(
            "{name}: {hits} of {} rays hit, {edges} edge cases",
            rays.len()
        );
        assert!(hits > 500, "{name}: the rays must hit");
        assert!(edges * 100 <= rays.len(), "{name}: {edges} edge cases");
    }
}

#[test]
fn gpu_traversal_matches_cpu_on_a_random_soup() {
    let mut scene = quads("soup", &[]);
    scene.materials.push(Material {
        double_sided: true,
        ..Material::default()
    });
    let mut seed = 12345u32;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed as f32 / u32::MAX as f32
    };
    for t in 0..3000u32 {
        let c = Vec3::new(rnd(), rnd(), rnd()) * 10.0;
        let base = scene.positions.len() as u32;
        for _ in 0..3 {
            scene
                .positions
                .push(c + Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5));
            scene.uvs.push(Vec2::ZERO);
        }
        scene.triangles.push([base, base + 1, base + 2]);
        scene.triangle_materials.push(t % 2);
    }
    let rays = rays_for(&scene, 3000);
    let (hits, _) = compare(&scene, &rays);
    assert!(hits > 300);
}

#[test]
fn gpu_traversal_applies_the_alpha_test() {
    // A masked quad (left half transparent) 1 m before a wall: rays through the transparent half
    // must reach the wall, both on the GPU and the CPU.
    let scene = masked_quad_before_wall();
    let rays: Vec<QueryRay> = (0..64)
        .map(|i| QueryRay {
            origin: [0.0; 3],
            t_min: 0.0,
            dir: [(i as f32 + 0.5) / 64.0 - 0.5, 0.13, -1.0],
            t_max: f32::MAX,
        })
        .collect();
    compare(&scene, &rays);
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &scene, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &Bvh::build(&scene), &scene).unwrap();
    let closest = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &rays, QueryMode::ClosestHit).unwrap();
    // dir.z = -1, so t is the depth: 3 through the transparent left half, 2 on the right half.
    assert!(
        (closest[16].t - 3.0).abs() < 1e-4 && (closest[48].t - 2.0).abs() < 1e-4,
        "{:?} {:?}",
        closest[16].t,
        closest[48].t
    );
}

#[test]
fn the_smallest_trees_trace_as_on_the_cpu() {
    // One triangle (the root is a leaf: the wide tree's one node has one slot), one quad (two
    // triangles, one leaf or two), and no triangle at all (one node of unused slots).
    let mut one = quads("one triangle", &[]);
    for p in [
        Vec3::new(-1.0, -1.0, -2.0),
        Vec3::new(1.0, -1.0, -2.0),
        Vec3::new(0.0, 1.0, -2.0),
    ] {
        one.positions.push(p);
        one.uvs.push(Vec2::ZERO);
    }
    one.triangles.push([0, 1, 2]);
    one.triangle_materials.push(0);
    let quad = quads(
        "one quad",
        &[[
            Vec3::new(-1.0, -1.0, -2.0),
            Vec3::new(1.0, -1.0, -2.0),
            Vec3::new(1.0, 1.0, -2.0),
            Vec3::new(-1.0, 1.0, -2.0),
        ]],
    );
    let rays: Vec<QueryRay> = (0..16)
        .map(|i| QueryRay {
            origin: [0.0; 3],
            t_min: 0.0,
            dir: [
                (i as f32 - 7.5) / 6.0,
                ((i * 5) % 16) as f32 / 8.0 - 1.0,
                -1.0,
            ],
            t_max: f32::MAX,
        })
        .collect();
    let (hits, _) = compare(&one, &rays);
    assert!(hits > 0, "the triangle must be hit");
    let (hits, _) = compare(&quad, &rays);
    assert!(hits > 0, "the quad must be hit");
    let empty = quads("empty", &[]);
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &empty, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &Bvh::build(&empty), &empty).unwrap();
    for mode in [QueryMode::ClosestHit, QueryMode::AllHits] {
        let results = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &rays, mode).unwrap();
        assert!(
            results
                .iter()
                .all(|r| r.t < 0.0 && r.hit_count == 0 && r.stack_overflow == 0),
            "{mode:?}: {:?}",
            results[0]
        );
    }
}
