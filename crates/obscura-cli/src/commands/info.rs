use anyhow::Result;
use clap::Args;

#[derive(Args)]
pub struct InfoArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Print the technique names, comma-separated, and nothing else (no GPU needed).
    #[arg(long, conflicts_with = "json")]
    techniques: bool,
}

pub fn run(options: &obscura::GpuOptions, args: &InfoArgs) -> Result<()> {
    if args.techniques {
        println!(
            "{}",
            obscura::technique::names_where(|_| true).replace(", ", ",")
        );
        return Ok(());
    }
    let gpu = obscura::Gpu::new(options)?;
    let s = &gpu.summary;
    let sd = obscura::sources::stochastic_depth::SdCapabilities::of(&gpu.adapter, &gpu.device);
    if args.json {
        let mut json = serde_json::to_value(s)?;
        if let Some(object) = json.as_object_mut() {
            object.insert("sd_format".into(), sd.format.clone().into());
            object.insert(
                "sd_map_sample_counts".into(),
                serde_json::to_value(&sd.map_sample_counts)?,
            );
            object.insert(
                "sd_sample_counts".into(),
                serde_json::to_value(&sd.sample_counts)?,
            );
            object.insert("sd_layouts".into(), sd.layouts.clone().into());
            object.insert(
                "techniques".into(),
                serde_json::to_value(
                    obscura::technique::TABLE
                        .iter()
                        .map(|r| {
                            serde_json::json!({
                                "name": r.name,
                                "estimator": r.estimator.name(),
                                "source": r.source.name(),
                                "schedule": r.schedule.name(),
                                "paper": r.paper,
                                "needs": r.needs(),
                            })
                        })
                        .collect::<Vec<_>>(),
                )?,
            );
        }
        println!("{}", serde_json::to_string_pretty(&json)?);
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
    if sd.sample_counts.is_empty() {
        println!(
            "SD map       unavailable on this device: {} cannot run",
            obscura::technique::names_where(|r| r.needs().stochastic_depth_map)
        );
    } else {
        println!(
            "SD map       {}, {:?} samples per target",
            sd.format, sd.map_sample_counts
        );
        println!("--sd-samples {}", sd.layouts);
    }
    Ok(())
}
