//! The user's guide of mbd (`guide/*.md`) and its README, as this crate's documentation. Every
//! Rust snippet in them is a module of the `snippets` test (written by `build.rs`), compiled
//! against the built crates and run by `cargo test -p mbd-guide`. The same chapters are
//! `mbd::guide` in mbd's own documentation, not compiled there.
#![doc = include_str!("../../README.md")]

macro_rules! chapters {
    ($($(#[$attr:meta])* $name:ident = $file:literal;)*) => {
        $(
            $(#[$attr])*
            #[doc = include_str!(concat!("../../guide/", $file))]
            pub mod $name {}
        )*
    };
}

chapters! {
    index = "README.md";
    dsl = "dsl.md";
    joint_coordinates = "joint-coordinates.md";
    spatial = "spatial.md";
    generated_api = "generated-api.md";
    kinematics = "kinematics.md";
    dynamics = "dynamics.md";
    linearization = "linearization.md";
    animation_and_plots = "animation-and-plots.md";
    numerical_stability = "numerical-stability.md";
    performance = "performance.md";
    build_time = "build-time.md";
    embedded = "embedded.md";
    examples = "examples.md";
}
