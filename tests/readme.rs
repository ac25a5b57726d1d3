//! README.md cannot rot: its library quick start is `examples/quick_start.rs` verbatim (from
//! the first `use`) and runs, its table lists every letter of the scheme language, and its
//! scene is `scenes/shear.toml` verbatim.

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
