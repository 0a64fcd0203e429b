//! One rendered frame as the page receives it: typed arrays of the visible image.

use wasm_bindgen::prelude::*;

/// A frame's images, row-major from the top row, `width`×`height` (guard band cropped).
#[wasm_bindgen]
pub struct Frame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) ao: Vec<f32>,
    pub(crate) depth: Vec<f32>,
    pub(crate) normals: Vec<f32>,
    pub(crate) albedo: Vec<u8>,
    pub(crate) timings: Option<String>,
    pub(crate) ms_to_first_read: f64,
}

#[wasm_bindgen]
impl Frame {
    /// Visible width, pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Visible height, pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// AO, 1 = unoccluded, 0 = fully occluded (the library's convention).
    #[wasm_bindgen(getter)]
    pub fn ao(&self) -> Vec<f32> {
        self.ao.clone()
    }

    /// Linear depth (view distance along the view axis, scene units), 0 on the background.
    /// Empty unless the request asked for `gbuffer`.
    #[wasm_bindgen(getter)]
    pub fn depth(&self) -> Vec<f32> {
        self.depth.clone()
    }

    /// View-space normals, x, y, z per pixel (zero on the background). Empty unless the request
    /// asked for `gbuffer`.
    #[wasm_bindgen(getter)]
    pub fn normals(&self) -> Vec<f32> {
        self.normals.clone()
    }

    /// Base colour, sRGB-encoded RGBA8 per pixel (alpha 0 on the background). Empty unless the
    /// request asked for `gbuffer`.
    #[wasm_bindgen(getter)]
    pub fn albedo(&self) -> Vec<u8> {
        self.albedo.clone()
    }

    /// GPU time per pass in milliseconds, as JSON (`{"gbuffer": 0.8, …}`), where the request
    /// asked for timings and the device has timestamp queries; otherwise `undefined`.
    #[wasm_bindgen(getter)]
    pub fn timings(&self) -> Option<String> {
        self.timings.clone()
    }

    /// Wall time from the request to the AO read back, milliseconds (the browser's clock:
    /// includes pipeline creation on a renderer's first frame).
    #[wasm_bindgen(getter, js_name = wallMs)]
    pub fn wall_ms(&self) -> f64 {
        self.ms_to_first_read
    }

    /// The AO as the float EXR file `obscura render --out x.exr` writes.
    pub fn exr(&self) -> Result<Vec<u8>, JsError> {
        crate::api::ao_to_exr(self.width, self.height, &self.ao)
    }
}
