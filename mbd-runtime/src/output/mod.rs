//! Output of an analysis: animations (an HTML page and an SVG, `animation`, `drawing`), CSV,
//! plots and a progress bar. Built on everything below; nothing is built on it.

#[cfg(feature = "animation")]
pub(crate) mod animation;
#[cfg(feature = "std")]
pub(crate) mod csv;
#[cfg(feature = "animation")]
pub(crate) mod drawing;
#[cfg(feature = "plots")]
pub(crate) mod plot;
#[cfg(feature = "progress")]
pub(crate) mod progress;
