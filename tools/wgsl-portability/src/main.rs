//! Does every shader obscura compiles also compile for Metal and DirectX 12? CI runs on lavapipe
//! (Vulkan), so wgpu only ever translates our WGSL to SPIR-V there. This tool takes the modules a
//! run wrote with `OBSCURA_DUMP_WGSL=DIR` (every module obscura made, as it made it:
//! `gpu::checked_module`, `gpu::shader_module`) and puts each entry point through what wgpu's
//! Metal and DirectX 12 backends do with it: naga validation with the capabilities that
//! backend's writer supports, the `override` constants at their defaults, then the MSL or HLSL
//! writer. Any failure is printed and the exit status is 1.
//!
//! `@early_depth_test(force)` is removed first: wgpu offers SHADER_EARLY_DEPTH_TEST on Vulkan and
//! GL only, and obscura strips the attribute from the stochastic depth map where the device lacks
//! the feature (`sources/stochastic_depth`) and builds the one other module that has it (the
//! G-buffer's 64-bit visibility words) only where the device has it.
//!
//! Usage: `cargo run --release --manifest-path tools/wgsl-portability/Cargo.toml -- DIR`.

use naga::back::{hlsl, msl, pipeline_constants::process_overrides};
use naga::valid::{Capabilities, ValidationFlags, Validator};
use std::process::ExitCode;

/// The Metal Shading Language version written: 2.4, the version wgpu's Metal backend uses on
/// macOS 12 and iOS 15 (newer systems get newer versions).
const MSL_VERSION: (u8, u8) = (2, 4);
/// The HLSL shader models written: 5.1 (FXC, which wgpu's DirectX 12 backend falls back to
/// without DXC) and 6.0 (the lowest DXC model it detects).
const SHADER_MODELS: [hlsl::ShaderModel; 2] = [hlsl::ShaderModel::V5_1, hlsl::ShaderModel::V6_0];

fn main() -> ExitCode {
    let Some(dir) = std::env::args().nth(1) else {
        eprintln!("usage: wgsl-portability DIR (the directory of an OBSCURA_DUMP_WGSL run)");
        return ExitCode::from(2);
    };
    let mut paths: Vec<_> = match std::fs::read_dir(&dir) {
        Ok(entries) => entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
            .collect(),
        Err(e) => {
            eprintln!("cannot read {dir}: {e}");
            return ExitCode::from(2);
        }
    };
    paths.sort();
    if paths.is_empty() {
        eprintln!("{dir} holds no .wgsl files: run obscura with OBSCURA_DUMP_WGSL={dir} first");
        return ExitCode::from(2);
    }
    let (mut translated, mut failures) = (0usize, Vec::new());
    for path in &paths {
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let source = match std::fs::read_to_string(path) {
            Ok(s) => s.replace("@early_depth_test(force)", ""),
            Err(e) => {
                failures.push(format!("{name}: unreadable: {e}"));
                continue;
            }
        };
        match translate(&source) {
            Ok(n) => translated += n,
            Err(errors) => failures.extend(errors.into_iter().map(|e| format!("{name}: {e}"))),
        }
    }
    for f in &failures {
        println!("{f}");
    }
    println!(
        "{} modules: {translated} entry-point translations to MSL {}.{} and HLSL {:?}, {} failures",
        paths.len(),
        MSL_VERSION.0,
        MSL_VERSION.1,
        SHADER_MODELS,
        failures.len()
    );
    if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// Every entry point of WGSL `source` through both writers: how many translations succeeded,
/// or every error.
fn translate(source: &str) -> Result<usize, Vec<String>> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| vec![format!("parse: {}", e.emit_to_string(source))])?;
    let mut done = 0;
    let mut errors = Vec::new();
    let backends: [(&str, Capabilities); 2] = [
        ("MSL", msl::supported_capabilities()),
        ("HLSL", hlsl::supported_capabilities()),
    ];
    for (backend, capabilities) in backends {
        let info = match Validator::new(ValidationFlags::all(), capabilities).validate(&module) {
            Ok(info) => info,
            Err(e) => {
                errors.push(format!("{backend}: {}", e.emit_to_string(source)));
                continue;
            }
        };
        for entry in &module.entry_points {
            let point = (entry.stage, entry.name.as_str());
            let written = process_overrides(&module, &info, Some(point), &Default::default())
                .map_err(|e| format!("overrides: {e}"))
                .and_then(|(module, info)| write(backend, &module, &info, point));
            match written {
                Ok(n) => done += n,
                Err(e) => errors.push(format!("{backend}, {}: {e}", entry.name)),
            }
        }
    }
    if errors.is_empty() {
        Ok(done)
    } else {
        Err(errors)
    }
}

fn write(
    backend: &str,
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    (stage, name): (naga::ShaderStage, &str),
) -> Result<usize, String> {
    let entry_point = Some((stage, name.to_owned()));
    if backend == "MSL" {
        let options = msl::Options {
            lang_version: MSL_VERSION,
            ..Default::default()
        };
        let pipeline = msl::PipelineOptions {
            entry_point,
            ..Default::default()
        };
        msl::write_string(module, info, &options, &pipeline)
            .map(|_| 1)
            .map_err(|e| e.to_string())
    } else {
        for shader_model in SHADER_MODELS {
            let options = hlsl::Options {
                shader_model,
                fake_missing_bindings: true,
                ..Default::default()
            };
            let pipeline = hlsl::PipelineOptions {
                entry_point: entry_point.clone(),
            };
            let mut out = String::new();
            hlsl::Writer::new(&mut out, &options, &pipeline)
                .write(module, info, None)
                .map_err(|e| format!("shader model {shader_model:?}: {e}"))?;
        }
        Ok(SHADER_MODELS.len())
    }
}
