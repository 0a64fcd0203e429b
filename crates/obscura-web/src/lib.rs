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

// The JavaScript API exists only in the wasm build: natively the crate is the plain Rust the
// API rests on (requests, the row table) and its tests, so that a native `cargo test --workspace`
// builds no wasm-bindgen (whose proc macros would change `syn`'s features and with them the
// native build every other crate shares).
#[cfg(target_arch = "wasm32")]
mod api;
#[cfg(target_arch = "wasm32")]
mod frame;
pub mod request;
pub mod rows;
#[cfg(target_arch = "wasm32")]
mod viewer;

#[cfg(target_arch = "wasm32")]
pub use api::*;
#[cfg(target_arch = "wasm32")]
pub use frame::Frame;
#[cfg(target_arch = "wasm32")]
pub use viewer::Viewer;
