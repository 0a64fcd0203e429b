//! The page's handle on the GPU and the loaded scene: makes renderers and renders frames.

use crate::api::js_error;
use crate::frame::Frame;
use crate::request::RenderRequest;
use obscura::bvh::BvhCache;
use obscura::scene::{Camera, Scene};
use obscura::{Gpu, PassProfiler, Renderer};
use wasm_bindgen::prelude::*;

/// Renderers kept alive for reuse, most recent last: two, for the split screen's two rows (a
/// renderer's first frame compiles its pipelines, seconds in a software browser).
const KEPT_RENDERERS: usize = 2;

/// A WebGPU device, the loaded scene and the renderers made for it.
#[wasm_bindgen]
pub struct Viewer {
    gpu: Gpu,
    scene: Option<Scene>,
    bvh: BvhCache,
    /// (what it was made for, the renderer).
    renderers: Vec<(String, Renderer)>,
}

/// Whether this JavaScript global has `navigator.gpu` (WebGPU).
fn has_webgpu() -> bool {
    let global = js_sys::global();
    js_sys::Reflect::get(&global, &"navigator".into())
        .ok()
        .filter(|n| !n.is_undefined())
        .and_then(|n| js_sys::Reflect::get(&n, &"gpu".into()).ok())
        .is_some_and(|gpu| !gpu.is_undefined() && !gpu.is_null())
}

/// A camera as the page's JSON (`{eye, target, up, fov}`).
fn camera_json(camera: &Camera) -> serde_json::Value {
    serde_json::json!({
        "eye": camera.eye.to_array(),
        "target": camera.target.to_array(),
        "up": camera.up.to_array(),
        "fov": camera.fov_y_deg,
    })
}

#[wasm_bindgen]
impl Viewer {
    /// A viewer on the browser's WebGPU adapter. `limits`: `"adapter"` (the default: what the
    /// adapter allows, as the native library asks for) or `"default"` (WebGPU's default limits,
    /// what every browser grants). Throws where the browser has no WebGPU, or gives no adapter.
    pub async fn create(limits: Option<String>) -> Result<Viewer, JsError> {
        if !has_webgpu() {
            return Err(JsError::new(
                "this browser has no WebGPU (navigator.gpu is missing): use a recent Chrome, \
                 Edge or Safari, or Firefox with WebGPU enabled, over https or on localhost",
            ));
        }
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::BROWSER_WEBGPU,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                ..Default::default()
            })
            .await
            .map_err(|e| {
                JsError::new(&format!(
                    "WebGPU is present but gave no adapter ({e}): the GPU may be blocked for this \
                     browser (chrome://gpu says why) or the page is not a secure context"
                ))
            })?;
        let limits = match limits.as_deref() {
            None | Some("adapter") => adapter.limits(),
            Some("default") => wgpu::Limits::default(),
            Some(other) => {
                return Err(JsError::new(&format!(
                    "unknown limits '{other}': use \"adapter\" or \"default\""
                )))
            }
        };
        let gpu = Gpu::from_adapter_async(adapter, limits)
            .await
            .map_err(js_error)?;
        Ok(Viewer {
            gpu,
            scene: None,
            bvh: BvhCache::new(),
            renderers: Vec::new(),
        })
    }

    /// The adapter, as JSON: `{name, backend, deviceType, driver, timestampQueries,
    /// maxTextureDimension2d, maxStorageBufferBindingSize}`.
    #[wasm_bindgen(js_name = adapterInfo)]
    pub fn adapter_info(&self) -> String {
        let s = &self.gpu.summary;
        let info = self.gpu.adapter.get_info();
        serde_json::json!({
            "name": s.name,
            "vendor": info.vendor,
            "backend": s.backend,
            "deviceType": s.device_type,
            "driver": s.driver,
            "timestampQueries": s.timestamp_queries,
            "maxTextureDimension2d": s.max_texture_dimension_2d,
            "maxStorageBufferBindingSize": s.max_storage_buffer_binding_size,
        })
        .to_string()
    }

    /// Load a built-in scene by name ([`crate::builtin_scenes`]); returns [`Viewer::scene_info`].
    #[wasm_bindgen(js_name = loadBuiltin)]
    pub fn load_builtin(&mut self, name: &str) -> Result<String, JsError> {
        let scene = obscura::scene::builtin(name).map_err(js_error)?;
        Ok(self.set_scene(scene))
    }

    /// Load a `.glb`, or a `.gltf` with embedded buffers, from its bytes; `name` is the file's
    /// name (its extension picks the format). Returns [`Viewer::scene_info`]. Throws the
    /// loader's message for a broken file; the scene loaded before stays.
    #[wasm_bindgen(js_name = loadGltf)]
    pub fn load_gltf(&mut self, name: &str, bytes: &[u8]) -> Result<String, JsError> {
        let scene = obscura::scene::load_bytes(name, bytes).map_err(js_error)?;
        Ok(self.set_scene(scene))
    }

    fn set_scene(&mut self, scene: Scene) -> String {
        self.scene = Some(scene);
        self.bvh = BvhCache::new();
        self.renderers.clear();
        self.scene_info().expect("a scene was just set")
    }

    /// The loaded scene as JSON: `{name, triangles, center, radius, cameras: [{name, eye,
    /// target, up, fov}]}` (`radius`: half the bounds' diagonal, for an orbit camera).
    #[wasm_bindgen(js_name = sceneInfo)]
    pub fn scene_info(&self) -> Result<String, JsError> {
        let scene = self.scene()?;
        let bounds = scene.bounds();
        let cameras: Vec<serde_json::Value> = scene
            .cameras
            .iter()
            .map(|c| {
                let mut json = camera_json(&c.camera);
                json["name"] = c.name.clone().into();
                json
            })
            .collect();
        Ok(serde_json::json!({
            "name": scene.name,
            "triangles": scene.triangle_count(),
            "center": bounds.center().to_array(),
            "radius": 0.5 * bounds.diagonal(),
            "cameras": cameras,
        })
        .to_string())
    }

    /// The camera a frame without one uses (the scene's first, else the automatic one, as
    /// `obscura render` without `--camera`), for an image of aspect ratio `aspect`, as JSON.
    #[wasm_bindgen(js_name = defaultCamera)]
    pub fn default_camera(&self, aspect: f32) -> Result<String, JsError> {
        let scene = self.scene()?;
        let camera = obscura::bvh::framing::default_camera(scene, aspect).0;
        Ok(camera_json(&camera).to_string())
    }

    fn scene(&self) -> Result<&Scene, JsError> {
        self.scene
            .as_ref()
            .ok_or_else(|| JsError::new("no scene loaded: call loadBuiltin or loadGltf first"))
    }

    /// Render one frame. `request` is the JSON of `{technique, width, height, preset?,
    /// settings?, guardBand?, camera?: {eye, target, up?, fov?}, gbuffer?, timings?}`
    /// (docs/WEB.md). Throws the library's message for a bad request, a row this device cannot
    /// run, or a GPU error. Calls must not overlap (await each).
    pub async fn render(&mut self, request: &str) -> Result<Frame, JsError> {
        let started = js_sys::Date::now();
        let request = RenderRequest::parse(request).map_err(js_error)?;
        let settings = request.settings().map_err(js_error)?;
        let camera = request.camera(self.scene()?).map_err(js_error)?;
        let (width, height, guard_band) = (request.width, request.height, request.guard_band());
        let key = format!(
            "{}|{width}x{height}+{guard_band}",
            settings.to_json_string()
        );
        let gpu = self.gpu.clone();
        let index = match self.renderers.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                let scene = self.scene()?;
                let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
                let made = Renderer::with_bvh_cache(
                    &gpu, scene, &settings, width, height, guard_band, &self.bvh,
                );
                let invalid = scope.pop().await;
                let renderer = made.map_err(js_error)?;
                if let Some(e) = invalid {
                    return Err(unsupported(&settings, &e));
                }
                if self.renderers.len() == KEPT_RENDERERS {
                    self.renderers.remove(0);
                }
                self.renderers.push((key, renderer));
                self.renderers.len() - 1
            }
        };
        // Most recently used last, so that the other row's renderer is the one kept.
        let entry = self.renderers.remove(index);
        self.renderers.push(entry);
        let renderer = &mut self.renderers.last_mut().expect("just pushed").1;

        let mut profiler = match request.timings && gpu.summary.timestamp_queries {
            true => Some(PassProfiler::new(&gpu, 1).map_err(js_error)?),
            false => None,
        };
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let rendered = renderer.render(&camera, profiler.as_mut());
        let invalid = scope.pop().await;
        rendered.map_err(js_error)?;
        if let Some(e) = invalid {
            return Err(unsupported(&settings, &e));
        }
        let ao = renderer.read_ao_async().await.map_err(js_error)?;
        let ms_to_first_read = js_sys::Date::now() - started;
        let (mut depth, mut normals, mut albedo) = (Vec::new(), Vec::new(), Vec::new());
        if request.gbuffer {
            let gbuffer = renderer.read_gbuffer_async().await.map_err(js_error)?;
            depth = gbuffer.visible_depth(guard_band);
            normals = gbuffer
                .visible_normals(guard_band)
                .iter()
                .flat_map(|n| n.to_array())
                .collect();
            albedo = renderer
                .read_albedo_async()
                .await
                .map_err(js_error)?
                .concat();
        }
        let timings = match &profiler {
            Some(p) => {
                let frames = p.read_async(&gpu).await.map_err(js_error)?;
                frames
                    .last()
                    .map(|t| serde_json::to_string(t).expect("a map of numbers"))
            }
            None => None,
        };
        Ok(Frame {
            width,
            height,
            ao,
            depth,
            normals,
            albedo,
            timings,
            ms_to_first_read,
        })
    }
}

/// A validation error while making or running a row's passes: on the web this is how a row
/// that needs more than the device grants (WebGPU's limits are lower than native ones) fails.
fn unsupported(settings: &obscura::AoSettings, error: &wgpu::Error) -> JsError {
    JsError::new(&format!(
        "technique '{}' cannot run on this WebGPU device: {error}",
        settings.technique
    ))
}
