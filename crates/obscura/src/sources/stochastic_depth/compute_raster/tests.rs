//! The compute-rasterised map against the hardware's: the same fragments, up to rounding.

use super::{ITEM_CAPACITY, OWN_ITEMS, TILE_TESTS};
use crate::pipeline::renderer::Renderer;
use crate::raster::test_support::{gpu, moved};
use crate::scene::{self, AlphaMode, Camera, Material, Scene, Texture};
use crate::settings::{AoSettings, SdMask, SdRasterizer, SdSelection};
use crate::technique::Technique;
use glam::{Vec2, Vec3};

const SIZE: (u32, u32, u32) = (96, 64, 8);

/// One frame's map (sample layers as written) and the compute passes' counters.
type Frame = (Vec<Vec<f32>>, Option<[u32; 6]>);

/// The maps of `settings` rendered from each of `cameras` by `rasterizer` (sample layers as
/// written), and the compute passes' counters of each frame.
fn maps(
    scene: &Scene,
    settings: &AoSettings,
    rasterizer: SdRasterizer,
    cameras: &[Camera],
) -> Vec<Frame> {
    let gpu = gpu();
    let mut s = *settings;
    s.stochastic_depth.rasterizer = rasterizer;
    let mut r = Renderer::new(&gpu, scene, &s, SIZE.0, SIZE.1, SIZE.2).unwrap();
    cameras
        .iter()
        .map(|c| {
            r.render(c, None).unwrap();
            let map = r.read_stochastic_depth_as_written().unwrap().unwrap();
            let counts = r.stochastic_depth_map().unwrap().compute_counts(&gpu);
            (map, counts)
        })
        .collect()
}

/// Pixels whose S depths differ between `a` and `b`: in how many depths they hold, and in any
/// depth by more than a relative 1e-3.
fn differences(a: &[Vec<f32>], b: &[Vec<f32>]) -> (usize, usize) {
    let held = |m: &[Vec<f32>], p: usize| m.iter().filter(|l| l[p] > 0.0).count();
    let pixels = 0..a[0].len();
    let count = pixels.clone().filter(|&p| held(a, p) != held(b, p)).count();
    let depth = pixels
        .filter(|&p| {
            a.iter()
                .zip(b)
                .any(|(x, y)| (x[p] - y[p]).abs() > 1e-3 * x[p].max(y[p]))
        })
        .count();
    (count, depth)
}

/// The two rasterisers' maps of `settings` agree on every camera: at most 2 of the 8,960 pixels
/// hold a different number of depths, and at most 4 a depth more than 1e-3 (relative) apart.
/// What differs is rounding: the hardware interpolates depth between its snapped corners where
/// the compute passes take the triangle's plane, and a fragment at the separation's edge or a
/// pixel centre within rounding of an edge can fall either way. Returns
/// the depths stored.
fn assert_same_maps(what: &str, scene: &Scene, settings: &AoSettings, cameras: &[Camera]) -> usize {
    let hardware = maps(scene, settings, SdRasterizer::Hardware, cameras);
    let compute = maps(scene, settings, SdRasterizer::Compute, cameras);
    let mut stored = 0;
    for (f, ((h, _), (c, counts))) in hardware.iter().zip(&compute).enumerate() {
        let (count, depth) = differences(h, c);
        assert!(
            count <= 2 && depth <= 4,
            "{what}, frame {f}: {count} pixels hold another number of depths, {depth} other \
             depths (counters {counts:?})"
        );
        stored += h.iter().flatten().filter(|&&d| d > 0.0).count();
    }
    stored
}

/// The default settings of `technique`, edited by `edit`.
/// A stochastic-depth row's settings, the map without a band of its own unless `edit` gives it
/// one: these tests count the framebuffer's fragments, and one case below bands the map.
fn sd(technique: Technique, edit: impl Fn(&mut AoSettings)) -> AoSettings {
    let mut s = AoSettings {
        technique,
        ..AoSettings::default()
    };
    s.stochastic_depth.guard_band = Some(0);
    edit(&mut s);
    s
}

/// Every built-in scene, camera and a moved camera; the stochastic map at S = 4, the 16 nearest
/// layers (almost every fragment, so a missing or extra one shows), SD-SVAO's requested pixels
/// with the depth mask and with the stencil, and a map with its own band.
#[test]
fn the_compute_map_holds_the_hardware_maps_fragments() {
    let settings = [
        ("S = 4", sd(Technique::SdVao, |_| {})),
        (
            "16 nearest",
            sd(Technique::SdVao, |s| {
                s.stochastic_depth.samples = 16;
                s.stochastic_depth.selection = SdSelection::Nearest;
            }),
        ),
        ("sd-svao, depth mask", sd(Technique::SdSvao, |_| {})),
        (
            "sd-svao, stencil",
            sd(Technique::SdSvao, |s| {
                s.stochastic_depth.mask = SdMask::Stencil
            }),
        ),
        (
            "band 6",
            sd(Technique::SdVao, |s| {
                s.stochastic_depth.guard_band = Some(6)
            }),
        ),
    ];
    let mut stored = 0;
    for name in scene::builtin_names() {
        let scene = scene::builtin(name).unwrap();
        for named in &scene.cameras {
            let cameras = [named.camera, moved(&scene, &named.camera)];
            for (label, s) in &settings {
                let what = format!("{name} {}, {label}", named.name);
                stored += assert_same_maps(&what, &scene, s, &cameras);
            }
        }
    }
    assert!(stored > 100_000, "the maps stored only {stored} depths");
}

/// `auto` is resolved when a renderer is made and the renderer names the rasteriser it chose:
/// on a CPU adapter (lavapipe in CI) the hardware, as documented, and the map made under `auto`
/// is, bit for bit, the map of the rasteriser it names (for `sd-vao` and `sd-svao`).
#[test]
fn auto_names_the_rasteriser_it_chose() {
    let gpu = gpu();
    let scene = scene::builtin("stairs").unwrap();
    let cameras: Vec<Camera> = scene.cameras.iter().map(|n| n.camera).collect();
    for technique in [Technique::SdVao, Technique::SdSvao] {
        let settings = sd(technique, |_| {});
        assert_eq!(settings.stochastic_depth.rasterizer, SdRasterizer::Auto);
        let r = Renderer::new(&gpu, &scene, &settings, SIZE.0, SIZE.1, SIZE.2).unwrap();
        let chosen = r.settings().stochastic_depth.rasterizer;
        assert_ne!(chosen, SdRasterizer::Auto, "{technique:?}");
        if gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu {
            assert_eq!(chosen, SdRasterizer::Hardware, "{technique:?}");
        }
        let auto = maps(&scene, &settings, SdRasterizer::Auto, &cameras);
        let named = maps(&scene, &settings, chosen, &cameras);
        for (f, ((a, _), (b, _))) in auto.iter().zip(&named).enumerate() {
            assert!(
                a == b,
                "{technique:?}, camera {f}: auto's map is not {chosen}'s"
            );
        }
    }
}

/// The tile tests (which tiles of a box, and which items, a triangle may touch) only skip work:
/// with them and without them the compute passes make the same map, bit for bit, on every
/// built-in view and the near-plane scene, for the 16 nearest layers (every hidden fragment
/// counts) and `sd-svao`'s requested pixels.
#[test]
fn the_tile_tests_skip_no_fragment() {
    let nearest = sd(Technique::SdVao, |s| {
        s.stochastic_depth.samples = 16;
        s.stochastic_depth.selection = SdSelection::Nearest;
    });
    let requested = sd(Technique::SdSvao, |_| {});
    let (near_floor, near_camera) = near_floor_scene();
    let mut views = vec![(near_floor, vec![near_camera])];
    for name in scene::builtin_names() {
        let scene = scene::builtin(name).unwrap();
        let cameras = scene
            .cameras
            .iter()
            .flat_map(|n| [n.camera, moved(&scene, &n.camera)])
            .collect();
        views.push((scene, cameras));
    }
    let mut stored = 0;
    for (scene, cameras) in &views {
        for (label, s) in [("16 nearest", &nearest), ("sd-svao", &requested)] {
            // Room for every triangle (the small frames overflow the default room on `layers`),
            // so that none is left to the hardware, which rounds otherwise.
            ITEM_CAPACITY.with(|c| c.set(Some(1 << 20)));
            let with = std::panic::catch_unwind(|| maps(scene, s, SdRasterizer::Compute, cameras));
            TILE_TESTS.with(|t| t.set(false));
            let without =
                std::panic::catch_unwind(|| maps(scene, s, SdRasterizer::Compute, cameras));
            TILE_TESTS.with(|t| t.set(true));
            // Every large triangle's items written by its workgroup together.
            OWN_ITEMS.with(|o| o.set(0));
            let together =
                std::panic::catch_unwind(|| maps(scene, s, SdRasterizer::Compute, cameras));
            OWN_ITEMS.with(|o| o.set(super::OWN_ITEMS_DEFAULT));
            ITEM_CAPACITY.with(|c| c.set(None));
            let (with, without) = (with.unwrap(), without.unwrap());
            let together = together.unwrap();
            for (f, ((a, _), (b, _))) in with.iter().zip(&together).enumerate() {
                assert!(
                    a == b,
                    "{} {label}, frame {f}: written together, the maps differ",
                    scene.name
                );
            }
            for (f, m) in with.iter().chain(&without).chain(&together).enumerate() {
                let counts = m.1.unwrap();
                assert_eq!(
                    counts[2..4],
                    [0, 0],
                    "{} {label}, {f}: {counts:?}",
                    scene.name
                );
            }
            for (f, ((a, _), (b, _))) in with.iter().zip(&without).enumerate() {
                assert!(a == b, "{} {label}, frame {f}: the maps differ", scene.name);
                stored += a.iter().flatten().filter(|&&d| d > 0.0).count();
            }
        }
    }
    assert!(stored > 100_000, "the maps stored only {stored} depths");
}

/// Quad `corners` (counter-clockwise seen from its front) with material `material`, its texture
/// repeated `repeat` times across.
fn push_quad(scene: &mut Scene, corners: [Vec3; 4], material: u32, repeat: f32) {
    let base = scene.positions.len() as u32;
    scene.positions.extend(corners);
    scene.uvs.extend(
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(u, v)| Vec2::new(u, v) * repeat),
    );
    scene.triangles.push([base, base + 1, base + 2]);
    scene.triangles.push([base, base + 2, base + 3]);
    scene.triangle_materials.extend([material; 2]);
}

/// A floor that reaches behind the camera (its triangles cross the near plane), an occluder, an
/// alpha-tested checkerboard behind it and a back wall.
fn near_floor_scene() -> (Scene, Camera) {
    let mut scene = Scene {
        name: "near floor".into(),
        materials: vec![
            Material {
                name: "plain".into(),
                base_color: [1.0; 4],
                base_color_texture: None,
                alpha_mode: AlphaMode::Opaque,
                double_sided: false,
            },
            Material {
                name: "leaf".into(),
                base_color: [1.0; 4],
                base_color_texture: Some(0),
                alpha_mode: AlphaMode::Mask { cutoff: 0.5 },
                double_sided: true,
            },
        ],
        textures: vec![Texture {
            name: "checker".into(),
            width: 2,
            height: 2,
            rgba8: vec![
                255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0,
            ],
        }],
        ..Default::default()
    };
    let v = Vec3::new;
    // Seen from above.
    let floor = [
        v(-40.0, 0.0, 40.0),
        v(40.0, 0.0, 40.0),
        v(40.0, 0.0, -40.0),
        v(-40.0, 0.0, -40.0),
    ];
    push_quad(&mut scene, floor, 0, 1.0);
    // Facing the camera (+z).
    let wall =
        |x: f32, top: f32, z: f32| [v(-x, 0.0, z), v(x, 0.0, z), v(x, top, z), v(-x, top, z)];
    push_quad(&mut scene, wall(1.0, 1.5, -3.0), 0, 1.0);
    push_quad(&mut scene, wall(3.0, 2.5, -5.0), 1, 6.0);
    push_quad(&mut scene, wall(8.0, 4.0, -8.0), 0, 1.0);
    let camera = Camera::new(v(0.3, 1.0, 0.0), v(0.0, 0.6, -5.0), 70.0).unwrap();
    (scene, camera)
}

/// Triangles that cross the near plane are clipped as the hardware clips them (none is left to
/// it), alpha-tested ones are cut where the texture says, and the map is the hardware's.
#[test]
fn triangles_crossing_the_near_plane_are_clipped() {
    let (scene, camera) = near_floor_scene();
    let settings = sd(Technique::SdVao, |s| {
        s.stochastic_depth.samples = 16;
        s.stochastic_depth.selection = SdSelection::Nearest;
    });
    let stored = assert_same_maps("near floor", &scene, &settings, &[camera]);
    assert!(stored > 1000, "the map stored {stored} depths");
    let counts = maps(&scene, &settings, SdRasterizer::Compute, &[camera])[0]
        .1
        .unwrap();
    assert_eq!(
        counts[2..4],
        [0, 0],
        "triangles left to the hardware: {counts:?}"
    );
}

/// Slivers that reach far past the guard band on the left (so they are clipped) and show a few
/// pixel centres each inside the frame (so their parts are small), behind a wall: the parts
/// that clipping leaves are rasterised by the invocation that clipped them, and the map is the
/// hardware's.
#[test]
fn small_parts_of_clipped_triangles_are_rasterised() {
    let mut scene = Scene {
        name: "slivers".into(),
        materials: vec![Material {
            name: "plain".into(),
            base_color: [1.0; 4],
            base_color_texture: None,
            alpha_mode: AlphaMode::Opaque,
            double_sided: true,
        }],
        ..Default::default()
    };
    let v = Vec3::new;
    // The first layer: a wall over the whole frame, 2 m in front of the camera.
    push_quad(
        &mut scene,
        [
            v(-10.0, -10.0, -2.0),
            v(10.0, -10.0, -2.0),
            v(10.0, 10.0, -2.0),
            v(-10.0, 10.0, -2.0),
        ],
        0,
        1.0,
    );
    // Slivers 4 m away, in framebuffer pixels (SIZE plus its band on each side): from far left
    // of the guard band to a tip at column `tip`, 0.8 px high around the centres of row `row`.
    let (fw, fh) = (SIZE.0 + 2 * SIZE.2, SIZE.1 + 2 * SIZE.2);
    let depth = 4.0;
    let pixel = 2.0 * depth * 30f32.to_radians().tan() / SIZE.1 as f32;
    let at = |x: f32, y: f32| {
        v(
            (x - fw as f32 / 2.0) * pixel,
            (fh as f32 / 2.0 - y) * pixel,
            -depth,
        )
    };
    let mut tips = 0;
    for i in 0..12u32 {
        let row = 10.0 + 5.0 * i as f32;
        let tip = 6.0 + (i % 8) as f32;
        tips += tip as usize;
        let base = scene.positions.len() as u32;
        scene.positions.extend([
            at(-20_000.0, row + 0.5),
            at(tip, row + 0.1),
            at(tip, row + 0.9),
        ]);
        scene.uvs.extend([Vec2::ZERO; 3]);
        scene.triangles.push([base, base + 1, base + 2]);
        scene.triangle_materials.push(0);
    }
    let camera = Camera::new(Vec3::ZERO, v(0.0, 0.0, -1.0), 60.0).unwrap();
    let settings = sd(Technique::SdVao, |s| {
        s.stochastic_depth.samples = 16;
        s.stochastic_depth.selection = SdSelection::Nearest;
    });
    let stored = assert_same_maps("slivers", &scene, &settings, &[camera]);
    // Each sliver covers the centres left of its tip in its row (about `tip` of them).
    assert!(
        stored >= tips * 9 / 10 && stored <= tips,
        "the map stored {stored} depths of the slivers' {tips} pixel centres"
    );
    let counts = maps(&scene, &settings, SdRasterizer::Compute, &[camera])[0]
        .1
        .unwrap();
    assert_eq!(counts[2..4], [0, 0], "{counts:?}");
    // The fragments each pass counted: the slivers' centres by the bin pass (the clipping
    // invocation's own), the wall's, over the whole framebuffer, by the tile pass.
    assert_eq!(counts[4] as usize, tips, "{counts:?}");
    assert_eq!(counts[5], fw * fh, "{counts:?}");
}

/// Where the records or items do not fit their buffers, the triangles they belong to are drawn
/// by the hardware as well, each once (a clipped triangle too), and the map is the same.
#[test]
fn triangles_whose_items_do_not_fit_are_left_to_the_hardware() {
    let tower = scene::builtin("tower").unwrap();
    let tower_camera = tower.cameras[0].camera;
    let (near_floor, near_camera) = near_floor_scene();
    let settings = sd(Technique::SdVao, |s| {
        s.stochastic_depth.samples = 16;
        s.stochastic_depth.selection = SdSelection::Nearest;
    });
    for (scene, camera, capacity, at_least, own_items) in [
        (&tower, tower_camera, 8, 100, super::OWN_ITEMS_DEFAULT),
        (&near_floor, near_camera, 1, 2, super::OWN_ITEMS_DEFAULT),
        // Items written by the workgroup together, overflowing (clipped triangles' parts too).
        (&tower, tower_camera, 8, 100, 0),
        (&near_floor, near_camera, 1, 2, 0),
    ] {
        ITEM_CAPACITY.with(|c| c.set(Some(capacity)));
        OWN_ITEMS.with(|o| o.set(own_items));
        let small = std::panic::catch_unwind(|| {
            let what = format!("{}, {capacity} items", scene.name);
            let stored = assert_same_maps(&what, scene, &settings, &[camera]);
            let counts = maps(scene, &settings, SdRasterizer::Compute, &[camera])[0].1;
            (stored, counts.unwrap())
        });
        ITEM_CAPACITY.with(|c| c.set(None));
        OWN_ITEMS.with(|o| o.set(super::OWN_ITEMS_DEFAULT));
        let (stored, counts) = small.unwrap();
        assert!(
            stored > 1000,
            "{}: the map stored {stored} depths",
            scene.name
        );
        // (Every triangle left to the hardware has a record or items that did not fit.)
        assert!(
            counts[2] >= at_least && counts[2] <= counts[3],
            "{}: {counts:?}",
            scene.name
        );
    }
}
