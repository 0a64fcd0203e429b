use anyhow::Result;
use clap::Args;
use obscura::scene;

#[derive(Args)]
pub struct ScenesArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(serde::Serialize)]
struct SceneInfo {
    name: String,
    triangles: usize,
    cameras: Vec<String>,
    /// Camera paths (`--path NAME`).
    paths: Vec<String>,
}

pub fn run(args: &ScenesArgs) -> Result<()> {
    let mut list = Vec::new();
    for name in scene::builtin_names() {
        let s = scene::builtin(name)?;
        list.push(SceneInfo {
            name: name.to_string(),
            triangles: s.triangle_count(),
            cameras: s.cameras.iter().map(|c| c.name.clone()).collect(),
            paths: s.path_names(),
        });
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&list)?);
    } else {
        for s in &list {
            println!(
                "{:<10} {:>7} triangles   cameras: {}   paths: {}",
                s.name,
                s.triangles,
                s.cameras.join(", "),
                s.paths.join(", ")
            );
        }
        println!("\nFiles: --scene path/to/scene.glb|.gltf|.obj (cameras: the file's, else an automatic framing; path: orbit).");
    }
    Ok(())
}
