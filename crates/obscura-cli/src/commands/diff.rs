//! `obscura diff`: how far apart two AO images are (e.g. the same render before and after a
//! change; `scripts/check-images.sh` uses it).

use anyhow::{bail, Result};
use clap::Args;
use obscura::output;
use std::path::PathBuf;

#[derive(Args)]
pub struct DiffArgs {
    /// First image (.exr or .png; the first channel is compared).
    a: PathBuf,
    /// Second image, the same size.
    b: PathBuf,
    /// Fail (exit 1) when the largest absolute difference is above this (a finite number, 0 or
    /// more).
    #[arg(long, value_parser = parse_threshold, allow_hyphen_values = true)]
    max_abs: Option<f32>,
}

/// A threshold on a difference: finite and not negative. NaN would compare false with every
/// difference (issue 62: `--max-abs NaN` was accepted), and a negative one fails every pair.
fn parse_threshold(text: &str) -> Result<f32, String> {
    let value: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a number: give one like 0.01"))?;
    if !value.is_finite() || value < 0.0 {
        return Err(format!(
            "{text} is not a finite number of 0 or more: give the largest difference allowed, \
             like 0.01"
        ));
    }
    Ok(value)
}

pub fn run(args: &DiffArgs) -> Result<()> {
    let a = output::read_ao(&args.a)?;
    let b = output::read_ao(&args.b)?;
    if (a.width, a.height) != (b.width, b.height) {
        bail!(
            "'{}' is {}x{} but '{}' is {}x{}: compare images of the same size",
            args.a.display(),
            a.width,
            a.height,
            args.b.display(),
            b.width,
            b.height
        );
    }
    let (mut max_abs, mut sum_abs, mut differing) = (0.0f32, 0.0f64, 0usize);
    for (x, y) in a.values.iter().zip(&b.values) {
        let d = if x.is_nan() && y.is_nan() {
            0.0
        } else {
            (x - y).abs()
        };
        // NaN against a number counts as an infinite difference.
        let d = if d.is_nan() { f32::INFINITY } else { d };
        max_abs = max_abs.max(d);
        sum_abs += f64::from(d);
        differing += usize::from(d > 0.0);
    }
    let pixels = a.values.len().max(1);
    println!(
        "{} vs {}: max |a-b| {max_abs:e}, mean |a-b| {:e}, {differing} of {pixels} pixels differ",
        args.a.display(),
        args.b.display(),
        sum_abs / pixels as f64
    );
    if let Some(bound) = args.max_abs {
        if max_abs > bound {
            bail!("max |a-b| {max_abs:e} is over --max-abs {bound:e}");
        }
    }
    Ok(())
}
