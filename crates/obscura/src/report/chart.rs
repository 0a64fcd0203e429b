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
/// Farthest a label's anchor sits from its dot, in px: further away it reads as another dot's.
pub(super) const LABEL_REACH: f64 = 30.0;
/// Width of one character and height of one line of the 11 px labels, roughly.
const CHAR_W: f64 = 6.5;
const LINE_H: f64 = 12.0;

/// A dot's label: its text (the name, or a number listed beside the plot), anchor point and
/// SVG `text-anchor`.
struct Label {
    text: String,
    x: f64,
    y: f64,
    anchor: &'static str,
    numbered: bool,
}

/// Box of a text of `chars` characters anchored at (x, y) (baseline): (left, top, right, bottom).
fn text_box(x: f64, y: f64, chars: usize, anchor: &str) -> [f64; 4] {
    let w = CHAR_W * chars as f64;
    let left = match anchor {
        "end" => x - w,
        "middle" => x - w / 2.0,
        _ => x,
    };
    [left, y - 9.0, left + w, y + 3.0]
}

fn overlaps(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// A place for each dot's label within [`LABEL_REACH`] of it that covers no dot and no label
/// placed before: its name where one fits, else a number (which fits more often; placed
/// right of the dot when nothing is free, overlapping rather than moving away). Greedy, in
/// the dots' order; labels stay within `bounds` (left, top, right, bottom).
fn place_labels(dots: &[(f64, f64)], names: &[&str], bounds: [f64; 4]) -> Vec<Label> {
    // Offsets (dx, dy of the baseline, anchor), nearest first.
    let mut candidates = Vec::new();
    for dy in [4.0, -8.0, 16.0, -20.0, 28.0] {
        for (dx, anchor) in [(7.0, "start"), (-7.0, "end"), (0.0, "middle")] {
            let d: f64 = f64::hypot(dx, dy - 4.0);
            if f64::hypot(dx, dy) <= LABEL_REACH && (anchor != "middle" || dy.abs() > 6.0) {
                candidates.push((d, dx, dy, anchor));
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut taken: Vec<[f64; 4]> = dots
        .iter()
        .map(|&(x, y)| [x - 4.0, y - 4.0, x + 4.0, y + 4.0])
        .collect();
    let mut next_number = 1;
    let mut labels = Vec::new();
    for (&(cx, cy), name) in dots.iter().zip(names) {
        let free = |text: &str, taken: &[[f64; 4]]| {
            candidates.iter().find_map(|&(_, dx, dy, anchor)| {
                let b = text_box(cx + dx, cy + dy, text.chars().count(), anchor);
                let inside = b[0] >= bounds[0]
                    && b[1] >= bounds[1]
                    && b[2] <= bounds[2]
                    && b[3] <= bounds[3];
                let own = [cx - 4.0, cy - 4.0, cx + 4.0, cy + 4.0];
                (inside && !taken.iter().any(|t| *t != own && overlaps(t, &b))).then_some((
                    cx + dx,
                    cy + dy,
                    anchor,
                    b,
                ))
            })
        };
        let (text, numbered, (x, y, anchor, b)) = match free(name, &taken) {
            Some(place) => (name.to_string(), false, place),
            None => {
                let number = next_number.to_string();
                next_number += 1;
                let place = free(&number, &taken).unwrap_or_else(|| {
                    (
                        cx + 7.0,
                        cy + 4.0,
                        "start",
                        text_box(cx + 7.0, cy + 4.0, 2, "start"),
                    )
                });
                (number, true, place)
            }
        };
        taken.push(b);
        labels.push(Label {
            text,
            x,
            y,
            anchor,
            numbered,
        });
    }
    labels
}

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
    // Every label sits next to its dot (issue 62: labels pushed down a line per collision ended
    // far from their dots); a dot with no free place nearby gets a number, named in a list beside
    // the plot.
    let dots: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (px(p.1), py(p.2.max(floor))))
        .collect();
    let labels = place_labels(
        &dots,
        &points.iter().map(|p| p.0).collect::<Vec<_>>(),
        [ml, 0.0, ml + pw, mt + ph + 2.0],
    );
    // The numbered dots' names, in columns down the right margin.
    let numbered: Vec<(&str, &str)> = points
        .iter()
        .zip(&labels)
        .filter(|(_, l)| l.numbered)
        .map(|(p, l)| (l.text.as_str(), p.0))
        .collect();
    let rows = (((HEIGHT - mb) - (mt + 28.0)) / LINE_H).floor().max(1.0) as usize;
    let column_w = numbered
        .iter()
        .map(|(n, name)| CHAR_W * (n.len() + name.len() + 1) as f64 + 12.0)
        .fold(mr - 8.0, f64::max);
    // Wider than WIDTH only when the list of numbered dots needs more than one column.
    let width = ml + pw + 8.0 + numbered.len().div_ceil(rows).max(1) as f64 * column_w;

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {width} {HEIGHT}\" font-family=\"sans-serif\" font-size=\"11\">"
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
    for ((name, ms, mse), ((cx, cy), label)) in points.iter().zip(dots.iter().zip(&labels)) {
        let fill = if front.contains(name) { "#2a7" } else { "#36c" };
        let _ = writeln!(
            svg,
            "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"4\" fill=\"{fill}\"><title>{name}: \
             {ms:.3} ms, MSE {mse:.3e}</title></circle>\
             <text class=\"label\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"{}\">{}</text>",
            label.x, label.y, label.anchor, label.text
        );
    }
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#2a7\">● Pareto front</text>",
        ml + pw + 8.0,
        mt + 10.0
    );
    for (i, (number, name)) in numbered.iter().enumerate() {
        let _ = writeln!(
            svg,
            "<text x=\"{:.1}\" y=\"{:.1}\">{number} {name}</text>",
            ml + pw + 8.0 + (i / rows) as f64 * column_w,
            mt + 28.0 + (i % rows) as f64 * LINE_H
        );
    }
    svg.push_str("</svg>\n");
    Some(svg)
}
