//! No import circles between the library's top-level modules (docs/ARCHITECTURE.md): every
//! `crate::MODULE` path outside comments and test code is an edge from the file's top-level
//! module; the graph must be acyclic. Also the layering the architecture names: no module imports
//! one of a layer above its own (`gpu/` knows nothing of the techniques, filters do not reach into
//! schedules, sources or estimators), nothing imports the crate root (`lib.rs` only declares
//! modules and re-exports), and every shader's folder under `shaders/` names a `src/` module.
//!
//! Test code (`#[cfg(test)]` modules, `tests.rs` and `*_tests.rs` files) is left out of the
//! graph: the in-crate tests of the raster passes, the sources and the schedules drive a whole
//! `pipeline::Renderer`, which is above them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The library's top-level modules, from the bottom layer up (docs/ARCHITECTURE.md).
const LAYERS: [&[&str]; 11] = [
    &["scene", "hash", "gpu", "bindings", "shaders", "knob"],
    // The kernels and their settings: they know neither the table nor the whole settings.
    &["estimators"],
    // The table names the estimators (their caps literals point at their modules).
    &["technique"],
    &["error", "output", "view"],
    &["settings", "frame", "raster", "bvh"],
    &["sources"],
    &["schedules", "filter"],
    &["pipeline"],
    &["engine_input", "engine_geometry"],
    &["reference", "metrics", "report"],
    // Datasets render rows and the ground truth and write them: above everything.
    &["dataset"],
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The modules `lib.rs` declares.
fn modules() -> BTreeSet<String> {
    std::fs::read_dir(src())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "lib.rs")
        .map(|n| n.trim_end_matches(".rs").to_string())
        .collect()
}

/// Every file under `root` whose extension is `extension`, sorted.
fn files_under(root: &Path, extension: &str) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == extension) {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// Every `.rs` file under `src/` but `lib.rs`, with its top-level module.
fn files() -> Vec<(PathBuf, String)> {
    let src = src();
    files_under(&src, "rs")
        .into_iter()
        .filter_map(|path| {
            let relative = path.strip_prefix(&src).unwrap();
            let top = relative.components().next().unwrap().as_os_str();
            let top = top.to_string_lossy().trim_end_matches(".rs").to_string();
            (top != "lib").then_some((path, top))
        })
        .collect()
}

/// The lines of `path` outside comments; with `tests` false, also outside test code.
fn code_lines(path: &Path, tests: bool) -> Vec<String> {
    let name = path.file_name().unwrap().to_string_lossy();
    if !tests && (name == "tests.rs" || name.ends_with("_tests.rs")) {
        return Vec::new();
    }
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut code = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let test_module = lines[i].trim() == "#[cfg(test)]"
            && lines.get(i + 1).is_some_and(|l| {
                let l = l.trim_start();
                (l.starts_with("mod ") || l.starts_with("pub(crate) mod ")) && l.ends_with('{')
            });
        if test_module && !tests {
            // Skip to the module's closing brace.
            let mut depth = 0i32;
            i += 1;
            while i < lines.len() {
                depth +=
                    lines[i].matches('{').count() as i32 - lines[i].matches('}').count() as i32;
                if depth == 0 {
                    break;
                }
                i += 1;
            }
        } else if !lines[i].trim_start().starts_with("//") {
            code.push(lines[i].to_string());
        }
        i += 1;
    }
    code
}

/// The first segment of every `crate::` path in `code` (each member of a `crate::{..}` group).
fn crate_paths(code: &[String]) -> Vec<String> {
    let text = code.join("\n");
    let ident = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut names = Vec::new();
    for (i, _) in text.match_indices("crate::") {
        let rest = &text[i + 7..];
        if let Some(group) = rest.strip_prefix('{') {
            let (mut depth, mut member) = (0, String::new());
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        names.push(ident(&member));
                        member.clear();
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 && c != '}' {
                    member.push(c);
                }
            }
            names.push(ident(&member));
        } else {
            names.push(ident(rest));
        }
    }
    names.retain(|n| !n.is_empty());
    names
}

fn edges() -> BTreeMap<String, BTreeSet<String>> {
    let modules = modules();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (path, top) in files() {
        for name in crate_paths(&code_lines(&path, false)) {
            if modules.contains(&name) && name != top {
                edges.entry(top.clone()).or_default().insert(name);
            }
        }
    }
    edges
}

#[test]
fn modules_import_no_circle() {
    let edges = edges();
    // Depth-first search for a back edge.
    fn visit(
        node: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) {
        if done.contains(node) {
            return;
        }
        if let Some(i) = path.iter().position(|n| n == node) {
            panic!("import circle: {} -> {node}", path[i..].join(" -> "));
        }
        path.push(node.to_string());
        for next in edges.get(node).into_iter().flatten() {
            visit(next, edges, path, done);
        }
        path.pop();
        done.insert(node.to_string());
    }
    let mut done = BTreeSet::new();
    for node in edges.keys() {
        visit(node, &edges, &mut Vec::new(), &mut done);
    }
    assert!(
        edges.contains_key("pipeline"),
        "the scan found the modules: {edges:?}"
    );
}

#[test]
fn lower_layers_do_not_import_upward() {
    let edges = edges();
    let forbidden: [(&str, &[&str]); 4] = [
        (
            "gpu",
            &[
                "sources",
                "technique",
                "estimators",
                "schedules",
                "pipeline",
            ],
        ),
        (
            "filter",
            &["sources", "estimators", "schedules", "pipeline"],
        ),
        ("technique", &["sources", "schedules", "pipeline"]),
        (
            "estimators",
            &["sources", "schedules", "pipeline", "reference"],
        ),
    ];
    for (module, above) in forbidden {
        for other in above {
            assert!(
                !edges.get(module).is_some_and(|e| e.contains(*other)),
                "{module} imports {other}"
            );
        }
    }
}

#[test]
fn no_module_imports_a_layer_above() {
    let layer = |m: &str| {
        LAYERS
            .iter()
            .position(|l| l.contains(&m))
            .unwrap_or_else(|| panic!("module {m} has no layer in LAYERS (docs/ARCHITECTURE.md)"))
    };
    for module in modules() {
        layer(&module);
    }
    let upward: Vec<String> = edges()
        .iter()
        .flat_map(|(a, bs)| bs.iter().map(move |b| (a, b)))
        .filter(|(a, b)| layer(b) > layer(a))
        .map(|(a, b)| format!("{a} -> {b}"))
        .collect();
    assert!(upward.is_empty(), "upward imports: {upward:?}");
}

/// `crate::X` names a module, never an item of the crate root: `lib.rs` declares modules and
/// re-exports them for users, and the modules import each other by the module that defines the
/// item. Test code included.
#[test]
fn nothing_imports_the_crate_root() {
    let modules = modules();
    let mut root = Vec::new();
    for (path, _) in files() {
        for name in crate_paths(&code_lines(&path, true)) {
            if !modules.contains(&name) && !["self", "super", "crate"].contains(&name.as_str()) {
                root.push(format!("{}: crate::{name}", path.display()));
            }
        }
    }
    assert!(root.is_empty(), "imports of the crate root: {root:#?}");
    let lib = std::fs::read_to_string(src().join("lib.rs")).unwrap();
    let defined: Vec<&str> = lib
        .lines()
        .filter(|l| {
            let l = l.trim_start();
            let l = l.strip_prefix("pub ").unwrap_or(l);
            [
                "fn ",
                "struct ",
                "enum ",
                "impl",
                "const ",
                "static ",
                "type ",
                "trait ",
                "macro_rules!",
            ]
            .iter()
            .any(|k| l.starts_with(k))
        })
        .collect();
    assert!(
        defined.is_empty(),
        "lib.rs defines items; move them into a module: {defined:?}"
    );
}

/// The estimators depend on nothing above them but the frame and the technique table: their
/// parameters are their own, not the settings module's.
#[test]
fn estimators_import_no_settings_sources_schedules_or_pipeline() {
    let edges = edges();
    let found: Vec<&String> = edges
        .get("estimators")
        .into_iter()
        .flatten()
        .filter(|m| ["settings", "sources", "schedules", "pipeline"].contains(&m.as_str()))
        .collect();
    assert!(found.is_empty(), "estimators imports {found:?}");
}

/// `shaders/` mirrors `src/`: every WGSL file lies in a folder named after the `src/` module
/// that uses it, or in `common/` (helpers several modules share); none at the root.
#[test]
fn every_shader_folder_names_a_module() {
    let modules = modules();
    let shaders = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let all = files_under(&shaders, "wgsl");
    let mut stray = Vec::new();
    for path in &all {
        let relative = path.strip_prefix(&shaders).unwrap();
        let mut components = relative.components();
        let top = components.next().unwrap().as_os_str().to_string_lossy();
        if components.next().is_none() || (top != "common" && !modules.contains(&*top)) {
            stray.push(relative.display().to_string());
        }
    }
    let count = all.len();
    assert!(count > 50, "the scan found {count} shaders");
    assert!(
        stray.is_empty(),
        "shaders outside a folder named after their src/ module (or common/): {stray:?}"
    );
}
