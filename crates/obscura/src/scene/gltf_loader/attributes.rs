//! Vertex attributes as floats, whatever component type the file stores them in: the core
//! types (float positions and normals; float or normalized unsigned texture coordinates) and, in
//! files that use `KHR_mesh_quantization`, the integer types that extension allows (gltfpack,
//! glTF-Transform's `quantize` and Draco-free web pipelines write them).
//!
//! Why not the `gltf` crate's readers: `read_positions` and `read_normals` reinterpret any
//! accessor's bytes as `f32`, and `read_tex_coords(..).into_f32()` normalizes integer
//! coordinates even where the accessor says they are not normalized (the extension allows that).

use gltf::accessor::{util::Item, DataType, Dimensions, Iter};
use gltf::{buffer, Accessor};

use super::checks;

/// The component types an attribute may have. `KHR_mesh_quantization` (its "Extending Mesh
/// Attributes" table): POSITION as float or (normalized or not) signed and unsigned bytes and
/// shorts; NORMAL as float or normalized signed bytes and shorts; TEXCOORD_n as float or (normalized
/// or not) signed and unsigned bytes and shorts. Core glTF 2.0 (§3.7.2.1): float POSITION and
/// NORMAL, TEXCOORD_n float or normalized unsigned bytes and shorts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Attribute {
    Position,
    Normal,
    TexCoord,
    /// `EXT_mesh_gpu_instancing`'s per-instance TRANSLATION, ROTATION and SCALE (instancing.rs).
    InstanceTranslation,
    InstanceRotation,
    InstanceScale,
}

impl Attribute {
    fn name(self) -> &'static str {
        match self {
            Attribute::Position => "POSITION",
            Attribute::Normal => "NORMAL",
            Attribute::TexCoord => "TEXCOORD",
            Attribute::InstanceTranslation => "instance TRANSLATION",
            Attribute::InstanceRotation => "instance ROTATION",
            Attribute::InstanceScale => "instance SCALE",
        }
    }

    fn dimensions(self) -> Dimensions {
        match self {
            Attribute::Position | Attribute::Normal => Dimensions::Vec3,
            Attribute::InstanceTranslation | Attribute::InstanceScale => Dimensions::Vec3,
            Attribute::TexCoord => Dimensions::Vec2,
            Attribute::InstanceRotation => Dimensions::Vec4,
        }
    }

    /// The component types allowed, and whether integer ones must be normalized.
    fn allowed(self, quantized: bool) -> (&'static [DataType], bool) {
        use DataType::{F32, I16, I8, U16, U8};
        match (self, quantized) {
            (Attribute::Position, false) | (Attribute::Normal, false) => (&[F32], true),
            (Attribute::TexCoord, false) => (&[F32, U8, U16], true),
            (Attribute::Position, true) | (Attribute::TexCoord, true) => {
                (&[F32, I8, U8, I16, U16], false)
            }
            (Attribute::Normal, true) => (&[F32, I8, I16], true),
            // EXT_mesh_gpu_instancing: translations and scales float, rotations (quaternions)
            // float or normalized signed bytes and shorts, with or without quantization.
            (Attribute::InstanceTranslation | Attribute::InstanceScale, _) => (&[F32], true),
            (Attribute::InstanceRotation, _) => (&[F32, I8, I16], true),
        }
    }
}

/// Checks accessor `acc` as `what` (the attribute's shape, its component type, and that every
/// byte it reads lies in its buffer view) and reads it as `N`-component float vectors.
/// `quantized`: the file uses `KHR_mesh_quantization`.
pub(super) fn read<const N: usize>(
    acc: &Accessor,
    buffers: &[buffer::Data],
    what: Attribute,
    quantized: bool,
) -> Result<Vec<[f32; N]>, String>
where
    [f32; N]: Item,
    [i8; N]: Item,
    [u8; N]: Item,
    [i16; N]: Item,
    [u16; N]: Item,
{
    let (types, must_normalize) = what.allowed(quantized);
    checks::accessor(acc, what.dimensions(), types, what.name()).map_err(|e| {
        // A type only the extension allows, in a file that does not declare it.
        if !quantized && what.allowed(true).0.contains(&acc.data_type()) {
            format!("{e} (these need KHR_mesh_quantization in the file's extensionsUsed)")
        } else {
            e
        }
    })?;
    let normalized = acc.normalized();
    if acc.data_type() != DataType::F32 && must_normalize && !normalized {
        return Err(format!(
            "{} accessor {} is {:?} but not normalized; glTF requires normalized integers here",
            what.name(),
            acc.index(),
            acc.data_type()
        ));
    }
    let values = match acc.data_type() {
        DataType::F32 => convert::<f32, N>(acc, buffers, |c| c),
        DataType::I8 => convert::<i8, N>(acc, buffers, |c| scale(c as f32, 127.0, normalized)),
        DataType::U8 => convert::<u8, N>(acc, buffers, |c| scale(c as f32, 255.0, normalized)),
        DataType::I16 => convert::<i16, N>(acc, buffers, |c| scale(c as f32, 32767.0, normalized)),
        DataType::U16 => convert::<u16, N>(acc, buffers, |c| scale(c as f32, 65535.0, normalized)),
        other => {
            return Err(format!(
                "{} accessor {} is {other:?}",
                what.name(),
                acc.index()
            ))
        }
    }
    .ok_or_else(|| format!("its {} data cannot be read", what.name()))?;
    if values.len() != acc.count() {
        return Err(format!(
            "read {} of {} {} values",
            values.len(),
            acc.count(),
            what.name()
        ));
    }
    Ok(values)
}

/// An integer component as stored, or normalized by the type's largest value (glTF 2.0
/// §3.11, "Animations", gives the conversions: c / 255 and c / 65535 for unsigned types,
/// max(c / 127, −1) and max(c / 32767, −1) for signed ones).
fn scale(c: f32, largest: f32, normalized: bool) -> f32 {
    if normalized {
        (c / largest).max(-1.0)
    } else {
        c
    }
}

fn convert<T: Copy, const N: usize>(
    acc: &Accessor,
    buffers: &[buffer::Data],
    to_f32: impl Fn(T) -> f32,
) -> Option<Vec<[f32; N]>>
where
    [T; N]: Item,
{
    let iter = Iter::<[T; N]>::new(acc.clone(), |b: buffer::Buffer| {
        buffers.get(b.index()).map(|d| d.0.as_slice())
    })?;
    Some(iter.map(|v| v.map(&to_f32)).collect())
}
