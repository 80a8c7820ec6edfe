//! The examples of `examples/`, each a module: one compilation of them for the showcase and the
//! tests (Cargo.toml says why). Each file is also a program of its own; its `main` is unused here.
//! `bump` and `slider_crank_inverse` are modules of `linear_models` and `flywheel_engine`, which
//! build on them (a second `mod` would compile them twice).

#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/double_a_arm.rs"]
pub mod double_a_arm;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/double_wishbone_3d.rs"]
pub mod double_wishbone_3d;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/excavator.rs"]
pub mod excavator;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/filmstrip.rs"]
pub mod filmstrip;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/flywheel_engine.rs"]
pub mod flywheel_engine;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/four_bar.rs"]
pub mod four_bar;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/free_four_bar.rs"]
pub mod free_four_bar;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/gyroscope.rs"]
pub mod gyroscope;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/linear_models.rs"]
pub mod linear_models;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/macpherson.rs"]
pub mod macpherson;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/pumped_pendulum.rs"]
pub mod pumped_pendulum;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/rssr.rs"]
pub mod rssr;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/slider_crank.rs"]
pub mod slider_crank;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/spatial_slider_crank.rs"]
pub mod spatial_slider_crank;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/stewart_platform.rs"]
pub mod stewart_platform;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/suspension_dynamics.rs"]
pub mod suspension_dynamics;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/variable_pendulum.rs"]
pub mod variable_pendulum;
#[allow(dead_code)] // `main`, and what only `main` uses
#[path = "../../examples/web_cutter.rs"]
pub mod web_cutter;
pub use flywheel_engine::slider_crank_inverse;
pub use linear_models::bump;
