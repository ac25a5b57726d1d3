//! README.md cannot rot: its library quick start is `examples/quick_start.rs` verbatim (from
//! the first `use`) and runs, its table lists every letter of the scheme language, its scene
//! is `scenes/shear.toml` verbatim, and its layout, like docs/architecture.md's list of
//! crates, names every member of the workspace.

#[path = "../examples/quick_start.rs"]
mod quick_start;

const README: &str = include_str!("../README.md");

#[test]
fn quick_start_is_shown_verbatim_and_runs() {
    let example = include_str!("../examples/quick_start.rs");
    let body = &example[example.find("use dpd::").unwrap()..];
    assert!(
        README.contains(&format!("```rust\n{body}```")),
        "README.md does not show examples/quick_start.rs as it is"
    );
    quick_start::main().unwrap();
}

#[test]
fn letters_table_lists_every_letter() {
    for l in dpd::lang::letters::LETTERS {
        let row = format!("| `{}` |", l.spelling);
        assert!(README.contains(&row), "README.md lacks the letter {row}");
    }
}

#[test]
fn scene_example_is_the_shipped_scene() {
    let scene = include_str!("../scenes/shear.toml");
    assert!(README.contains(&format!("```toml\n{scene}```")));
}

/// The `## ` section of `doc` whose heading is `heading`.
fn section<'a>(doc: &'a str, heading: &str) -> &'a str {
    let start = doc
        .find(&format!("\n## {heading}\n"))
        .unwrap_or_else(|| panic!("no section `## {heading}`"));
    let body = &doc[start + heading.len() + 5..];
    &body[..body.find("\n## ").unwrap_or(body.len())]
}

/// The value of the first `key = "value"` line of a manifest (after `after`).
fn manifest_value(manifest: &str, after: &str, key: &str) -> String {
    let rest = &manifest[manifest.find(after).unwrap()..];
    let line = rest
        .lines()
        .find(|l| l.starts_with(&format!("{key} = ")))
        .unwrap();
    line.split('"').nth(1).unwrap().to_string()
}

#[test]
fn layout_and_architecture_name_every_workspace_member() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let workspace = include_str!("../Cargo.toml");
    let members_line = workspace
        .lines()
        .find(|l| l.starts_with("members = ["))
        .unwrap();
    let members: Vec<&str> = members_line.split('"').skip(1).step_by(2).collect();
    assert!(members.len() >= 10, "{members:?}");
    let layout = section(README, "Layout");
    let architecture = include_str!("../docs/architecture.md");
    let crates = section(architecture, "Crates");
    let root_package = manifest_value(workspace, "[package]", "name");
    assert!(crates.contains(&format!("`{root_package}`")));
    for member in members {
        assert!(
            layout.contains(&format!("`{member}/`")),
            "README.md's layout lacks `{member}/`"
        );
        let manifest = std::fs::read_to_string(root.join(member).join("Cargo.toml")).unwrap();
        let name = manifest_value(&manifest, "[package]", "name");
        assert!(
            crates.contains(&format!("`{name}`")),
            "docs/architecture.md's crates lack `{name}` ({member}/)"
        );
    }
}
