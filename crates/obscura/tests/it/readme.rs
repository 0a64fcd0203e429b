//! The README and docs/ARCHITECTURE.md show the technique table generated from
//! `obscura::technique::TABLE`: when a row changes, this test prints the table to paste.

use std::path::Path;

#[test]
fn docs_show_the_technique_table() {
    let table = obscura::technique::markdown_table();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for doc in ["README.md", "docs/ARCHITECTURE.md"] {
        let text = std::fs::read_to_string(root.join(doc)).unwrap();
        assert!(
            text.contains(&table),
            "{doc} does not show the current technique table; paste this:\n\n{table}"
        );
    }
}
