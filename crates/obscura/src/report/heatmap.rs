//! Signed-difference heat maps and the choice of their common scale.

/// Colour of differences at `-scale` and beyond: technique darker (more
/// occluded) than the reference.
pub(super) const NEGATIVE_END: [u8; 3] = [0, 0, 255];
/// Colour of a zero difference.
pub(super) const ZERO: [u8; 3] = [255, 255, 255];
/// Colour of differences at `+scale` and beyond: technique brighter (less
/// occluded) than the reference.
pub(super) const POSITIVE_END: [u8; 3] = [255, 0, 0];
/// Colour of a NaN difference: black is on neither ramp, so it stands out.
const NAN_COLOR: [u8; 3] = [0, 0, 0];

/// Smallest heat map scale [`diff_scale`] picks: differences below 1/255 do
/// not even survive the 8-bit grey PNGs, and an exact match should stay white
/// instead of turning float rounding noise into colour.
const MIN_SCALE: f64 = 0.01;

/// Percentage of pooled `|diff|` values that lie within the scale.
const PERCENTILE: usize = 99;

/// Signed differences (technique − reference) as RGB8, three bytes per value.
///
/// The ramp is linear in sRGB bytes, like matplotlib's `bwr` colour map and
/// like a CSS `linear-gradient` between the same three colours (which is how
/// the page draws its legend): `0` is white `(255, 255, 255)`; positive
/// differences (technique brighter) fade to pure red `(255, 0, 0)` at
/// `+scale`, negative ones (technique darker) to pure blue `(0, 0, 255)` at
/// `-scale`; beyond `±scale` they saturate. The map is monotonic: red never
/// decreases and blue never increases as the difference grows.
///
/// `scale` should be positive and finite. A zero, negative or NaN `scale`
/// saturates every non-zero difference (only its sign is shown). NaN
/// differences are drawn black.
pub fn heatmap_rgb(diff: &[f32], scale: f32) -> Vec<u8> {
    let mut rgb = Vec::with_capacity(diff.len() * 3);
    for &d in diff {
        rgb.extend_from_slice(&color(d, scale));
    }
    rgb
}

fn color(d: f32, scale: f32) -> [u8; 3] {
    if d.is_nan() {
        return NAN_COLOR;
    }
    let t = if scale > 0.0 {
        let t = d / scale;
        // ±∞ / +∞: no meaningful magnitude; show it as no difference rather
        // than as a NaN marker (the difference itself is not NaN).
        if t.is_nan() {
            0.0
        } else {
            t.clamp(-1.0, 1.0)
        }
    } else if d == 0.0 {
        0.0
    } else {
        d.signum()
    };
    // The channels that fade towards the saturated end.
    let fade = ((1.0 - t.abs()) * 255.0).round() as u8;
    if t >= 0.0 {
        [255, fade, fade]
    } else {
        [fade, fade, 255]
    }
}

/// The common heat map scale for `techniques` against `reference`: the 99th
/// percentile (nearest rank) of `|technique − reference|` pooled over every
/// pixel of every technique, rounded up to the next 1-2-5 step (see
/// `nice_ceil`). Inputs are already validated (same lengths, finite values).
///
/// Rounding up is monotonic, so the rounded percentile is the same rank of
/// the *rounded* values: a histogram over the few scale steps finds it in
/// constant memory, where pooling the differences themselves would take
/// 4 bytes × pixels × techniques (200 MB for six techniques at 4K).
pub(super) fn diff_scale<'a>(
    reference: &[f32],
    techniques: impl Iterator<Item = &'a [f32]>,
) -> f64 {
    let steps = nice_steps();
    let mut counts = vec![0usize; steps.len()];
    let mut n = 0usize;
    for technique in techniques {
        for (a, r) in technique.iter().zip(reference) {
            // f32, like the heat map pixels themselves.
            counts[step_index(&steps, f64::from((a - r).abs()))] += 1;
            n += 1;
        }
    }
    // Nearest rank: the smallest value with at least 99 % of the values at
    // or below it. Integer arithmetic, because 0.99 · n in floating point
    // can land just above an integer and shift the rank by one.
    let rank = (n * PERCENTILE).div_ceil(100).max(1);
    let mut seen = 0;
    for (step, count) in steps.iter().zip(counts) {
        seen += count;
        if seen >= rank {
            return *step;
        }
    }
    // No differences at all.
    MIN_SCALE
}

/// The 1-2-5 series from [`MIN_SCALE`] (0.01, 0.02, 0.05, 0.1, …) up to
/// 5e30, ascending.
fn nice_steps() -> Vec<f64> {
    (-2..=30)
        .flat_map(|exponent| {
            [1, 2, 5].map(|mantissa| {
                // Parsed from decimal so that a step is the double nearest to
                // 0.05 etc. and prints as such in the legend.
                format!("{mantissa}e{exponent}")
                    .parse::<f64>()
                    .expect("a decimal literal parses")
            })
        })
        .filter(|&step| step >= MIN_SCALE)
        .collect()
}

/// Index of the smallest step that is at least `v`; the last step for
/// larger (absurd) values.
fn step_index(steps: &[f64], v: f64) -> usize {
    // `v` usually comes from an f32 (0.1f32 is 0.100000001…): without the
    // tolerance it would round up to 0.2.
    let target = v * (1.0 - 1e-6);
    steps
        .partition_point(|&step| step < target)
        .min(steps.len() - 1)
}

/// The smallest value of the 1-2-5 series (0.01, 0.02, 0.05, 0.1, …) that is
/// at least `v`: never below [`MIN_SCALE`], never above 5e30 (only absurd AO
/// values get there). [`diff_scale`] applies the same rounding through its
/// histogram; this is the scalar form the tests check it against.
#[cfg(test)]
pub(super) fn nice_ceil(v: f64) -> f64 {
    let steps = nice_steps();
    steps[step_index(&steps, v)]
}
