//! Writes every Rust snippet of the README and the user's guide (`guide/*.md` and
//! `guide/projects/*.md`) as a module of the `snippets` test (`tests/snippets.rs`): each snippet
//! is a whole program, its `fn main` run by a `#[test]` named after the page and the snippet's
//! place on it. The snippets are compiled with the other tests — in the build, beside the other
//! crates, and once until a page changes — where rustdoc compiled them anew, alone, on every run
//! of the tests (about 70 s of one core, 2026-12-06).
//!
//! A code block is Rust when it is tagged ```` ```rust ````; a block tagged otherwise (```` ```toml ````,
//! ```` ```text ````, …) is left alone, and an untagged block, a Rust block with rustdoc's
//! attributes (`ignore`, `no_run`, …) or with a hidden line (`# `) stops the build with the page
//! and line: nothing is skipped silently, and a reader copies what the test runs.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::{env, fs};

fn main() {
    let root = Path::new(&env::var("CARGO_MANIFEST_DIR").expect("cargo sets it")).parent().expect("the workspace").to_path_buf();
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets it")).join("snippets");
    fs::create_dir_all(&out).expect("OUT_DIR is writable");
    let mut pages = vec![PathBuf::from("README.md")];
    let mut guide: Vec<PathBuf> = Vec::new();
    for dir in ["guide", "guide/projects"] {
        guide.extend(
            fs::read_dir(root.join(dir))
                .expect("the guide exists")
                .map(|e| e.expect("a directory entry").path())
                .filter(|p| p.extension().is_some_and(|e| e == "md"))
                .map(|p| p.strip_prefix(&root).expect("inside the workspace").to_path_buf()),
        );
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
    }
    guide.sort();
    pages.extend(guide);
    let mut modules = String::new();
    for page in &pages {
        let path = root.join(page);
        println!("cargo:rerun-if-changed={}", path.display());
        let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for (ordinal, (line, code)) in snippets(page, &text).into_iter().enumerate() {
            let at = format!("{}:{line}", page.display());
            // Named by the page and the snippet's place on it (1, 2, …), not its line, so that an
            // edit above a snippet leaves its test's name as it was.
            let name: String = format!("{}_{}", page.display(), ordinal + 1)
                .chars()
                .map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' })
                .collect();
            let file = out.join(format!("{name}.rs"));
            // `fn main() -> Result<(), E>` fails the test with its error; `fn main()` by a panic.
            let run = if code.contains("fn main() -> ") {
                format!("if let Err(e) = main() {{\n        panic!(\"the snippet at {at} returned an error: {{e:?}}\");\n    }}")
            } else {
                "main();".to_string()
            };
            let body = format!("// {at}\n{code}\n#[test]\nfn runs() {{\n    {run}\n}}\n");
            fs::write(&file, body).expect("OUT_DIR is writable");
            writeln!(modules, "#[path = {:?}]\nmod {name};", file.display().to_string()).expect("a String");
        }
    }
    fs::write(out.join("mod.rs"), modules).expect("OUT_DIR is writable");
}

/// The Rust snippets of a page: (the line of the opening fence, the code).
fn snippets(page: &Path, text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut open: Option<(usize, bool, String)> = None;
    for (index, line) in text.lines().enumerate() {
        let fence = line.trim_start();
        if !fence.starts_with("```") {
            if let Some((_, true, code)) = &mut open {
                let at = format!("{}:{}", page.display(), index + 1);
                assert!(
                    line != "#" && !line.starts_with("# "),
                    "{at}: a hidden line (rustdoc's `# `): a snippet shows all a reader copies"
                );
                code.push_str(line);
                code.push('\n');
            }
            continue;
        }
        match open.take() {
            Some((start, rust, code)) => {
                if rust {
                    found.push((start, code));
                }
            }
            None => {
                let info = fence.trim_start_matches('`').trim();
                let at = format!("{}:{}", page.display(), index + 1);
                assert!(!info.is_empty(), "{at}: an untagged code block (rustdoc would compile it as Rust): tag it ```rust, ```text, …");
                let rust = info.split([',', ' ']).next() == Some("rust");
                assert!(
                    !rust || info == "rust",
                    "{at}: ```{info}: the guide's snippets are whole programs that run; attributes are not supported"
                );
                open = Some((index + 1, rust, String::new()));
            }
        }
    }
    assert!(open.is_none(), "{}: a code block is not closed", page.display());
    found
}
