//! A BVH deeper than the GPU traversal stack: the overflow must be reported, never silent.

use crate::common::*;
use glam::{Vec2, Vec3};
use obscura::bvh::gpu::{trace_batch, GpuBvh, QueryMode, QueryRay};
use obscura::bvh::Bvh;
use obscura::raster::gpu_scene::GpuScene;

/// Triangles at x = 1.3^k: each new one is farther out than the last by a fixed ratio, so the
/// hierarchy degenerates into a chain (86 levels for 330 triangles) whose wide walk along the
/// row needs more stack than the GPU has.
fn chain(count: u32) -> obscura::scene::Scene {
    let mut s = quads("chain", &[]);
    for k in 0..count {
        let x = 1.3f32.powi(k as i32);
        let base = s.positions.len() as u32;
        for p in [
            Vec3::new(x, -1.0, -1.0),
            Vec3::new(x, 1.0, -1.0),
            Vec3::new(x, 0.0, 1.0),
        ] {
            s.positions.push(p);
            s.uvs.push(Vec2::ZERO);
        }
        s.triangles.push([base, base + 1, base + 2]);
        s.triangle_materials.push(0);
    }
    s.materials[0].double_sided = true;
    s
}

/// Along +x through every triangle of the chain: every level has both children to visit.
fn along_the_chain() -> QueryRay {
    QueryRay {
        origin: [0.5, 0.0, 0.0],
        t_min: 0.0,
        dir: [1.0, 0.0, 0.0],
        t_max: f32::MAX,
    }
}

#[test]
fn stack_overflow_is_reported() {
    let scene = chain(330);
    let bvh = Bvh::build_obvhs_unbounded(&scene);
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &scene, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &bvh, &scene).unwrap();
    println!(
        "chain BVH depth {}, stack bound {}",
        bvh.max_depth(),
        gpu_bvh.stack_bound
    );
    assert!(
        gpu_bvh.stack_bound > obscura::bvh::gpu::STACK_SIZE,
        "the test needs a deeper tree"
    );
    let along = along_the_chain();
    let result = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &[along], QueryMode::AllHits).unwrap();
    assert_eq!(
        result[0].stack_overflow, 1,
        "the overflow must be flagged: {:?}",
        result[0]
    );
    // A short ray that needs no deep stack is not flagged.
    let short = QueryRay {
        t_max: 0.6,
        ..along
    };
    let result = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &[short], QueryMode::AllHits).unwrap();
    assert_eq!((result[0].stack_overflow, result[0].hit_count), (0, 1));
}

#[test]
fn a_polygon_fan_traces_without_overflow() {
    // One OBJ face of 5000 vertices, fanned into 4998 triangles sharing a vertex: its SAH tree is
    // about 1300 levels deep and rays through it overflowed the GPU stack (wrong AO). The build
    // bounds the depth now; the unbounded tree shows the defect was real.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fan.obj");
    let mut obj = String::new();
    for k in 0..5000 {
        let a = std::f32::consts::TAU * k as f32 / 5000.0;
        obj += &format!("v {} {} -3\n", a.cos(), a.sin());
    }
    obj += "f";
    for k in 1..=5000 {
        obj += &format!(" {k}");
    }
    obj += "\n";
    std::fs::write(&path, obj).unwrap();
    let scene = obscura::scene::load(path.to_str().unwrap()).unwrap();
    assert!(
        scene.triangles.len() >= 4990,
        "{} triangles",
        scene.triangles.len()
    );
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &scene, &gpu.device.limits()).unwrap();
    // Rays through the disc at many points, every hit wanted.
    let rays: Vec<QueryRay> = (0..64)
        .map(|k| {
            let a = std::f32::consts::TAU * k as f32 / 64.0;
            let r = 0.9 * (k as f32 / 64.0);
            QueryRay {
                origin: [r * a.cos(), r * a.sin(), 0.0],
                t_min: 0.0,
                dir: [0.0, 0.0, -1.0],
                t_max: f32::MAX,
            }
        })
        .collect();
    // (rays that overflowed, rays that found no hit)
    let trace = |bvh: &Bvh| {
        let gpu_bvh = GpuBvh::new(&gpu.device, bvh, &scene).unwrap();
        let results = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &rays, QueryMode::AllHits).unwrap();
        (
            results.iter().filter(|r| r.stack_overflow != 0).count(),
            results.iter().filter(|r| r.hit_count == 0).count(),
        )
    };
    let unbounded = Bvh::build_obvhs_unbounded(&scene);
    let bounded = Bvh::build(&scene);
    println!(
        "fan: depth {} unbounded, {} bounded",
        unbounded.max_depth(),
        bounded.max_depth()
    );
    let (overflowed, missed) = trace(&unbounded);
    println!("unbounded: {overflowed} of 64 rays overflowed, {missed} found no hit");
    assert!(overflowed > 0, "the unbounded tree must show the defect");
    assert!(bounded.max_depth() <= obscura::bvh::build::MAX_DEPTH);
    // Whatever its shape, a bounded tree's walk fits the GPU stack (two-wide where four-wide
    // could not).
    let bound = GpuBvh::new(&gpu.device, &bounded, &scene)
        .unwrap()
        .stack_bound;
    assert!(
        bound <= obscura::bvh::gpu::STACK_SIZE,
        "stack bound {bound}"
    );
    // Every ray through the disc hits it, and none overflows.
    assert_eq!(trace(&bounded), (0, 0));
}

#[test]
fn a_tree_too_deep_for_the_four_wide_walk_is_walked_two_wide() {
    // 200 triangles of the chain: the BVH2 is 54 levels deep, within the GPU stack, but its
    // four-wide walk could need 79 entries. The upload falls back to two children a node, and
    // the ray along the chain then finds every hit the CPU finds, with no overflow.
    let scene = chain(200);
    let bvh = Bvh::build_obvhs_unbounded(&scene);
    let (_, four_wide) = obscura::bvh::wide::widen(bvh.nodes(), 4);
    let stack = obscura::bvh::gpu::STACK_SIZE;
    assert!(
        bvh.max_depth() <= stack && four_wide > stack,
        "the test needs a tree between the two bounds: depth {}, four-wide {four_wide}",
        bvh.max_depth()
    );
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &scene, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &bvh, &scene).unwrap();
    assert!(
        gpu_bvh.stack_bound <= stack,
        "bound {}",
        gpu_bvh.stack_bound
    );
    let along = along_the_chain();
    let result = trace_batch(&gpu, &gpu_scene, &gpu_bvh, &[along], QueryMode::AllHits).unwrap();
    let ray = obscura::bvh::Ray::new(Vec3::from(along.origin), Vec3::from(along.dir));
    let cpu = bvh.all_hits(&scene, &ray, along.t_min, along.t_max).len();
    assert!(cpu > 100, "the ray must cross the chain: {cpu} hits");
    assert_eq!(
        (result[0].stack_overflow, result[0].hit_count as usize),
        (0, cpu)
    );
}
