//! The GPU VAO kernel against its plain CPU implementation on the same (read-back) G-buffer.

mod common;
use common::*;
use obscura::reference::cpu_vao::cpu_vao;
use obscura::{scene, AoSettings, Renderer};

fn compare(scene_name: &str, samples: u32) {
    let gpu = gpu();
    let scene = scene::builtin(scene_name).unwrap();
    let mut settings = AoSettings::default();
    settings.vao.samples = samples;
    let (w, h) = (160, 96);
    for named in &scene.cameras {
        let mut r = Renderer::new(&gpu, &scene, &settings, w, h, 16).unwrap();
        r.render(&named.camera, None).unwrap();
        let gpu_ao = r.read_raw_ao().unwrap();
        let gbuffer = r.read_gbuffer().unwrap();
        let screen = r.view().unwrap().screen();
        let cpu = cpu_vao(&gbuffer, &screen, &settings.vao);
        let mut worst = 0.0f32;
        let mut ambiguous_mismatches = 0;
        for (i, (&g, &c)) in gpu_ao.iter().zip(&cpu.ao).enumerate() {
            let diff = (g - c).abs();
            if diff > 1.0 / 255.0 {
                // Only pixels where a sample lies within 1e-3 px of a pixel edge may snap differently.
                assert!(
                    cpu.ambiguous[i],
                    "{scene_name}/{}: pixel {} GPU {} CPU {}",
                    named.name, i, gpu_ao[i], cpu.ao[i]
                );
                ambiguous_mismatches += 1;
            } else {
                worst = worst.max(diff);
            }
        }
        let occluded = gpu_ao.iter().filter(|&&v| v < 0.9).count();
        assert!(
            occluded > gpu_ao.len() / 50,
            "{scene_name}/{}: the view must show occlusion",
            named.name
        );
        assert!(
            ambiguous_mismatches <= gpu_ao.len() / 500,
            "{scene_name}/{}: {ambiguous_mismatches} edge-snapping mismatches",
            named.name
        );
        println!(
            "{scene_name}/{}: max |GPU-CPU| {worst:.2e}, {ambiguous_mismatches} edge-snapping mismatches",
            named.name
        );
    }
}

#[test]
fn gpu_matches_cpu_on_stairs() {
    compare("stairs", 8);
}

#[test]
fn gpu_matches_cpu_on_colonnade() {
    compare("colonnade", 8);
}

#[test]
fn gpu_matches_cpu_with_32_samples() {
    compare("layers", 32);
}
