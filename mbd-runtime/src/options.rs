//! The one shape of every solver's and integrator's options (ARCHITECTURE.md, "Options").
//!
//! An options type is a `#[non_exhaustive]` struct with public fields to read, each documented
//! with its unit and default; [`Default`] and `new()` give the defaults; a `with_<field>` setter
//! sets each field, so that options are written as
//!
//! ```
//! # use mbd_runtime::Dopri5Options;
//! let options = Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12);
//! # let _: Dopri5Options<f64> = options;
//! ```
//!
//! and a field added later breaks no one's code. Options that hold tolerances or lengths are
//! generic over the scalar type `T` of the mechanism (default `f64`), so that a value is given
//! in the type the solver computes in. [`options!`](crate::options!) writes all of it from one
//! declaration, so no options type can drift from the shape.

/// Declares an options struct in the library's one shape: `#[non_exhaustive]`, public
/// documented fields, `new()` and [`Default`] giving the declared defaults, and a `with_<field>`
/// setter for every field. Each field is written `field: Type = default => with_field`; in a
/// generic options type, `T` is the scalar (`T::from_f64(1e-10)`). The setter's name is spelt
/// out (macro_rules cannot join identifiers) and checked at compile time to be `with_` and the
/// field's.
macro_rules! options {
    (
        $(#[$meta:meta])*
        pub struct $name:ident $(<$T:ident>)? {
            $(
                $(#[$field_meta:meta])*
                $field:ident : $ty:ty = $default:expr => $setter:ident
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[non_exhaustive]
        pub struct $name $(<$T = f64>)? {
            $(
                $(#[$field_meta])*
                pub $field: $ty,
            )*
        }

        impl $(<$T: $crate::Real>)? $name $(<$T>)? {
            /// The defaults, as each field documents them.
            pub fn new() -> Self {
                Self { $($field: $default,)* }
            }

            $(
                #[doc = concat!("Sets [`", stringify!($field), "`](Self::", stringify!($field), ") (its unit and default are on the field).")]
                #[must_use]
                pub fn $setter(mut self, $field: $ty) -> Self {
                    const _: () = assert!(
                        $crate::options::is_setter_of(stringify!($setter), stringify!($field)),
                        concat!("the setter of `", stringify!($field), "` must be `with_", stringify!($field), "`")
                    );
                    self.$field = $field;
                    self
                }
            )*
        }

        impl $(<$T: $crate::Real>)? Default for $name $(<$T>)? {
            fn default() -> Self {
                Self::new()
            }
        }
    };
}

pub(crate) use options;

/// Whether `setter` is `with_` followed by `field` (for [`options!`]'s compile-time check).
pub(crate) const fn is_setter_of(setter: &str, field: &str) -> bool {
    let (s, f) = (setter.as_bytes(), field.as_bytes());
    if s.len() != f.len() + 5 {
        return false;
    }
    let prefix = b"with_";
    let mut i = 0;
    while i < s.len() {
        let expected = if i < 5 { prefix[i] } else { f[i - 5] };
        if s[i] != expected {
            return false;
        }
        i += 1;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::is_setter_of;

    #[test]
    fn a_setter_is_with_and_its_field() {
        assert!(is_setter_of("with_tolerance", "tolerance"));
        assert!(!is_setter_of("with_tolerances", "tolerance"));
        assert!(!is_setter_of("set_tolerance", "tolerance"));
        assert!(!is_setter_of("with_rtol", "atol"));
    }
}

/// The public surface a user's code and numbers depend on — every public item's signature in
/// this crate's sources and the documented defaults of every options type — is kept in
/// `api.txt` beside this crate's manifest, and the CHANGELOG names its hash. A change to a
/// default or a public signature fails this test until it is blessed (`MBD_BLESS=1 cargo test -p
/// mbd-runtime --lib api`, which rewrites `api.txt`) and the CHANGELOG's `api-surface` line is set
/// to the new hash — with the entry that says what changed, which is what the test is for.
#[cfg(all(test, feature = "std"))]
mod api {
    extern crate std;
    use std::format;
    use std::string::String;
    use std::vec::Vec;

    use crate::*;

    /// Each options type's defaults as `Debug` prints them (f64).
    fn defaults() -> String {
        let mut out = String::new();
        let mut add = |name: &str, value: String| out += &format!("{name}::default() = {value}\n");
        add("KinematicOptions", format!("{:?}", KinematicOptions::<f64>::default()));
        add("StaticOptions", format!("{:?}", StaticOptions::<f64>::default()));
        add("DynamicsOptions", format!("{:?}", DynamicsOptions::<f64>::default()));
        add("SimulationOptions", format!("{:?}", SimulationOptions::<f64>::default()));
        add("Rk4Options", format!("{:?}", Rk4Options::<f64>::default()));
        add("Dopri5Options", format!("{:?}", Dopri5Options::<f64>::default()));
        add("Dop853Options", format!("{:?}", Dop853Options::<f64>::default()));
        add("GeneralizedAlphaOptions", format!("{:?}", GeneralizedAlphaOptions::<f64>::default()));
        add("ErrorControl", format!("{:?}", ErrorControl::<f64>::default()));
        add("BdfOptions", format!("{:?}", BdfOptions::<f64>::default()));
        add("Radau5Options", format!("{:?}", Radau5Options::<f64>::default()));
        add("AutoOptions", format!("{:?}", AutoOptions::<f64>::default()));
        add("InverseDynamicsOptions", format!("{:?}", InverseDynamicsOptions::<f64>::default()));
        #[cfg(feature = "alloc")]
        add("LinearizeOptions", format!("{:?}", LinearizeOptions::default()));
        out
    }

    /// The public items of one source file: each line that starts with `pub ` (a `pub fn`'s
    /// whole signature, to its `{` or `;`), the variants of a `pub enum`, and the items of a
    /// `pub trait` (each `fn`'s whole signature, its `const`s and `type`s: what an implementor
    /// writes); up to the file's `#[cfg(test)]` module (a `#[cfg(test)] mod tests;` line is
    /// skipped: `integrate/mod.rs` and `lib.rs` have theirs at the top).
    fn public_items(source: &str) -> Vec<String> {
        let mut items = Vec::new();
        let mut lines = source.lines().map(str::trim);
        // Inside a `pub enum` or `pub trait` body: its depth (1 directly in it).
        let mut inside: Option<(Body, i32)> = None;
        while let Some(line) = lines.next() {
            if line == "#[cfg(test)]" {
                match lines.next() {
                    Some(item) if item.ends_with(';') => continue,
                    _ => break,
                }
            }
            if let Some((body, depth)) = inside.as_mut() {
                *depth += match body {
                    Body::Enum => enum_line(line, *depth, &mut items),
                    Body::Trait => trait_line(line, *depth, &mut lines, &mut items),
                };
                if *depth <= 0 {
                    inside = None;
                }
                continue;
            }
            if !line.starts_with("pub ") {
                continue;
            }
            let mut item = String::from(line);
            if line.starts_with("pub fn") || line.starts_with("pub const fn") {
                item = to_brace(joined(line, &mut lines));
            }
            if line.starts_with("pub enum") && line.ends_with('{') {
                inside = Some((Body::Enum, 1));
            }
            if line.starts_with("pub trait") || line.starts_with("pub unsafe trait") {
                // The header may go on over lines (bounds, `where`) to its `{`.
                inside = Some((Body::Trait, braces(&joined(line, &mut lines)))).filter(|&(_, d)| d > 0);
            }
            items.push(item);
        }
        items
    }

    /// The body whose lines [`public_items`] reads.
    enum Body {
        Enum,
        Trait,
    }

    /// A line of a `pub enum`'s body at `depth`: a variant's name where it starts one. Returns
    /// the change of depth (braces and parentheses).
    fn enum_line(line: &str, depth: i32, items: &mut Vec<String>) -> i32 {
        if line.starts_with("//") || line.starts_with("#[") {
            return 0;
        }
        if depth == 1 && line.starts_with(|c: char| c.is_ascii_uppercase()) {
            items.push(format!("    {}", line.split([' ', '{', '(', ',']).next().unwrap_or(line)));
        }
        line.matches(['{', '(']).count() as i32 - line.matches(['}', ')']).count() as i32
    }

    /// A line of a `pub trait`'s body at `depth`: an item's whole signature where it starts one
    /// (reading on through `lines`). Returns the change of depth.
    fn trait_line<'a>(line: &str, depth: i32, lines: &mut impl Iterator<Item = &'a str>, items: &mut Vec<String>) -> i32 {
        if depth == 1 && ["fn ", "const ", "type ", "unsafe fn "].iter().any(|p| line.starts_with(p)) {
            let item = joined(line, lines);
            let change = braces(&item);
            items.push(format!("    {}", to_brace(item)));
            change
        } else {
            braces(line)
        }
    }

    /// Opening less closing braces.
    fn braces(line: &str) -> i32 {
        line.matches('{').count() as i32 - line.matches('}').count() as i32
    }

    /// `first` and the lines after it, up to the one that holds its `{` or ends with `;`, joined.
    fn joined<'a>(first: &str, lines: &mut impl Iterator<Item = &'a str>) -> String {
        let mut item = String::from(first);
        while !(item.contains('{') || item.ends_with(';')) {
            match lines.next() {
                Some(next) => item = format!("{item} {next}"),
                None => break,
            }
        }
        item
    }

    /// `item` up to its first `{`, inclusive.
    fn to_brace(mut item: String) -> String {
        if let Some(brace) = item.find('{') {
            item.truncate(brace + 1);
        }
        item
    }

    /// Every source file's public items, by path, then the defaults.
    fn surface() -> String {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = Vec::new();
        let mut dirs = std::vec![root.clone()];
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(&dir).expect("the sources") {
                let path = entry.expect("a source").path();
                if path.is_dir() {
                    dirs.push(path);
                } else if path.extension().is_some_and(|e| e == "rs") && !path.ends_with("tests.rs") && !path.ends_with("test_support.rs") {
                    files.push(path);
                }
            }
        }
        files.sort();
        let mut out = String::new();
        for path in files {
            let source = std::fs::read_to_string(&path).expect("a readable source");
            let items = public_items(&source);
            if !items.is_empty() {
                out += &format!("## {}\n", path.strip_prefix(&root).expect("under src").display());
                for item in items {
                    out += &item;
                    out.push('\n');
                }
            }
        }
        out + "## defaults\n" + &defaults()
    }

    /// FNV-1a, 64 bits: a hash to name a surface by, no cryptography needed.
    fn fnv1a(text: &str) -> u64 {
        text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
    }

    #[test]
    fn api_surface_and_defaults_are_in_the_changelog() {
        let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let snapshot = manifest.join("api.txt");
        let now = surface();
        // Every options type's defaults are in the surface: a new one must be added to `defaults`.
        for line in now.lines() {
            let name = line.trim_start_matches("pub struct ").split(['<', ' ', '{']).next().unwrap_or("");
            if line.starts_with("pub struct ") && name.ends_with("Options") {
                assert!(now.contains(&format!("\n{name}::default() = ")), "add {name}'s defaults to `defaults()` in options.rs");
            }
        }
        if std::env::var_os("MBD_BLESS").is_some() {
            std::fs::write(&snapshot, &now).expect("api.txt written");
        }
        let kept = std::fs::read_to_string(&snapshot).unwrap_or_default();
        if kept != now {
            let first = kept.lines().zip(now.lines()).position(|(a, b)| a != b).unwrap_or(kept.lines().count().min(now.lines().count()));
            panic!(
                "the public API or a default of mbd-runtime changed (first difference at line {} of api.txt: {:?} is now {:?}).\n\
                 Add an entry to CHANGELOG.md saying what changed and how to migrate, then run\n\
                 MBD_BLESS=1 cargo test -p mbd-runtime --lib api, and set the CHANGELOG's api-surface line to the hash it reports.",
                first + 1,
                kept.lines().nth(first).unwrap_or(""),
                now.lines().nth(first).unwrap_or("")
            );
        }
        let hash = format!("{:016x}", fnv1a(&now));
        let changelog = std::fs::read_to_string(manifest.join("../CHANGELOG.md")).expect("CHANGELOG.md");
        let line = format!("<!-- api-surface: {hash} -->");
        assert!(
            changelog.contains(&line),
            "api.txt (the public API and defaults of mbd-runtime) changed: CHANGELOG.md must say what changed, and hold the line\n{line}\n\
             in place of its api-surface line"
        );
    }

    #[test]
    fn public_items_reads_signatures_and_variants() {
        let source = "#[cfg(test)]\nmod tests;\npub fn f<T>(\n    a: T,\n) -> T {\n    a\n}\npub fn g(&self) -> u32 { 1 }\nfn private() {}\npub enum E {\n    /// in (−π, π]\n    A { x: f64 },\n    B,\n}\npub const C: u32 = 1;\n#[cfg(test)]\nmod tests {\npub fn hidden() {}\n}\n";
        assert_eq!(
            public_items(source),
            ["pub fn f<T>( a: T, ) -> T {", "pub fn g(&self) -> u32 {", "pub enum E {", "    A", "    B", "pub const C: u32 = 1;"]
        );
    }
}
