//! The examples' mechanisms again in joint coordinates: each `mechanism!` of `examples/*.rs`
//! with `joint_coordinates;` added as its first statement, in a module of its own
//! (`joint::<file>_<n>`), and the macros `every_example_both_ways!` (planar) and
//! `every_spatial_example_both_ways!` that name each pair (joint type, body-coordinate type,
//! label) for the tests that the two agree (`tests/joint_coordinates.rs`,
//! `tests/spatial_joint_coordinates.rs`). Text, not tokens: the examples are read as a user wrote them,
//! so an example added to `examples/` is checked both ways without a list to keep. A mechanism
//! joint coordinates cannot express yet says so with a `// body coordinates only` comment
//! inside its `mechanism!`, and is left out.

use std::fmt::Write;
use std::path::Path;

fn main() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    println!("cargo:rerun-if-changed={}", examples.display());
    let mut files: Vec<_> = std::fs::read_dir(&examples)
        .expect("examples/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    let (mut modules, mut pairs, mut spatial_pairs) = (String::new(), String::new(), String::new());
    for file in files {
        println!("cargo:rerun-if-changed={}", file.display());
        let text = std::fs::read_to_string(&file).expect("an example");
        let stem = file.file_stem().and_then(|s| s.to_str()).expect("a file name");
        if stem == "showcase" {
            continue;
        }
        let pairs = if text.contains("spatial;") { &mut spatial_pairs } else { &mut pairs };
        for (n, block) in mechanisms(&text).into_iter().enumerate().filter(|(_, b)| !b.contains("// body coordinates only")) {
            let (name, open) = name_and_body(block);
            let module = format!("{stem}_{n}");
            let joint = format!("{}\n        joint_coordinates;{}", &block[..open], &block[open..]);
            writeln!(modules, "#[allow(dead_code)]\npub mod {module} {{\n    use mbd::prelude::*;\n    {joint}\n}}").unwrap();
            writeln!(pairs, "        $check!($crate::joint::{module}::{name}, $crate::{stem}::{name}, \"{stem}: {name}\");").unwrap();
        }
    }
    let out = format!(
        "/// The examples' mechanisms in joint coordinates (build.rs).\npub mod joint {{\n{modules}}}\n\n\
         /// Calls `$check!(joint type, body-coordinate type, label)` for every planar example's mechanism.\n\
         #[macro_export]\nmacro_rules! every_example_both_ways {{\n    ($check:ident) => {{\n{pairs}    }};\n}}\n\n\
         /// Calls `$check!(joint type, body-coordinate type, label)` for every spatial example's mechanism.\n\
         #[macro_export]\nmacro_rules! every_spatial_example_both_ways {{\n    ($check:ident) => {{\n{spatial_pairs}    }};\n}}\n"
    );
    std::fs::write(Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("both_ways.rs"), out).expect("written");
}

/// Each `mechanism! { ... }` of a file, braces matched.
fn mechanisms(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(start) = text[from..].find("mechanism! {").map(|i| from + i) {
        let mut depth = 0;
        let mut end = start;
        for (i, c) in text[start..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = start + i + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.push(&text[start..end]);
        from = end;
    }
    out
}

/// The mechanism's name and the byte just after the `{` that opens its statements: the first
/// identifier after `mechanism! {`, its doc comments and attributes and `pub` skipped.
fn name_and_body(block: &str) -> (String, usize) {
    let mut rest = block["mechanism! {".len()..].char_indices().map(|(i, c)| (i + "mechanism! {".len(), c)).peekable();
    let mut word = String::new();
    let mut in_comment = false;
    while let Some((i, c)) = rest.next() {
        if in_comment {
            in_comment = c != '\n';
            continue;
        }
        match c {
            '/' if block[i..].starts_with("//") => in_comment = true,
            '#' => {
                // an attribute: up to its closing bracket
                for (_, c) in rest.by_ref() {
                    if c == ']' {
                        break;
                    }
                }
            }
            c if c.is_alphanumeric() || c == '_' => word.push(c),
            '{' if !word.is_empty() => return (word, i + 1),
            _ if word == "pub" => word.clear(),
            _ => {}
        }
    }
    panic!("a mechanism! without a name: {block}");
}
