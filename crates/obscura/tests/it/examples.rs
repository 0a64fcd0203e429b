//! The examples run as tests, so `cargo test` (and CI) keeps them working as written.

use crate::common;

#[allow(dead_code)] // its `main`: the test calls `run` with a path of its own
#[path = "../../examples/engine_depth.rs"]
mod engine_depth;

#[test]
fn engine_depth_example_writes_an_occluded_image() {
    common::gpu(); // quiets the Vulkan loader as the other tests do
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("engine_depth.png");
    let mean = engine_depth::run(&out).unwrap();
    let image = obscura::output::read_ao(&out).unwrap();
    assert_eq!((image.width, image.height), (320, 180));
    // A box in front of a floor-wall corner: occluded, but not black.
    assert!(
        (0.3..0.98).contains(&mean),
        "mean AO of the occluded pixels {mean}"
    );
    let darkest = image.values.iter().copied().fold(1.0, f32::min);
    assert!(
        darkest < 0.85,
        "the box's contact and the floor-wall corner are darker: {darkest}"
    );
    // The open floor in front (bottom centre) is unoccluded.
    let open = image.values[(175 * 320 + 160) as usize];
    assert!(open > 0.97, "open floor {open}");
}

#[allow(dead_code)]
#[path = "../../examples/engine_meshes.rs"]
mod engine_meshes;

#[test]
fn engine_meshes_example_traces_the_engine_s_own_geometry() {
    common::gpu();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("engine_meshes.png");
    engine_meshes::run(&out, obscura::Technique::RtVao).unwrap();
    let image = obscura::output::read_ao(&out).unwrap();
    assert_eq!((image.width, image.height), (320, 180));
    let at = |x: u32, y: u32| image.values[(y * 320 + x) as usize];
    // The pillar's face (image centre) and the open floor in front are unoccluded; the foot of
    // the back wall and of the pillar are not.
    assert!(at(160, 60) > 0.97, "pillar face {}", at(160, 60));
    assert!(at(160, 175) > 0.97, "open floor {}", at(160, 175));
    let darkest = image.values.iter().copied().fold(1.0, f32::min);
    assert!(darkest < 0.8, "no contact occlusion: {darkest}");
}

#[allow(dead_code)] // its `main`: the test calls `run` at a small size
#[path = "../../examples/raster_fill_probe.rs"]
mod raster_fill_probe;

#[test]
fn raster_fill_probe_times_every_pass_for_each_depth_format() {
    let gpu = common::gpu();
    let rows = raster_fill_probe::run(&gpu, 64, 48, 3, 1).unwrap();
    // Depth32Float and Depth16Unorm are core formats; Depth24Plus too.
    let formats: Vec<_> = rows.iter().map(|r| r.format).collect();
    for format in ["d32f", "d24", "d16"] {
        assert!(
            formats.contains(&format),
            "{format} missing from {formats:?}"
        );
    }
    for row in &rows {
        for (median, pass) in row.medians.iter().zip(raster_fill_probe::PASSES) {
            assert!(
                median.is_finite() && *median >= 0.0,
                "{} {pass}: {median}",
                row.format
            );
        }
    }
}
