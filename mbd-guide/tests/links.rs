//! Every relative link of the README, the guide and the project's other Markdown pages leads
//! somewhere: the file exists, and an anchor (`page.md#section`, `#section`) names one of the
//! target's headings as GitHub makes them. The README was split into the guide's chapters; a
//! link that pointed into a section that moved fails here instead of on a reader.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace").to_path_buf()
}

/// The Markdown pages a reader follows links through.
fn pages() -> Vec<PathBuf> {
    let root = root();
    let mut pages: Vec<PathBuf> = ["README.md", "CHANGELOG.md", "ARCHITECTURE.md"].iter().map(|p| root.join(p)).collect();
    for dir in ["guide", "guide/projects", "docs"] {
        for entry in fs::read_dir(root.join(dir)).expect("the folder exists") {
            let path = entry.expect("a directory entry").path();
            if path.extension().is_some_and(|e| e == "md") {
                pages.push(path);
            }
        }
    }
    pages.sort();
    pages
}

/// The lines outside fenced code blocks.
fn prose(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut fenced = false;
    text.lines().enumerate().filter(move |(_, line)| {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            return false;
        }
        !fenced
    })
}

/// GitHub's anchor of a heading: lower case, punctuation other than `-` and `_` removed,
/// spaces made hyphens; a repeated heading gets `-1`, `-2`, … .
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    for (_, line) in prose(text) {
        let Some(title) = line.strip_prefix('#').map(|t| t.trim_start_matches('#')) else { continue };
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let mut candidate = slug.clone();
        let mut k = 0;
        while seen.contains(&candidate) {
            k += 1;
            candidate = format!("{slug}-{k}");
        }
        seen.insert(candidate);
    }
    seen
}

/// The targets of the inline links `[text](target)` of one line.
fn targets(line: &str) -> Vec<String> {
    // Inline code (`f(x)](y)` in a DSL example) holds no links.
    let line: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
    let mut out = Vec::new();
    let mut rest = line.as_str();
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(end) = after.find(')') else { break };
        out.push(after[..end].to_string());
        rest = &after[end..];
    }
    out
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let text = fs::read_to_string(&page).expect("a page");
        for (number, line) in prose(&text) {
            for target in targets(line) {
                let target = target.as_str();
                if target.contains("://") || target.starts_with("mailto:") || target.contains(' ') {
                    continue;
                }
                checked += 1;
                let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
                let path = if file.is_empty() { page.clone() } else { page.parent().expect("a folder").join(file) };
                let shown = format!("{}:{}: `{target}`", page.strip_prefix(root()).unwrap_or(&page).display(), number + 1);
                if !path.exists() {
                    broken.push(format!("{shown}: no file {}", path.display()));
                } else if !anchor.is_empty() {
                    let target_text = fs::read_to_string(&path).unwrap_or_default();
                    if !anchors(&target_text).contains(anchor) {
                        broken.push(format!("{shown}: no heading with the anchor `#{anchor}`"));
                    }
                }
            }
        }
    }
    assert!(checked > 50, "only {checked} links found: the scan is broken");
    assert!(broken.is_empty(), "{} broken links:\n{}", broken.len(), broken.join("\n"));
}

#[test]
fn anchors_are_githubs() {
    let text =
        "# Joint coordinates (`joint_coordinates;`)\n## What accuracy costs: the study\n## Tests\n## Tests\n```\n# not a heading\n```\n";
    let expected: BTreeSet<String> = ["joint-coordinates-joint_coordinates", "what-accuracy-costs-the-study", "tests", "tests-1"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(anchors(text), expected);
}

/// Every chapter of `guide/` is in the guide's documentation twice: here, where its programs
/// run (`mbd-guide/src/lib.rs`), and in `mbd`'s own docs, `mbd::guide` (`src/lib.rs`).
#[test]
fn every_chapter_is_tested_and_documented() {
    let root = root();
    let lists = [root.join("mbd-guide/src/lib.rs"), root.join("src/lib.rs")].map(|p| fs::read_to_string(&p).expect("a lib.rs"));
    let mut chapters = 0;
    for entry in fs::read_dir(root.join("guide")).expect("the guide") {
        let name = entry.expect("an entry").file_name().into_string().expect("a UTF-8 name");
        if !name.ends_with(".md") {
            continue;
        }
        chapters += 1;
        for (list, file) in lists.iter().zip(["mbd-guide/src/lib.rs", "src/lib.rs"]) {
            assert!(list.contains(&format!("{name}\"")), "guide/{name} is not in {file}'s chapters");
        }
    }
    assert!(chapters >= 13, "{chapters} chapters found");
}
