//! No import circles between the library's top-level modules (docs/ARCHITECTURE.md): every
//! `crate::MODULE` path outside comments is an edge from the file's top-level module; the graph
//! must be acyclic. Also the layering the architecture names: `gpu/` knows nothing of the
//! techniques, and filters do not reach into schedules, sources or estimators.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn edges() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let modules: BTreeSet<String> = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "lib.rs")
        .map(|n| n.trim_end_matches(".rs").to_string())
        .collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut stack = vec![src.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix(&src).unwrap();
            let top = relative.components().next().unwrap().as_os_str();
            let top = top.to_string_lossy().trim_end_matches(".rs").to_string();
            if top == "lib" {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
                for (i, _) in line.match_indices("crate::") {
                    let name: String = line[i + 7..]
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if modules.contains(&name) && name != top {
                        edges.entry(top.clone()).or_default().insert(name);
                    }
                }
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
        (
            "technique",
            &["sources", "estimators", "schedules", "pipeline"],
        ),
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
