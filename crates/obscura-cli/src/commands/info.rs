use anyhow::Result;
use clap::Args;

#[derive(Args)]
pub struct InfoArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(options: &obscura::GpuOptions, args: &InfoArgs) -> Result<()> {
    let gpu = obscura::Gpu::new(options)?;
    let s = &gpu.summary;
    if args.json {
        println!("{}", serde_json::to_string_pretty(s)?);
        return Ok(());
    }
    println!("adapter      {} ({}, {})", s.name, s.device_type, s.backend);
    println!("driver       {} {}", s.driver, s.driver_info);
    println!("vendor:device {:#06x}:{:#06x}", s.vendor, s.device);
    println!(
        "timestamps   {}",
        if s.timestamp_queries {
            "yes"
        } else {
            "no (obscura bench unavailable)"
        }
    );
    println!(
        "max texture  {} px, {} array layers",
        s.max_texture_dimension_2d, s.max_texture_array_layers
    );
    println!(
        "max storage  {} bytes per binding",
        s.max_storage_buffer_binding_size
    );
    println!(
        "compute      workgroup {:?}, {} invocations",
        s.max_compute_workgroup_size, s.max_compute_invocations_per_workgroup
    );
    println!("depth MSAA   {:?} samples", s.depth_msaa_sample_counts);
    if s.sd_sample_counts.is_empty() {
        println!("SD map       unavailable on this device: sd-vao and sd-svao cannot run");
    } else {
        println!(
            "SD map       {}, {:?} samples per target",
            s.sd_format, s.sd_map_sample_counts
        );
        println!("--sd-samples {}", s.sd_layouts);
    }
    Ok(())
}
