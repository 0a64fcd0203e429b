//! Structural similarity (SSIM), Wang, Bovik, Sheikh & Simoncelli,
//! IEEE TIP 13(4), 2004 — see the module docs of [`crate::metrics`] for the
//! exact conventions.

use super::input::check_pair;
use super::sum::Sum;
use super::{Image, MetricsError};

/// Side length of the Gaussian window (11, as in Wang et al. 2004).
pub const SSIM_WINDOW: usize = 11;
/// Standard deviation of the Gaussian window, in pixels.
pub const SSIM_SIGMA: f64 = 1.5;
/// Luminance stabiliser constant `K1`.
pub const SSIM_K1: f64 = 0.01;
/// Contrast stabiliser constant `K2`.
pub const SSIM_K2: f64 = 0.03;
/// Dynamic range `L` of the images (AO is in `[0, 1]`).
pub const SSIM_L: f64 = 1.0;
/// `C1 = (K1·L)²`.
pub const SSIM_C1: f64 = (SSIM_K1 * SSIM_L) * (SSIM_K1 * SSIM_L);
/// `C2 = (K2·L)²`.
pub const SSIM_C2: f64 = (SSIM_K2 * SSIM_L) * (SSIM_K2 * SSIM_L);

/// Number of windowed moments: `E[x]`, `E[y]`, `E[x²]`, `E[y²]`, `E[xy]`.
const MOMENTS: usize = 5;

/// Mean SSIM of `a` and `b` over the valid region (every pixel whose whole
/// 11×11 window lies inside the image).
///
/// Equals scikit-image's `structural_similarity(a, b, data_range=1,
/// gaussian_weights=True, sigma=1.5, use_sample_covariance=False)` on
/// `float64` data. Symmetric in its arguments; 1 for identical images.
///
/// # Errors
/// Invalid layout, size mismatch, a non-finite sample, or an image smaller
/// than 11×11 ([`MetricsError::WindowTooLarge`]).
pub fn ssim(a: &Image, b: &Image) -> Result<f64, MetricsError> {
    let map = ssim_map(a, b)?;
    // The valid region is non-empty after `check_window_fits`.
    let sum: Sum = map.iter().copied().collect();
    Ok(sum.value() / map.len() as f64)
}

/// Per-pixel SSIM over the valid region: a row-major
/// `(width − 10) × (height − 10)` map whose entry `(i, j)` belongs to the
/// window centred on image pixel `(i + 5, j + 5)`.
///
/// # Errors
/// As [`ssim()`].
pub fn ssim_map(a: &Image, b: &Image) -> Result<Vec<f64>, MetricsError> {
    check_pair(a, b, "a", "b")?;
    check_window_fits(a)?;
    Ok(ssim_map_unchecked(a, b))
}

/// The SSIM window must fit inside the image in both directions.
pub(super) fn check_window_fits(img: &Image) -> Result<(), MetricsError> {
    if img.width < SSIM_WINDOW || img.height < SSIM_WINDOW {
        Err(MetricsError::WindowTooLarge {
            window: SSIM_WINDOW,
            width: img.width,
            height: img.height,
        })
    } else {
        Ok(())
    }
}

/// Normalised 1-D Gaussian taps, built exactly as `scipy.ndimage` does for
/// `gaussian_filter(sigma=1.5, truncate=3.5)` (radius `int(3.5·1.5 + 0.5) = 5`):
/// `exp(−x² / 2σ²)` for `x = −5..=5`, divided by their sum. The 2-D window is
/// the outer product, which is therefore also normalised.
fn gaussian_taps() -> [f64; SSIM_WINDOW] {
    let radius = (SSIM_WINDOW / 2) as f64;
    let mut taps = [0.0; SSIM_WINDOW];
    for (i, tap) in taps.iter_mut().enumerate() {
        let x = i as f64 - radius;
        *tap = (-0.5 / (SSIM_SIGMA * SSIM_SIGMA) * (x * x)).exp();
    }
    let sum: f64 = taps.iter().sum();
    for tap in &mut taps {
        *tap /= sum;
    }
    taps
}

/// SSIM from the five windowed moments `[E x, E y, E x², E y², E xy]`.
///
/// Population statistics, as in the paper: `σx² = E[x²] − μx²` etc. The
/// `E[x²] − μx²` form can round to a tiny negative number for flat windows;
/// that is harmless because `C2` (9e-4) dwarfs it, and clamping would break
/// bit-compatibility with the reference implementation for no gain.
#[inline]
fn ssim_from_moments(m: [f64; MOMENTS]) -> f64 {
    let [mx, my, mxx, myy, mxy] = m;
    let vx = mxx - mx * mx;
    let vy = myy - my * my;
    let vxy = mxy - mx * my;
    let numerator = (2.0 * mx * my + SSIM_C1) * (2.0 * vxy + SSIM_C2);
    // Both factors are ≥ C1, C2 > 0 (up to the rounding noted above), so the
    // division is always defined.
    let denominator = (mx * mx + my * my + SSIM_C1) * (vx + vy + SSIM_C2);
    numerator / denominator
}

/// Separable "valid" Gaussian filtering of the five moment images, then the
/// SSIM formula per output pixel. Inputs must already be validated.
///
/// Memory is `O(11 · width)`: the horizontally filtered rows live in a ring of
/// 11 rows instead of five full-size intermediate images (which would be
/// ~80 MB of `f64` at 1920×1080). Cost is `2 · 11 · 5` multiply-adds per pixel.
fn ssim_map_unchecked(a: &Image, b: &Image) -> Vec<f64> {
    let width = a.width;
    let out_w = width - (SSIM_WINDOW - 1);
    let out_h = a.height - (SSIM_WINDOW - 1);
    let taps = gaussian_taps();

    // One horizontally filtered row: MOMENTS planes of `out_w` values each.
    let row_len = MOMENTS * out_w;
    let filter_row = |y: usize, out: &mut [f64]| {
        let ra = &a.data[y * width..(y + 1) * width];
        let rb = &b.data[y * width..(y + 1) * width];
        for ox in 0..out_w {
            let mut m = [0.0f64; MOMENTS];
            for (t, &w) in taps.iter().enumerate() {
                let x = f64::from(ra[ox + t]);
                let y = f64::from(rb[ox + t]);
                m[0] += w * x;
                m[1] += w * y;
                m[2] += w * (x * x);
                m[3] += w * (y * y);
                m[4] += w * (x * y);
            }
            for (c, &v) in m.iter().enumerate() {
                out[c * out_w + ox] = v;
            }
        }
    };

    // Image row `y` is stored in ring slot `y % SSIM_WINDOW`.
    let mut ring = vec![0.0f64; SSIM_WINDOW * row_len];
    for y in 0..SSIM_WINDOW - 1 {
        filter_row(y, &mut ring[y * row_len..(y + 1) * row_len]);
    }

    let mut acc = vec![0.0f64; row_len];
    let mut map = Vec::with_capacity(out_w * out_h);
    for oy in 0..out_h {
        let newest = oy + SSIM_WINDOW - 1;
        let slot = newest % SSIM_WINDOW;
        filter_row(newest, &mut ring[slot * row_len..(slot + 1) * row_len]);

        // Vertical pass over whole rows (contiguous, vectorisable).
        acc.fill(0.0);
        for (t, &w) in taps.iter().enumerate() {
            let slot = (oy + t) % SSIM_WINDOW;
            let src = &ring[slot * row_len..(slot + 1) * row_len];
            for (dst, &s) in acc.iter_mut().zip(src) {
                *dst += w * s;
            }
        }
        map.extend((0..out_w).map(|ox| {
            ssim_from_moments([
                acc[ox],
                acc[out_w + ox],
                acc[2 * out_w + ox],
                acc[3 * out_w + ox],
                acc[4 * out_w + ox],
            ])
        }));
    }
    map
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integer mixer shared with `tools/skimage_ssim_reference.py` (the Python
    /// masks to 32 bits where Rust wraps).
    fn hash32(i: u32) -> u32 {
        let mut x = i.wrapping_mul(0x9E37_79B1) ^ 0x85EB_CA6B;
        x ^= x >> 15;
        x = x.wrapping_mul(0x2C1B_3C6D);
        x ^= x >> 12;
        x = x.wrapping_mul(0x297A_2D39);
        x ^= x >> 15;
        x
    }

    /// 24-bit pseudo-random integer.
    fn noise24(seed: u32, idx: usize) -> i64 {
        i64::from(hash32(seed * 65536 + idx as u32) >> 8)
    }

    /// The fixtures of the Python script. Values are 24-bit integers / 2²⁴,
    /// exactly representable in both f32 and f64, so both sides see
    /// bit-identical inputs.
    fn fixture(kind: &str, w: usize, h: usize) -> (Vec<f32>, Vec<f32>) {
        let mut a = Vec::with_capacity(w * h);
        let mut b = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let (ai, bi) = match kind {
                    "noise" => {
                        let ai = noise24(1, i);
                        (ai, (3 * ai + noise24(2, i)) / 4)
                    }
                    "gradient" => {
                        let ai = x as i64 * 400_000
                            + y as i64 * 200_000
                            + i64::from(hash32(3 * 65536 + i as u32) >> 12);
                        (ai, (5 * ai + 3 * noise24(4, i)) / 8)
                    }
                    "ao" => {
                        let dx = x as i64 - (w / 2) as i64;
                        let dy = y as i64 - (h / 2) as i64;
                        let base = 16_777_215 - ((dx * dx + dy * dy) * 300_000).min(12_000_000);
                        let ai = base - (noise24(5, i) >> 4);
                        let bi = if (x + y) % 3 != 0 {
                            (ai * 7 + noise24(6, i)) / 8
                        } else {
                            ai
                        };
                        (ai, bi)
                    }
                    _ => unreachable!(),
                };
                assert!((0..1 << 24).contains(&ai) && (0..1 << 24).contains(&bi));
                // < 2²⁴, so `as f32` is exact, and dividing by 2²⁴ is exact.
                a.push(ai as f32 / 16_777_216.0);
                b.push(bi as f32 / 16_777_216.0);
            }
        }
        (a, b)
    }

    fn sum(v: &[f32]) -> f64 {
        v.iter().map(|&x| f64::from(x)).sum()
    }

    /// One scikit-image reference case.
    struct SkimageCase {
        kind: &'static str,
        w: usize,
        h: usize,
        /// Σa and Σb as printed by the script: exact (multiples of 2⁻²⁴ well
        /// inside 53 bits), so they prove the Rust generator reproduces the
        /// Python fixture bit for bit.
        sum_a: f64,
        sum_b: f64,
        mssim: f64,
        /// Valid-region map `S[5:-5, 5:-5]`: first and last entries.
        first: f64,
        last: f64,
    }

    // Reference values from scikit-image 0.26.0 (numpy 2.4.6, scipy 1.17.1,
    // Python 3.11, `pip install scikit-image numpy`), computed by a script kept
    // outside the crate (tools/skimage_ssim_reference.py of the metrics_dev
    // scratch crate). Its essential call, on float64 inputs:
    //
    //     from skimage.metrics import structural_similarity
    //     # a, b: float64 arrays of shape (h, w) built by `fixture` below
    //     m, S = structural_similarity(a, b, data_range=1.0, gaussian_weights=True,
    //                                  sigma=1.5, use_sample_covariance=False,
    //                                  full=True)
    //     print(repr(m), repr(S[5:-5, 5:-5][0, 0]), repr(S[5:-5, 5:-5][-1, -1]))
    //
    // Observed agreement is ≤ 1.2e-14 on every value (summation order
    // differs); the asserted tolerance is 1e-6.
    //
    // Fixtures (x = column, y = row, i = y*w + x, integers then / 2**24):
    //   hash32 = the integer mixer above; noise24(s, i) = hash32(s*65536 + i) >> 8
    //   "noise":    a = noise24(1,i);  b = (3a + noise24(2,i)) // 4
    //   "gradient": a = 400000x + 200000y + (hash32(3*65536 + i) >> 12);
    //               b = (5a + 3*noise24(4,i)) // 8
    //   "ao":       a = 16777215 - min(300000*((x-w//2)^2 + (y-h//2)^2), 12000000)
    //                   - (noise24(5,i) >> 4);
    //               b = (7a + noise24(6,i)) // 8 if (x+y) % 3 else a
    const SKIMAGE_CASES: [SkimageCase; 4] = [
        SkimageCase {
            kind: "noise",
            w: 16,
            h: 16,
            sum_a: 122.82017946243286,
            sum_b: 123.54852509498596,
            mssim: 0.9305525877110148,
            first: 0.9443584776897315,
            last: 0.9358643194755434,
        },
        SkimageCase {
            kind: "gradient",
            w: 24,
            h: 20,
            sum_a: 201.15156829357147,
            sum_b: 217.4024977684021,
            mssim: 0.21609180195349295,
            first: 0.21625936531722526,
            last: 0.2768738620466621,
        },
        SkimageCase {
            kind: "ao",
            w: 11,
            h: 13,
            sum_a: 80.4669508934021,
            sum_b: 79.99262988567352,
            mssim: 0.9423902940898601,
            first: 0.9480442571909372,
            last: 0.9467901413826233,
        },
        SkimageCase {
            kind: "ao",
            w: 32,
            h: 27,
            sum_a: 263.5147457122803,
            sum_b: 277.1121845841408,
            mssim: 0.8329919614522027,
            first: 0.6531479913842079,
            last: 0.6249788631949016,
        },
    ];

    #[test]
    fn agrees_with_scikit_image() {
        for case in &SKIMAGE_CASES {
            let (a, b) = fixture(case.kind, case.w, case.h);
            assert_eq!(sum(&a), case.sum_a, "{} fixture a differs", case.kind);
            assert_eq!(sum(&b), case.sum_b, "{} fixture b differs", case.kind);
            let ia = Image::new(case.w, case.h, &a).unwrap();
            let ib = Image::new(case.w, case.h, &b).unwrap();
            let m = ssim(&ia, &ib).unwrap();
            assert!(
                (m - case.mssim).abs() < 1e-6,
                "{} {}x{}: {m} vs skimage {}",
                case.kind,
                case.w,
                case.h,
                case.mssim
            );
            let map = ssim_map(&ia, &ib).unwrap();
            assert_eq!(map.len(), (case.w - 10) * (case.h - 10));
            assert!((map[0] - case.first).abs() < 1e-6);
            assert!((map[map.len() - 1] - case.last).abs() < 1e-6);
        }
    }

    #[test]
    fn image_with_itself_is_one() {
        let (a, b) = fixture("ao", 32, 27);
        for data in [&a, &b] {
            let img = Image::new(32, 27, data).unwrap();
            assert!((ssim(&img, &img).unwrap() - 1.0).abs() < 1e-12);
            for s in ssim_map(&img, &img).unwrap() {
                assert!((s - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn symmetric_bit_for_bit() {
        // Every operation in the formula is commutative in (x, y) and the two
        // images pass through identical code paths, so swapping the arguments
        // must not change a single bit.
        let (a, b) = fixture("gradient", 24, 20);
        let ia = Image::new(24, 20, &a).unwrap();
        let ib = Image::new(24, 20, &b).unwrap();
        assert_eq!(ssim(&ia, &ib).unwrap(), ssim(&ib, &ia).unwrap());
        assert_eq!(ssim_map(&ia, &ib).unwrap(), ssim_map(&ib, &ia).unwrap());
    }

    #[test]
    fn constant_images_closed_form() {
        // For constant images x ≡ c1, y ≡ c2 every window is constant, so with
        // normalised weights μx = c1, μy = c2 and σx² = σy² = σxy = 0. The
        // contrast-structure factor is (2·0 + C2)/(0 + 0 + C2) = 1 and
        //     SSIM = (2·c1·c2 + C1) / (c1² + c2² + C1)
        // at every valid pixel, hence also for the mean. (Exact in real
        // arithmetic; in floating point the weights sum to 1 only up to an ulp
        // or so, hence the 1e-12 tolerance.)
        let c1_const = SSIM_C1;
        for &(c1, c2) in &[
            (0.25f32, 0.75f32),
            (0.9, 0.3),
            (1.0, 0.0),
            (0.0, 0.0),
            (0.6, 0.6),
        ] {
            let (w, h) = (13, 17);
            let a = vec![c1; w * h];
            let b = vec![c2; w * h];
            let ia = Image::new(w, h, &a).unwrap();
            let ib = Image::new(w, h, &b).unwrap();
            let (c1, c2) = (f64::from(c1), f64::from(c2));
            let expected = (2.0 * c1 * c2 + c1_const) / (c1 * c1 + c2 * c2 + c1_const);
            let m = ssim(&ia, &ib).unwrap();
            assert!((m - expected).abs() < 1e-12, "{c1} {c2}: {m} vs {expected}");
            let map = ssim_map(&ia, &ib).unwrap();
            assert_eq!(map.len(), 3 * 7);
            assert!(map.iter().all(|s| (s - expected).abs() < 1e-12));
        }
        // Spot value: c1 = 0.25, c2 = 0.75 → (0.375 + 1e-4) / (0.625 + 1e-4).
        let a = vec![0.25f32; 121];
        let b = vec![0.75f32; 121];
        let m = ssim(
            &Image::new(11, 11, &a).unwrap(),
            &Image::new(11, 11, &b).unwrap(),
        )
        .unwrap();
        assert!((m - 0.3751 / 0.6251).abs() < 1e-12);
    }

    #[test]
    fn two_tone_step_closed_form() {
        // x is `p` left of column 12 and `q` from column 12 on (24×12 image);
        // y has the same step with values p', q' (a contrast change and/or
        // luminance shift of x: p' = αp + β, q' = αq + β). A window starting at
        // column ox sees the left value with total weight
        //     W = Σ_{t : ox + t < 12} g_t   (g = normalised 1-D Gaussian taps;
        // rows do not matter because every row is identical). For a two-valued
        // distribution with probabilities W and 1 − W:
        //     μx = pW + q(1−W),          μy = p'W + q'(1−W),
        //     σx² = W(1−W)(p−q)²,        σy² = W(1−W)(p'−q')²,
        //     σxy = W(1−W)(p−q)(p'−q').
        // Windows that lie entirely on one side (W ∈ {0, 1}) reduce to the
        // constant-image formula; the others exercise the contrast/structure
        // term against an independent computation.
        let g = {
            let raw: Vec<f64> = (0..11)
                .map(|t| {
                    let x = t as f64 - 5.0;
                    (-x * x / (2.0 * 1.5 * 1.5)).exp()
                })
                .collect();
            let s: f64 = raw.iter().sum();
            raw.into_iter().map(|v| v / s).collect::<Vec<_>>()
        };
        let (w, h, edge) = (24usize, 12usize, 12usize);
        let (p, q) = (0.25f32, 0.75f32);
        // (p', q'): α = 0.5, β = 0.25 (contrast halved); α = −1, β = 1
        // (inverted); α = 1, β = 0.125 (pure shift); α = 1, β = 0 (identical).
        for &(pp, qq) in &[(0.375f32, 0.625f32), (0.75, 0.25), (0.375, 0.875), (p, q)] {
            let step = |l: f32, r: f32| -> Vec<f32> {
                (0..w * h)
                    .map(|i| if i % w < edge { l } else { r })
                    .collect()
            };
            let a = step(p, q);
            let b = step(pp, qq);
            let map = ssim_map(
                &Image::new(w, h, &a).unwrap(),
                &Image::new(w, h, &b).unwrap(),
            )
            .unwrap();
            let out_w = w - 10;
            assert_eq!(map.len(), out_w * (h - 10));
            let (p, q, pp, qq) = (f64::from(p), f64::from(q), f64::from(pp), f64::from(qq));
            let mut expected_mean = 0.0;
            for ox in 0..out_w {
                let wl: f64 = (0..11).filter(|t| ox + t < edge).map(|t| g[t]).sum();
                let wr = 1.0 - wl;
                let mx = p * wl + q * wr;
                let my = pp * wl + qq * wr;
                let vx = wl * wr * (p - q) * (p - q);
                let vy = wl * wr * (pp - qq) * (pp - qq);
                let vxy = wl * wr * (p - q) * (pp - qq);
                let expected = (2.0 * mx * my + SSIM_C1) * (2.0 * vxy + SSIM_C2)
                    / ((mx * mx + my * my + SSIM_C1) * (vx + vy + SSIM_C2));
                expected_mean += expected / out_w as f64;
                for oy in 0..h - 10 {
                    let got = map[oy * out_w + ox];
                    assert!(
                        (got - expected).abs() < 1e-12,
                        "({pp},{qq}) ox={ox}: {got} vs {expected}"
                    );
                }
            }
            let m = ssim(
                &Image::new(w, h, &a).unwrap(),
                &Image::new(w, h, &b).unwrap(),
            )
            .unwrap();
            assert!((m - expected_mean).abs() < 1e-12);
        }
    }

    #[test]
    fn constants_are_the_papers() {
        assert_eq!(SSIM_WINDOW, 11);
        assert_eq!(SSIM_SIGMA, 1.5);
        assert!((SSIM_C1 - 1e-4).abs() < 1e-18);
        assert!((SSIM_C2 - 9e-4).abs() < 1e-18);
        let taps = gaussian_taps();
        assert!((taps.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(taps[0], taps[10]);
    }

    #[test]
    fn errors_instead_of_panics() {
        let d = vec![0.5f32; 11 * 11];
        let ok = Image::new(11, 11, &d).unwrap();
        assert_eq!(ssim_map(&ok, &ok).unwrap().len(), 1);

        let narrow = vec![0.5f32; 10 * 40];
        let narrow = Image::new(10, 40, &narrow).unwrap();
        assert_eq!(
            ssim(&narrow, &narrow),
            Err(MetricsError::WindowTooLarge {
                window: 11,
                width: 10,
                height: 40
            })
        );
        let short = vec![0.5f32; 40 * 10];
        let short = Image::new(40, 10, &short).unwrap();
        assert!(matches!(
            ssim_map(&short, &short),
            Err(MetricsError::WindowTooLarge { .. })
        ));
        let tiny = [0.5f32];
        let tiny = Image::new(1, 1, &tiny).unwrap();
        assert!(matches!(
            ssim(&tiny, &tiny),
            Err(MetricsError::WindowTooLarge { .. })
        ));

        let other = vec![0.5f32; 12 * 11];
        let other = Image::new(12, 11, &other).unwrap();
        assert!(matches!(
            ssim(&ok, &other),
            Err(MetricsError::SizeMismatch { .. })
        ));

        let mut nan = d.clone();
        nan[11 * 3 + 2] = f32::NAN;
        let nan = Image::new(11, 11, &nan).unwrap();
        assert_eq!(
            ssim(&ok, &nan),
            Err(MetricsError::NonFinite {
                image: "b",
                x: 2,
                y: 3
            })
        );
        assert!(matches!(
            ssim_map(&nan, &ok),
            Err(MetricsError::NonFinite { image: "a", .. })
        ));
    }
}
