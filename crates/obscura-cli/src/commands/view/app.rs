//! The window: eframe on wgpu, its device handed to obscura (`Gpu::from_device`) so the AO is
//! rendered and displayed without leaving the GPU. Left panel: technique, presets, settings,
//! split screen, views, camera; right panel: per-pass GPU timings; centre: the image, driven by
//! the fly camera. Errors from a settings combination stay in the panel; errors before the
//! window opens, or in `--screenshot` runs, end the command with a non-zero status.

use super::camera::{FlyCamera, Motion};
use super::controls;
use super::frame::{DebugView, Frame};
use super::reference::ReferenceJob;
use super::StartState;
use anyhow::{anyhow, Result};
use eframe::egui::{self, Key};
use eframe::{egui_wgpu, wgpu};
use obscura::scene::Camera;
use obscura::{AoSettings, Gpu, Technique};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The keys, as the help overlay (F1 / H) shows them.
const KEYS: &[(&str, &str)] = &[
    ("W A S D", "move forward, left, back, right"),
    ("Q / E", "move down / up"),
    ("Shift", "move four times faster"),
    ("drag (left or right button)", "look around"),
    ("drag the yellow line", "move the split"),
    ("mouse wheel", "movement speed"),
    (
        "1 … 8",
        "view: AO, composite, normals, depth, SD layer, sample masks, requested pixels, reference",
    ),
    ("B", "split screen on / off"),
    ("R", "trace the reference of this view (background)"),
    (
        "C",
        "print the camera as flags and as a path keyframe (stdout)",
    ),
    ("Home", "back to the starting camera"),
    ("F1 / H", "this help"),
    ("Esc", "close the help, else quit"),
];

/// Features obscura uses where the adapter has them (as `Gpu::new` asks for).
fn wanted_features() -> wgpu::Features {
    obscura::gpu::WANTED_FEATURES
}

fn backend_from(name: &str) -> Result<wgpu::Backends> {
    match name.to_ascii_lowercase().as_str() {
        "vulkan" | "vk" => Ok(wgpu::Backends::VULKAN),
        "metal" => Ok(wgpu::Backends::METAL),
        "dx12" | "d3d12" => Ok(wgpu::Backends::DX12),
        "gl" | "gles" | "opengl" => Ok(wgpu::Backends::GL),
        _ => Err(anyhow!(
            "unknown backend '{name}': use vulkan, metal, dx12 or gl"
        )),
    }
}

/// eframe's device set-up: obscura's features and the adapter's limits, the backend and adapter
/// asked for (`--backend`/`OBSCURA_BACKEND`, `--adapter`), discrete GPUs first.
fn wgpu_configuration(options: &obscura::GpuOptions) -> Result<egui_wgpu::WgpuConfiguration> {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    let backend = options.backend.clone().or_else(|| {
        std::env::var("OBSCURA_BACKEND")
            .ok()
            .filter(|s| !s.is_empty())
    });
    setup.instance_descriptor.backends = match &backend {
        Some(b) => backend_from(b)?,
        None => wgpu::Backends::PRIMARY,
    };
    setup.device_descriptor = Arc::new(|adapter: &wgpu::Adapter| wgpu::DeviceDescriptor {
        label: Some("obscura view"),
        required_features: adapter.features() & wanted_features(),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    let filter = options.adapter.clone();
    setup.native_adapter_selector = Some(Arc::new(move |adapters, surface| {
        let mut usable: Vec<&wgpu::Adapter> = adapters
            .iter()
            .filter(|a| surface.is_none_or(|s| a.is_surface_supported(s)))
            .collect();
        if let Some(f) = &filter {
            let needle = f.to_ascii_lowercase();
            let names: Vec<String> = usable.iter().map(|a| a.get_info().name).collect();
            usable.retain(|a| a.get_info().name.to_ascii_lowercase().contains(&needle));
            if usable.is_empty() {
                return Err(format!(
                    "no GPU adapter matching '{f}' can draw to this window; the adapters here \
                     are: {}",
                    names.join("; ")
                ));
            }
        }
        usable.sort_by_key(|a| match a.get_info().device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        });
        usable.first().map(|a| (*a).clone()).ok_or_else(|| {
            "no GPU adapter can draw to this window. obscura needs Vulkan, Metal or DX12; on a \
             machine without a GPU install Mesa's software Vulkan driver (Debian/Ubuntu: `sudo \
             apt-get install mesa-vulkan-drivers`)"
                .to_string()
        })
    }));
    Ok(egui_wgpu::WgpuConfiguration {
        wgpu_setup: setup.into(),
        ..Default::default()
    })
}

pub fn run_window(options: &obscura::GpuOptions, start: StartState) -> Result<()> {
    let wgpu_options = wgpu_configuration(options)?;
    let (w, h) = start.size.unwrap_or((1280, 720));
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(format!("obscura view — {}", start.scene.name))
            .with_inner_size([w as f32 + 560.0, (h as f32 + 16.0).max(640.0)]),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options,
        ..Default::default()
    };
    let outcome: Arc<Mutex<Option<anyhow::Error>>> = Arc::default();
    let sink = outcome.clone();
    eframe::run_native(
        "obscura view",
        native,
        Box::new(move |cc| {
            let state = cc
                .wgpu_render_state
                .as_ref()
                .ok_or("eframe started without its wgpu renderer")?;
            let gpu = Gpu::from_device(
                state.adapter.clone(),
                state.device.clone(),
                state.queue.clone(),
            );
            Ok(Box::new(ViewerApp::new(
                gpu,
                state.renderer.clone(),
                start,
                sink,
            )))
        }),
    )
    .map_err(|e| {
        anyhow!(
            "could not open the viewer window: {e}. It needs a display (DISPLAY or \
             WAYLAND_DISPLAY; headless: run it under Xvfb) and a GPU adapter that can draw to it; \
             `obscura view --offscreen-frames N` renders without a window"
        )
    })?;
    let error = outcome.lock().map(|mut e| e.take()).unwrap_or(None);
    match error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// egui's wgpu renderer, shared with eframe (native textures are registered with it).
type EguiRenderer = Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>;

struct ViewerApp {
    gpu: Gpu,
    egui_renderer: EguiRenderer,
    start: StartState,
    outcome: Arc<Mutex<Option<anyhow::Error>>>,
    frame: Option<Frame>,
    texture: Option<egui::TextureId>,
    fly: FlyCamera,
    camera: Camera,
    /// The settings being edited (A; B uses them with its own technique).
    settings: AoSettings,
    split_on: bool,
    split_technique: Technique,
    /// The divider's position, a fraction of the image width.
    split_frac: f32,
    dragging_divider: bool,
    view: DebugView,
    /// `None`: the default for the image height.
    guard_band: Option<u32>,
    reference: ReferenceJob,
    show_help: bool,
    frames: u32,
    last_instant: Instant,
    frame_ms: f32,
    /// A size the image area asked for, and since when (resizes wait until it settles).
    pending_size: Option<((u32, u32), Instant)>,
    message: Option<String>,
    error: Option<String>,
}

impl ViewerApp {
    fn new(
        gpu: Gpu,
        egui_renderer: EguiRenderer,
        start: StartState,
        outcome: Arc<Mutex<Option<anyhow::Error>>>,
    ) -> Self {
        let diagonal = start.scene.bounds().diagonal();
        Self {
            fly: FlyCamera::from_camera(&start.camera, diagonal),
            camera: start.camera,
            settings: start.settings,
            split_on: start.split.is_some(),
            split_technique: start.split.unwrap_or(Technique::Vao),
            split_frac: 0.5,
            dragging_divider: false,
            view: start.view,
            guard_band: start.guard_band,
            reference: ReferenceJob::default(),
            show_help: false,
            frames: 0,
            last_instant: Instant::now(),
            frame_ms: 0.0,
            pending_size: None,
            message: None,
            error: None,
            frame: None,
            texture: None,
            gpu,
            egui_renderer,
            start,
            outcome,
        }
    }

    fn split(&self) -> Option<Technique> {
        self.split_on.then_some(self.split_technique)
    }

    /// End the run with `error` (screenshot runs) or show it (interactive).
    fn fail(&mut self, ctx: &egui::Context, error: anyhow::Error) {
        if self.start.screenshot.is_some() || self.start.frames.is_some() {
            if let Ok(mut slot) = self.outcome.lock() {
                slot.get_or_insert(error);
            }
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        } else {
            self.error = Some(format!("{error:#}"));
        }
    }

    fn print_camera(&mut self) {
        let flags = self.fly.flags();
        let key = self.fly.keyframe(0.0);
        println!("{flags}");
        println!("{key}");
        self.message = Some(format!("printed to stdout:\n{flags}\n{key}"));
    }

    fn start_reference(&mut self) {
        let Some(frame) = &self.frame else { return };
        self.reference.start(
            frame.scene.clone(),
            frame.bvh.clone(),
            self.camera,
            (frame.width, frame.height, frame.guard_band),
            self.settings.vao,
        );
        self.view = DebugView::Reference;
    }

    /// Keyboard and wheel (when no text field has the focus); returns the camera motion.
    fn keys(&mut self, ctx: &egui::Context) -> Motion {
        let mut motion = Motion::default();
        // Sliders keep the focus after a click: only a text field being edited takes the keys.
        if ctx.text_edit_focused() {
            return motion;
        }
        let axis = |i: &egui::InputState, plus: Key, minus: Key| {
            f32::from(u8::from(i.key_down(plus))) - f32::from(u8::from(i.key_down(minus)))
        };
        ctx.input(|i| {
            motion.forward = axis(i, Key::W, Key::S);
            motion.right = axis(i, Key::D, Key::A);
            motion.up = axis(i, Key::E, Key::Q);
            motion.fast = i.modifiers.shift;
        });
        let pressed = |k: Key| ctx.input(|i| i.key_pressed(k));
        if pressed(Key::F1) || pressed(Key::H) {
            self.show_help = !self.show_help;
        }
        if pressed(Key::Escape) {
            if self.show_help {
                self.show_help = false;
            } else {
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        if pressed(Key::C) {
            self.print_camera();
        }
        if pressed(Key::R) {
            self.start_reference();
        }
        if pressed(Key::B) {
            self.split_on = !self.split_on;
        }
        if pressed(Key::Home) {
            self.fly =
                FlyCamera::from_camera(&self.start.camera, self.start.scene.bounds().diagonal());
        }
        let digits = [
            Key::Num1,
            Key::Num2,
            Key::Num3,
            Key::Num4,
            Key::Num5,
            Key::Num6,
            Key::Num7,
            Key::Num8,
        ];
        for (k, v) in digits.into_iter().zip(DebugView::ALL) {
            if pressed(k) {
                self.view = v;
            }
        }
        motion
    }

    fn settings_panel(&mut self, ui: &mut egui::Ui) {
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("technique");
            controls::technique_combo(ui, "A", &mut self.settings.technique);
            ui.label(self.settings.technique.row().summary);
            controls::presets(ui, &mut self.settings, self.start.units_per_metre);
            let scale = self.start.scene.bounds().diagonal();
            controls::parameters(ui, &mut self.settings, scale);
            let default_guard = self
                .frame
                .as_ref()
                .map_or(64, |f| obscura::default_guard_band(f.height));
            let mut auto = self.guard_band.is_none();
            ui.horizontal(|ui| {
                ui.checkbox(&mut auto, "default guard band");
                if auto {
                    ui.label(format!("{default_guard} px"));
                }
            });
            if auto {
                self.guard_band = None;
            } else {
                let g = self.guard_band.get_or_insert(default_guard);
                ui.add(egui::Slider::new(g, 0..=256).text("guard band (px)"));
            }
            if let Some(e) = self.frame.as_ref().and_then(|f| f.a.error.as_ref()) {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.separator();
            ui.heading("split screen");
            ui.checkbox(&mut self.split_on, "split (B on the right)");
            if self.split_on {
                controls::technique_combo(ui, "B", &mut self.split_technique);
                ui.add(egui::Slider::new(&mut self.split_frac, 0.05..=0.95).text("divider"));
                if let Some(e) = self
                    .frame
                    .as_ref()
                    .and_then(|f| f.b.as_ref())
                    .and_then(|b| b.error.as_ref())
                {
                    ui.colored_label(egui::Color32::LIGHT_RED, e);
                }
            }
            ui.separator();
            ui.heading("view");
            for (i, v) in DebugView::ALL.into_iter().enumerate() {
                let available = v.available(self.settings.technique);
                ui.add_enabled_ui(available, |ui| {
                    ui.radio_value(&mut self.view, v, format!("{} {}", i + 1, v.name()));
                });
            }
            if matches!(
                self.view,
                DebugView::SdLayer | DebugView::SampleMasks | DebugView::RequestedPixels
            ) {
                ui.small("read back from the GPU every frame (slow by design)");
            }
            ui.separator();
            ui.heading("reference");
            match self.reference.poll() {
                Some(progress) => {
                    ui.add(egui::ProgressBar::new(progress).text("tracing on the CPU…"));
                    ui.ctx().request_repaint();
                }
                None => {
                    if ui.button("trace reference (R)").clicked() {
                        self.start_reference();
                    }
                }
            }
            if let Some(done) = &self.reference.done {
                let current = done.camera == self.camera;
                ui.small(format!(
                    "vao model, {:.1} s{}",
                    done.seconds,
                    if current {
                        ""
                    } else {
                        " (for an earlier view)"
                    }
                ));
            }
            if let Some(e) = &self.reference.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.separator();
            ui.heading("camera");
            ui.add(egui::Slider::new(&mut self.fly.fov, 10.0..=120.0).text("fov (°)"));
            ui.add(
                egui::Slider::new(&mut self.fly.speed, 1e-3..=1e4)
                    .logarithmic(true)
                    .text("speed"),
            );
            if ui.button("copy camera (C)").clicked() {
                self.print_camera();
            }
            if let Some(m) = &self.message {
                ui.small(m);
            }
            ui.small("F1 or H: keys");
        });
    }

    fn timings_panel(&self, ui: &mut egui::Ui) {
        ui.heading("frame");
        ui.label(format!(
            "{:.2} ms ({:.0} frames/s)",
            self.frame_ms,
            1000.0 / self.frame_ms.max(1e-3)
        ));
        if let Some(f) = &self.frame {
            ui.label(format!(
                "{}x{} + {} px guard band",
                f.width, f.height, f.guard_band
            ));
        }
        ui.small(format!(
            "{} ({}, {})",
            self.gpu.summary.name, self.gpu.summary.backend, self.gpu.summary.device_type
        ));
        if let Some(warning) = crate::args::software_timings_warning(&self.gpu) {
            ui.colored_label(ui.visuals().warn_fg_color, warning);
        }
        ui.separator();
        ui.heading("GPU passes");
        match self.frame.as_ref().and_then(|f| f.timings.as_ref()) {
            None => {
                ui.label("no GPU timings on this adapter");
            }
            Some(panes) => {
                for (i, timings) in panes.iter().enumerate() {
                    let who = match (i, &self.frame) {
                        (0, Some(f)) => f.a.settings.technique.name(),
                        (_, Some(f)) => f.b.as_ref().map_or("B", |b| b.settings.technique.name()),
                        _ => "",
                    };
                    ui.strong(who);
                    egui::Grid::new(("timings", i))
                        .striped(true)
                        .show(ui, |ui| {
                            for (name, ms) in timings {
                                ui.label(name);
                                ui.label(format!("{ms:.3} ms"));
                                ui.end_row();
                            }
                            ui.strong("total");
                            ui.strong(format!("{:.3} ms", timings.values().sum::<f64>()));
                            ui.end_row();
                        });
                }
                ui.small("one frame in 30 is timed");
            }
        }
        let budgets = self.frame.as_ref().map_or(&[][..], |f| &f.budgets[..]);
        for (i, report) in budgets.iter().enumerate() {
            let Some(r) = report else { continue };
            ui.separator();
            ui.heading(if i == 0 {
                "ray budget"
            } else {
                "ray budget (B)"
            });
            ui.label(format!("budget {} rays a frame", r.budget));
            ui.label(format!(
                "spent {} of {} wanted ({:.0} %)",
                r.granted,
                r.wanted,
                100.0 * f64::from(r.granted) / f64::from(r.wanted.max(1))
            ));
        }
    }

    fn help(&mut self, ctx: &egui::Context) {
        let mut open = self.show_help;
        egui::Window::new("keys")
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .show(ctx, |ui| {
                egui::Grid::new("keys").striped(true).show(ui, |ui| {
                    for (key, what) in KEYS {
                        ui.strong(*key);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
        self.show_help = self.show_help && open;
    }

    /// The size the image should have for this area (pixels; even, for half resolution).
    fn wanted_size(&self, area: egui::Vec2, pixels_per_point: f32) -> (u32, u32) {
        if let Some(size) = self.start.size {
            return size;
        }
        let even = |v: f32| (((v * pixels_per_point) as u32) & !1).max(16);
        (even(area.x), even(area.y))
    }

    /// Render into the display image (creating or resizing things first) and keep egui's
    /// texture pointing at it.
    fn render(&mut self, size: (u32, u32)) -> Result<()> {
        let settle = {
            let now = Instant::now();
            match self.pending_size {
                Some((s, since)) if s == size => now.duration_since(since).as_millis() >= 150,
                _ => {
                    self.pending_size = Some((size, now));
                    self.frame.is_none()
                }
            }
        };
        let guard_band = |h: u32| {
            self.guard_band
                .unwrap_or_else(|| obscura::default_guard_band(h))
        };
        let split = self.split();
        let new_texture;
        match &mut self.frame {
            None => {
                let (w, h) = size;
                self.frame = Some(Frame::new(
                    self.gpu.clone(),
                    self.start.scene.clone(),
                    self.settings,
                    split,
                    (w, h, guard_band(h)),
                    self.camera,
                ));
                new_texture = true;
            }
            Some(frame) => {
                let (w, h) = if settle {
                    size
                } else {
                    (frame.width, frame.height)
                };
                new_texture = frame.configure(self.settings, split, (w, h, guard_band(h)));
            }
        }
        let frame = self.frame.as_mut().expect("created above");
        let split_x = Some((self.split_frac * frame.width as f32) as u32);
        let reference = self
            .reference
            .image_for(&self.camera, frame.width, frame.height);
        let profile = self.frames.is_multiple_of(30);
        frame.render(&self.camera, self.view, split_x, reference, profile)?;
        let view = frame.display.texture().create_view(&Default::default());
        let mut renderer = self.egui_renderer.write();
        match self.texture {
            Some(id) if new_texture => renderer.update_egui_texture_from_wgpu_texture(
                &self.gpu.device,
                &view,
                wgpu::FilterMode::Linear,
                id,
            ),
            Some(_) => {}
            None => {
                self.texture = Some(renderer.register_native_texture(
                    &self.gpu.device,
                    &view,
                    wgpu::FilterMode::Linear,
                ))
            }
        }
        Ok(())
    }

    /// After `--frames` frames: save `--screenshot` (the image), ask eframe for the whole window
    /// (`NAME.window.png`, the panels included), and close once it came (or 30 frames later).
    fn finish_run(&mut self, ctx: &egui::Context) {
        let Some(limit) = self.start.frames else {
            return;
        };
        if self.frames < limit {
            return;
        }
        let Some(path) = self.start.screenshot.clone() else {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        };
        if self.frames == limit {
            let saved = match &self.frame {
                Some(frame) => save(path.clone(), frame),
                None => Err(anyhow!("no frame was rendered")),
            };
            if let Err(e) = saved {
                self.fail(ctx, e);
                return;
            }
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(Default::default()));
            return;
        }
        // eframe answers the command with an input event a frame or two later.
        let image = ctx.input(|input| {
            input.events.iter().find_map(|event| match event {
                egui::Event::Screenshot { image, .. } => Some(image.clone()),
                _ => None,
            })
        });
        if let Some(image) = image {
            let window = path.with_extension("window.png");
            let [w, h] = image.size;
            let result = super::save_png(&window, w as u32, h as u32, image.as_raw().to_vec());
            match result {
                Ok(()) => eprintln!("wrote {}", window.display()),
                Err(e) => eprintln!("warning: could not save the window image: {e:#}"),
            }
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        } else if self.frames > limit + 30 {
            eprintln!("warning: no window image came back from eframe; only the image was saved");
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }
}

fn save(path: PathBuf, frame: &Frame) -> Result<()> {
    for pane in std::iter::once(&frame.a).chain(frame.b.as_ref()) {
        if let Some(e) = &pane.error {
            return Err(anyhow!("{}: {e}", pane.settings.technique));
        }
    }
    super::save_png(&path, frame.width, frame.height, frame.read_rgba()?)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let now = Instant::now();
        let dt = now
            .duration_since(self.last_instant)
            .as_secs_f32()
            .min(0.25);
        self.last_instant = now;
        let ms = dt * 1e3;
        self.frame_ms = if self.frame_ms == 0.0 {
            ms
        } else {
            0.9 * self.frame_ms + 0.1 * ms
        };
        let mut motion = self.keys(&ctx);
        egui::Panel::left("settings")
            .default_size(290.0)
            .resizable(true)
            .show(ui, |ui| self.settings_panel(ui));
        egui::Panel::right("timings")
            .default_size(250.0)
            .resizable(true)
            .show(ui, |ui| self.timings_panel(ui));
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let area = ui.available_rect_before_wrap();
            let (rect, response) = ui.allocate_exact_size(area.size(), egui::Sense::drag());
            let size = self.wanted_size(rect.size(), ctx.pixels_per_point());
            // The image keeps its aspect ratio inside the area (a fixed --size may not fit).
            let aspect = size.0 as f32 / size.1 as f32;
            let fit = if rect.width() / rect.height() > aspect {
                egui::vec2(rect.height() * aspect, rect.height())
            } else {
                egui::vec2(rect.width(), rect.width() / aspect)
            };
            let image_rect = egui::Rect::from_center_size(rect.center(), fit);
            let divider_x = image_rect.left() + self.split_frac * image_rect.width();
            if response.drag_started() {
                self.dragging_divider = self.split_on
                    && response
                        .interact_pointer_pos()
                        .is_some_and(|p| (p.x - divider_x).abs() < 8.0);
            }
            if response.dragged() {
                let delta = response.drag_delta();
                if self.dragging_divider {
                    self.split_frac =
                        (self.split_frac + delta.x / image_rect.width().max(1.0)).clamp(0.05, 0.95);
                } else {
                    motion.drag = [delta.x, delta.y];
                }
            }
            if response.hovered() {
                let scroll = ctx.input(|i| i.smooth_scroll_delta.y);
                if scroll != 0.0 {
                    self.fly.speed = (self.fly.speed * (1.0 + scroll * 0.002)).clamp(1e-3, 1e4);
                }
            }
            self.fly.update(&motion, dt);
            self.camera = self.fly.camera(&self.camera);
            // Rebuilding renderers while a slider is dragged would stall every step: wait for
            // the release (the first frame always builds).
            let busy = ctx.input(|i| i.pointer.any_down()) && self.frame.is_some();
            let stale_settings = self.frame.as_ref().is_some_and(|f| {
                f.a.settings != self.settings
                    || f.b.as_ref().map(|b| b.settings.technique) != self.split()
            });
            if !(busy && stale_settings) {
                if let Err(e) = self.render(size) {
                    self.fail(&ctx, e);
                }
            } else if let Some(frame) = &mut self.frame {
                // Keep rendering the current settings while the slider moves.
                let split_x = Some((self.split_frac * frame.width as f32) as u32);
                if let Err(e) = frame.render(&self.camera, self.view, split_x, None, false) {
                    self.fail(&ctx, e);
                }
            }
            if let Some(id) = self.texture {
                ui.painter().image(
                    id,
                    image_rect,
                    egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                    egui::Color32::WHITE,
                );
            }
            let mut notes = Vec::new();
            if let Some(note) = self.frame.as_ref().and_then(|f| f.view_note.clone()) {
                notes.push(note);
            }
            if let Some(e) = &self.error {
                notes.push(e.clone());
            }
            if !notes.is_empty() {
                ui.painter().text(
                    rect.left_top() + egui::vec2(8.0, 8.0),
                    egui::Align2::LEFT_TOP,
                    notes.join("\n"),
                    egui::FontId::proportional(14.0),
                    egui::Color32::YELLOW,
                );
            }
            ui.painter().text(
                rect.left_bottom() + egui::vec2(8.0, -8.0),
                egui::Align2::LEFT_BOTTOM,
                "F1 / H: keys",
                egui::FontId::proportional(12.0),
                egui::Color32::from_gray(200),
            );
        });
        self.help(&ctx);
        // `--view reference`: trace it for the first frame's view. A `--frames` run waits for it,
        // so its screenshot shows the reference.
        let tracing = self.reference.poll().is_some();
        if self.view == DebugView::Reference
            && !tracing
            && self.reference.done.is_none()
            && self.reference.error.is_none()
            && self.frame.is_some()
        {
            self.start_reference();
        }
        if !(tracing && self.start.frames.is_some()) {
            self.frames += 1;
        }
        self.finish_run(&ctx);
        ctx.request_repaint();
    }
}
