//! `obscura`: render, inspect and time screen-space ambient occlusion.

mod args;
mod commands;
mod progress;
mod setting_flags;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "obscura",
    version,
    about = "Ambient occlusion that keeps the geometry a depth buffer hides"
)]
struct Cli {
    /// Use the first adapter whose name contains this (see `obscura info`).
    #[arg(long, global = true)]
    adapter: Option<String>,
    /// Force a backend: vulkan, metal, dx12 or gl (also OBSCURA_BACKEND). On gl only `info` and
    /// the ground truth run: the AO passes refuse it with what to use instead.
    #[arg(long, global = true)]
    backend: Option<String>,
    /// Use the N-th GPU (from 0) in PCI bus order, as nvidia-smi numbers them (on a host with
    /// several GPUs of one kind; `dataset --devices` uses the first N).
    #[arg(long, global = true, value_name = "N")]
    gpu_index: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the GPU adapter, backend, driver and the limits obscura cares about.
    Info(commands::info::InfoArgs),
    /// List the built-in scenes and their cameras.
    Scenes(commands::scenes::ScenesArgs),
    /// Render one AO image.
    Render(commands::render::RenderArgs),
    /// Ray-trace the ground-truth AO of one view (on the GPU; --cpu for the CPU oracle).
    Reference(commands::reference::ReferenceCmdArgs),
    /// Compare techniques with the ground truth: report.json, report.md and index.html.
    Compare(commands::compare::CompareArgs),
    /// Render AO along a camera path: numbered frames, animations, per-frame JSON and, with
    /// --with-reference, temporal error and popping against the ground truth.
    Path(commands::path::PathArgs),
    /// Render every built-in scene's close-up with every technique into a folder with an index.html.
    Demo(commands::demo::DemoArgs),
    /// Time every pass with GPU timestamp queries (medians over frames).
    Bench(commands::bench::BenchArgs),
    /// Render a dataset from a spec (TOML, docs/DATASETS.md): views of many scenes with their
    /// G-buffer, AO rows and ground truth, in resumable shards.
    Dataset(commands::dataset::DatasetArgs),
    /// Compare two AO images: largest and mean absolute difference.
    Diff(commands::diff::DiffArgs),
    /// Interactive viewer: fly camera, every technique and setting, debug views, split screen,
    /// the reference on demand and per-pass GPU timings (F1 in the window lists the keys).
    View(Box<commands::view::ViewArgs>),
}

fn main() -> ExitCode {
    // First thing, before any thread: it may set XDG_RUNTIME_DIR (Gpu::new would otherwise).
    obscura::gpu::quiet_headless_vulkan();
    // eframe logs a failed start itself; `view` says it once, with what to do.
    env_logger::Builder::from_env(
        env_logger::Env::default().default_filter_or("warn,eframe::native::run=off"),
    )
    .init();
    // Ctrl-C, SIGTERM and SIGHUP (ctrlc's "termination" feature): remove any output still being
    // written, so nothing half-written is left behind.
    let _ = ctrlc::set_handler(|| {
        obscura::output::remove_partial_files();
        eprintln!("\ninterrupted");
        std::process::exit(130);
    });
    let cli = Cli::parse();
    let gpu_options = obscura::GpuOptions {
        adapter: cli.adapter,
        backend: cli.backend,
        ordinal: cli.gpu_index,
    };
    let result = match cli.command {
        Command::Info(a) => commands::info::run(&gpu_options, &a),
        Command::Scenes(a) => commands::scenes::run(&a),
        Command::Render(a) => commands::render::run(&gpu_options, &a),
        Command::Reference(a) => commands::reference::run(&gpu_options, &a),
        Command::Compare(a) => commands::compare::run(&gpu_options, &a),
        Command::Path(a) => commands::path::run(&gpu_options, &a),
        Command::Demo(a) => commands::demo::run(&gpu_options, &a),
        Command::Bench(a) => commands::bench::run(&gpu_options, &a),
        Command::Dataset(a) => commands::dataset::run(&gpu_options, &a),
        Command::Diff(a) => commands::diff::run(&a),
        Command::View(a) => commands::view::run(&gpu_options, &a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {:#}", args::for_user(e));
            ExitCode::FAILURE
        }
    }
}
