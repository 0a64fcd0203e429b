//! Checks made before handing data to the `gltf` crate's readers.
//!
//! `gltf` validates indices between JSON objects, but some malformed inputs still reach a
//! `panic!`, `unwrap()` or unchecked slice inside it (gltf 1.4.1): a POSITION accessor index out
//! of range (gltf-json's own validation indexes it), a GLB header shorter than itself, an image
//! with neither `uri` nor `bufferView`, an embedded image without `mimeType`, a URI whose
//! percent-decoding is not UTF-8, a buffer view past the end of its buffer, an accessor of the
//! wrong type, count 0, or a stride smaller than its element. Each is turned into a message here,
//! before the crate sees it.

use gltf::accessor::{DataType, Dimensions};
use gltf::{buffer, Accessor, Document};

use crate::scene::thousands;

/// Largest element count accepted for one accessor (2^26, far above any real scene's mesh):
/// bounds memory for sparse accessors, whose count is not limited by any buffer's size.
const MAX_ELEMENTS: usize = 1 << 26;

/// Largest element count accepted for an accessor without a bufferView (2^24): its elements are
/// zeros the file does not hold (under its sparse entries), so its count alone sets what reading
/// it allocates; a kilobyte file could otherwise make gigabytes (issue 62, defect 5). Accessors
/// with a bufferView are bounded by the file's own size ([`view_range`]).
const MAX_UNBACKED_ELEMENTS: usize = 1 << 24;

/// A `.glb` header must cover at least its own 12 bytes and not claim more than the file holds.
pub(super) fn glb_header(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let Some(length) = bytes.get(8..12) else {
        return Err(format!(
            "truncated binary glTF: {} bytes, shorter than the 12-byte header",
            bytes.len()
        ));
    };
    let length = u32::from_le_bytes([length[0], length[1], length[2], length[3]]) as usize;
    if length < 20 {
        return Err(format!(
            "binary glTF header gives a length of {length} bytes, too short for any content"
        ));
    }
    if length > bytes.len() {
        return Err(format!(
            "truncated binary glTF: the header says {length} bytes but the file has {}",
            bytes.len()
        ));
    }
    Ok(())
}

/// Indices that gltf-json's validation uses without checking them first (a primitive's POSITION
/// accessor, read for its min/max), or lets through to readers that unwrap them (an animation
/// channel's target node: the camera paths read every channel's; a node's skin and a skin's
/// joints: skinned meshes are placed by them).
pub(super) fn before_validation(json: &gltf::json::Root) -> Result<(), String> {
    for (n, node) in json.nodes.iter().enumerate() {
        if let Some(skin) = node.skin.filter(|s| s.value() >= json.skins.len()) {
            return Err(format!(
                "node {n} uses skin {}, but there are only {}",
                skin.value(),
                json.skins.len()
            ));
        }
    }
    for (s, skin) in json.skins.iter().enumerate() {
        if let Some(joint) = skin.joints.iter().find(|j| j.value() >= json.nodes.len()) {
            return Err(format!(
                "skin {s} uses node {} as a joint, but there are only {} nodes",
                joint.value(),
                json.nodes.len()
            ));
        }
    }
    for (a, animation) in json.animations.iter().enumerate() {
        for (c, channel) in animation.channels.iter().enumerate() {
            let node = channel.target.node.value();
            let sampler = channel.sampler.value();
            if node >= json.nodes.len() || sampler >= animation.samplers.len() {
                return Err(format!(
                    "animation {a} channel {c} targets node {node} with sampler {sampler}, but \
                     there are {} nodes and {} samplers",
                    json.nodes.len(),
                    animation.samplers.len()
                ));
            }
        }
    }
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(index) = prim.attributes.get(&Checked::Valid(Semantic::Positions)) {
                if index.value() >= json.accessors.len() {
                    return Err(format!(
                        "mesh {m} primitive {p}: POSITION uses accessor {}, but there are only {}",
                        index.value(),
                        json.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Image sources and URIs the importer would panic on.
pub(super) fn document(doc: &Document) -> Result<(), String> {
    let json = doc.as_json();
    for (i, buffer) in json.buffers.iter().enumerate() {
        if let Some(uri) = &buffer.uri {
            check_uri(uri).map_err(|e| format!("buffer {i}: {e}"))?;
        }
    }
    for (i, image) in json.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view) {
            (Some(uri), _) => check_uri(uri).map_err(|e| format!("image {i}: {e}"))?,
            (None, Some(_)) if image.mime_type.is_none() => {
                return Err(format!(
                    "image {i} is stored in a buffer view but has no mimeType"
                ))
            }
            (None, Some(_)) => {}
            (None, None) => return Err(format!("image {i} has neither a uri nor a bufferView")),
        }
    }
    Ok(())
}

/// A relative URI must percent-decode to UTF-8 (`gltf` unwraps that decoding).
fn check_uri(uri: &str) -> Result<(), String> {
    if uri.contains(':') {
        return Ok(()); // data: and file: URIs are parsed without percent-decoding
    }
    match super::super::files::percent_decode(uri) {
        Some(_) => Ok(()),
        None => Err(format!("uri '{uri}' does not percent-decode to UTF-8 text")),
    }
}

/// Every buffer view lies inside the loaded data of its buffer.
pub(super) fn views(doc: &Document, buffers: &[buffer::Data]) -> Result<(), String> {
    for view in doc.views() {
        let buffer = view.buffer().index();
        let have = buffers.get(buffer).map_or(0, |b| b.0.len());
        let end = view.offset().checked_add(view.length());
        if end.is_none_or(|end| end > have) {
            return Err(format!(
                "buffer view {} covers bytes {}..{} but buffer {buffer} has only {have} bytes",
                view.index(),
                view.offset(),
                view.offset().saturating_add(view.length())
            ));
        }
    }
    Ok(())
}

/// The accessor has the expected shape and every byte it reads lies inside its buffer view.
pub(super) fn accessor(
    acc: &Accessor,
    dims: Dimensions,
    types: &[DataType],
    what: &str,
) -> Result<(), String> {
    let name = format!("{what} accessor {}", acc.index());
    if acc.dimensions() != dims || !types.contains(&acc.data_type()) {
        return Err(format!(
            "{name} is {:?} of {:?}, expected {dims:?} of one of {types:?}",
            acc.dimensions(),
            acc.data_type()
        ));
    }
    let count = acc.count();
    if count == 0 || count > MAX_ELEMENTS {
        return Err(format!(
            "{name} has count {count} (must be 1..={MAX_ELEMENTS})"
        ));
    }
    if acc.view().is_none() && count > MAX_UNBACKED_ELEMENTS {
        return Err(format!(
            "{name} has count {} without a bufferView (zeros the file does not hold, under its \
             sparse entries), more than the limit of {} for such accessors: store its elements \
             in a bufferView",
            thousands(count as u64),
            thousands(MAX_UNBACKED_ELEMENTS as u64)
        ));
    }
    let elem = acc.size();
    match (acc.view(), acc.sparse()) {
        (Some(view), _) => view_range(&name, &view, acc.offset(), count, elem)?,
        (None, None) => return Err(format!("{name} has neither a bufferView nor sparse data")),
        (None, Some(_)) => {}
    }
    if let Some(sparse) = acc.sparse() {
        let n = sparse.count();
        if n == 0 || n > count {
            return Err(format!(
                "{name} has {n} sparse entries for {count} elements"
            ));
        }
        let indices = sparse.indices();
        let index_size = indices.index_type().size();
        view_range(&name, &indices.view(), indices.offset(), n, index_size)?;
        let values = sparse.values();
        view_range(&name, &values.view(), values.offset(), n, elem)?;
    }
    Ok(())
}

/// `count` elements of `elem` bytes, `offset` bytes into `view`, at the view's stride.
fn view_range(
    name: &str,
    view: &buffer::View,
    offset: usize,
    count: usize,
    elem: usize,
) -> Result<(), String> {
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "{name}: buffer view {} has byteStride {stride}, smaller than the {elem}-byte element",
            view.index()
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|x| x.checked_add(elem))
        .and_then(|x| x.checked_add(offset));
    match end {
        Some(end) if end <= view.length() => Ok(()),
        _ => Err(format!(
            "{name} reads {count} elements from byte {offset} of buffer view {}, which has only {} \
             bytes",
            view.index(),
            view.length()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glb_headers() {
        assert!(glb_header(b"{}").is_ok());
        assert!(glb_header(b"glTF\x02\x00").unwrap_err().contains("12-byte"));
        let mut h = b"glTF\x02\x00\x00\x00\x04\x00\x00\x00".to_vec();
        assert!(glb_header(&h).unwrap_err().contains("length of 4"));
        h[8] = 100;
        assert!(glb_header(&h).unwrap_err().contains("says 100"));
    }

    #[test]
    fn uris() {
        assert!(check_uri("a%20b.bin").is_ok());
        assert!(check_uri("100%.bin").is_ok());
        assert!(check_uri("data:application/octet-stream;base64,AAAA").is_ok());
        assert!(check_uri("bad%FF.bin").unwrap_err().contains("bad%FF.bin"));
    }
}
