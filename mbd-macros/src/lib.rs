//! The `mechanism!` macro of mbd.
//!
//! Data flows one way through plain-Rust stages, each unit-tested without a compiler in the loop:
//! [`parse`] (tokens → syntax tree with spans) → [`model`] (names resolved, rules checked, every
//! mistake reported at once) → [`formulation`] (symbolic Φ, Φ_q, ν, γ in planar body coordinates,
//! on the [`sym`] expression graph) → [`emit`] (straight-line Rust; [`schur`] the sparse solve of the equations of motion) → [`expand`] (the mechanism's
//! type and trait implementations; [`json`] its model description).

mod emit;
mod expand;
mod formulation;
mod json;
mod model;
mod parse;
mod schur;
mod sym;

use proc_macro::TokenStream;

/// Declares a planar mechanism in body coordinates and generates its constraint equations, their
/// exact Jacobian and the velocity and acceleration right-hand sides as straight-line Rust.
///
/// See the README's DSL reference for the grammar and `docs/formulation.md` for the equations.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    expand::expand(input.into()).into()
}
