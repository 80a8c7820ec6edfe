//! The `mechanism!` macro of mbd.
//!
//! Data flows one way through plain-Rust stages, each unit-tested without a compiler in the loop:
//! `bind` (each `let`'s name replaced by its expression on the tokens) → `part` (sub-assemblies
//! instantiated) and `repeat` (`for` loops and indexed names unrolled
//! on the tokens; `names` keeps each made identifier's written form for every text) →
//! `scene` (the base mechanism and each scene's statements, expanded one by one) → `parse`
//! (tokens → syntax tree with spans) → `model` (names resolved, rules checked, every
//! mistake reported at once; each joint, driver and force kind resolved by its own file in
//! `elements` and `forces`) → `formulation` (symbolic Φ, Φ_q, ν, γ, M, h on the `sym`
//! expression graph, written against the body frames of `frames`, the seam where a
//! formulation plugs in) → `emit` (straight-line Rust; `forward` and `schur` the sparse
//! solve of the equations of motion) → `expand` (the mechanism's type and trait
//! implementations; `json` its model description). `ARCHITECTURE.md` is the map.

// No function over 150 lines (`clippy.toml`).
#![warn(clippy::too_many_lines)]

mod bind;
mod coordinates;
mod docs;
mod elements;
mod emit;
mod expand;
mod forces;
mod formulation;
mod forward;
mod frames;
#[cfg(test)]
mod fuzz;
mod json;
mod mirror;
mod model;
mod names;
mod newton;
mod parse;
mod part;
mod repeat;
mod scalar;
mod scene;
mod schur;
mod sym;
mod tree;
mod wording;

use proc_macro::TokenStream;

/// Declares a planar or spatial (`spatial;`) mechanism in body coordinates and generates its
/// constraint equations, their
/// exact Jacobian and the velocity and acceleration right-hand sides as straight-line Rust.
///
/// See the DSL reference of the user's guide (`guide/dsl.md`) for the grammar and `docs/formulation.md` for the equations.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    expand::expand(input.into()).into()
}
