//! **mbd** — multibody dynamics for Rust, generated at compile time.
//!
//! Write a mechanism with [`mechanism!`]; the macro derives its constraints, their Jacobian and
//! the velocity and acceleration right-hand sides symbolically and emits them as straight-line,
//! allocation-free Rust. [`mbd_runtime`]'s solvers (re-exported here) do the analyses.
#![cfg_attr(not(feature = "std"), no_std)]

pub use mbd_macros::mechanism;
pub use mbd_runtime::*;

/// Everything a user of `mechanism!` needs: `use mbd::prelude::*;`.
pub mod prelude {
    pub use core::f64::consts::PI;
    pub use mbd_macros::mechanism;
    pub use mbd_runtime::*;
}
