//! Soak (issue 15): many frames at a small size, the camera orbiting the scene, the technique
//! switching in turn through every row of the table (a new `Renderer` each time, as a tool that
//! switches techniques would), resident memory sampled. After a first cycle through all
//! techniques (warm-up: pipeline caches, driver pools), memory must stay flat.
//!
//! `$OBSCURA_SOAK_FRAMES` frames (default 200, the CI run; RELIABILITY.md records the long runs),
//! techniques switched every `min(500, frames / (2 · techniques))` frames (`$OBSCURA_SOAK_SWITCH`). `$OBSCURA_SOAK_SIZE`
//! (default 64x48) and `$OBSCURA_SOAK_TECHNIQUES` (comma-separated; default every row) set up the
//! device run. The time of every block of 50 frames is reported: flat too.
//!
//! Memory is compared in use (`resident_in_use`): the allocator's freed heap handed back before
//! each of the two samples; the peak is sampled every frame as it is.
//!
//! Its own test binary, unlike the other tests (one binary, tests/it/): it samples the resident
//! memory of the whole process, which the other tests' allocations would move.

mod common;
use common::*;
use glam::Quat;
use obscura::{Renderer, Technique};

/// Resident set size in bytes (Linux: `/proc/self/statm`), or `None` elsewhere.
fn resident_bytes() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096)
}

/// Resident memory in use: the GPU idle (so dropped resources are freed) and the allocator's
/// freed heap handed back first. glibc keeps the heap a freed renderer leaves (on lavapipe most of
/// it is the driver's shader compiler's, which runs on the CPU) and the first five renderers grew
/// the process from 111 to 137 MiB that way, then nothing; with the heap trimmed the same run stays
/// at 104 MiB from the second renderer to the sixtieth (RELIABILITY.md, Findings). A leak is memory
/// the program still holds, which trimming does not return.
fn resident_in_use(gpu: &obscura::Gpu) -> Option<u64> {
    gpu.finish().unwrap();
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free heap pages to the system; it has no preconditions.
    unsafe {
        libc::malloc_trim(0);
    }
    resident_bytes()
}

/// Renderers made before memory is first sampled (see the warm-up).
const FIRST_RENDERERS: usize = 4;

#[test]
fn memory_stays_flat_over_many_frames_and_technique_switches() {
    let frames: usize = std::env::var("OBSCURA_SOAK_FRAMES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    let gpu = gpu();
    let scene = obscura::scene::builtin("colonnade").unwrap();
    let base = scene.cameras[0].camera;
    let techniques: Vec<Technique> = match std::env::var("OBSCURA_SOAK_TECHNIQUES") {
        Ok(list) => list.split(',').map(|t| t.parse().unwrap()).collect(),
        Err(_) => Technique::all().collect(),
    };
    let (w, h) = std::env::var("OBSCURA_SOAK_SIZE")
        .ok()
        .and_then(|s| {
            let (w, h) = s.split_once('x')?;
            Some((w.parse().ok()?, h.parse().ok()?))
        })
        .unwrap_or((64u32, 48u32));
    // The default guard band at real sizes; 8 px at the tiny CI size.
    let guard_band = if h >= 360 {
        obscura::default_guard_band(h)
    } else {
        8
    };
    let per_technique = std::env::var("OBSCURA_SOAK_SWITCH")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or((frames / (2 * techniques.len())).clamp(1, 500));
    let cycle = per_technique * techniques.len();
    // Warm-up: the first cycle through the techniques, at most half of the run
    // (`$OBSCURA_SOAK_WARMUP` frames when given: NVIDIA's driver pools grow for ~20k frames), and
    // never fewer than the first four renderers: the heap of the first few freed renderers is
    // fragmented, so memory in use still grows by a few MiB until the fourth and then stays
    // (lavapipe, `vao` alone, a renderer every 100 frames: 73, 101, 102, 103, 103.4, 103.6 … 104.6
    // MiB at the sixtieth; RELIABILITY.md). A run that ends before its warm-up is lengthened.
    let warmup = std::env::var("OBSCURA_SOAK_WARMUP")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(cycle.min(frames / 2))
        .max(FIRST_RENDERERS * per_technique)
        .max(1);
    let (mut after_warmup, mut peak) = (None, 0u64);
    let mut renderer: Option<Renderer> = None;
    let start = std::time::Instant::now();
    let (mut block_start, mut block_ms) = (std::time::Instant::now(), Vec::new());
    let total = frames.max(2 * warmup);
    for frame in 0..total {
        if frame % per_technique == 0 {
            let technique = techniques[(frame / per_technique) % techniques.len()];
            drop(renderer.take()); // the old one's GPU resources go first
            renderer = Some(
                Renderer::new(
                    &gpu,
                    &scene,
                    &technique_settings(technique, true),
                    w,
                    h,
                    guard_band,
                )
                .unwrap(),
            );
        }
        // Orbit the close-up's target, a full turn every 360 frames.
        let turn = Quat::from_rotation_y((frame as f32).to_radians());
        let mut camera = base;
        camera.eye = base.target + turn * (base.eye - base.target);
        let r = renderer.as_mut().unwrap();
        r.render(&camera, None).unwrap();
        if frame % 50 == 49 {
            // Waits for the GPU, so the frames do not pile up in the queue.
            let ao = r.read_ao().unwrap();
            if let Some((i, bad)) = ao
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && (0.0..=1.0).contains(*v)))
            {
                let technique = r.ambient_occlusion().unwrap().settings().technique;
                panic!("{technique}, frame {frame}: AO {bad} at pixel {i}");
            }
            assert_eq!(r.read_stack_overflows().unwrap(), 0);
            // Blocks that switched technique include pipeline creation: left out.
            if (frame + 1 - 50) / per_technique == frame / per_technique {
                block_ms.push(block_start.elapsed().as_secs_f64() * 1e3 / 50.0);
            }
            block_start = std::time::Instant::now();
        }
        if let Some(rss) = resident_bytes() {
            peak = peak.max(rss);
            if frame + 1 == warmup {
                after_warmup = resident_in_use(&gpu);
            }
        }
    }
    let last = resident_in_use(&gpu).unwrap_or(0);
    let Some(warm) = after_warmup else {
        println!("no /proc/self/statm: memory not sampled");
        return;
    };
    let growth = last as f64 / warm as f64 - 1.0;
    let mut sorted = block_ms.clone();
    sorted.sort_by(f64::total_cmp);
    if let (Some(first), Some(last_block)) = (block_ms.first(), block_ms.last()) {
        println!(
            "soak: ms per frame over blocks of 50 frames (within one technique): first {first:.2}, \
             median {:.2}, last {last_block:.2}, max {:.2}",
            sorted[sorted.len() / 2],
            sorted[sorted.len() - 1]
        );
    }
    println!(
        "soak: {} frames at {w}x{h}+{guard_band} in {:.1} s, {} techniques x {per_technique} \
         frames per turn; resident {:.1} MiB after warm-up, {:.1} MiB at the end ({:+.2} %), \
         peak {:.1} MiB",
        total,
        start.elapsed().as_secs_f64(),
        techniques.len(),
        warm as f64 / 1048576.0,
        last as f64 / 1048576.0,
        100.0 * growth,
        peak as f64 / 1048576.0
    );
    // Allocator and driver pools move a little between samples: a leak of one frame's textures
    // per switch or per frame would show far above this.
    assert!(
        growth < 0.05,
        "resident memory grew {:.1} %",
        100.0 * growth
    );
}
