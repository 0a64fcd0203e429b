//! Draw order for the depth-tested raster passes: the scene's triangles in spatially compact
//! chunks, drawn nearest first and skipped when outside the view.
//!
//! Why: on the GPUs we measure on, the G-buffer's raster pass is bound by rasterisation and depth
//! testing (BENCHMARKS.md, issue 16). A fragment behind one already drawn is rejected by the early
//! (and coarse, hierarchical) depth test before it is shaded, so drawing near surfaces first
//! shades fewer fragments; a chunk outside the frustum costs no vertex or triangle work. Triangles
//! are sorted along a Morton (Z-order) curve of their centroids within each draw group (Morton,
//! "A computer oriented geodetic data base and a new technique in file sequencing", IBM 1966), so
//! consecutive triangles are near each other and a run of them has a small bounding box.

use glam::{Mat4, Vec3, Vec4};
use std::ops::Range;

/// Triangles per chunk. Measured on the H200 (BENCHMARKS.md): 256 shades fewer fragments than
/// 1024 on Sponza, Sibenik and `colonnade`, and 64 no fewer than 256 (Sponza: 1,025 draws).
pub const CHUNK_TRIANGLES: usize = 256;

/// One draw: the triangles `.1` with pipeline (and bind group) number `.0`.
pub(crate) type Draw = (usize, Range<u32>);

/// A run of consecutive triangles of one draw group and their bounding box (world space).
#[derive(Clone, Debug, PartialEq)]
pub struct Chunk {
    /// Indices into the scene's (draw-ordered) triangles.
    pub triangles: Range<u32>,
    /// Bounding box, min corner.
    pub min: Vec3,
    /// Bounding box, max corner.
    pub max: Vec3,
}

/// The 30-bit Morton code of `p` quantised to 1024 cells per axis of the box `lo..hi`.
fn morton(p: Vec3, lo: Vec3, hi: Vec3) -> u32 {
    let cell = ((p - lo) / (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE)) * 1023.0)
        .clamp(Vec3::ZERO, Vec3::splat(1023.0))
        .as_uvec3();
    // Spread the 10 bits of v to every third bit.
    let spread = |v: u32| {
        let mut v = v & 0x3ff;
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    };
    spread(cell.x) | (spread(cell.y) << 1) | (spread(cell.z) << 2)
}

/// Sorts `order` (triangle indices, already grouped by `group`) along the Morton curve within
/// each group; `corners(t)` gives triangle `t`'s three corners.
pub fn sort_within_groups(
    order: &mut [usize],
    group: impl Fn(usize) -> u32,
    corners: impl Fn(usize) -> [Vec3; 3],
    bounds: (Vec3, Vec3),
) {
    order.sort_by_cached_key(|&t| {
        let [a, b, c] = corners(t);
        (group(t), morton((a + b + c) / 3.0, bounds.0, bounds.1), t)
    });
}

/// Chunks of at most [`CHUNK_TRIANGLES`] consecutive triangles of `corners` (in draw order),
/// never crossing a boundary in `groups` (the start of each group after the first).
pub fn chunks(corners: &[[Vec3; 3]], groups: &[u32]) -> Vec<Chunk> {
    let mut out = Vec::new();
    let mut start = 0usize;
    while start < corners.len() {
        let boundary = groups
            .iter()
            .map(|&g| g as usize)
            .find(|&g| g > start)
            .unwrap_or(corners.len());
        let end = (start + CHUNK_TRIANGLES).min(boundary);
        let (min, max) = corners[start..end].iter().flatten().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        out.push(Chunk {
            triangles: start as u32..end as u32,
            min,
            max,
        });
        start = end;
    }
    out
}

/// The chunks of `chunks` that may be seen through `view_projection` (conservative: a chunk is
/// left out only when all eight corners of its box are outside the same clip plane), the one
/// whose box centre is nearest to `eye` first. The centre, not the box's nearest point: a long
/// chunk (a floor, a wall) that reaches the eye would otherwise come first wherever most of it
/// lies, and measured on Sponza that order shaded 52 % more fragments than the centre's
/// (BENCHMARKS.md).
pub fn visible_front_to_back(chunks: &[Chunk], view_projection: Mat4, eye: Vec3) -> Vec<&Chunk> {
    let mut visible: Vec<(f32, &Chunk)> = chunks
        .iter()
        .filter(|c| !outside(c, view_projection))
        .map(|c| (((c.min + c.max) * 0.5).distance_squared(eye), c))
        .collect();
    // Stable: equal distances keep the scene's order, so the frame is deterministic.
    visible.sort_by(|a, b| a.0.total_cmp(&b.0));
    visible.into_iter().map(|(_, c)| c).collect()
}

/// Every corner of the chunk's box outside one clip plane (reversed Z: the near plane is
/// z = w, everything in front of it has z ≤ w; no far plane).
fn outside(chunk: &Chunk, view_projection: Mat4) -> bool {
    let corners = (0..8).map(|i| {
        let pick = |bit, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        let p = Vec3::new(
            pick(1, chunk.min.x, chunk.max.x),
            pick(2, chunk.min.y, chunk.max.y),
            pick(4, chunk.min.z, chunk.max.z),
        );
        view_projection * p.extend(1.0)
    });
    let planes: [fn(Vec4) -> bool; 5] = [
        |c| c.x < -c.w,
        |c| c.x > c.w,
        |c| c.y < -c.w,
        |c| c.y > c.w,
        |c| c.z > c.w,
    ];
    let corners: Vec<Vec4> = corners.collect();
    planes
        .iter()
        .any(|outside_plane| corners.iter().all(|&c| outside_plane(c)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn morton_interleaves_the_axes() {
        let (lo, hi) = (Vec3::ZERO, Vec3::splat(1023.0));
        assert_eq!(morton(Vec3::new(1.0, 0.0, 0.0), lo, hi), 0b001);
        assert_eq!(morton(Vec3::new(0.0, 1.0, 0.0), lo, hi), 0b010);
        assert_eq!(morton(Vec3::new(0.0, 0.0, 1.0), lo, hi), 0b100);
        assert_eq!(morton(Vec3::splat(1023.0), lo, hi), (1 << 30) - 1);
    }

    #[test]
    fn chunks_respect_groups_and_size() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let corners = vec![tri; 2 * CHUNK_TRIANGLES + 10];
        let c = chunks(&corners, &[5, 5, 2 * CHUNK_TRIANGLES as u32 + 10]);
        let ranges: Vec<_> = c.iter().map(|c| c.triangles.clone()).collect();
        let n = CHUNK_TRIANGLES as u32;
        assert_eq!(
            ranges,
            vec![0..5, 5..5 + n, 5 + n..5 + 2 * n, 5 + 2 * n..2 * n + 10]
        );
        assert_eq!((c[0].min, c[0].max), (Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)));
    }

    #[test]
    fn culls_only_what_is_outside_and_orders_by_distance() {
        // Camera at the origin looking down −z, 90° field of view, reversed-Z infinite.
        let projection = glam::camera::rh::proj::directx::perspective_infinite_reverse(
            90f32.to_radians(),
            1.0,
            0.1,
        );
        let boxed = |min: Vec3, max: Vec3| Chunk {
            triangles: 0..1,
            min,
            max,
        };
        let chunks = [
            boxed(Vec3::new(-1.0, -1.0, -20.0), Vec3::new(1.0, 1.0, -19.0)), // far, ahead
            boxed(Vec3::new(-1.0, -1.0, 2.0), Vec3::new(1.0, 1.0, 3.0)),     // behind
            boxed(Vec3::new(30.0, -1.0, -11.0), Vec3::new(31.0, 1.0, -10.0)), // right, outside
            boxed(Vec3::new(-1.0, -1.0, -5.0), Vec3::new(1.0, 1.0, -4.0)),   // near, ahead
            boxed(Vec3::new(-50.0, -50.0, -1.0), Vec3::new(50.0, 50.0, 1.0)), // around the eye
        ];
        let seen = visible_front_to_back(&chunks, projection, Vec3::ZERO);
        let order: Vec<_> = seen
            .iter()
            .map(|c| chunks.iter().position(|d| std::ptr::eq(*c, d)).unwrap())
            .collect();
        assert_eq!(order, vec![4, 3, 0]);
    }
}
