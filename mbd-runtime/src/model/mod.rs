//! The model: the traits every generated mechanism implements (`mechanism`, with the forward
//! dynamics' trait, options and errors in `dynamics`), each body's pose and twist (`body`), named
//! access (`named`, `planar`) and the caller's work space (`workspace`). Built on `linalg`; the
//! solvers, integrators and output are built on it.

pub(crate) mod body;
pub(crate) mod dynamics;
pub(crate) mod group;
pub(crate) mod mechanism;
pub(crate) mod named;
pub(crate) mod planar;
pub mod workspace;
