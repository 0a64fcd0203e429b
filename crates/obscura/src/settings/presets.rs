//! Quality levels per technique ([`Preset`], [`AoSettings::preset`]).

use super::*;

/// A quality level: [`AoSettings::preset`] says per technique what each sets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The cheapest: blur radius 2 (VAO, HBAO+), fewer samples (HBAO 4 × 4, HBAO+ 4 directions,
    /// GTAO and GTAO-VB 1 × 2) and one stochastic depth sample per pixel.
    Low,
    /// The defaults ([`AoSettings::default`]) for every technique.
    #[default]
    Medium,
    /// More samples than the defaults where the estimator has room (VAO 16, HBAO 8 × 10, GTAO
    /// and GTAO-VB 3 × 3).
    High,
    /// The most samples (VAO 32, HBAO 16 × 20, GTAO 9 × 3, GTAO-VB 3 × 5, S = 8) and, for VAO
    /// and HBAO+, blur radius 6.
    Ultra,
}

impl Preset {
    /// Every preset, cheapest first.
    pub const ALL: [Preset; 4] = [Preset::Low, Preset::Medium, Preset::High, Preset::Ultra];

    /// The preset's name in settings files and on the command line (`low` … `ultra`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Low => "low",
            Preset::Medium => "medium",
            Preset::High => "high",
            Preset::Ultra => "ultra",
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        Preset::ALL
            .into_iter()
            .find(|p| p.name() == wanted)
            .ok_or_else(|| SettingsError::UnknownPreset(s.to_string()))
    }
}

impl AoSettings {
    /// The settings of `technique` at a quality level: [`AoSettings::default`] with the fields
    /// below changed, chosen by the axes of the technique's row (estimator, hidden-depth source;
    /// the schedule changes nothing: a two-phase technique gets the settings of its single-pass
    /// twin, so that both give the same image). Every other field keeps its default: a preset
    /// never changes the scene-dependent radius, thickness, exponent, normalisation, peel
    /// separation or blur sharpness, nor the seed or `sd-svao`'s mask (and the guard band is not
    /// a setting at all). `Medium` is exactly [`AoSettings::default`] for every technique.
    ///
    /// Per estimator and source (docs/SETTINGS.md has the table with every column): VAO
    /// `vao.samples` 8, 8, 16, 32 and `blur.radius` 2, 4, 4, 6; HBAO+ 4 × 4 directions × steps
    /// at low, else 8 × 4, `blur.radius` as VAO; HBAO directions × steps 4×4, 8×4, 8×10, 16×20;
    /// GTAO slices × steps 1×2, 2×2, 3×3, 9×3; GTAO-VB 1×2, 2×2, 3×3, 3×5; the
    /// stochastic depth map S = 1, 4, 4, 8 with α = 1.5/S throughout (at most 1: at S = 1 the
    /// nearest hidden surface).
    ///
    /// `low` keeps to one sample per pixel, which every adapter with the map's format rasterises
    /// (WebGPU guarantees 1× and 4× multisampling only).
    pub fn preset(technique: Technique, preset: Preset) -> AoSettings {
        let row = technique.row();
        let mut s = AoSettings {
            technique,
            ..AoSettings::default()
        };
        match row.estimator {
            Estimator::Vao => match preset {
                Preset::Low => {
                    s.vao.samples = 8;
                    s.blur.radius = 2;
                }
                Preset::Medium => {}
                Preset::High => s.vao.samples = 16,
                Preset::Ultra => {
                    s.vao.samples = 32;
                    s.blur.radius = 6;
                }
            },
            // 8 × 4 = 32 samples is already the most the two-phase mask holds.
            Estimator::HbaoPlus => match preset {
                Preset::Low => {
                    s.hbao_plus.directions = 4;
                    s.blur.radius = 2;
                }
                Preset::Medium | Preset::High => {}
                Preset::Ultra => s.blur.radius = 6,
            },
            // Seed 001 Tab. 1's 8 × 4 as the default, seed 004's smallest grid (8 × 10) as high.
            Estimator::Hbao => {
                let (directions, steps) = match preset {
                    Preset::Low => (4, 4),
                    Preset::Medium => (8, 4),
                    Preset::High => (8, 10),
                    Preset::Ultra => (16, 20),
                };
                s.hbao.directions = directions;
                s.hbao.steps = steps;
            }
            // The common XeGTAO-style grid, slices × steps 1×2, 2×2, 3×3, 9×3.
            Estimator::Gtao => {
                let (slices, steps) = match preset {
                    Preset::Low => (1, 2),
                    Preset::Medium => (2, 2),
                    Preset::High => (3, 3),
                    Preset::Ultra => (9, 3),
                };
                s.gtao.slices = slices;
                s.gtao.steps = steps;
            }
            // Seed 004's 8 directions as the default; the steps per level are ours.
            Estimator::PyramidHbao => {
                let (directions, steps) = match preset {
                    Preset::Low => (4, 3),
                    Preset::Medium => (8, 4),
                    Preset::High => (8, 6),
                    Preset::Ultra => (16, 6),
                };
                s.pyramid_hbao.directions = directions;
                s.pyramid_hbao.steps = steps;
            }
            // Seed 001 Tab. 1's 32 as the default, the most the two-phase mask holds.
            Estimator::Ssao => {
                s.ssao.samples = match preset {
                    Preset::Low => 8,
                    Preset::Medium | Preset::High | Preset::Ultra => 32,
                };
            }
            // SAO's published code ships 11 taps; fewer and more around it.
            Estimator::Sao => {
                s.sao.samples = match preset {
                    Preset::Low => 7,
                    Preset::Medium => 11,
                    Preset::High => 16,
                    Preset::Ultra => 32,
                };
            }
            // The common GTAO grid (slices × steps 1×2, 2×2, 3×3) as far as three slices and 32
            // samples allow: ultra is 3 × 5 instead of 9 × 3.
            Estimator::GtaoVb => {
                let (slices, steps) = match preset {
                    Preset::Low => (1, 2),
                    Preset::Medium => (2, 2),
                    Preset::High => (3, 3),
                    Preset::Ultra => (3, 5),
                };
                s.gtao_vb.slices = slices;
                s.gtao_vb.steps = steps;
            }
        }
        match row.source {
            Source::StochasticDepth => {
                let sd = &mut s.stochastic_depth;
                match preset {
                    // One sample: every adapter with the format rasterises it (WebGPU
                    // guarantees 1× and 4× only). α stays 1.5/S throughout.
                    Preset::Low => sd.samples = 1,
                    Preset::Medium | Preset::High => {}
                    Preset::Ultra => sd.samples = 8,
                }
            }
            Source::FirstLayer
            | Source::DualDepth
            | Source::ColumnRays
            | Source::RayStochasticDepth
            | Source::DepthPyramid => {}
        }
        s
    }
}
