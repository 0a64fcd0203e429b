//! `cost.svg`: quality against cost, one point per technique (MSE against GPU milliseconds, both
//! on log axes), and the Pareto front that answers "which technique should I use".
//!
//! Written by hand: a dozen labelled points on two log axes is a page of SVG, while a plotting
//! crate (plotters) needs a font backend (font-kit or ab_glyph and a font file) to lay out its
//! labels, which a headless CI machine does not have.

use super::{Report, TechniqueResult};
use std::fmt::Write;

const WIDTH: f64 = 640.0;
const HEIGHT: f64 = 400.0;
/// Left, right, top, bottom margins (axis labels and point labels need room).
const MARGIN: [f64; 4] = [70.0, 120.0, 30.0, 50.0];

/// The techniques no other technique beats on both counts: none is at least as fast *and* at
/// least as accurate (MSE) while strictly better on one. In the report's order; techniques
/// without a time are left out.
pub fn pareto_front(results: &[TechniqueResult]) -> Vec<&str> {
    let timed: Vec<(&TechniqueResult, f64)> = results
        .iter()
        .filter_map(|r| r.gpu_ms.map(|ms| (r, ms)))
        .filter(|(r, ms)| ms.is_finite() && r.mse.is_finite())
        .collect();
    timed
        .iter()
        .filter(|(r, ms)| {
            !timed
                .iter()
                .any(|(o, o_ms)| o_ms <= ms && o.mse <= r.mse && (o_ms < ms || o.mse < r.mse))
        })
        .map(|(r, _)| r.technique.as_str())
        .collect()
}

/// A log10 axis over `[lo, hi]` (both positive), widened to whole 1-2-5 steps.
struct LogAxis {
    lo: f64,
    hi: f64,
}

impl LogAxis {
    fn new(values: impl Iterator<Item = f64>) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if !lo.is_finite() {
            (lo, hi) = (1.0, 10.0);
        }
        let steps = |v: f64| {
            let decade = 10f64.powf(v.log10().floor());
            [1.0, 2.0, 5.0, 10.0].map(|m| m * decade)
        };
        let lo = steps(lo).into_iter().rev().find(|s| *s <= lo).unwrap_or(lo);
        let hi = steps(hi).into_iter().find(|s| *s >= hi).unwrap_or(hi);
        Self {
            lo,
            hi: if hi > lo { hi } else { lo * 10.0 },
        }
    }

    /// Position of `v` in [0, 1].
    fn at(&self, v: f64) -> f64 {
        (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
    }

    /// 1-2-5 ticks within the axis; decades only where it spans more than three.
    fn ticks(&self) -> Vec<f64> {
        let first = self.lo.log10().floor() as i32;
        let last = self.hi.log10().ceil() as i32;
        let mantissas: &[f64] = if last - first > 3 {
            &[1.0]
        } else {
            &[1.0, 2.0, 5.0]
        };
        (first..=last)
            .flat_map(|e| mantissas.iter().map(move |m| m * 10f64.powi(e)))
            .filter(|t| *t >= self.lo * 0.999 && *t <= self.hi * 1.001)
            .collect()
    }
}

fn tick_label(v: f64) -> String {
    if (1e-3..1e4).contains(&v) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        format!("{v:.0e}")
    }
}

/// The chart, or `None` when no technique has a time.
pub fn cost_chart_svg(report: &Report) -> Option<String> {
    let points: Vec<(&str, f64, f64)> = report
        .results
        .iter()
        .filter_map(|r| Some((r.technique.as_str(), r.gpu_ms?, r.mse)))
        .filter(|(_, ms, mse)| *ms > 0.0 && ms.is_finite() && mse.is_finite())
        .collect();
    if points.is_empty() {
        return None;
    }
    // An exact match (MSE 0) cannot sit on a log axis: it is drawn at the bottom.
    let floor = points
        .iter()
        .map(|p| p.2)
        .filter(|m| *m > 0.0)
        .fold(f64::INFINITY, f64::min)
        .min(1e-6);
    let x = LogAxis::new(points.iter().map(|p| p.1));
    let y = LogAxis::new(points.iter().map(|p| p.2.max(floor)));
    let [ml, mr, mt, mb] = MARGIN;
    let (pw, ph) = (WIDTH - ml - mr, HEIGHT - mt - mb);
    let px = |v: f64| ml + x.at(v) * pw;
    let py = |v: f64| mt + (1.0 - y.at(v)) * ph;
    let front = pareto_front(&report.results);

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"sans-serif\" font-size=\"11\">"
    );
    let _ = writeln!(
        svg,
        "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\
         <rect x=\"{ml}\" y=\"{mt}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#888\"/>"
    );
    for t in x.ticks() {
        let cx = px(t);
        let _ = writeln!(
            svg,
            "<line x1=\"{cx:.1}\" y1=\"{mt}\" x2=\"{cx:.1}\" y2=\"{:.1}\" stroke=\"#eee\"/>\
             <text x=\"{cx:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            mt + ph,
            mt + ph + 15.0,
            tick_label(t)
        );
    }
    for t in y.ticks() {
        let cy = py(t);
        let _ = writeln!(
            svg,
            "<line x1=\"{ml}\" y1=\"{cy:.1}\" x2=\"{:.1}\" y2=\"{cy:.1}\" stroke=\"#eee\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
            ml + pw,
            ml - 5.0,
            cy + 4.0,
            tick_label(t)
        );
    }
    let time = if report.software_adapter {
        "CPU adapter ms per frame (not GPU timings)"
    } else {
        "GPU ms per frame (without the G-buffer)"
    };
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{time}</text>\
         <text transform=\"translate(14 {:.1}) rotate(-90)\" text-anchor=\"middle\">MSE against the \
         reference</text>",
        ml + pw / 2.0,
        HEIGHT - 8.0,
        mt + ph / 2.0
    );
    // The front as a step line: what the best technique at each budget achieves.
    let mut on_front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| front.contains(&p.0))
        .map(|p| (px(p.1), py(p.2.max(floor))))
        .collect();
    on_front.sort_by(|a, b| a.0.total_cmp(&b.0));
    if on_front.len() > 1 {
        let path: Vec<String> = on_front
            .iter()
            .map(|(cx, cy)| format!("{cx:.1},{cy:.1}"))
            .collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"#2a7\" stroke-dasharray=\"4 3\"/>",
            path.join(" ")
        );
    }
    // Labels that would overlap one already placed move down a line (points of equal cost and
    // error are common: the ray-traced techniques all sit at the reference).
    let mut placed: Vec<(f64, f64, f64)> = Vec::new();
    for (name, ms, mse) in &points {
        let (cx, cy) = (px(*ms), py(mse.max(floor)));
        let width = 6.5 * name.len() as f64;
        let mut ly = cy + 4.0;
        while placed
            .iter()
            .any(|&(x, y, w)| (ly - y).abs() < 12.0 && cx + 6.0 < x + w && x < cx + 6.0 + width)
        {
            ly += 12.0;
        }
        placed.push((cx + 6.0, ly, width));
        let fill = if front.contains(name) { "#2a7" } else { "#36c" };
        let _ = writeln!(
            svg,
            "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"4\" fill=\"{fill}\"><title>{name}: \
             {ms:.3} ms, MSE {mse:.3e}</title></circle>\
             <text x=\"{:.1}\" y=\"{ly:.1}\">{name}</text>",
            cx + 6.0,
        );
    }
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#2a7\">● Pareto front</text>",
        ml + pw + 8.0,
        mt + 10.0
    );
    svg.push_str("</svg>\n");
    Some(svg)
}
