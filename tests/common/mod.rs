//! Every example, for `tests/examples.rs`, which runs them all; the other tests declare only the
//! examples they use, and the reproducible generator `rng.rs`, themselves (`mod common` in each).
#![allow(dead_code)]

#[path = "../../examples/double_a_arm.rs"]
pub mod double_a_arm;
#[path = "../../examples/double_wishbone_3d.rs"]
pub mod double_wishbone_3d;
#[path = "../../examples/excavator.rs"]
pub mod excavator;
#[path = "../../examples/filmstrip.rs"]
pub mod filmstrip;
#[path = "../../examples/flywheel_engine.rs"]
pub mod flywheel_engine;
#[path = "../../examples/four_bar.rs"]
pub mod four_bar;
#[path = "../../examples/free_four_bar.rs"]
pub mod free_four_bar;
#[path = "../../examples/gyroscope.rs"]
pub mod gyroscope;
#[path = "../../examples/linear_models.rs"]
pub mod linear_models;
#[allow(unused_imports)] // not every test uses it
pub use linear_models::bump;
#[path = "../../examples/macpherson.rs"]
pub mod macpherson;
#[path = "../../examples/pumped_pendulum.rs"]
pub mod pumped_pendulum;
#[path = "../../examples/rssr.rs"]
pub mod rssr;
#[path = "../../examples/slider_crank.rs"]
pub mod slider_crank;
#[path = "../../examples/spatial_slider_crank.rs"]
pub mod spatial_slider_crank;
#[path = "../../examples/stewart_platform.rs"]
pub mod stewart_platform;
#[path = "../../examples/suspension_dynamics.rs"]
pub mod suspension_dynamics;
#[path = "../../examples/variable_pendulum.rs"]
pub mod variable_pendulum;
#[path = "../../examples/web_cutter.rs"]
pub mod web_cutter;
// slider_crank_inverse is `flywheel_engine::slider_crank_inverse`: flywheel_engine builds on it,
// and a second `mod` would compile it twice.
