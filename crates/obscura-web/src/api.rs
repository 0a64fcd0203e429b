//! The JavaScript API's free functions and the module's start-up (wasm32 only).

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
/// hiddenDepth}]` ([`crate::rows::techniques_json`]).
#[wasm_bindgen]
pub fn techniques() -> String {
    crate::rows::techniques_json()
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
