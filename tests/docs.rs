//! `cargo doc` is warning-free, and the documentation of a generated type is one a user can live
//! in: `doc-check/` (a crate outside the workspace holding a planar and a spatial mechanism, as a
//! user's crate would) is documented with warnings as errors, alongside mbd, mbd-runtime and
//! mbd-macros, and the generated pages are read back for their tables. Runs cargo itself in `target/nested`, like `tests/no_std.rs`.
use std::path::Path;
use std::process::Command;

/// The page's text: tags dropped, entities `&lt;`, `&gt;`, `&amp;`, `&quot;`, `&#39;` decoded.
fn text(html: &str) -> String {
    let mut out = String::with_capacity(html.len());
    let mut in_tag = false;
    for c in html.chars() {
        match c {
            '<' => in_tag = true,
            '>' if in_tag => {
                in_tag = false;
                out.push(' ');
            }
            _ if !in_tag => out.push(c),
            _ => {}
        }
    }
    let out = out.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&#39;", "'").replace("&amp;", "&");
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Asserts that `page` holds the table row `row` ("| 2 | crank.phi | rad |").
fn has_row(page: &str, row: &str) {
    let cells = row.trim_matches('|').split('|').map(str::trim).collect::<Vec<_>>().join(" ");
    assert!(page.contains(&cells), "the page lacks the row {row:?}");
}

#[test]
fn generated_types_document_their_tables_without_warnings() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target_dir = root.join("target/nested");
    let out = Command::new(env!("CARGO"))
        .args(["doc", "--quiet", "--no-deps", "-p", "mbd-doc-check", "-p", "mbd", "-p", "mbd-runtime", "-p", "mbd-macros"])
        .arg("--manifest-path")
        .arg(root.join("doc-check/Cargo.toml"))
        .arg("--target-dir")
        .arg(&target_dir)
        .env("RUSTDOCFLAGS", "-D warnings")
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "cargo doc failed or warned:\n{}", String::from_utf8_lossy(&out.stderr));
    let page = |name: &str| text(&std::fs::read_to_string(target_dir.join("doc/mbd_doc_check").join(name)).expect("the page"));

    let planar = page("struct.SliderCrank.html");
    for row in [
        // coordinates with their index and unit
        "| 2 | crank.phi | rad |",
        "| 6 | slider.x | m |",
        // points and their accessors
        "| crank.A | SliderCrank::crank_a |",
        // joints: index into JOINTS, name, kind, rows
        "| 0 | pin | revolute | 0–1 |",
        "| 3 | level | constraint | 6 |",
        // rows with the unit of their multiplier
        "| 1 | pin: y | N |",
        "| 7 | upright: user | J per unit of the row |",
        // force elements and the velocities they act on
        "| return_spring | 6, 7 |",
    ] {
        has_row(&planar, row);
    }
    assert!(planar.contains("3 planar bodies, 9 coordinates and velocities, 8 constraint rows (1 degree of freedom)"));
    // internals stay out: the Newton matrix's plumbing and the model JSON's text
    for internal in ["NewtonMatrix", "newton_storage", "sparse_position_solve", "\"bodies\":"] {
        assert!(!planar.contains(internal), "the planar page shows {internal}");
    }

    let spatial = page("struct.SpatialSliderCrank.html");
    for row in [
        "| 6 | crank.e3 | 1 |",
        "| 7 | slider.x | m |",
        "| 5 | crank.wz | rad/s |",
        "| 9 | guide: twist | N·m |",
        "| 10 | rod: length | N |",
    ] {
        has_row(&spatial, row);
    }
}
