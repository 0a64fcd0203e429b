//! A view's arrays as file bytes: a multi-channel EXR or a NumPy `.npz`. Encoded in memory, so
//! that the file's hash is known before it is written (atomically, by `output`), and
//! deterministic: the same arrays give the same bytes on every run.

use super::spec::Format;

/// One array of a view: `components` floats per pixel (1 or 3), row-major from the top row.
pub struct Array {
    /// Its name (`depth`, `normals`, `ao.gtao`).
    pub name: String,
    /// Floats per pixel.
    pub components: usize,
    /// `width × height × components` values.
    pub values: Vec<f32>,
}

/// The EXR channel-name suffixes of a three-component array: colours R, G, B; vectors X, Y, Z.
fn suffixes(name: &str) -> [&'static str; 3] {
    if name == "albedo" {
        ["R", "G", "B"]
    } else {
        ["X", "Y", "Z"]
    }
}

/// The bytes of a view file holding `arrays`.
pub fn encode(
    format: Format,
    width: u32,
    height: u32,
    arrays: &[Array],
) -> Result<Vec<u8>, String> {
    match format {
        Format::Exr => exr_bytes(width, height, arrays),
        Format::Npz => npz_bytes(width, height, arrays),
    }
}

/// One 32-bit float channel per component (`depth`, `normals.X`, …), ZIP-compressed scan lines
/// in increasing order, encoded on one thread: the exr crate's default (tiles, unspecified line
/// order, parallel compression) may write blocks in whichever order its threads finish, and the
/// same image would not always give the same bytes.
fn exr_bytes(width: u32, height: u32, arrays: &[Array]) -> Result<Vec<u8>, String> {
    use exr::prelude::*;
    let mut channels = Vec::new();
    for a in arrays {
        for c in 0..a.components {
            let name = if a.components == 1 {
                a.name.clone()
            } else {
                format!("{}.{}", a.name, suffixes(&a.name)[c])
            };
            let values: Vec<f32> = a
                .values
                .iter()
                .skip(c)
                .step_by(a.components)
                .copied()
                .collect();
            channels.push(AnyChannel {
                name: Text::from(name.as_str()),
                sample_data: FlatSamples::F32(values),
                // Data, not colour: stored exactly (the flag only matters for lossy codecs).
                quantize_linearly: true,
                sampling: Vec2(1, 1),
            });
        }
    }
    let layer = Layer::new(
        (width as usize, height as usize),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .non_parallel()
        .to_buffered(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// A `.npy` file (NumPy's format 1.0: magic, header length, a Python dict literal padded with
/// spaces to a multiple of 64 bytes, then the little-endian data). Written by hand because the
/// format is a dozen lines and the crates that write it pull in ndarray for one function.
fn npy_bytes(shape: &[usize], values: &[f32]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape}, }}");
    // magic (6) + version (2) + length (2) + header + '\n', a multiple of 64.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + 4 * values.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// A zip of one `NAME.npy` per array, stored (uncompressed, as `numpy.savez` writes), every
/// entry dated 1980-01-01 (the zip format's earliest date) so that no clock enters the bytes.
fn npz_bytes(width: u32, height: u32, arrays: &[Array]) -> Result<Vec<u8>, String> {
    use std::io::Write;
    use zip::write::SimpleFileOptions;
    let options = SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .last_modified_time(zip::DateTime::DEFAULT)
        .unix_permissions(0o644);
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for a in arrays {
        let (w, h) = (width as usize, height as usize);
        let shape = if a.components == 1 {
            vec![h, w]
        } else {
            vec![h, w, a.components]
        };
        zip.start_file(format!("{}.npy", a.name), options)
            .map_err(|e| e.to_string())?;
        zip.write_all(&npy_bytes(&shape, &a.values))
            .map_err(|e| e.to_string())?;
    }
    Ok(zip.finish().map_err(|e| e.to_string())?.into_inner())
}
