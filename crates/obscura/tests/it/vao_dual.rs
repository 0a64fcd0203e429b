//! `vao-dual` (seed 000 §2.1): VAO with a second depth layer from depth peeling.

use crate::common::*;
use glam::Vec3;
use obscura::bvh::Bvh;
use obscura::metrics::{mse, Image};
use obscura::reference::ground_truth::{render_reference, ReferenceSettings};
use obscura::{scene, Renderer, Technique};

#[test]
fn depth_peeling_recovers_the_second_layer() {
    // A square 1 m before a wall: behind the square the second layer is the wall (depth 3),
    // elsewhere there is nothing behind the wall (0).
    let quad = |half: f32, z: f32| {
        [
            Vec3::new(-half, -half, z),
            Vec3::new(half, -half, z),
            Vec3::new(half, half, z),
            Vec3::new(-half, half, z),
        ]
    };
    let scene = quads("layers", &[quad(5.0, -3.0), quad(1.0, -2.0)]);
    let gpu = gpu();
    let mut r = Renderer::new(
        &gpu,
        &scene,
        &technique_settings(Technique::VaoDual, false),
        64,
        64,
        0,
    )
    .unwrap();
    r.render(&camera(Vec3::ZERO, Vec3::NEG_Z, 90.0), None)
        .unwrap();
    let first = r.read_gbuffer().unwrap().depth;
    let second = r.read_second_layer().unwrap().unwrap();
    let (mut behind, mut alone) = (0, 0);
    for (z1, z2) in first.iter().zip(&second) {
        if (z1 - 2.0).abs() < 1e-4 {
            assert!((z2 - 3.0).abs() < 1e-4, "behind the square: {z2}");
            behind += 1;
        } else {
            assert!(
                (z1 - 3.0).abs() < 1e-4 && *z2 == 0.0,
                "wall only: {z1} {z2}"
            );
            alone += 1;
        }
    }
    assert!(behind > 500 && alone > 500);
}

#[test]
fn vao_dual_equals_vao_with_one_layer() {
    let gpu = gpu();
    let scene = height_field();
    let mut cam = camera(Vec3::new(0.0, 7.0, 0.0), Vec3::ZERO, 30.0);
    cam.up = Vec3::NEG_Z;
    let render = |technique| {
        let mut r = Renderer::new(
            &gpu,
            &scene,
            &technique_settings(technique, false),
            96,
            64,
            32,
        )
        .unwrap();
        r.render(&cam, None).unwrap();
        r.read_ao().unwrap()
    };
    let (vao, dual) = (render(Technique::Vao), render(Technique::VaoDual));
    let worst = max_abs_diff(&vao, &dual);
    assert!(worst <= 1e-6, "max |vao - vao-dual| {worst}");
}

#[test]
fn vao_dual_is_closer_to_the_ground_truth_than_vao() {
    let gpu = gpu();
    for name in ["stairs", "colonnade"] {
        let scene = scene::builtin(name).unwrap();
        let bvh = Bvh::build(&scene);
        let (w, h) = (160, 96);
        let mut errors = Vec::new();
        let mut reference = Vec::new();
        for technique in [Technique::Vao, Technique::VaoDual] {
            let mut r = Renderer::new(
                &gpu,
                &scene,
                &technique_settings(technique, false),
                w,
                h,
                16,
            )
            .unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            if reference.is_empty() {
                reference = render_reference(
                    &scene,
                    &bvh,
                    *r.view().unwrap(),
                    &ReferenceSettings::default(),
                    &|_| {},
                );
            }
            let ao = r.read_ao().unwrap();
            let img = |d: &[f32]| Image::new(w as usize, h as usize, d.to_vec().leak()).unwrap();
            errors.push(mse(&img(&ao), &img(&reference)).unwrap());
        }
        println!(
            "{name}: MSE vao {:.3e}, vao-dual {:.3e}",
            errors[0], errors[1]
        );
        assert!(
            errors[1] < errors[0],
            "{name}: vao-dual {} vs vao {}",
            errors[1],
            errors[0]
        );
    }
}
