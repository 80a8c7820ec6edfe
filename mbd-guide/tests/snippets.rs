//! Every Rust snippet of the README and the user's guide, each a whole program: written by
//! `build.rs` as a module of this test, compiled against the built crates and its `fn main`
//! run by a test named after its page and its place there (`guide_dsl_md_1::runs`, the page's
//! first; a failure names the page and line). A snippet that no longer compiles fails the build;
//! one that panics or returns an error fails its test.

include!(concat!(env!("OUT_DIR"), "/snippets/mod.rs"));
