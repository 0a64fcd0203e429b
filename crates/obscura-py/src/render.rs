//! `render`, `gbuffer` and `engine_ao`: the library's `Renderer` (the CLI's `render`) and its
//! engine path (`EngineInput`), GIL released during the GPU work.

use crate::arrays;
use crate::device::{gpu_of, Device};
use crate::errors::{from_lib, input};
use crate::scene::Scene;
use crate::settings::{resolve, Given};
use crate::view::{camera_of, Size};
use numpy::{PyArray2, PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods};
use obscura::engine_input::arrays::{ao_from_arrays, EngineArrays, NormalArray};
use obscura::ScreenGeometry;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The most frames `frames=` takes (the CLI's `render --frames` limit).
const MAX_FRAMES: u32 = 4096;

/// Renders the AO of one view, as ``obscura render`` does: ``technique`` (a row name; default
/// the settings' own, else ``"vao"``) with ``settings`` (a dict of fields, nested or dotted, or
/// a ``.toml``/``.json`` settings file) over ``preset`` in the scene's ``units``, from
/// ``camera`` (a ``Camera``, a camera name or None), ``frames`` frames from the same camera.
/// Returns the AO as a C-contiguous float32 array of shape (height, width), rows top to bottom,
/// 1 = unoccluded (background 1). Settings and sizes are checked before any GPU work; the GIL
/// is released while it renders.
#[pyfunction]
#[pyo3(signature = (scene, technique=None, settings=None, *, camera=None, width=640, height=360,
    guard_band=None, preset=None, units=None, frames=1, device=None))]
#[allow(clippy::too_many_arguments)]
pub fn render<'py>(
    py: Python<'py>,
    scene: &Bound<'py, Scene>,
    technique: Option<&str>,
    settings: Option<&Bound<'py, PyAny>>,
    camera: Option<&Bound<'py, PyAny>>,
    width: u32,
    height: u32,
    guard_band: Option<u32>,
    preset: Option<&str>,
    units: Option<&str>,
    frames: u32,
    device: Option<&Bound<'py, Device>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let size = Size::new(width, height, guard_band)?;
    if !(1..=MAX_FRAMES).contains(&frames) {
        return Err(input(format!("frames {frames} must be 1 to {MAX_FRAMES}")));
    }
    let given = Given::from_py(settings)?;
    let settings = resolve(technique, given.as_ref(), preset, units)?;
    let camera = camera_of(py, scene, camera, size)?.camera;
    let gpu = gpu_of(py, device)?;
    let scene = scene.get().scene.clone();
    let ao = py
        .detach(|| -> Result<Vec<f32>, obscura::Error> {
            let mut renderer = size.renderer(&gpu, &scene, &settings)?;
            // Frame after frame as the CLI's `render --frames`: under hemisphere.time_budget
            // each frame is timed and the next one's ray budget follows it.
            for _ in 0..frames {
                renderer.render_frame(&camera)?;
            }
            renderer.read_ao()
        })
        .map_err(from_lib)?;
    arrays::image(py, ao, size.width, size.height)
}

/// The G-buffer of one view, as every technique sees it, for the engine path or your own
/// analysis: a dict with ``depth`` (linear view depth, 0 = background), ``normals`` (view-space
/// unit normals, (…, 3)), both over the whole framebuffer (guard band included: shape
/// (height + 2·guard_band, width + 2·guard_band)), ``projection`` and ``view_matrix`` (4×4,
/// ``m @ v``) of that framebuffer, and ``guard_band``. float32, C-contiguous.
#[pyfunction]
#[pyo3(signature = (scene, *, camera=None, width=640, height=360, guard_band=None, device=None))]
pub fn gbuffer<'py>(
    py: Python<'py>,
    scene: &Bound<'py, Scene>,
    camera: Option<&Bound<'py, PyAny>>,
    width: u32,
    height: u32,
    guard_band: Option<u32>,
    device: Option<&Bound<'py, Device>>,
) -> PyResult<Bound<'py, PyDict>> {
    let size = Size::new(width, height, guard_band)?;
    let camera = camera_of(py, scene, camera, size)?.camera;
    let gpu = gpu_of(py, device)?;
    let scene = scene.get().scene.clone();
    let settings = obscura::AoSettings::default();
    let (g, view) = py
        .detach(|| -> Result<_, obscura::Error> {
            let mut r = size.renderer(&gpu, &scene, &settings)?;
            r.render(&camera, None)?;
            let view = *r
                .view()
                .ok_or_else(|| obscura::Error::Input("nothing rendered".into()))?;
            Ok((r.read_gbuffer()?, view))
        })
        .map_err(from_lib)?;
    let out = PyDict::new(py);
    out.set_item("depth", arrays::image(py, g.depth, g.width, g.height)?)?;
    out.set_item(
        "normals",
        arrays::vectors(py, &g.normals, g.width, g.height)?,
    )?;
    out.set_item("projection", arrays::matrix(py, view.projection()))?;
    out.set_item("view_matrix", arrays::matrix(py, view.view_matrix()))?;
    out.set_item("guard_band", size.guard_band)?;
    Ok(out)
}

/// The engine path (the library's ``EngineInput``): AO from an engine's frame as arrays.
/// ``depth``: NDC z in [0, 1] of every framebuffer pixel, float32 C-contiguous of shape
/// (height + 2·guard_band, width + 2·guard_band), any convention ``projection`` (4×4,
/// ``m @ v``) rasterises with (standard or reversed Z, finite or infinite far, perspective or
/// orthographic). ``normals``: None (reconstructed from the depth) or float32 (…, …, 3) in
/// ``normal_space`` ``"view"`` or ``"world"`` (with ``view_matrix``, world to view). Returns the
/// AO of the visible (height, width) centre. Techniques that need the scene's triangles are
/// refused (``SettingsError``).
#[pyfunction]
#[pyo3(signature = (depth, projection, normals=None, *, normal_space="view", view_matrix=None,
    technique=None, settings=None, guard_band=0, preset=None, units=None, device=None))]
#[allow(clippy::too_many_arguments)]
pub fn engine_ao<'py>(
    py: Python<'py>,
    depth: PyReadonlyArray2<'py, f32>,
    projection: [[f32; 4]; 4],
    normals: Option<PyReadonlyArray3<'py, f32>>,
    normal_space: &str,
    view_matrix: Option<[[f32; 4]; 4]>,
    technique: Option<&str>,
    settings: Option<&Bound<'py, PyAny>>,
    guard_band: u32,
    preset: Option<&str>,
    units: Option<&str>,
    device: Option<&Bound<'py, Device>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let given = Given::from_py(settings)?;
    let settings = resolve(technique, given.as_ref(), preset, units)?;
    let shape = depth.shape();
    let (fh, fw) = (shape[0] as u32, shape[1] as u32);
    if fw <= 2 * guard_band || fh <= 2 * guard_band {
        return Err(input(format!(
            "depth is {fw}x{fh}: it must cover the visible image and the guard band of \
             {guard_band} px on every side"
        )));
    }
    let (width, height) = (fw - 2 * guard_band, fh - 2 * guard_band);
    Size::new(width, height, Some(guard_band))?;
    let projection = arrays::mat4(projection);
    let screen =
        ScreenGeometry::from_projection(projection, width, height, guard_band).map_err(from_lib)?;
    let depth = depth
        .as_slice()
        .map_err(|_| input("depth must be C-contiguous (numpy.ascontiguousarray)"))?;
    let normal_values: Option<&[f32]> = match &normals {
        None => None,
        Some(n) => {
            if n.shape() != [fh as usize, fw as usize, 3] {
                return Err(input(format!(
                    "normals have shape {:?}: give ({fh}, {fw}, 3), the depth's pixels",
                    n.shape()
                )));
            }
            Some(
                n.as_slice()
                    .map_err(|_| input("normals must be C-contiguous (numpy.ascontiguousarray)"))?,
            )
        }
    };
    let normals = match (normal_values, normal_space, view_matrix) {
        (None, _, _) => NormalArray::Reconstruct,
        (Some(n), "view", None) => NormalArray::View(bytemuck_vec3(n)),
        (Some(n), "world", Some(m)) => NormalArray::World(bytemuck_vec3(n), arrays::mat4(m)),
        (Some(_), "world", None) => {
            return Err(input(
                "world-space normals need view_matrix (world to view)",
            ))
        }
        (Some(_), "view", Some(_)) => {
            return Err(input(
                "view_matrix goes with normal_space=\"world\" (view-space normals need none)",
            ))
        }
        (Some(_), other, _) => {
            return Err(input(format!(
                "normal_space '{other}' is not \"view\" or \"world\""
            )))
        }
    };
    let gpu = gpu_of(py, device)?;
    let frame = EngineArrays {
        depth,
        projection,
        normals,
    };
    let ao = py
        .detach(|| ao_from_arrays(&gpu, &settings, screen, &frame))
        .map_err(from_lib)?;
    arrays::image(py, ao, width, height)
}

/// xyz triples of a flat slice (its length a multiple of 3, checked by the shape).
fn bytemuck_vec3(flat: &[f32]) -> &[[f32; 3]] {
    let (chunks, _) = flat.as_chunks::<3>();
    chunks
}

/// An AO image file (``.exr``: the first channel as float32; ``.png``: grey 0..1) as a float32
/// array of shape (height, width): what ``obscura render --out`` and ``reference --out`` write.
#[pyfunction]
pub fn read_ao<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let image = py
        .detach(|| obscura::output::read_ao(&path))
        .map_err(from_lib)?;
    arrays::image(py, image.values, image.width, image.height)
}
