//! A BVH deeper than the GPU traversal stack: the overflow must be reported, never silent.

mod common;
use common::*;
use glam::{Vec2, Vec3};
use obscura::bvh::gpu::{trace_batch, GpuBvh, QueryMode, QueryRay};
use obscura::bvh::Bvh;
use obscura::raster::gpu_scene::GpuScene;

/// Triangles at x = 1.5^k: each new one is far from all before it, so the hierarchy degenerates
/// into a chain about as deep as the triangle count.
fn chain(count: u32) -> obscura::scene::Scene {
    let mut s = quads("chain", &[]);
    for k in 0..count {
        let x = 1.5f32.powi(k as i32);
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

#[test]
fn stack_overflow_is_reported() {
    let scene = chain(210);
    let bvh = Bvh::build(&scene);
    println!("chain BVH depth {}", bvh.max_depth());
    assert!(
        bvh.max_depth() > obscura::bvh::gpu::STACK_SIZE,
        "the test needs a deeper tree"
    );
    let gpu = gpu();
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, &scene, &gpu.device.limits()).unwrap();
    let gpu_bvh = GpuBvh::new(&gpu.device, &bvh, &scene);
    // Along +x through every triangle: every level has both children to visit.
    let along = QueryRay {
        origin: [0.5, 0.0, 0.0],
        t_min: 0.0,
        dir: [1.0, 0.0, 0.0],
        t_max: f32::MAX,
    };
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
