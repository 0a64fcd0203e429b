//! A Bevy app that lights a glTF scene with obscura's AO or with Bevy's own SSAO, side by side in
//! time: in a window, a key switches the row; headless, it times each choice and writes
//! screenshots, as the peer benchmark of BENCHMARKS.md does for Bevy alone.
//!
//! ```sh
//! # a window; Tab / Shift+Tab: next / previous choice, 1–4: preset low … ultra,
//! # H: half resolution, B: blur off / on
//! cargo run --release -p bevy_obscura --example sponza -- --scene sponza.glb
//! # headless: each choice for 200 frames after 30 of warm-up, GPU times and screenshots
//! cargo run --release -p bevy_obscura --example sponza -- --scene sponza.glb --headless \
//!     --size 1920x1080 --frames 200 --warmup 30 --out bench-out
//! ```
//!
//! obscura's rows run with every radius at `--ao-radius` (default 0.5 world units, the radius of
//! BENCHMARKS.md's ground truths). Without `--scene` it shows obscura's built-in `stairs`. The default camera is the Sponza view
//! of BENCHMARKS.md (`--eye -9.5,1.8,-0.4 --target 0,3.5,0.6 --fov 60`).

use bevy::app::PluginsState;
use bevy::asset::{AssetPlugin, RenderAssetUsages};
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::gltf::GltfAssetLabel;
use bevy::image::Image;
use bevy::input::ButtonInput;
use bevy::light::GlobalAmbientLight;
use bevy::pbr::{ScreenSpaceAmbientOcclusion, ScreenSpaceAmbientOcclusionQualityLevel};
use bevy::prelude::*;
use bevy::render::diagnostic::RenderDiagnosticsPlugin;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::renderer::RenderDevice;
use bevy::render::settings::{Backends, RenderCreation, WgpuSettings};
use bevy::render::{pipelined_rendering::PipelinedRenderingPlugin, RenderPlugin};
use bevy::window::{ExitCondition, WindowPlugin};
use bevy::winit::WinitPlugin;
use bevy::world_serialization::WorldAssetRoot;
use bevy_obscura::{ObscuraAo, ObscuraPlugin};
use obscura::settings::{AoSettings, Preset, Resolution};
use std::path::PathBuf;

/// What lights the frame's ambient term.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Choice {
    /// Bevy's SSAO at one of its quality levels.
    Bevy(ScreenSpaceAmbientOcclusionQualityLevel),
    /// A row of obscura's table.
    Obscura(Row),
}

/// A row of obscura's table at a preset and resolution, with or without its blur.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Row {
    technique: &'static str,
    preset: Preset,
    resolution: Resolution,
    blur: bool,
}

/// A row at a preset, full resolution, blurred (the presets' own setting).
const fn row(technique: &'static str, preset: Preset) -> Choice {
    Choice::Obscura(Row {
        technique,
        preset,
        resolution: Resolution::Full,
        blur: true,
    })
}

/// [`row`] at half resolution.
const fn half(technique: &'static str, preset: Preset) -> Choice {
    Choice::Obscura(Row {
        technique,
        preset,
        resolution: Resolution::Half,
        blur: true,
    })
}

/// [`row`] without its blur.
const fn unblurred(technique: &'static str, preset: Preset, resolution: Resolution) -> Choice {
    Choice::Obscura(Row {
        technique,
        preset,
        resolution,
        blur: false,
    })
}

impl Choice {
    /// The choices the issue compares, Bevy's first, then obscura's cheapest first.
    const ALL: [Choice; 15] = [
        Choice::Bevy(ScreenSpaceAmbientOcclusionQualityLevel::Medium),
        Choice::Bevy(ScreenSpaceAmbientOcclusionQualityLevel::High),
        unblurred("gtao", Preset::Low, Resolution::Half),
        unblurred("gtao", Preset::Low, Resolution::Full),
        half("gtao", Preset::Low),
        half("vao", Preset::Low),
        row("gtao", Preset::Low),
        row("vao", Preset::Low),
        row("vao", Preset::Medium),
        row("gtao", Preset::Medium),
        row("gtao", Preset::High),
        row("gtao-vb", Preset::Medium),
        row("sd-hbao+", Preset::Medium),
        row("hemisphere", Preset::Medium),
        row("rtao", Preset::Medium),
    ];

    fn name(self) -> String {
        match self {
            Choice::Bevy(q) => format!("bevy-ssao-{}", format!("{q:?}").to_lowercase()),
            Choice::Obscura(r) => {
                let mut name = format!("{}-{}", r.technique, r.preset.name());
                if r.resolution != Resolution::Full {
                    name += &format!("-{}", r.resolution);
                }
                if !r.blur {
                    name += "-unblurred";
                }
                name
            }
        }
    }

    /// Puts the choice on the camera, an obscura row with every radius `radius` (world units).
    /// `ScreenSpaceAmbientOcclusion` stays on the camera throughout (`ObscuraAo` requires it):
    /// removing it would drop the render world's SSAO texture.
    fn apply(self, camera: &mut EntityWorldMut, radius: f32) {
        match self {
            Choice::Bevy(quality_level) => {
                camera.remove::<ObscuraAo>();
                camera.insert(ScreenSpaceAmbientOcclusion {
                    quality_level,
                    ..default()
                });
            }
            Choice::Obscura(r) => {
                let technique = r.technique.parse().expect("a row of the table");
                let mut settings = AoSettings::preset(technique, r.preset);
                settings.resolution = r.resolution;
                settings.blur.enabled = settings.blur.enabled && r.blur;
                settings.set_every_radius(radius);
                camera.insert(ObscuraAo::with_settings(settings));
            }
        }
    }
}

struct Args {
    scene: Option<PathBuf>,
    size: (u32, u32),
    eye: Vec3,
    target: Vec3,
    fov: f32,
    headless: bool,
    frames: u32,
    warmup: u32,
    out: PathBuf,
    only: Option<String>,
    radius: f32,
    /// `--eye` or `--target` given (else a built-in scene is seen from its own camera).
    camera_given: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        scene: None,
        size: (1280, 720),
        eye: Vec3::new(-9.5, 1.8, -0.4),
        target: Vec3::new(0.0, 3.5, 0.6),
        fov: 60.0,
        headless: false,
        frames: 200,
        warmup: 30,
        out: PathBuf::from("sponza-out"),
        only: None,
        radius: 0.5,
        camera_given: false,
    };
    let mut it = std::env::args().skip(1);
    let vec3 = |s: String| -> Result<Vec3, String> {
        let v: Vec<f32> = s
            .split(',')
            .map(|x| x.trim().parse().map_err(|_| format!("'{s}' is not x,y,z")))
            .collect::<Result<_, _>>()?;
        (v.len() == 3)
            .then(|| Vec3::new(v[0], v[1], v[2]))
            .ok_or(format!("'{s}' is not x,y,z"))
    };
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--scene" => a.scene = Some(value()?.into()),
            "--size" => {
                let v = value()?;
                let (w, h) = v
                    .split_once('x')
                    .ok_or(format!("--size '{v}' is not WxH"))?;
                a.size = (
                    w.parse().map_err(|_| format!("--size '{v}'"))?,
                    h.parse().map_err(|_| format!("--size '{v}'"))?,
                );
            }
            "--eye" => (a.eye, a.camera_given) = (vec3(value()?)?, true),
            "--target" => (a.target, a.camera_given) = (vec3(value()?)?, true),
            "--fov" => {
                a.fov = value()?
                    .parse()
                    .map_err(|_| "--fov takes degrees".to_string())?
            }
            "--headless" => a.headless = true,
            "--frames" => {
                a.frames = value()?
                    .parse()
                    .map_err(|_| "--frames takes a count".to_string())?
            }
            "--warmup" => {
                a.warmup = value()?
                    .parse()
                    .map_err(|_| "--warmup takes a count".to_string())?
            }
            "--out" => a.out = value()?.into(),
            "--only" => a.only = Some(value()?),
            "--ao-radius" => {
                a.radius = value()?
                    .parse()
                    .map_err(|_| "--ao-radius takes world units".to_string())?;
                if !(a.radius.is_finite() && a.radius > 0.0) {
                    return Err("--ao-radius must be a positive number of world units".into());
                }
            }
            other => {
                return Err(format!(
                    "unknown flag '{other}' (see the example's top comment)"
                ))
            }
        }
    }
    if a.size.0 == 0 || a.size.1 == 0 || a.frames == 0 {
        return Err("--size and --frames must be positive".into());
    }
    Ok(a)
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    if let Some(scene) = &args.scene {
        if !scene.is_file() {
            eprintln!(
                "error: --scene '{}' is not a file: give a .glb or .gltf",
                scene.display()
            );
            std::process::exit(2);
        }
    }
    let result = if args.headless {
        headless(&args)
    } else {
        windowed(&args)
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

/// Bevy's plugins for this app: assets from the scene's folder, Vulkan, GPU time spans.
fn app(args: &Args, headless: bool) -> App {
    // Absolute: Bevy resolves a relative root against the executable's folder.
    let asset_root = args
        .scene
        .as_ref()
        .and_then(|s| std::fs::canonicalize(s).ok())
        .and_then(|s| s.parent().map(|p| p.to_string_lossy().into_owned()))
        .unwrap_or_else(|| ".".into());
    let mut app = App::new();
    let plugins = DefaultPlugins
        .set(AssetPlugin {
            file_path: asset_root,
            ..default()
        })
        .set(RenderPlugin {
            synchronous_pipeline_compilation: headless,
            render_creation: RenderCreation::Automatic(Box::new(WgpuSettings {
                backends: Some(Backends::VULKAN),
                ..default()
            })),
            ..default()
        });
    if headless {
        app.add_plugins(
            plugins
                .set(WindowPlugin {
                    primary_window: None,
                    exit_condition: ExitCondition::DontExit,
                    ..default()
                })
                .disable::<WinitPlugin>()
                .disable::<PipelinedRenderingPlugin>(),
        );
    } else {
        app.add_plugins(plugins);
    }
    app.add_plugins((ObscuraPlugin, RenderDiagnosticsPlugin))
        .insert_resource(GlobalAmbientLight {
            color: Color::WHITE,
            brightness: 1500.0,
            ..default()
        });
    app
}

/// The scene and a sun; the camera with `target`. Returns the camera and the scene's asset
/// while it loads.
fn spawn_world(
    app: &mut App,
    args: &Args,
    target: Option<RenderTarget>,
) -> (Entity, Option<UntypedHandle>) {
    let world = app.world_mut();
    let mut transform = Transform::from_translation(args.eye).looking_at(args.target, Vec3::Y);
    let loading = match &args.scene {
        Some(path) => {
            let name = path
                .file_name()
                .expect("a file")
                .to_string_lossy()
                .into_owned();
            let scene = world
                .resource::<AssetServer>()
                .load(GltfAssetLabel::Scene(0).from_asset(name));
            world.spawn(WorldAssetRoot(scene.clone()));
            Some(scene.untyped())
        }
        None => {
            spawn_builtin(world, "stairs", &mut transform, args);
            None
        }
    };
    world.spawn((
        DirectionalLight {
            illuminance: 8000.0,
            shadow_maps_enabled: true,
            ..default()
        },
        Transform::from_xyz(2.0, 10.0, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let mut camera = world.spawn((
        Camera3d::default(),
        Projection::Perspective(PerspectiveProjection {
            fov: args.fov.to_radians(),
            aspect_ratio: args.size.0 as f32 / args.size.1 as f32,
            ..default()
        }),
        transform,
        Msaa::Off,
        // Bevy's default (TonyMcMapface) needs the `tonemapping_luts` feature; ACES needs none.
        Tonemapping::AcesFitted,
    ));
    if let Some(target) = target {
        camera.insert(target);
    }
    (camera.id(), loading)
}

/// obscura's built-in scene as white meshes (`bevy_obscura::scene_meshes`); `camera` becomes the scene's
/// own camera unless the command line gave one.
fn spawn_builtin(world: &mut World, name: &str, camera: &mut Transform, args: &Args) {
    let scene = obscura::scene::load(name).expect("a built-in scene");
    if !args.camera_given {
        let c = scene.default_camera(args.size.0 as f32 / args.size.1 as f32);
        let v = |v: glam::Vec3| Vec3::new(v.x, v.y, v.z);
        *camera = Transform::from_translation(v(c.eye)).looking_at(v(c.target), v(c.up));
    }
    for (mesh, double_sided) in bevy_obscura::scene_meshes(&scene) {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial {
                cull_mode: (!double_sided).then_some(bevy::render::render_resource::Face::Back),
                double_sided,
                ..default()
            });
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material)));
    }
}

#[derive(Resource)]
struct Switcher {
    camera: Entity,
    /// Where in [`Choice::ALL`] Tab goes on from.
    index: usize,
    /// What the camera has: `Choice::ALL[index]`, or it changed by the preset, H and B keys.
    choice: Choice,
    radius: f32,
}

fn windowed(args: &Args) -> Result<(), String> {
    let mut app = app(args, false);
    let (camera, _) = spawn_world(&mut app, args, None);
    let first = row("gtao", Preset::High);
    let index = Choice::ALL
        .iter()
        .position(|c| *c == first)
        .expect("gtao high is a choice");
    first.apply(&mut app.world_mut().entity_mut(camera), args.radius);
    println!(
        "{} (Tab: next, Shift+Tab: previous, 1-4: preset, H: half resolution, B: blur)",
        first.name()
    );
    app.insert_resource(Switcher {
        camera,
        index,
        choice: first,
        radius: args.radius,
    })
    .add_systems(Update, switch);
    app.run();
    Ok(())
}

/// Tab / Shift+Tab cycles the choices, 1–4 sets an obscura row's preset, H switches it between
/// full and half resolution, B turns its blur off and on.
fn switch(world: &mut World) {
    let keys = world.resource::<ButtonInput<KeyCode>>();
    let switcher = world.resource::<Switcher>();
    let Some((index, choice)) = next_choice(keys, switcher.index, switcher.choice) else {
        return;
    };
    let (camera, radius) = (switcher.camera, switcher.radius);
    let mut switcher = world.resource_mut::<Switcher>();
    (switcher.index, switcher.choice) = (index, choice);
    choice.apply(&mut world.entity_mut(camera), radius);
    println!("{}", choice.name());
    if let Ok(mut window) = world.query::<&mut Window>().single_mut(world) {
        window.title = format!("bevy_obscura: {}", choice.name());
    }
}

/// The choice the keys pressed this frame lead to from `choice` (at `index` of [`Choice::ALL`]),
/// with its index; None when they change nothing.
fn next_choice(
    keys: &ButtonInput<KeyCode>,
    index: usize,
    choice: Choice,
) -> Option<(usize, Choice)> {
    let shift = keys.pressed(KeyCode::ShiftLeft) || keys.pressed(KeyCode::ShiftRight);
    let step =
        keys.just_pressed(KeyCode::Tab)
            .then_some(if shift { Choice::ALL.len() - 1 } else { 1 });
    let preset = [
        KeyCode::Digit1,
        KeyCode::Digit2,
        KeyCode::Digit3,
        KeyCode::Digit4,
    ]
    .iter()
    .position(|k| keys.just_pressed(*k))
    .map(|i| Preset::ALL[i]);
    let toggle_half = keys.just_pressed(KeyCode::KeyH);
    let toggle_blur = keys.just_pressed(KeyCode::KeyB);
    match (step, preset, choice) {
        (Some(step), _, _) => {
            let index = (index + step) % Choice::ALL.len();
            Some((index, Choice::ALL[index]))
        }
        (None, Some(preset), Choice::Obscura(r)) => {
            Some((index, Choice::Obscura(Row { preset, ..r })))
        }
        (None, None, Choice::Obscura(r)) if toggle_half || toggle_blur => {
            let resolution = match (toggle_half, r.resolution) {
                (true, Resolution::Full) => Resolution::Half,
                (true, _) => Resolution::Full,
                (false, same) => same,
            };
            let blur = r.blur != toggle_blur;
            let changed = Row {
                resolution,
                blur,
                ..r
            };
            Some((index, Choice::Obscura(changed)))
        }
        _ => None,
    }
}

fn headless(args: &Args) -> Result<(), String> {
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("--out '{}': {e}", args.out.display()))?;
    let mut app = app(args, true);
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    let mut image = Image::new_uninit(
        Extent3d {
            width: args.size.0,
            height: args.size.1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    let image = app.world_mut().resource_mut::<Assets<Image>>().add(image);
    let target = RenderTarget::Image(image.clone().into());
    let (camera, loading) = spawn_world(&mut app, args, Some(target));
    // Let the scene load (meshes, textures) before timing anything.
    if let Some(scene) = loading {
        let mut frames = 0;
        while !app
            .world()
            .resource::<AssetServer>()
            .is_loaded_with_dependencies(&scene)
        {
            let state = app.world().resource::<AssetServer>().load_state(&scene);
            if let bevy::asset::LoadState::Failed(e) = state {
                return Err(format!("the scene did not load: {e}"));
            }
            frame(&mut app);
            frames += 1;
            if frames > 10_000 {
                return Err("the scene did not load in 10000 frames".into());
            }
        }
    }
    let mut report = Vec::new();
    for choice in Choice::ALL
        .iter()
        .filter(|c| args.only.as_ref().is_none_or(|o| *o == c.name()))
    {
        choice.apply(&mut app.world_mut().entity_mut(camera), args.radius);
        let mut samples: std::collections::BTreeMap<String, Vec<f64>> = Default::default();
        for i in 0..args.warmup + args.frames {
            frame(&mut app);
            // Each span's measurement of this frame, then the history cleared, so that a pass
            // that stopped running (Bevy's SSAO after a switch) leaves no stale value behind.
            let mut store = app.world_mut().resource_mut::<DiagnosticsStore>();
            let paths: Vec<DiagnosticPath> = store
                .iter()
                .map(|d| d.path().clone())
                .filter(|p| {
                    p.as_str().starts_with("render/") && p.as_str().ends_with("/elapsed_gpu")
                })
                .collect();
            for path in paths {
                let Some(d) = store.get_mut(&path) else {
                    continue;
                };
                if let Some(m) = d.measurement().filter(|_| i >= args.warmup) {
                    samples
                        .entry(path.as_str().to_string())
                        .or_default()
                        .push(m.value);
                }
                d.clear_history();
            }
        }
        let medians: Vec<String> = samples
            .iter_mut()
            .map(|(path, v)| {
                v.sort_by(f64::total_cmp);
                format!("\"{path}\": {:.4}", v[v.len() / 2])
            })
            .collect();
        println!("{}: {}", choice.name(), medians.join(", "));
        report.push(format!(
            "  \"{}\": {{{}}}",
            choice.name(),
            medians.join(", ")
        ));
        save_screenshots(&app, camera, &image, &args.out.join(choice.name()))?;
    }
    let adapter = app
        .world()
        .resource::<bevy::render::renderer::RenderAdapterInfo>();
    let json = format!(
        "{{\n  \"adapter\": \"{}\",\n  \"driver\": \"{} {}\",\n  \"size\": [{}, {}],\n  \"frames\": {},\n  \"warmup\": {},\n  \"median_ms\": {{\n{}\n  }}\n}}\n",
        adapter.name, adapter.driver, adapter.driver_info, args.size.0, args.size.1, args.frames, args.warmup,
        report.join(",\n")
    );
    let path = args.out.join("times.json");
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

fn frame(app: &mut App) {
    app.update();
    let device = app.world().resource::<RenderDevice>();
    let _ = device
        .wgpu_device()
        .poll(wgpu::PollType::wait_indefinitely());
}

/// `NAME.png` (the lit frame) and `NAME.ao.png` (the AO its lighting read).
fn save_screenshots(
    app: &App,
    camera: Entity,
    image: &Handle<Image>,
    stem: &std::path::Path,
) -> Result<(), String> {
    let render_world = app.sub_app(bevy::render::RenderApp).world();
    let view = app
        .world()
        .get::<bevy::render::sync_world::RenderEntity>(camera)
        .ok_or("no render entity")?
        .id();
    let ao = bevy_obscura::read_view_ao(render_world, view)?;
    let gray: Vec<u8> = ao
        .values
        .iter()
        .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let save =
        |path: std::path::PathBuf, w: u32, h: u32, bytes: Vec<u8>, color: image::ColorType| {
            image::save_buffer(&path, &bytes, w, h, color)
                .map_err(|e| format!("{}: {e}", path.display()))
        };
    save(
        stem.with_extension("ao.png"),
        ao.width,
        ao.height,
        gray,
        image::ColorType::L8,
    )?;
    let (width, height, rgba) = bevy_obscura::read_target_rgba8(render_world, image)?;
    save(
        stem.with_extension("png"),
        width,
        height,
        rgba,
        image::ColorType::Rgba8,
    )
}

/// The window's keys (run by `cargo test`: the example is built with `test = true`).
#[cfg(test)]
mod tests {
    use super::*;

    /// The camera after the key presses `presses` (each one frame: pressed, then released), from
    /// the window's first choice.
    fn after(
        presses: &[&[KeyCode]],
    ) -> (
        Switcher,
        Option<ObscuraAo>,
        Option<ScreenSpaceAmbientOcclusion>,
    ) {
        let mut world = World::new();
        world.init_resource::<ButtonInput<KeyCode>>();
        let camera = world.spawn_empty().id();
        let first = row("gtao", Preset::High);
        first.apply(&mut world.entity_mut(camera), 0.5);
        let index = Choice::ALL.iter().position(|c| *c == first).unwrap();
        world.insert_resource(Switcher {
            camera,
            index,
            choice: first,
            radius: 0.5,
        });
        for keys in presses {
            let mut input = world.resource_mut::<ButtonInput<KeyCode>>();
            for key in *keys {
                input.press(*key);
            }
            switch(&mut world);
            let mut input = world.resource_mut::<ButtonInput<KeyCode>>();
            input.release_all();
            input.clear();
        }
        let switcher = world.remove_resource::<Switcher>().unwrap();
        let entity = world.entity(camera);
        (
            switcher,
            entity.get::<ObscuraAo>().cloned(),
            entity.get::<ScreenSpaceAmbientOcclusion>().cloned(),
        )
    }

    fn settings(ao: Option<ObscuraAo>) -> AoSettings {
        ao.expect("an obscura row on the camera").resolved()
    }

    #[test]
    fn tab_and_shift_tab_walk_the_choices_and_wrap() {
        let start = Choice::ALL
            .iter()
            .position(|c| *c == row("gtao", Preset::High))
            .unwrap();
        let (s, ao, _) = after(&[&[KeyCode::Tab]]);
        assert_eq!((s.index, s.choice), (start + 1, Choice::ALL[start + 1]));
        assert_eq!(settings(ao).technique.to_string(), "gtao-vb");
        // Back past the first choice to the last.
        let back: Vec<&[KeyCode]> = vec![&[KeyCode::ShiftLeft, KeyCode::Tab]; start + 1];
        let (s, ao, _) = after(&back);
        assert_eq!(s.index, Choice::ALL.len() - 1);
        assert_eq!(settings(ao).technique.to_string(), "rtao");
        // Forward to Bevy's SSAO: obscura's component goes, Bevy's quality is set.
        let forward: Vec<&[KeyCode]> = vec![&[KeyCode::Tab]; Choice::ALL.len() - start];
        let (s, ao, ssao) = after(&forward);
        assert_eq!(s.index, 0);
        assert!(ao.is_none(), "Bevy's SSAO alone");
        assert_eq!(
            ssao.unwrap().quality_level,
            ScreenSpaceAmbientOcclusionQualityLevel::Medium
        );
    }

    #[test]
    fn digits_set_the_preset_h_the_resolution_and_b_the_blur() {
        let (s, ao, _) = after(&[&[KeyCode::Digit1], &[KeyCode::KeyH], &[KeyCode::KeyB]]);
        let mut expected = AoSettings::preset("gtao".parse().unwrap(), Preset::Low);
        expected.resolution = Resolution::Half;
        expected.blur.enabled = false;
        expected.set_every_radius(0.5);
        assert_eq!(settings(ao), expected);
        assert_eq!(s.choice.name(), "gtao-low-half-unblurred");
        // The changes stay through later presses, and H and B switch back.
        let (s, ao, _) = after(&[
            &[KeyCode::KeyH],
            &[KeyCode::KeyB],
            &[KeyCode::Digit4],
            &[KeyCode::KeyH],
            &[KeyCode::KeyB],
        ]);
        assert_eq!(s.choice.name(), "gtao-ultra");
        let mut expected = AoSettings::preset("gtao".parse().unwrap(), Preset::Ultra);
        expected.set_every_radius(0.5);
        assert_eq!(settings(ao), expected);
    }

    #[test]
    fn keys_that_do_not_apply_change_nothing() {
        // On Bevy's SSAO the preset, H and B keys do nothing; a key of no meaning never does.
        let to_bevy: Vec<&[KeyCode]> = vec![
            &[KeyCode::ShiftLeft, KeyCode::Tab];
            Choice::ALL
                .iter()
                .position(|c| *c == row("gtao", Preset::High))
                .unwrap()
                - 1
        ];
        let (s, _, _) = after(&to_bevy);
        assert!(matches!(s.choice, Choice::Bevy(_)), "{:?}", s.choice);
        let mut more = to_bevy.clone();
        more.extend([
            &[KeyCode::Digit1][..],
            &[KeyCode::KeyH],
            &[KeyCode::KeyB],
            &[KeyCode::KeyQ],
        ]);
        let (t, ao, ssao) = after(&more);
        assert_eq!((t.index, t.choice), (s.index, s.choice));
        assert!(ao.is_none());
        assert_eq!(
            ssao.unwrap().quality_level,
            ScreenSpaceAmbientOcclusionQualityLevel::High
        );
    }
}
