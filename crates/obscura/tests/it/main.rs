//! The integration tests of `obscura`, one binary: each former `tests/NAME.rs` is the module
//! `NAME` (`tests/it/NAME.rs`), the shared helpers `common` (`tests/common/mod.rs`). Only
//! `tests/soak.rs` stays its own binary (it samples the process's resident memory).

#[path = "../common/mod.rs"]
mod common;

mod bent_normals;
mod blur;
mod cpu_oracle;
mod dataset;
mod deep_bvh;
mod double_sided;
mod engine_geometry;
mod engine_input;
mod examples;
mod far_from_origin;
mod fuzz_loaders;
mod gbuffer;
mod gpu_bvh;
mod gpu_reference;
mod gtao_vb;
mod half_resolution;
mod hbao_plus;
mod hemisphere;
mod hemisphere_maps;
mod horizon;
mod interleaved;
mod misuse;
mod module_graph;
mod multiview;
mod nearest_layers;
mod pipeline;
mod profiler;
mod pyramid;
mod radius_cap;
mod ray_budget;
mod ray_stochastic_depth;
mod readme;
mod reference;
mod rows_against_truth;
mod rt_vao;
mod scale_invariance;
mod send_and_sync;
mod settings_data;
mod shading_normals;
mod source_twins;
mod ssao;
mod stochastic_depth;
mod temporal;
mod two_phase_twins;
mod validation_sweep;
mod vao_analytic;
mod vao_dual;
mod webgpu_limits;
