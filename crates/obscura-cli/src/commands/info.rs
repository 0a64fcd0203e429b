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
    let sd = obscura::sources::stochastic_depth::SdCapabilities::of(&gpu.device);
    let words = obscura::raster::gbuffer::visibility_words_available(&gpu.device);
    if args.json {
        let mut json = serde_json::to_value(s)?;
        if let Some(object) = json.as_object_mut() {
            object.insert("visibility_words".into(), words.into());
            object.insert("sd_format".into(), sd.format.clone().into());
            object.insert("sd_early_tests".into(), sd.early_tests.into());
            object.insert("sd_compute_rasterizer".into(), sd.compute_rasterizer.into());
            object.insert(
                "sd_sample_counts".into(),
                serde_json::to_value(&sd.sample_counts)?,
            );
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
    let yes_no = |b: bool, no: &'static str| if b { "yes" } else { no };
    println!(
        "visibility   {}",
        if words {
            "64-bit atomic words (no colour target)"
        } else {
            "R32Uint colour target (SHADER_INT64_ATOMIC_MIN_MAX or early tests missing: the same G-buffer, slower)"
        }
    );
    println!(
        "SD map       {}, --sd-samples {:?}",
        sd.format, sd.sample_counts
    );
    println!(
        "SD early tests {}",
        yes_no(
            sd.early_tests,
            "no (SHADER_EARLY_DEPTH_TEST missing: the same map, slower)"
        )
    );
    println!(
        "SD compute rasterizer {}",
        yes_no(
            sd.compute_rasterizer,
            "no (too few storage buffers per shader stage: --sd-rasterizer hardware only)"
        )
    );
    Ok(())
}
