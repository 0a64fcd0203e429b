//! obscura in the browser: the library's [`obscura::Renderer`] behind a JavaScript API made with
//! `wasm-bindgen`, on the browser's WebGPU (docs/WEB.md).
//!
//! The page asks for frames with a JSON-like request ([`request::RenderRequest`]: technique,
//! preset or settings, size, camera) and gets back a [`frame::Frame`] whose images are typed
//! arrays (AO, depth, normals, base colour, pass timings), drawn by the page itself. Every error is
//! a JavaScript exception carrying the library's message. Nothing here is a second
//! implementation: scenes load, cameras default and settings resolve through the same library
//! functions the CLI calls, so a frame equals `obscura render`'s of the same view (the browser
//! tests hold them to it).

mod frame;
mod request;
mod viewer;

pub use frame::Frame;
pub use viewer::Viewer;

use wasm_bindgen::prelude::*;

/// A library error as a JavaScript `Error` with its message (`JsError` keeps the text and gives
/// the page a stack).
pub(crate) fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// The built-in scenes' names (`stairs`, …), for the page's scene menu.
#[wasm_bindgen(js_name = builtinScenes)]
pub fn builtin_scenes() -> Vec<String> {
    obscura::scene::builtin_names()
        .iter()
        .map(|s| s.to_string())
        .collect()
}

/// Every technique row as JSON: `[{name, summary, paper, estimator, source, schedule,
/// hiddenDepth}]` (`hiddenDepth`: whether its source recovers what the depth buffer hides,
/// [`obscura::technique::Source::sees_hidden_geometry`]).
#[wasm_bindgen]
pub fn techniques() -> String {
    let rows: Vec<serde_json::Value> = obscura::Technique::all()
        .map(|t| {
            let row = t.row();
            serde_json::json!({
                "name": row.name,
                "summary": row.summary,
                "paper": row.paper,
                "estimator": row.estimator.name(),
                "source": row.source.name(),
                "schedule": row.schedule.name(),
                "hiddenDepth": row.source.sees_hidden_geometry(),
            })
        })
        .collect();
    serde_json::Value::Array(rows).to_string()
}

/// The presets' names (`low`, `medium`, `high`, `ultra`).
#[wasm_bindgen]
pub fn presets() -> Vec<String> {
    obscura::Preset::ALL
        .iter()
        .map(|p| p.name().to_string())
        .collect()
}

/// An AO image (`width`×`height` values, row-major) as the float EXR file `obscura render --out
/// x.exr` writes, for download and for comparing with the CLI (`obscura diff`).
#[wasm_bindgen(js_name = aoToExr)]
pub fn ao_to_exr(width: u32, height: u32, ao: &[f32]) -> Result<Vec<u8>, JsError> {
    obscura::output::ao_exr_bytes(width, height, ao).map_err(js_error)
}

/// Panics reach the browser console with their message (a wasm panic otherwise shows only as
/// "unreachable executed"), and the library's log lines (warnings about a scene) go there too.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| console_error(&info.to_string())));
    // Fails only when a logger is set already (start runs once).
    let _ = log::set_logger(&CONSOLE).map(|()| log::set_max_level(log::LevelFilter::Warn));
}

#[wasm_bindgen]
extern "C" {
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(message: &str);
    #[wasm_bindgen(js_namespace = console, js_name = warn)]
    fn console_warn(message: &str);
}

/// `log` records on the browser console.
struct Console;
static CONSOLE: Console = Console;

impl log::Log for Console {
    fn enabled(&self, metadata: &log::Metadata) -> bool {
        metadata.level() <= log::Level::Warn
    }

    fn log(&self, record: &log::Record) {
        if self.enabled(record.metadata()) {
            console_warn(&format!("obscura: {}", record.args()));
        }
    }

    fn flush(&self) {}
}

#[cfg(test)]
mod tests {
    #[test]
    fn rows_say_whether_they_see_hidden_geometry() {
        let rows: Vec<serde_json::Value> = serde_json::from_str(&super::techniques()).unwrap();
        assert_eq!(rows.len(), obscura::Technique::all().count());
        let hidden = |name: &str| {
            rows.iter().find(|r| r["name"] == name).unwrap()["hiddenDepth"]
                .as_bool()
                .unwrap()
        };
        for name in ["sd-vao", "rt-vao", "vao-dual", "ray-sd-hbao", "rtao"] {
            assert!(hidden(name), "{name}");
        }
        for name in ["vao", "gtao", "hbao+", "sao", "pyramid-hbao", "hemisphere"] {
            assert!(!hidden(name), "{name}");
        }
    }

    #[test]
    fn exr_bytes_are_the_clis_file() {
        let ao = [0.25f32, 0.5, 0.75, 1.0, 0.0, 0.125];
        let bytes = obscura::output::ao_exr_bytes(3, 2, &ao).unwrap();
        let dir = tempfile_dir();
        let path = dir.join("ao.exr");
        std::fs::write(&path, bytes).unwrap();
        let read = obscura::output::read_ao(&path).unwrap();
        assert_eq!((read.width, read.height), (3, 2));
        assert_eq!(read.values, ao);
        assert!(obscura::output::ao_exr_bytes(3, 3, &ao).is_err());
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// A fresh folder under the system's temporary one (no dev-dependency for one test).
    fn tempfile_dir() -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("obscura-web-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }
}
