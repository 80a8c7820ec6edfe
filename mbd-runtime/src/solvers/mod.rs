//! The analyses at a state: kinematics (assembly, position, velocity and acceleration, sweeps)
//! and its errors, the redundancy report, statics, inverse dynamics with joint reactions,
//! linearization, and finite-difference derivatives of a mechanism. Built on the model and
//! `linalg`; the integrators are built on them.

pub mod dense_forward;
pub(crate) mod error;
pub(crate) mod finite_differences;
pub(crate) mod flow;
pub(crate) mod friction;
pub(crate) mod inverse;
pub(crate) mod kinematics;
#[cfg(feature = "alloc")]
pub mod linearize;
pub(crate) mod newton;
pub mod redundancy;
pub mod statics;
