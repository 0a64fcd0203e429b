//! Temporal metrics along a camera path (issue 13): how much a technique's AO changes from one
//! frame to the next beyond what the reference's own AO changes, measured at the same surface
//! points.
//!
//! # Matching pixels between frames (reprojection)
//! The scenes are static and the camera motion is known, so a visible pixel `p` of frame `t`
//! with linear depth `z` is the world point `X = V_t⁻¹ · unproject(p, z)`. Projected into frame
//! `t − 1` it lands at pixel coordinates `q` with linear depth `z'`. Frame `t − 1`'s images are
//! read there bilinearly, using only the four texels whose own depth is within
//! [`DEPTH_TOLERANCE`]`· z'` of `z'` (the same surface) and renormalising their weights. A pixel
//! with no such texel (it was hidden or off screen in frame `t − 1`: a disocclusion) or with no
//! geometry is not matched and counts in neither metric.
//!
//! # Temporal error
//! With `a` the technique's AO, `r` the reference's and `'` the value read at the reprojected
//! position in the previous frame:
//!
//! ```text
//! temporal_error = mean over matched pixels of all frame pairs of |(a_t − a'_{t−1}) − (r_t − r'_{t−1})|
//! ```
//!
//! # Popping
//! The fraction of matched pixels where the technique's AO changes by more than
//! [`POP_CHANGE`] (0.1) while the reference changes by less than [`POP_REFERENCE_STILL`] (0.02):
//! occlusion that appears or vanishes for no reason in the scene.
//!
//! Both are also reported per frame pair (the worst pair is what a viewer notices).

use super::error::MetricsError;
use super::input::Image;
use crate::view::FrameView;
use glam::Vec2;

/// A technique's AO change between frames above which a pixel may count as popping.
pub const POP_CHANGE: f64 = 0.1;
/// The reference's AO change below which the scene counts as still at a pixel.
pub const POP_REFERENCE_STILL: f64 = 0.02;
/// Relative depth difference within which a previous-frame texel is the same surface.
pub const DEPTH_TOLERANCE: f32 = 0.03;

/// One frame of a path as the metrics need it: its view and its visible linear depth
/// (row-major, `view.width × view.height`; 0 or non-finite = no geometry).
#[derive(Clone, Copy, Debug)]
pub struct PathFrame<'a> {
    /// The frame's camera and image geometry.
    pub view: FrameView,
    /// Visible linear depth.
    pub depth: &'a [f32],
}

/// Where each pixel of a frame was in the previous frame: up to four texels of the previous
/// frame with bilinear weights (summing to 1), or nothing.
#[derive(Clone, Debug)]
pub struct Reprojection {
    taps: Vec<Option<[(u32, f32); 4]>>,
}

impl Reprojection {
    /// Matches every pixel of `current` to `previous` (same size required).
    pub fn new(previous: &PathFrame, current: &PathFrame) -> Result<Self, MetricsError> {
        let (w, h) = (current.view.width as usize, current.view.height as usize);
        Image::new(
            previous.view.width as usize,
            previous.view.height as usize,
            previous.depth,
        )?;
        Image::new(w, h, current.depth)?;
        if (previous.view.width, previous.view.height) != (current.view.width, current.view.height)
        {
            return Err(MetricsError::SizeMismatch {
                expected: (w, h),
                found: (previous.view.width as usize, previous.view.height as usize),
            });
        }
        let cur_screen = current.view.screen();
        let prev_screen = previous.view.screen();
        let to_world = current.view.view_matrix().inverse();
        let to_prev = previous.view.view_matrix() * to_world;
        let g_cur = current.view.guard_band as f32;
        let g_prev = previous.view.guard_band as f32;
        let taps = (0..w * h)
            .map(|i| {
                let z = current.depth[i];
                if !(z.is_finite() && z > 0.0) {
                    return None;
                }
                let px = Vec2::new((i % w) as f32 + 0.5 + g_cur, (i / w) as f32 + 0.5 + g_cur);
                let p_prev = to_prev.transform_point3(cur_screen.pixel_to_view(px, z));
                let z_prev = -p_prev.z;
                if z_prev.is_nan() || z_prev <= 0.0 {
                    return None;
                }
                // Visible-image coordinates of the point in the previous frame, texel centres at
                // integers.
                let q = prev_screen.view_to_pixel(p_prev) - Vec2::splat(g_prev + 0.5);
                bilinear_taps(q, w, h, |j| {
                    let d = previous.depth[j];
                    d.is_finite() && d > 0.0 && (d - z_prev).abs() <= DEPTH_TOLERANCE * z_prev
                })
            })
            .collect();
        Ok(Self { taps })
    }

    /// The previous frame's `image` at pixel `i`'s reprojected position, or `None` (unmatched).
    pub fn sample(&self, image: &[f32], i: usize) -> Option<f32> {
        self.taps[i].map(|taps| taps.iter().map(|&(j, w)| w * image[j as usize]).sum())
    }

    /// The fraction of pixels matched.
    pub fn matched_fraction(&self) -> f64 {
        self.taps.iter().filter(|t| t.is_some()).count() as f64 / self.taps.len().max(1) as f64
    }
}

/// Bilinear taps around `q` (texel centres at integers) restricted to the texels `keep` accepts,
/// weights renormalised; `None` when none is accepted or `q` is off the image.
fn bilinear_taps(
    q: Vec2,
    w: usize,
    h: usize,
    keep: impl Fn(usize) -> bool,
) -> Option<[(u32, f32); 4]> {
    if !(q.x > -0.5 && q.y > -0.5 && q.x < w as f32 - 0.5 && q.y < h as f32 - 0.5) {
        return None;
    }
    let base = q.floor();
    let f = q - base;
    let mut taps = [(0u32, 0.0f32); 4];
    let mut total = 0.0;
    for (k, (dx, dy)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
        let (x, y) = (base.x as i64 + dx, base.y as i64 + dy);
        if x < 0 || y < 0 || x >= w as i64 || y >= h as i64 {
            continue;
        }
        let j = y as usize * w + x as usize;
        let weight =
            (if dx == 1 { f.x } else { 1.0 - f.x }) * (if dy == 1 { f.y } else { 1.0 - f.y });
        if weight > 0.0 && keep(j) {
            taps[k] = (j as u32, weight);
            total += weight;
        }
    }
    (total > 1e-6).then(|| taps.map(|(j, w)| (j, w / total)))
}

/// The temporal metrics of one frame pair (frame `t − 1` to `t`).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct PairMetrics {
    /// Mean |(a_t − a'_{t−1}) − (r_t − r'_{t−1})| over matched pixels (0 when none matched).
    pub temporal_error: f64,
    /// Fraction of matched pixels that pop.
    pub popping: f64,
    /// Fraction of the frame's pixels matched to the previous frame.
    pub matched: f64,
    /// Number of matched pixels.
    #[serde(skip)]
    pub matched_pixels: usize,
}

/// The metrics of one frame pair: `ao`/`reference` of the previous and the current frame.
pub fn pair_metrics(
    reprojection: &Reprojection,
    ao: (&[f32], &[f32]),
    reference: (&[f32], &[f32]),
) -> Result<PairMetrics, MetricsError> {
    let n = reprojection.taps.len();
    for (image, data) in [
        ("technique", ao.0),
        ("technique", ao.1),
        ("reference", reference.0),
        ("reference", reference.1),
    ] {
        if data.len() != n {
            return Err(MetricsError::DataLength {
                width: n,
                height: 1,
                len: data.len(),
            });
        }
        if let Some(i) = data.iter().position(|v| !v.is_finite()) {
            return Err(MetricsError::NonFinite { image, x: i, y: 0 });
        }
    }
    let (mut sum, mut pops, mut matched) = (0.0f64, 0usize, 0usize);
    for i in 0..n {
        let (Some(a_prev), Some(r_prev)) = (
            reprojection.sample(ao.0, i),
            reprojection.sample(reference.0, i),
        ) else {
            continue;
        };
        let da = f64::from(ao.1[i]) - f64::from(a_prev);
        let dr = f64::from(reference.1[i]) - f64::from(r_prev);
        sum += (da - dr).abs();
        if da.abs() > POP_CHANGE && dr.abs() < POP_REFERENCE_STILL {
            pops += 1;
        }
        matched += 1;
    }
    let per = |v: f64| {
        if matched == 0 {
            0.0
        } else {
            v / matched as f64
        }
    };
    Ok(PairMetrics {
        temporal_error: per(sum),
        popping: per(pops as f64),
        matched: matched as f64 / n.max(1) as f64,
        matched_pixels: matched,
    })
}

/// The temporal metrics of a whole path.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct PathMetrics {
    /// Mean over all matched pixels of all frame pairs.
    pub temporal_error: f64,
    /// Popping pixels over matched pixels, all frame pairs.
    pub popping: f64,
    /// Per frame pair (entry `k` is frame `k` to `k + 1`).
    pub pairs: Vec<PairMetrics>,
}

impl PathMetrics {
    /// Pools per-pair metrics, weighting each pair by its matched pixels.
    pub fn from_pairs(pairs: Vec<PairMetrics>) -> Self {
        let matched: usize = pairs.iter().map(|p| p.matched_pixels).sum();
        let pooled = |f: fn(&PairMetrics) -> f64| {
            if matched == 0 {
                0.0
            } else {
                pairs
                    .iter()
                    .map(|p| f(p) * p.matched_pixels as f64)
                    .sum::<f64>()
                    / matched as f64
            }
        };
        Self {
            temporal_error: pooled(|p| p.temporal_error),
            popping: pooled(|p| p.popping),
            pairs,
        }
    }
}

/// The temporal metrics of a technique along a path: `frames` (views and depths), the
/// technique's AO and the reference's AO per frame (visible images).
pub fn path_metrics(
    frames: &[PathFrame],
    ao: &[Vec<f32>],
    reference: &[Vec<f32>],
) -> Result<PathMetrics, MetricsError> {
    if ao.len() != frames.len() || reference.len() != frames.len() {
        return Err(MetricsError::InvalidParameter {
            name: "frames",
            requirement: "one AO and one reference image per frame",
        });
    }
    let pairs = (1..frames.len())
        .map(|t| {
            let reprojection = Reprojection::new(&frames[t - 1], &frames[t])?;
            pair_metrics(
                &reprojection,
                (&ao[t - 1], &ao[t]),
                (&reference[t - 1], &reference[t]),
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PathMetrics::from_pairs(pairs))
}

#[cfg(test)]
#[path = "temporal_tests.rs"]
mod tests;
