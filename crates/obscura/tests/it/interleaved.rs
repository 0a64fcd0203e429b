//! The interleaved schedule (docs/AUTHORS_CODE.md §1.7) with the VAO estimator, whose per-pixel
//! sample pattern is finer than HBAO+'s: unoccluded planes stay at 1, and snapping every sample to
//! the nearest pixel of its residue class mod 4 changes the image only a little. (HBAO+ and HBAO
//! over this schedule match CPU implementations exactly: tests/it/hbao_plus.rs, tests/it/horizon.rs.)

use crate::common::*;
use obscura::{scene, Renderer, Technique};

#[test]
fn unoccluded_plane_is_one_everywhere() {
    let gpu = gpu();
    for blur in [false, true] {
        for samples in [8, 16, 32] {
            let mut s = technique_settings(Technique::VaoInterleaved, blur);
            s.vao.samples = samples;
            let ao = tilted_floor_ao(&gpu, &s);
            let min = ao.iter().copied().fold(f32::MAX, f32::min);
            assert!(
                min > 1.0 - 1e-3,
                "{samples} samples, blur {blur}: min AO {min}"
            );
        }
    }
}

#[test]
fn close_to_the_full_resolution_schedule() {
    // Measured with the blur: mean |interleaved − single| 0.0054 stairs, 0.0037 colonnade, 0.0094
    // tower.
    let gpu = gpu();
    for name in ["stairs", "colonnade", "tower"] {
        let scene = scene::builtin(name).unwrap();
        let render = |t: Technique| {
            let s = technique_settings(t, true);
            let mut r = Renderer::new(&gpu, &scene, &s, 160, 96, 16).unwrap();
            r.render(&scene.cameras[0].camera, None).unwrap();
            r.read_ao().unwrap()
        };
        let (single, interleaved) = (render(Technique::Vao), render(Technique::VaoInterleaved));
        let mean = single
            .iter()
            .zip(&interleaved)
            .map(|(a, b)| (a - b).abs())
            .sum::<f32>()
            / single.len() as f32;
        println!("{name}: mean |vao-interleaved − vao| {mean:.4}");
        assert!(
            mean > 0.0,
            "{name}: the schedules must differ (samples snap)"
        );
        assert!(mean < 0.015, "{name}: {mean}");
    }
}
