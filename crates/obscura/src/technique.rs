//! The technique table: every technique is one row naming its estimator, hidden-depth source and
//! schedule (docs/ARCHITECTURE.md, "The three axes").
//!
//! This is the only place that matches on [`Technique`]. Everything else (pipeline assembly, the
//! CLI's help and lists, validation messages, `--debug-out` support, reports, the README table,
//! the shader validation test) reads the row's axes. Adding a technique is one [`Technique`]
//! variant and one row of [`TABLE`] here, plus at most one estimator `.rs`/`.wgsl` pair
//! (`docs/ARCHITECTURE.md`, "Adding a technique").

use crate::estimators::{self, EstimatorModule};
use std::fmt;
use std::str::FromStr;

/// Declares [`Technique`] and the list of its variants (so a test can hold every variant to
/// exactly one row).
macro_rules! techniques {
    ($(#[$first_doc:meta])* $first:ident $(, $(#[$rest_doc:meta])* $rest:ident)* $(,)?) => {
        /// An AO technique: a handle on its row of [`TABLE`].
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
        pub enum Technique {
            $(#[$first_doc])*
            #[default]
            $first,
            $($(#[$rest_doc])* $rest,)*
        }

        #[cfg(test)]
        const VARIANTS: &[Technique] = &[Technique::$first, $(Technique::$rest,)*];
    };
}

techniques!(
    /// `vao`: volumetric AO over the depth buffer (seed 000 §3.1–3.5). The default.
    Vao,
    /// `vao-interleaved`: VAO over 16 quarter-resolution depth layers.
    VaoInterleaved,
    /// `vao-dual`: VAO; occluded samples also read a second depth layer (depth peeling).
    VaoDual,
    /// `rt-vao`: VAO; occluded samples trace their camera-ray column through the BVH.
    RtVao,
    /// `rt-svao`: RT-VAO in two phases; phase 2 traces only the flagged samples (work list).
    RtSvao,
    /// `rt-svao-dense`: RT-SVAO with phase 2 walking every pixel (no work list).
    RtSvaoDense,
    /// `sd-vao`: VAO; occluded samples read every sample of a stochastic depth map.
    SdVao,
    /// `sd-svao`: SD-VAO in two phases; the map is rasterised only where phase 1 asked.
    SdSvao,
    /// `ray-sd-vao`: VAO in two phases over a stochastic depth map collected by rays through the
    /// BVH where phase 1 asked (seed 002 §3.1).
    RaySdVao,
    /// `ray-sd-vao-full`: VAO in one pass over a ray-traced stochastic depth map of every pixel.
    RaySdVaoFull,
    /// `hbao`: horizon-based AO, D directions × S steps (seed 001 §3.2, seed 004 §2.2.1).
    Hbao,
    /// `hbao-interleaved`: HBAO over 16 quarter-resolution depth layers.
    HbaoInterleaved,
    /// `hbao-dual`: HBAO; a step whose surface lies above the tangent plane but beyond R also
    /// reads the second depth layer.
    HbaoDual,
    /// `sd-hbao`: HBAO; a step above the tangent plane but beyond R reads every sample of the
    /// stochastic depth map (seed 001 §3.2, Algorithm 2).
    SdHbao,
    /// `hbao+`: per-sample horizon AO, 8 directions × 4 steps (the authors' baseline).
    HbaoPlus,
    /// `hbao+-interleaved`: HBAO+ over 16 quarter-resolution depth layers (the authors' way).
    HbaoPlusInterleaved,
    /// `hbao+-dual`: HBAO+; samples behind a too-near first surface also read the second layer.
    HbaoPlusDual,
    /// `ray-sd-hbao`: HBAO; a step above the tangent plane beyond R reads the ray-traced
    /// stochastic depth map (seed 002 §3.1 with seed 001's Algorithm 2).
    RaySdHbao,
    /// `sd-hbao+`: HBAO+ over the stochastic depth map (seed 001 §3.2, the authors' HBAO+SD).
    SdHbaoPlus,
    /// `sd-hbao+-stenciled`: SD-HBAO+ in two phases; the map is rasterised only where phase 1
    /// asked (seed 000 §3.9's pipeline around seed 001's estimator).
    SdHbaoPlusStenciled,
    /// `sd-hbao+-multiview`: SD-HBAO+ in the camera's view and in a second view beside it over a
    /// second stochastic depth map; AO = the larger occlusion (seed 001 §3.4, Algorithm 3).
    SdHbaoPlusMultiview,
    /// `ssao`: seed 001's SSAO, Alchemy AO with 32 samples.
    Ssao,
    /// `sd-ssao`: SSAO; a sample whose first surface does not occlude reads the stochastic depth
    /// map (seed 001 §3.2–3.3).
    SdSsao,
    /// `sd-ssao-stenciled`: SD-SSAO in two phases; the map is rasterised only where phase 1 asked.
    SdSsaoStenciled,
    /// `sao`: Scalable Ambient Obscurance, spiral taps over the depth pyramid.
    Sao,
    /// `pyramid-hbao`: Pyramid HBAO, directions walked over the levels of the depth pyramid.
    PyramidHbao,
    /// `gtao`: ground-truth-based AO, slices × steps with the analytic cosine-weighted integral.
    Gtao,
    /// `gtao-vb`: GTAO slices with a 32-sector visibility bitmask and constant thickness.
    GtaoVb,
    /// `gtao-vb-dual`: GTAO-VB; every sample also marks the sectors of the second depth layer.
    GtaoVbDual,
    /// `sd-gtao-vb`: GTAO-VB; every sample also marks the sectors of every stochastic depth sample.
    SdGtaoVb,
    /// `sd-gtao-vb-stenciled`: SD-GTAO-VB in two phases; the map is rasterised only where phase 1
    /// asked.
    SdGtaoVbStenciled,
    /// `ray-sd-gtao-vb`: GTAO-VB; every sample also marks the sectors of every depth of the
    /// ray-traced stochastic depth map.
    RaySdGtaoVb,
    /// `hemisphere`: cosine-weighted rays within R, each marched in screen space over the first
    /// depth layer with a thickness (screen-space ray-traced AO).
    Hemisphere,
    /// `hemisphere-dual`: hemisphere rays marched in screen space over two depth layers (depth
    /// peeling): the second layer bounds the first surface's thickness.
    HemisphereDual,
    /// `sd-hemisphere`: hemisphere rays marched in screen space over the first layer and every
    /// depth of the stochastic depth map: each hidden depth is a surface of its own.
    SdHemisphere,
    /// `ray-sd-hemisphere`: hemisphere rays marched over the first layer and every depth of the
    /// stochastic depth map collected by camera rays through the BVH.
    RaySdHemisphere,
    /// `rtao`: cosine-weighted rays within R, each traced through the BVH: the ground truth's
    /// model and rays, a few per pixel per frame.
    Rtao,
    /// `rtao-two-phase`: RTAO in two phases; phase 1 marches each ray in screen space and phase 2
    /// traces only the rays it could not prove free (work list).
    RtaoTwoPhase
);

/// `Estimator`, one variant per entry of the registry (`estimators::registry`).
macro_rules! estimator_enum {
    ($($(#[$attr:meta])* $name:ident: $variant:ident($settings:ident) = $doc:literal,)*) => {
        /// What turns depth samples into occlusion (`src/estimators/`, `shaders/estimators/`).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Estimator {
            $($(#[$attr])* #[doc = $doc] $variant,)*
        }

        impl Estimator {
            /// Every estimator, in the registry's order.
            // One push per entry: an entry's `cfg` can stand on a statement, not on an element
            // of `vec![…]`.
            #[allow(clippy::vec_init_then_push)]
            pub fn all() -> Vec<Estimator> {
                let mut all = Vec::new();
                $($(#[$attr])* all.push(Estimator::$variant);)*
                all
            }
        }
    };
}
estimators::registry!(estimator_enum);

/// Declares [`Source`] and the list of its variants ([`Source::all`]) from one list, so that a
/// test running every source cannot miss a new one.
macro_rules! sources {
    ($($(#[$doc:meta])* $variant:ident,)*) => {
        /// What answers "what lies behind the first surface here" (`src/sources/`,
        /// `shaders/sources/`).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Source {
            $($(#[$doc])* $variant,)*
        }

        impl Source {
            /// Every source, in declaration order.
            pub fn all() -> impl Iterator<Item = Source> {
                [$(Source::$variant,)*].into_iter()
            }
        }
    };
}

sources!(
    /// The first depth layer only: occluded samples keep the estimator's thickness model.
    FirstLayer,
    /// A second depth layer by depth peeling (seed 000 §2.1).
    DualDepth,
    /// The camera ray through the sample's pixel traced through the BVH (seed 000 §3.6). Reads
    /// the VAO estimator's columns: a VAO-only source.
    ColumnRays,
    /// The rasterised stratified stochastic depth map (seed 001 §3.1, seed 000 §3.7/§3.9).
    StochasticDepth,
    /// The stochastic depth map collected by camera rays through the BVH, N depths per pixel by
    /// reservoir sampling (seed 002 §3.1): no rasteriser.
    RayStochasticDepth,
    /// Levels of mean linear depth (seed 004 §3.3): samples read the level their estimator names.
    /// Hides nothing; the source of the estimators that need levels (SAO, Pyramid HBAO).
    DepthPyramid,
    /// Each hemisphere ray marched in screen space over the first depth layer, every surface
    /// taken to be `hemisphere.thickness` thick. Reads the hemisphere estimator's rays.
    ScreenRays,
    /// Each hemisphere ray marched in screen space over the first and second depth layers: the
    /// first surface no thicker than the gap to the second. Reads the hemisphere estimator's
    /// rays.
    ScreenRaysDual,
    /// Each hemisphere ray traced through the BVH in world space: nothing is hidden from it.
    /// Reads the hemisphere estimator's rays.
    BvhRays,
    /// Each hemisphere ray marched in screen space over the first layer and every depth of the
    /// rasterised stochastic depth map at the pixel; in the map's guard band, over its depths
    /// alone. Reads the hemisphere estimator's rays.
    ScreenRaysStochastic,
    /// Each hemisphere ray marched in screen space over the first layer and every depth of the
    /// ray-traced stochastic depth map. Reads the hemisphere estimator's rays.
    ScreenRaysRayStochastic,
);

/// Which passes run the estimator over the source (`src/schedules/`, `shaders/schedules/`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Schedule {
    /// One pass: every sample consults the source inline.
    Single,
    /// Phase 1 over the first layer flags samples in an 8-bit mask and compacts flagged pixels
    /// into a work list; phase 2 (indirect dispatch) resolves only those (seed 000 §3.8).
    TwoPhase,
    /// Two phases, phase 2 walking every pixel and returning at once where nothing is flagged.
    TwoPhaseDense,
    /// The depth split into 16 quarter-resolution layers (one per pixel residue mod 4), each
    /// pixel's samples read from its own layer (docs/AUTHORS_CODE.md §1.7, the authors' HBAO+).
    Interleaved,
    /// The single pass in the camera's view, then the estimator again in a second view beside it
    /// over a second stochastic depth map that keeps every layer; each pixel keeps the larger
    /// occlusion (seed 001 §3.4, Algorithm 3).
    Multiview,
}

/// One row of the technique table.
#[derive(Clone, Copy, Debug)]
pub struct TechniqueRow {
    /// The variant this row describes (every variant has exactly one row, tested).
    pub technique: Technique,
    /// The name the CLI, reports and JSON use.
    pub name: &'static str,
    /// One line for help texts and the README.
    pub summary: &'static str,
    /// Paper (README.md "Papers" numbering) and section.
    pub paper: &'static str,
    /// What turns the depth samples into occlusion.
    pub estimator: Estimator,
    /// What answers for the geometry behind the first depth layer.
    pub source: Source,
    /// Which passes run the estimator over the source.
    pub schedule: Schedule,
}

/// Every technique, in the order lists and reports show them.
pub const TABLE: &[TechniqueRow] = &[
    TechniqueRow {
        technique: Technique::Vao,
        name: "vao",
        summary: "Volumetric AO over the depth buffer",
        paper: "seed 000 §3.1–3.5",
        estimator: Estimator::Vao,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::VaoInterleaved,
        name: "vao-interleaved",
        summary: "VAO over 16 quarter-resolution depth layers (samples snap to their layer)",
        paper: "seed 000 §3.1–3.5, authors' code §1.7 (docs/AUTHORS_CODE.md)",
        estimator: Estimator::Vao,
        source: Source::FirstLayer,
        schedule: Schedule::Interleaved,
    },
    TechniqueRow {
        technique: Technique::VaoDual,
        name: "vao-dual",
        summary: "VAO; occluded samples also read a second depth layer (depth peeling)",
        paper: "seed 000 §2.1, §4.3",
        estimator: Estimator::Vao,
        source: Source::DualDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::RtVao,
        name: "rt-vao",
        summary: "VAO; occluded samples trace their camera-ray column through the BVH",
        paper: "seed 000 §3.6",
        estimator: Estimator::Vao,
        source: Source::ColumnRays,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::RtSvao,
        name: "rt-svao",
        summary: "RT-VAO in two phases; phase 2 traces only flagged samples (work list)",
        paper: "seed 000 §3.8",
        estimator: Estimator::Vao,
        source: Source::ColumnRays,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::RtSvaoDense,
        name: "rt-svao-dense",
        summary: "RT-SVAO with phase 2 walking every pixel (no work list)",
        paper: "seed 000 §3.8",
        estimator: Estimator::Vao,
        source: Source::ColumnRays,
        schedule: Schedule::TwoPhaseDense,
    },
    TechniqueRow {
        technique: Technique::SdVao,
        name: "sd-vao",
        summary: "VAO; occluded samples read every sample of a stochastic depth map",
        paper: "seed 000 §3.7, seed 001 §3.1",
        estimator: Estimator::Vao,
        source: Source::StochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdSvao,
        name: "sd-svao",
        summary: "SD-VAO in two phases; the map is rasterised only where phase 1 asked",
        paper: "seed 000 §3.9",
        estimator: Estimator::Vao,
        source: Source::StochasticDepth,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::RaySdVao,
        name: "ray-sd-vao",
        summary: "SD-SVAO with the map collected by rays through the BVH (reservoir of 4)",
        paper: "seed 002 §3.1",
        estimator: Estimator::Vao,
        source: Source::RayStochasticDepth,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::RaySdVaoFull,
        name: "ray-sd-vao-full",
        summary: "VAO over a stochastic depth map collected by rays for every pixel, one pass",
        paper: "seed 002 §3.1",
        estimator: Estimator::Vao,
        source: Source::RayStochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::Hbao,
        name: "hbao",
        summary: "HBAO: horizon angles along 8 directions × 4 steps, attenuation 1 − r/R",
        paper: "seed 001 §3.2, seed 004 §2.2.1",
        estimator: Estimator::Hbao,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::HbaoInterleaved,
        name: "hbao-interleaved",
        summary: "HBAO over 16 quarter-resolution depth layers (samples snap to their layer)",
        paper: "seed 001 §3.2, authors' code §1.7 (docs/AUTHORS_CODE.md)",
        estimator: Estimator::Hbao,
        source: Source::FirstLayer,
        schedule: Schedule::Interleaved,
    },
    TechniqueRow {
        technique: Technique::HbaoDual,
        name: "hbao-dual",
        summary: "HBAO; a step above the tangent plane but beyond R also reads the second layer",
        paper: "seed 001 §3.2 (Algorithm 2), seed 000 §2.1",
        estimator: Estimator::Hbao,
        source: Source::DualDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdHbao,
        name: "sd-hbao",
        summary: "HBAO; a step above the tangent plane beyond R reads the stochastic depth map",
        paper: "seed 001 §3.2 (Algorithm 2), §3.3",
        estimator: Estimator::Hbao,
        source: Source::StochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::RaySdHbao,
        name: "ray-sd-hbao",
        summary: "HBAO; a step above the tangent plane beyond R reads the ray-traced map",
        paper: "seed 002 §3.1, seed 001 §3.2 (Algorithm 2)",
        estimator: Estimator::Hbao,
        source: Source::RayStochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::HbaoPlus,
        name: "hbao+",
        summary: "HBAO+: per-sample horizon AO, 8 directions × 4 steps (the authors' baseline)",
        paper: "seed 000 §2.1, seed 001 §3.2",
        estimator: Estimator::HbaoPlus,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::HbaoPlusInterleaved,
        name: "hbao+-interleaved",
        summary: "HBAO+ over 16 quarter-resolution depth layers, as the authors ran it",
        paper: "seed 000 §2.1, authors' code §1.7 (docs/AUTHORS_CODE.md)",
        estimator: Estimator::HbaoPlus,
        source: Source::FirstLayer,
        schedule: Schedule::Interleaved,
    },
    TechniqueRow {
        technique: Technique::HbaoPlusDual,
        name: "hbao+-dual",
        summary: "HBAO+; samples behind a too-near first surface also read the second layer",
        paper: "seed 000 §2.1",
        estimator: Estimator::HbaoPlus,
        source: Source::DualDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdHbaoPlus,
        name: "sd-hbao+",
        summary: "HBAO+; samples in front but beyond R also read the stochastic depth map",
        paper: "seed 001 §3.2, authors' code §1.7 (docs/AUTHORS_CODE.md)",
        estimator: Estimator::HbaoPlus,
        source: Source::StochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdHbaoPlusStenciled,
        name: "sd-hbao+-stenciled",
        summary: "SD-HBAO+ in two phases; the map is rasterised only where phase 1 asked",
        paper: "seed 001 §3.2, seed 000 §3.9",
        estimator: Estimator::HbaoPlus,
        source: Source::StochasticDepth,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::SdHbaoPlusMultiview,
        name: "sd-hbao+-multiview",
        summary: "SD-HBAO+ also from a second view beside the camera; the larger occlusion wins",
        paper: "seed 001 §3.4, Algorithm 3",
        estimator: Estimator::HbaoPlus,
        source: Source::StochasticDepth,
        schedule: Schedule::Multiview,
    },
    TechniqueRow {
        technique: Technique::Ssao,
        name: "ssao",
        summary: "SSAO: Alchemy AO, 32 spiral samples within R (seed 001's SSAO baseline)",
        paper: "seed 001 §3.2, McGuire et al. 2011",
        estimator: Estimator::Ssao,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdSsao,
        name: "sd-ssao",
        summary: "SSAO; a sample whose first surface does not occlude reads the stochastic map",
        paper: "seed 001 §3.2, §3.3",
        estimator: Estimator::Ssao,
        source: Source::StochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdSsaoStenciled,
        name: "sd-ssao-stenciled",
        summary: "SD-SSAO in two phases; the map is rasterised only where phase 1 asked",
        paper: "seed 001 §3.2, seed 000 §3.9",
        estimator: Estimator::Ssao,
        source: Source::StochasticDepth,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::Sao,
        name: "sao",
        summary: "SAO: 11 spiral taps, each reading the pyramid level its distance calls for",
        paper: "McGuire et al. 2012 (seed 004 §2.2.2)",
        estimator: Estimator::Sao,
        source: Source::DepthPyramid,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::PyramidHbao,
        name: "pyramid-hbao",
        summary: "Pyramid HBAO: 8 directions walked over 5 pyramid levels, largest contribution",
        paper: "seed 004 §3",
        estimator: Estimator::PyramidHbao,
        source: Source::DepthPyramid,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::Gtao,
        name: "gtao",
        summary: "GTAO: two horizons per slice, analytic cosine-weighted visibility, falloff",
        paper: "Jimenez et al. 2016 (seed 003's baseline)",
        estimator: Estimator::Gtao,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::GtaoVb,
        name: "gtao-vb",
        summary: "GTAO slices with a 32-sector visibility bitmask and constant thickness",
        paper: "seed 003",
        estimator: Estimator::GtaoVb,
        source: Source::FirstLayer,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::GtaoVbDual,
        name: "gtao-vb-dual",
        summary: "GTAO-VB; every sample also marks the sectors of the second depth layer",
        paper: "seed 003, seed 000 §2.1",
        estimator: Estimator::GtaoVb,
        source: Source::DualDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdGtaoVb,
        name: "sd-gtao-vb",
        summary: "GTAO-VB; every sample also marks the sectors of every stochastic depth sample",
        paper: "seed 003, seed 001 §3.1",
        estimator: Estimator::GtaoVb,
        source: Source::StochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdGtaoVbStenciled,
        name: "sd-gtao-vb-stenciled",
        summary: "SD-GTAO-VB in two phases; the map is rasterised only where phase 1 asked",
        paper: "seed 003, seed 001 §3.1, seed 000 §3.9",
        estimator: Estimator::GtaoVb,
        source: Source::StochasticDepth,
        schedule: Schedule::TwoPhase,
    },
    TechniqueRow {
        technique: Technique::RaySdGtaoVb,
        name: "ray-sd-gtao-vb",
        summary: "GTAO-VB; every sample also marks the sectors of every ray-traced map depth",
        paper: "seed 003, seed 002 §3.1",
        estimator: Estimator::GtaoVb,
        source: Source::RayStochasticDepth,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::Hemisphere,
        name: "hemisphere",
        summary: "Hemisphere AO: cosine-weighted rays marched in screen space with a thickness",
        paper: "the ground truth's model (src/reference), screen-space ray marching",
        estimator: Estimator::Hemisphere,
        source: Source::ScreenRays,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::HemisphereDual,
        name: "hemisphere-dual",
        summary: "Hemisphere AO marched over two depth layers: surfaces as thick as the gap behind",
        paper: "the ground truth's model; seed 000 §2.1's second layer in the march (ours)",
        estimator: Estimator::Hemisphere,
        source: Source::ScreenRaysDual,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::SdHemisphere,
        name: "sd-hemisphere",
        summary: "Hemisphere AO marched over the first layer and every stochastic depth",
        paper: "the ground truth's model; seed 001 §3.1's map in the march (ours)",
        estimator: Estimator::Hemisphere,
        source: Source::ScreenRaysStochastic,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::RaySdHemisphere,
        name: "ray-sd-hemisphere",
        summary: "Hemisphere AO marched over the first layer and every ray-traced map depth",
        paper: "the ground truth's model; seed 002 §3.1's map in the march (ours)",
        estimator: Estimator::Hemisphere,
        source: Source::ScreenRaysRayStochastic,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::Rtao,
        name: "rtao",
        summary: "Ray-traced AO: cosine-weighted rays within R traced through the BVH",
        paper: "the ground truth's model (src/reference), rays through the compute BVH",
        estimator: Estimator::Hemisphere,
        source: Source::BvhRays,
        schedule: Schedule::Single,
    },
    TechniqueRow {
        technique: Technique::RtaoTwoPhase,
        name: "rtao-two-phase",
        summary:
            "RTAO in two phases: rays the screen proves free or blocked are not traced (work list)",
        paper: "seed 000 §3.8's two phases carried to hemisphere rays (ours)",
        estimator: Estimator::Hemisphere,
        source: Source::BvhRays,
        schedule: Schedule::TwoPhase,
    },
];

/// What a technique needs from the caller beyond depth and normals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Needs {
    /// The scene's triangles (uploaded as a `GpuScene`).
    pub triangles: bool,
    /// A BVH over the triangles.
    pub bvh: bool,
    /// The second depth layer (depth peeling).
    pub second_layer: bool,
    /// The scene is rasterised into a stochastic depth map.
    pub stochastic_depth_map: bool,
}

/// What presets change: each field's value at low, medium, high and ultra (medium is always the
/// default).
pub type PresetTable = &'static [(&'static str, [f64; 4])];

/// What the rest of the library needs to know of a hidden-depth source: one literal per source
/// ([`Source::caps`]), every field required, so that a new source answers every question.
#[derive(Clone, Copy, Debug)]
pub struct SourceCaps {
    /// Its name in the README's table and help texts (`first layer`, `column rays`, …).
    pub name: &'static str,
    /// Its settings section (`stochastic_depth`), empty where it has none: the viewer shows
    /// that section's knobs for its rows.
    pub section: &'static str,
    /// What it needs from the caller beyond depth and normals.
    pub needs: Needs,
    /// A stochastic depth map, rasterised or ray-traced (read by
    /// `shaders/sources/stochastic_depth/samples.wgsl`; `render --debug-out` shows it).
    pub maps_hidden_depth: bool,
    /// Resolving one flagged sample costs much more than looking at the first layer: a map's S
    /// depths, or a ray through the BVH. Not the second depth layer (one more read), which a
    /// deferred resolve made slower (docs/lab).
    pub costly_resolve: bool,
    /// It reads this estimator's own model and serves it alone (column rays: VAO's columns).
    pub only_for: Option<Estimator>,
    /// It serves pyramid levels: the estimators that read levels, and only those.
    pub serves_levels: bool,
    /// What presets change in its section: a field's value at low, medium, high, ultra.
    pub presets: PresetTable,
}

impl Source {
    /// Everything the library asks of the source.
    pub const fn caps(self) -> &'static SourceCaps {
        const NONE: Needs = Needs {
            triangles: false,
            bvh: false,
            second_layer: false,
            stochastic_depth_map: false,
        };
        // The maps' own caps, shared with the screen marches over them.
        const STOCHASTIC_DEPTH: SourceCaps = SourceCaps {
            name: "stochastic depth",
            section: "stochastic_depth",
            needs: Needs {
                triangles: true,
                stochastic_depth_map: true,
                ..NONE
            },
            maps_hidden_depth: true,
            costly_resolve: true,
            only_for: None,
            serves_levels: false,
            // One sample at low: every adapter with the map's format rasterises it (WebGPU
            // guarantees 1× and 4× only). α stays 1.5/S throughout.
            presets: &[("stochastic_depth.samples", [1.0, 4.0, 4.0, 8.0])],
        };
        const RAY_STOCHASTIC_DEPTH: SourceCaps = SourceCaps {
            name: "ray stochastic depth",
            section: "ray_sd",
            needs: Needs {
                triangles: true,
                bvh: true,
                ..NONE
            },
            maps_hidden_depth: true,
            costly_resolve: true,
            only_for: None,
            serves_levels: false,
            presets: &[],
        };
        match self {
            Source::FirstLayer => &SourceCaps {
                name: "first layer",
                section: "",
                needs: NONE,
                maps_hidden_depth: false,
                costly_resolve: false,
                only_for: None,
                serves_levels: false,
                presets: &[],
            },
            Source::DualDepth => &SourceCaps {
                name: "dual depth",
                section: "",
                needs: Needs {
                    second_layer: true,
                    ..NONE
                },
                maps_hidden_depth: false,
                costly_resolve: false,
                only_for: None,
                serves_levels: false,
                presets: &[],
            },
            Source::ColumnRays => &SourceCaps {
                name: "column rays",
                section: "",
                needs: Needs {
                    triangles: true,
                    bvh: true,
                    ..NONE
                },
                maps_hidden_depth: false,
                costly_resolve: true,
                only_for: Some(Estimator::Vao),
                serves_levels: false,
                presets: &[],
            },
            Source::StochasticDepth => &STOCHASTIC_DEPTH,
            Source::RayStochasticDepth => &RAY_STOCHASTIC_DEPTH,
            Source::DepthPyramid => &SourceCaps {
                name: "depth pyramid",
                section: "pyramid",
                needs: NONE,
                maps_hidden_depth: false,
                costly_resolve: false,
                only_for: None,
                serves_levels: true,
                presets: &[],
            },
            Source::ScreenRays => &SourceCaps {
                name: "screen rays",
                section: "",
                needs: NONE,
                maps_hidden_depth: false,
                costly_resolve: false,
                only_for: Some(Estimator::Hemisphere),
                serves_levels: false,
                presets: &[],
            },
            Source::ScreenRaysDual => &SourceCaps {
                name: "screen rays dual",
                section: "",
                needs: Needs {
                    second_layer: true,
                    ..NONE
                },
                maps_hidden_depth: false,
                costly_resolve: false,
                only_for: Some(Estimator::Hemisphere),
                serves_levels: false,
                presets: &[],
            },
            Source::ScreenRaysStochastic => &SourceCaps {
                name: "screen rays stochastic depth",
                // The march decides every ray in its first look.
                costly_resolve: false,
                only_for: Some(Estimator::Hemisphere),
                ..STOCHASTIC_DEPTH
            },
            Source::ScreenRaysRayStochastic => &SourceCaps {
                name: "screen rays ray stochastic depth",
                costly_resolve: false,
                only_for: Some(Estimator::Hemisphere),
                ..RAY_STOCHASTIC_DEPTH
            },
            Source::BvhRays => &SourceCaps {
                name: "bvh rays",
                section: "",
                needs: Needs {
                    triangles: true,
                    bvh: true,
                    ..NONE
                },
                maps_hidden_depth: false,
                costly_resolve: true,
                only_for: Some(Estimator::Hemisphere),
                serves_levels: false,
                presets: &[],
            },
        }
    }

    /// Whether it gives the estimator geometry the depth buffer hides: a second layer, the
    /// scene's triangles (rays, stochastic depth maps). The first layer, screen-space rays and
    /// the depth pyramid only re-read the depth buffer.
    pub fn sees_hidden_geometry(self) -> bool {
        let needs = self.needs();
        needs.second_layer || needs.triangles || needs.stochastic_depth_map
    }

    /// Whether it is a stochastic depth map ([`SourceCaps::maps_hidden_depth`]).
    pub fn maps_hidden_depth(self) -> bool {
        self.caps().maps_hidden_depth
    }

    /// Whether it is a screen march that reads depths behind the first layer at every step (the
    /// second layer, a stochastic depth map): phase 1 of a two-phase schedule binds none of them.
    pub fn marches_layers(self) -> bool {
        matches!(
            self,
            Source::ScreenRaysDual | Source::ScreenRaysStochastic | Source::ScreenRaysRayStochastic
        )
    }

    /// The stochastic depth map it reads, if any: [`Source::StochasticDepth`] (rasterised) or
    /// [`Source::RayStochasticDepth`] (ray-traced), also for the screen marches over them.
    pub fn map(self) -> Option<Source> {
        match self {
            Source::StochasticDepth | Source::ScreenRaysStochastic => Some(Source::StochasticDepth),
            Source::RayStochasticDepth | Source::ScreenRaysRayStochastic => {
                Some(Source::RayStochasticDepth)
            }
            _ => None,
        }
    }

    /// Whether resolving a flagged sample is costly ([`SourceCaps::costly_resolve`]).
    pub fn costly_resolve(self) -> bool {
        self.caps().costly_resolve
    }

    /// What this source needs from the caller beyond depth and normals.
    pub fn needs(self) -> Needs {
        self.caps().needs
    }

    /// The estimators this source can answer for: column rays read the VAO columns; the depth
    /// pyramid serves, and alone serves, the estimators that read levels.
    pub fn supports(self, estimator: Estimator) -> bool {
        let caps = self.caps();
        caps.only_for.is_none_or(|only| only == estimator)
            && caps.serves_levels == estimator.reads_levels()
    }

    /// Its name in the README's table and help texts (`first layer`, `column rays`, …).
    pub fn name(self) -> &'static str {
        self.caps().name
    }

    /// Its settings section ([`SourceCaps::section`]).
    pub fn section(self) -> &'static str {
        self.caps().section
    }
}

impl Schedule {
    /// Whether this is a two-phase schedule (work list or dense).
    pub fn two_phase(self) -> bool {
        match self {
            Schedule::TwoPhase | Schedule::TwoPhaseDense => true,
            Schedule::Single | Schedule::Interleaved | Schedule::Multiview => false,
        }
    }

    /// Whether its AO pass is the single pass (the multi-view schedule runs it, then a second
    /// view): where the single pass's own choices apply (deferred resolves).
    pub fn runs_single_pass(self) -> bool {
        match self {
            Schedule::Single | Schedule::Multiview => true,
            Schedule::TwoPhase | Schedule::TwoPhaseDense | Schedule::Interleaved => false,
        }
    }

    /// Whether this schedule can run `estimator`: a two-phase schedule adds phase 2's samples
    /// after all others and holds one bit per sample (at most 32), so it needs an
    /// [`Estimator::order_independent`] estimator.
    /// The interleaved schedule reads the first depth layer only, not pyramid levels.
    pub fn supports(self, estimator: Estimator) -> bool {
        match self {
            Schedule::Single => true,
            Schedule::TwoPhase | Schedule::TwoPhaseDense => estimator.order_independent(),
            Schedule::Interleaved => !estimator.reads_levels(),
            // Algorithm 3 needs only a position and a normal per pixel, as HBAO+ does (seed 001
            // §3.4 extends HBAO+ for that reason).
            Schedule::Multiview => estimator == Estimator::HbaoPlus,
        }
    }

    /// Whether this schedule can run over `source`: the multi-view one only over the stochastic
    /// depth map (its second view reads a second one); the interleaved one only over the first
    /// layer (it splits that layer and reads nothing else); the two-phase ones over any source
    /// but those whose first look reads what phase 1 does not bind (its request layout holds
    /// only what `source_request` writes): the depth pyramid's levels, and the second layer the
    /// dual screen march reads at every step (a march decides its rays in the first look, so a
    /// second phase would have nothing to do anyway).
    pub fn supports_source(self, source: Source) -> bool {
        match self {
            Schedule::Interleaved => source == Source::FirstLayer,
            Schedule::Multiview => source == Source::StochasticDepth,
            Schedule::TwoPhase | Schedule::TwoPhaseDense => {
                !source.caps().serves_levels && !source.marches_layers()
            }
            Schedule::Single => true,
        }
    }

    /// Its name in the README's table (`single pass`, `two-phase (work list)`, …).
    pub fn name(self) -> &'static str {
        match self {
            Schedule::Single => "single pass",
            Schedule::TwoPhase => "two-phase (work list)",
            Schedule::TwoPhaseDense => "two-phase (dense)",
            Schedule::Interleaved => "interleaved (4×4 layers)",
            Schedule::Multiview => "single pass + second view",
        }
    }
}

/// What the rest of the library needs to know of an estimator: one literal per estimator
/// ([`Estimator::caps`]), every field required, so that a new estimator answers every question
/// where it is added, with no list elsewhere left to miss it.
#[derive(Clone, Copy, Debug)]
pub struct EstimatorCaps {
    /// Its name in the README's table (`vao`, `hbao+`, `gtao-vb`, …).
    pub name: &'static str,
    /// Its settings section (`gtao_vb`: the fields `gtao_vb.*` and their knobs).
    pub section: &'static str,
    /// The field of its world radius R (`gtao_vb.radius`).
    pub radius: &'static str,
    /// Its `render --debug-out` image over the single-pass and interleaved schedules
    /// (`estimator_debug` in its WGSL): the file name and what it shows.
    pub debug_image: Option<(&'static str, &'static str)>,
    /// Its samples read levels of the depth pyramid (`estimator_sample_level`).
    pub reads_levels: bool,
    /// Its result is independent of the order its samples arrive in, as a two-phase schedule
    /// needs (phase 2 adds the flagged samples after all others). HBAO and GTAO walk each
    /// direction outwards, carrying a running horizon: single pass only.
    pub order_independent: bool,
    /// The single pass resolves its flagged samples after all the others, making each again
    /// from its index (single.wgsl's `DEFERRED_RESOLVE`), over a source whose resolve is
    /// costly. It pays where a sample is cheap to make again: VAO (a kernel entry turned by the
    /// pixel's rotation) and SSAO (a spiral tap). HBAO+ and GTAO-VB were measured 11 % slower
    /// that way on an H200 (docs/lab). Only order-independent estimators can.
    pub defers_resolves: bool,
    /// A sample that reads the raster stochastic depth map makes a value of each distinct depth
    /// of the pixel once, nearest first, instead of one per stored sample
    /// (stochastic_depth/samples.wgsl's `SD_DISTINCT`; S = 4), stopping where `hidden` is
    /// exact. Measured on an H200 (docs/lab, 2026-12-04, four views): GTAO-VB's pass 13–17 %
    /// faster and HBAO's 2–8 %, whose values cost many instructions; VAO's cheap values 5–9 %
    /// slower even with the stop, HBAO+'s and SSAO's from 6 % faster to 1 % slower by view.
    pub resolves_distinct_depths: bool,
    /// Its occluders' `hidden` is exact: false only where no deeper surface at the sample's
    /// pixel can change the sample's value, so that a sample reading its pixel's depths nearest
    /// first may stop there (samples.wgsl's `SD_SETTLED_STOPS`). GTAO-VB's is (a front face
    /// below the tangent plane, or a back face at the hemisphere's edge with its sector marked:
    /// every deeper point of the pixel's ray lies lower still). VAO's is not: a depth's column
    /// height along one pixel's ray rises with depth where the tangent-plane correction for the
    /// pixel's offset outweighs the view axis, so a deeper depth can lower the value. HBAO's,
    /// HBAO+'s and SSAO's follow seed 001 §3.3's heuristic (a sample that is not occluded reads
    /// no hidden depth), which a deeper surface can contradict.
    pub exact_hidden: bool,
    /// With bent normals, the first-layer lookup (frame.wgsl's `FIRST_LAYER_LOAD_LATE`) loads a
    /// sample's depth only after testing whether the sample falls on the shading pixel. Measured
    /// on an H200 (docs/lab, 2026-12-04): with bent normals the early load made VAO's pass 7 %
    /// and GTAO's 10 % slower, while HBAO+'s and GTAO-VB's were 1 % faster with it; without bent
    /// normals it is faster for all.
    pub late_load_with_bent_normals: bool,
    /// It reports a bent normal with its AO (`bent_normals`, seed 001 §4): the slice estimators,
    /// whose visible directions are known per slice, VAO, whose free column parts locate the
    /// free volume, and HBAO+, whose per-sample occlusion reads as a horizon elevation.
    pub bent_normals: bool,
    /// What presets change: a field's value at low, medium, high, ultra (medium is always the
    /// default), fields of its own section or the blur's.
    pub presets: PresetTable,
    /// Its module: WGSL, constants, settings knobs, parameter packing (`src/estimators/`).
    pub module: &'static EstimatorModule,
}

impl Estimator {
    /// Everything the library asks of the estimator.
    pub const fn caps(self) -> &'static EstimatorCaps {
        match self {
            Estimator::Vao => &EstimatorCaps {
                name: "vao",
                section: "vao",
                radius: "vao.radius",
                debug_image: None,
                reads_levels: false,
                order_independent: true,
                defers_resolves: true,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: true,
                bent_normals: true,
                presets: &[
                    ("vao.samples", [8.0, 8.0, 16.0, 32.0]),
                    ("blur.radius", [2.0, 4.0, 4.0, 6.0]),
                ],
                module: &estimators::vao::MODULE,
            },
            // Seed 001 Tab. 1's 8 × 4 as the default, seed 004's smallest grid (8 × 10) as high.
            Estimator::Hbao => &EstimatorCaps {
                name: "hbao",
                section: "hbao",
                radius: "hbao.radius",
                debug_image: Some((
                    "horizon.png",
                    "the mean final horizon elevation over the directions, -90° black to +90° white",
                )),
                reads_levels: false,
                order_independent: false,
                defers_resolves: false,
                resolves_distinct_depths: true,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[
                    ("hbao.directions", [4.0, 8.0, 8.0, 16.0]),
                    ("hbao.steps", [4.0, 4.0, 10.0, 20.0]),
                ],
                module: &estimators::hbao::MODULE,
            },
            // 8 × 4 = 32 samples is already the most the two-phase mask holds.
            Estimator::HbaoPlus => &EstimatorCaps {
                name: "hbao+",
                section: "hbao_plus",
                radius: "hbao_plus.radius",
                debug_image: Some((
                    "occlusion.png",
                    "the mean per-sample occlusion before 1 - 2 mean and the exponent, 0 black to 1 white",
                )),
                reads_levels: false,
                order_independent: true,
                defers_resolves: false,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: true,
                presets: &[
                    ("hbao_plus.directions", [4.0, 8.0, 8.0, 8.0]),
                    ("blur.radius", [2.0, 4.0, 4.0, 6.0]),
                ],
                module: &estimators::hbao_plus::MODULE,
            },
            // The common XeGTAO-style grid, slices × steps 1×2, 2×2, 3×3, 9×3.
            Estimator::Gtao => &EstimatorCaps {
                name: "gtao",
                section: "gtao",
                radius: "gtao.radius",
                debug_image: Some((
                    "horizon.png",
                    "the mean angle between each slice's two horizons, 0° black to 180° (open) white",
                )),
                reads_levels: false,
                order_independent: false,
                defers_resolves: false,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: true,
                bent_normals: true,
                presets: &[
                    ("gtao.slices", [1.0, 2.0, 3.0, 9.0]),
                    ("gtao.steps", [2.0, 2.0, 3.0, 3.0]),
                ],
                module: &estimators::gtao::MODULE,
            },
            // Seed 001 Tab. 1's 32 as the default, the most the two-phase mask holds.
            Estimator::Ssao => &EstimatorCaps {
                name: "ssao",
                section: "ssao",
                radius: "ssao.radius",
                debug_image: Some((
                    "occluders.png",
                    "the fraction of the samples that occlude, none black to all white",
                )),
                reads_levels: false,
                order_independent: true,
                defers_resolves: true,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[("ssao.samples", [8.0, 32.0, 32.0, 32.0])],
                module: &estimators::ssao::MODULE,
            },
            // SAO's published code ships 11 taps; fewer and more around it.
            Estimator::Sao => &EstimatorCaps {
                name: "sao",
                section: "sao",
                radius: "sao.radius",
                debug_image: Some((
                    "levels.png",
                    "the mean pyramid level the taps read, level 0 black to the top level white",
                )),
                reads_levels: true,
                order_independent: true,
                defers_resolves: false,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[("sao.samples", [7.0, 11.0, 16.0, 32.0])],
                module: &estimators::sao::MODULE,
            },
            // Seed 004's 8 directions as the default; the steps per level are ours.
            Estimator::PyramidHbao => &EstimatorCaps {
                name: "pyramid-hbao",
                section: "pyramid_hbao",
                radius: "pyramid_hbao.radius",
                debug_image: Some((
                    "levels.png",
                    "the mean pyramid level of each direction's largest contribution, 0 black to the top white",
                )),
                reads_levels: true,
                order_independent: false,
                defers_resolves: false,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[
                    ("pyramid_hbao.directions", [4.0, 8.0, 8.0, 16.0]),
                    ("pyramid_hbao.steps", [3.0, 4.0, 6.0, 6.0]),
                ],
                module: &estimators::pyramid_hbao::MODULE,
            },
            // The common GTAO grid (slices × steps 1×2, 2×2, 3×3) as far as three slices and 32
            // samples allow: ultra is 3 × 5 instead of 9 × 3.
            Estimator::GtaoVb => &EstimatorCaps {
                name: "gtao-vb",
                section: "gtao_vb",
                radius: "gtao_vb.radius",
                debug_image: Some((
                    "sectors.png",
                    "the bitmask occupancy, occupied sectors of all slices, none black to all white",
                )),
                reads_levels: false,
                order_independent: true,
                defers_resolves: false,
                resolves_distinct_depths: true,
                exact_hidden: true,
                late_load_with_bent_normals: false,
                bent_normals: true,
                presets: &[
                    ("gtao_vb.slices", [1.0, 2.0, 3.0, 3.0]),
                    ("gtao_vb.steps", [2.0, 2.0, 3.0, 5.0]),
                ],
                module: &estimators::gtao_vb::MODULE,
            },
            // Rays per pixel per frame and screen-march points. One ray is the default (its cost
            // through the BVH is most of the frame, docs/lab/2026-12-06-hemisphere.md); low
            // marches fewer points.
            Estimator::Hemisphere => &EstimatorCaps {
                name: "hemisphere",
                section: "hemisphere",
                radius: "hemisphere.radius",
                debug_image: Some((
                    "blocked.png",
                    "the fraction of the rays blocked, none black to all white",
                )),
                reads_levels: false,
                order_independent: true,
                defers_resolves: true,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[
                    ("hemisphere.rays", [1.0, 1.0, 2.0, 4.0]),
                    ("hemisphere.steps", [4.0, 8.0, 12.0, 16.0]),
                ],
                module: &estimators::hemisphere::MODULE,
            },
            #[cfg(test)]
            Estimator::Stub => &EstimatorCaps {
                name: "stub",
                section: "stub",
                radius: "stub.radius",
                debug_image: None,
                reads_levels: false,
                order_independent: true,
                defers_resolves: false,
                resolves_distinct_depths: false,
                exact_hidden: false,
                late_load_with_bent_normals: false,
                bent_normals: false,
                presets: &[("stub.samples", [4.0, 8.0, 16.0, 32.0])],
                module: &estimators::stub::MODULE,
            },
        }
    }

    /// Its name in the README's table (`vao`, `hbao`, `hbao+`, `gtao`, `gtao-vb`, …).
    pub fn name(self) -> &'static str {
        self.caps().name
    }

    /// Its settings section ([`EstimatorCaps::section`]).
    pub fn section(self) -> &'static str {
        self.caps().section
    }

    /// Its `render --debug-out` image ([`EstimatorCaps::debug_image`]).
    pub fn debug_image(self) -> Option<(&'static str, &'static str)> {
        self.caps().debug_image
    }

    /// Whether its samples read pyramid levels ([`EstimatorCaps::reads_levels`]).
    pub fn reads_levels(self) -> bool {
        self.caps().reads_levels
    }

    /// Whether the single pass defers its costly resolves ([`EstimatorCaps::defers_resolves`]).
    pub fn defers_resolves(self) -> bool {
        self.caps().defers_resolves
    }

    /// Whether it reads each distinct depth of a map once
    /// ([`EstimatorCaps::resolves_distinct_depths`]).
    pub fn resolves_distinct_depths(self) -> bool {
        self.caps().resolves_distinct_depths
    }

    /// Whether its `hidden` is exact ([`EstimatorCaps::exact_hidden`]).
    pub fn exact_hidden(self) -> bool {
        self.caps().exact_hidden
    }

    /// Whether the first-layer lookup loads late
    /// ([`EstimatorCaps::late_load_with_bent_normals`]).
    pub fn late_first_layer_load(self, bent_normals: bool) -> bool {
        bent_normals && self.caps().late_load_with_bent_normals
    }

    /// Whether a two-phase schedule can run it ([`EstimatorCaps::order_independent`]).
    pub fn order_independent(self) -> bool {
        self.caps().order_independent
    }

    /// Whether it reports a bent normal ([`EstimatorCaps::bent_normals`]).
    pub fn bent_normals(self) -> bool {
        self.caps().bent_normals
    }
}

impl TechniqueRow {
    /// What the row's source needs from the caller ([`Source::needs`]).
    pub fn needs(&self) -> Needs {
        self.source.needs()
    }

    /// Whether phase 1 may prove rays blocked with the triangle each pixel shows
    /// (`rtao-two-phase`: shaders/sources/bvh_rays_proof.wgsl), so that [`crate::Renderer`]'s G-buffer
    /// keeps its visible triangles for it.
    pub fn proves_rays_blocked(&self) -> bool {
        self.source == Source::BvhRays && self.schedule.two_phase()
    }

    /// Whether `render --debug-out` has images for it: two-phase schedules show their flagged
    /// samples, the stochastic depth source its map, the other schedules the estimator's debug
    /// image ([`Estimator::debug_image`]).
    pub fn has_debug_output(&self) -> bool {
        self.schedule.two_phase()
            || self.source.maps_hidden_depth()
            || self.estimator_debug_image().is_some()
    }

    /// The estimator's debug image where this row can make it (single pass and interleaved: the
    /// two-phase rows show their flagged samples instead).
    pub fn estimator_debug_image(&self) -> Option<(&'static str, &'static str)> {
        (!self.schedule.two_phase())
            .then(|| self.estimator.debug_image())
            .flatten()
    }
}

impl Technique {
    /// Every technique, in table order.
    pub fn all() -> impl Iterator<Item = Technique> {
        TABLE.iter().map(|r| r.technique)
    }

    /// This technique's row.
    pub fn row(self) -> &'static TechniqueRow {
        TABLE
            .iter()
            .find(|r| r.technique == self)
            .expect("every Technique has a row in TABLE (tested)")
    }

    /// The row's name (`vao`, `sd-svao`, …): what the CLI, settings files and reports use.
    pub fn name(self) -> &'static str {
        self.row().name
    }

    /// The row's estimator.
    pub fn estimator(self) -> Estimator {
        self.row().estimator
    }

    /// The row's hidden-depth source.
    pub fn source(self) -> Source {
        self.row().source
    }

    /// The row's schedule.
    pub fn schedule(self) -> Schedule {
        self.row().schedule
    }

    /// What the row needs from the caller beyond depth and normals ([`Source::needs`]).
    pub fn needs(self) -> Needs {
        self.row().needs()
    }
}

/// Names of the rows that satisfy `keep`, comma-separated (help texts and messages).
pub fn names_where(keep: impl Fn(&TechniqueRow) -> bool) -> String {
    TABLE
        .iter()
        .filter(|r| keep(r))
        .map(|r| r.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The README's technique table (a test keeps README.md equal to it).
pub fn markdown_table() -> String {
    let mut out = String::from(
        "| technique | estimator | hidden-depth source | schedule | paper | what |\n|---|---|---|---|---|---|\n",
    );
    for r in TABLE {
        out += &format!(
            "| `{}` | {} | {} | {} | {} | {} |\n",
            r.name,
            r.estimator.name(),
            r.source.name(),
            r.schedule.name(),
            r.paper,
            r.summary
        );
    }
    out
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A technique name that is not in [`TABLE`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("unknown technique '{0}': available: {list}", list = names_where(|_| true))]
pub struct UnknownTechnique(pub String);

impl FromStr for Technique {
    type Err = UnknownTechnique;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        TABLE
            .iter()
            .find(|r| r.name == wanted)
            .map(|r| r.technique)
            .ok_or_else(|| UnknownTechnique(s.to_string()))
    }
}

impl serde::Serialize for Technique {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for Technique {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_technique_has_exactly_one_row_with_a_unique_name() {
        assert_eq!(TABLE.len(), VARIANTS.len());
        for t in VARIANTS {
            assert_eq!(
                TABLE.iter().filter(|r| r.technique == *t).count(),
                1,
                "{t:?}"
            );
        }
        for r in TABLE {
            assert_eq!(
                TABLE.iter().filter(|o| o.technique == r.technique).count(),
                1
            );
            assert_eq!(TABLE.iter().filter(|o| o.name == r.name).count(), 1);
            assert_eq!(r.name.parse::<Technique>().unwrap(), r.technique);
            assert!(
                r.source.supports(r.estimator),
                "{}: source {:?} cannot answer for estimator {:?}",
                r.name,
                r.source,
                r.estimator
            );
            assert!(
                r.schedule.supports_source(r.source),
                "{}: schedule {:?} cannot run over source {:?}",
                r.name,
                r.schedule,
                r.source
            );
            assert!(
                r.schedule.supports(r.estimator),
                "{}: schedule {:?} cannot run estimator {:?}",
                r.name,
                r.schedule,
                r.estimator
            );
        }
    }

    #[test]
    fn unknown_names_list_the_table() {
        let err = "hbao-plus".parse::<Technique>().unwrap_err().to_string();
        for r in TABLE {
            assert!(err.contains(r.name), "{err}");
        }
    }

    #[test]
    fn serde_uses_the_names() {
        let json = serde_json::to_string(&Technique::RtSvaoDense).unwrap();
        assert_eq!(json, "\"rt-svao-dense\"");
        let back: Technique = serde_json::from_str(&json).unwrap();
        assert_eq!(back, Technique::RtSvaoDense);
        assert!(serde_json::from_str::<Technique>("\"nope\"").is_err());
    }
}
