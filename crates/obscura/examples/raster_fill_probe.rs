//! A device probe of the raster units' fill cost (issue 16; BENCHMARKS.md, "What a written
//! fragment costs"): full-screen layers drawn into a depth buffer of each depth format, timed per
//! render pass with timestamp queries. Each frame times, per format:
//! - `clear`: the depth clear alone;
//! - `4 written`: the clear and four full-screen layers, each nearer than the last (reversed Z,
//!   `Greater`), so every fragment writes;
//! - `1 written 3 rejected`: the same layers nearest first, so three fail the depth test;
//! - `4 written + R32Uint`: the first case with an `R32Uint` colour target written too (what the
//!   G-buffer's visibility pass writes);
//! - `read z`: a compute pass sampling the depth buffer afterwards;
//! - `R32Uint clear`: a colour clear alone;
//! - `4 written + u64 atomic`: the first case with no colour target, its fragments instead
//!   testing early (`@early_depth_test(force)`) and storing `(depth << 32) | id` by a 64-bit
//!   `atomicMax` in a storage buffer (a visibility buffer without colour writes; where the device
//!   has wgpu's `SHADER_INT64_ATOMIC_MIN_MAX`, else NaN);
//! - `u64 clear`: emptying that buffer in a compute pass (16 bytes an invocation).
//!
//! It prints the median of each, in ms. Not a benchmark of obscura's passes (`obscura bench` is):
//! it isolates what the hardware charges per pixel, which those passes are built around.
//!
//! ```sh
//! cargo run --release -p obscura --example raster_fill_probe [-- WIDTHxHEIGHT]
//! ```

use obscura::{Gpu, GpuError, GpuOptions, PassProfiler};

/// The timed passes, in the order of a row's medians.
pub const PASSES: [&str; 8] = [
    "clear",
    "4 written",
    "1 written 3 rejected",
    "4 written + R32Uint",
    "read z",
    "R32Uint clear",
    "4 written + u64 atomic",
    "u64 clear",
];

/// The 64-bit atomic case's fragment shader (compiled only where the device has the features).
const ATOMIC_SHADER: &str = r#"
override WIDTH: u32 = 1u;
@group(0) @binding(0) var<storage, read_write> vis: array<atomic<u64>>;
@vertex
fn vs(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.2 + 0.1 * f32(i), 1.0);
}
@fragment @early_depth_test(force)
fn fs_atomic(@builtin(position) p: vec4<f32>) {
    let i = u32(p.y) * WIDTH + u32(p.x);
    atomicMax(&vis[i], (u64(bitcast<u32>(p.z)) << 32u) | 7lu);
}
"#;

const SHADER: &str = r#"
struct Out { @builtin(position) clip: vec4<f32> }
// Instances 0..3: full-screen layers moving nearer (reversed Z: each passes `Greater`);
// 4..7: the same layers nearest first (only the first passes).
@vertex
fn vs(@builtin(vertex_index) v: u32, @builtin(instance_index) i: u32) -> Out {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    let k = select(f32(i), 7.0 - f32(i), i >= 4u);
    var o: Out;
    o.clip = vec4<f32>(uv * 2.0 - 1.0, 0.2 + 0.1 * k, 1.0);
    return o;
}
@fragment
fn fs_id() -> @location(0) u32 { return 7u; }
@group(0) @binding(0) var z: texture_depth_2d;
@group(0) @binding(1) var<storage, read_write> hits: array<atomic<u32>>;
// Reads every texel; the comparison keeps the load from being optimised away.
@compute @workgroup_size(8, 8)
fn read_z(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(z);
    if (any(id.xy >= size)) { return; }
    if (textureLoad(z, id.xy, 0) == 0.123) { atomicAdd(&hits[0], 1u); }
}
@group(0) @binding(0) var<storage, read_write> words: array<vec4<u32>>;
@compute @workgroup_size(64)
fn zero(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x < arrayLength(&words)) { words[id.x] = vec4<u32>(0u); }
}
"#;

/// One depth format's medians over the timed frames, ms, in the order of [`PASSES`].
pub struct Row {
    pub format: &'static str,
    pub medians: [f64; 8],
}

fn main() {
    let size = std::env::args().nth(1).unwrap_or("1920x1080".into());
    let parsed = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
        .filter(|&(w, h)| w > 0 && h > 0);
    let Some((width, height)) = parsed else {
        eprintln!("error: size '{size}' is not WIDTHxHEIGHT (e.g. 1920x1080)");
        std::process::exit(2);
    };
    let result = Gpu::new(&GpuOptions::default()).and_then(|gpu| {
        println!(
            "adapter: {} ({}, {}); {width}x{height}; medians of 120 frames after 20, ms",
            gpu.summary.name, gpu.summary.driver, gpu.summary.driver_info
        );
        run(&gpu, width, height, 120, 20)
    });
    match result {
        Ok(rows) => {
            println!("{:8} {}", "format", PASSES.join(" | "));
            for row in rows {
                let medians: Vec<String> = row.medians.iter().map(|m| format!("{m:.4}")).collect();
                println!("{:8} {}", row.format, medians.join(" "));
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

/// Times [`PASSES`] at `width`×`height` for every depth format the device has, `frames` frames
/// after `warmup`.
pub fn run(
    gpu: &Gpu,
    width: u32,
    height: u32,
    frames: u32,
    warmup: u32,
) -> Result<Vec<Row>, GpuError> {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("probe"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let sum = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 16,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let read_z = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("read z"),
        layout: None,
        module: &module,
        entry_point: Some("read_z"),
        compilation_options: Default::default(),
        cache: None,
    });
    let texture = |format, usage| {
        obscura::gpu::texture_2d(device, "probe target", width, height, format, usage)
    };
    let ids = texture(
        wgpu::TextureFormat::R32Uint,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let ids_view = ids.create_view(&Default::default());
    let atomics = device
        .features()
        .contains(wgpu::Features::SHADER_INT64 | wgpu::Features::SHADER_INT64_ATOMIC_MIN_MAX)
        && device
            .features()
            .contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST);
    let vis = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("probe u64 visibility"),
        size: 8 * u64::from(width) * u64::from(height),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let atomic_module = atomics.then(|| {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("probe atomics"),
            source: wgpu::ShaderSource::Wgsl(ATOMIC_SHADER.into()),
        })
    });
    let formats = [
        ("d32f", wgpu::TextureFormat::Depth32Float),
        ("d24", wgpu::TextureFormat::Depth24Plus),
        ("d16", wgpu::TextureFormat::Depth16Unorm),
        ("d24s8", wgpu::TextureFormat::Depth24PlusStencil8),
    ];
    let zero = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("zero"),
        layout: None,
        module: &module,
        entry_point: Some("zero"),
        compilation_options: Default::default(),
        cache: None,
    });
    let zero_bind = obscura::gpu::bind_group(
        device,
        "zero",
        &zero.get_bind_group_layout(0),
        &[vis.as_entire_binding()],
    );
    let words = (u64::from(width) * u64::from(height) / 2) as u32;
    let mut rows = Vec::new();
    for (name, format) in formats {
        if !device.features().contains(format.required_features()) {
            continue;
        }
        let z = texture(
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let z_attach = z.create_view(&Default::default());
        let z_sampled = z.create_view(&wgpu::TextureViewDescriptor {
            aspect: wgpu::TextureAspect::DepthOnly,
            ..Default::default()
        });
        // A full-screen-layer pipeline writing depth (`Greater`), with `fragment` (entry point,
        // colour targets, pipeline constants) where it has one.
        let constants = [("WIDTH", f64::from(width))];
        type Fragment<'a> = (
            &'a str,
            &'a [Option<wgpu::ColorTargetState>],
            &'a [(&'a str, f64)],
        );
        let pipeline = |module: &wgpu::ShaderModule, fragment: Option<Fragment>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: None,
                layout: None,
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: fragment.map(|(entry_point, targets, constants)| wgpu::FragmentState {
                    module,
                    entry_point: Some(entry_point),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants,
                        ..Default::default()
                    },
                    targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let id_targets = [Some(wgpu::TextureFormat::R32Uint.into())];
        let (depth_only, with_colour) = (
            pipeline(&module, None),
            pipeline(&module, Some(("fs_id", &id_targets, &[]))),
        );
        let atomic = atomic_module.as_ref().map(|module| {
            let pipeline = pipeline(module, Some(("fs_atomic", &[], &constants)));
            let bind = obscura::gpu::bind_group(
                device,
                "probe atomics",
                &pipeline.get_bind_group_layout(0),
                &[vis.as_entire_binding()],
            );
            (pipeline, bind)
        });
        let bind = obscura::gpu::bind_group(
            device,
            "read z",
            &read_z.get_bind_group_layout(0),
            &[
                wgpu::BindingResource::TextureView(&z_sampled),
                sum.as_entire_binding(),
            ],
        );
        let mut profiler = PassProfiler::new(gpu, frames + warmup)?;
        for _ in 0..frames + warmup {
            let mut encoder = device.create_command_encoder(&Default::default());
            let depth = Some(wgpu::RenderPassDepthStencilAttachment {
                view: &z_attach,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: format.has_stencil_aspect().then_some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0),
                    store: wgpu::StoreOp::Store,
                }),
            });
            let colour = [Some(wgpu::RenderPassColorAttachment {
                view: &ids_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })];
            // (pass, pipeline, instances, colour target)
            let draws: [(
                &str,
                Option<&wgpu::RenderPipeline>,
                std::ops::Range<u32>,
                bool,
            ); 4] = [
                (PASSES[0], None, 0..0, false),
                (PASSES[1], Some(&depth_only), 0..4, false),
                (PASSES[2], Some(&depth_only), 4..8, false),
                (PASSES[3], Some(&with_colour), 0..4, true),
            ];
            for (pass_name, pipeline, instances, with_ids) in draws {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: None,
                    color_attachments: if with_ids { &colour } else { &[] },
                    depth_stencil_attachment: depth.clone(),
                    timestamp_writes: Some(profiler.render_pass(pass_name)),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                if let Some(p) = pipeline {
                    pass.set_pipeline(p);
                    pass.draw(0..3, instances);
                }
            }
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: None,
                    timestamp_writes: Some(profiler.compute_pass(PASSES[4])),
                });
                pass.set_pipeline(&read_z);
                pass.set_bind_group(0, &bind, &[]);
                pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
            }
            {
                let clear = [Some(wgpu::RenderPassColorAttachment {
                    view: &ids_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })];
                let _pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: None,
                    color_attachments: &clear,
                    depth_stencil_attachment: None,
                    timestamp_writes: Some(profiler.render_pass(PASSES[5])),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
            }
            if let Some((pipeline, bind)) = &atomic {
                {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: None,
                        timestamp_writes: Some(profiler.compute_pass(PASSES[7])),
                    });
                    pass.set_pipeline(&zero);
                    pass.set_bind_group(0, &zero_bind, &[]);
                    pass.dispatch_workgroups(words.div_ceil(64), 1, 1);
                }
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: None,
                    color_attachments: &[],
                    depth_stencil_attachment: depth.clone(),
                    timestamp_writes: Some(profiler.render_pass(PASSES[6])),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, bind, &[]);
                pass.draw(0..3, 0..4);
            }
            profiler.end_frame(&mut encoder);
            gpu.queue.submit([encoder.finish()]);
        }
        let timings = profiler.read(gpu)?;
        let mut medians = [0.0; 8];
        for (median, pass) in medians.iter_mut().zip(PASSES) {
            let mut v: Vec<f64> = timings[warmup as usize..]
                .iter()
                .filter_map(|f| f.get(pass).copied())
                .collect();
            v.sort_by(f64::total_cmp);
            *median = v.get(v.len() / 2).copied().unwrap_or(f64::NAN);
        }
        rows.push(Row {
            format: name,
            medians,
        });
    }
    gpu.check_errors()?;
    Ok(rows)
}
