//! Runs every example of mbd in turn: the README's first command,
//! `cargo run --release --example showcase`. Then writes an animation of each example's main
//! mechanism to `target/showcase/<name>.html` (a page) and `<name>.svg` (an animated SVG),
//! relative to the current directory.

// Every example, compiled once in the library mbd-examples (which the tests share); each is also
// a program of its own (`cargo run --example four_bar`).
use mbd_examples::{
    bump, double_a_arm, double_wishbone_3d, elliptical, engine, excavator, filmstrip, flywheel_engine, four_bar, free_four_bar, gyroscope,
    head_neck, linear_models, macpherson, mountain_bike, pumped_pendulum, rssr, sled_test, slider_crank, slider_crank_inverse,
    spatial_slider_crank, stewart_platform, suspension_dynamics, swing, variable_pendulum, web_cutter, windshield_wiper,
};

#[cfg(test)]
#[path = "showcase/checks.rs"]
mod checks;

/// A function writing one example's animation.
type Animate = fn() -> Result<mbd::Animation, Box<dyn std::error::Error>>;

/// The animation of each example's main mechanism (checked by `checks::every_example_animates`).
const ANIMATIONS: [(&str, Animate); 27] = [
    ("slider_crank", slider_crank::animation),
    ("four_bar", four_bar::animation),
    ("variable_pendulum", variable_pendulum::animation),
    ("filmstrip", filmstrip::animation),
    ("web_cutter", web_cutter::animation),
    ("double_a_arm", double_a_arm::animation),
    ("macpherson", macpherson::animation),
    ("slider_crank_inverse", slider_crank_inverse::animation),
    ("flywheel_engine", flywheel_engine::animation),
    ("suspension_dynamics", suspension_dynamics::animation),
    ("pumped_pendulum", pumped_pendulum::animation),
    ("free_four_bar", free_four_bar::animation),
    ("gyroscope", gyroscope::animation),
    ("rssr", rssr::animation),
    ("spatial_slider_crank", spatial_slider_crank::animation),
    ("double_wishbone_3d", double_wishbone_3d::animation),
    ("stewart_platform", stewart_platform::animation),
    ("excavator", excavator::animation),
    ("bump", bump::animation),
    ("linear_models", linear_models::animation),
    ("swing", swing::animation),
    ("windshield_wiper", windshield_wiper::animation),
    ("engine", engine::animation),
    ("elliptical", elliptical::animation),
    ("head_neck", head_neck::animation),
    ("sled_test", sled_test::animation),
    ("mountain_bike", mountain_bike::animation),
];

fn main() {
    type Run = fn() -> Result<(), Box<dyn std::error::Error>>;
    let runs: [(&str, Run); 27] = [
        ("slider_crank", || Ok(slider_crank::run(true).map(drop)?)),
        ("four_bar", || Ok(four_bar::run(true).map(drop)?)),
        ("variable_pendulum", || Ok(variable_pendulum::run(true).map(drop)?)),
        ("filmstrip", || Ok(filmstrip::run(true).map(drop)?)),
        ("web_cutter", || Ok(web_cutter::run(true).map(drop)?)),
        ("double_a_arm", || Ok(double_a_arm::run(true).map(drop)?)),
        ("macpherson", || Ok(macpherson::run(true).map(drop)?)),
        ("slider_crank_inverse", || slider_crank_inverse::run(true).map(drop)),
        ("flywheel_engine", || flywheel_engine::run(true).map(drop)),
        ("suspension_dynamics", || suspension_dynamics::run(true).map(drop)),
        ("pumped_pendulum", || pumped_pendulum::run(true).map(drop)),
        ("free_four_bar", || free_four_bar::run(true).map(drop)),
        ("gyroscope", || gyroscope::run(true).map(drop)),
        ("rssr", || rssr::run(true).map(drop)),
        ("spatial_slider_crank", || spatial_slider_crank::run(true).map(drop)),
        ("double_wishbone_3d", || Ok(double_wishbone_3d::run(true).map(drop)?)),
        ("stewart_platform", || stewart_platform::run(true).map(drop)),
        ("excavator", || excavator::run(true).map(drop)),
        ("bump", || bump::run(true).map(drop)),
        ("linear_models", || linear_models::run(true).map(drop)),
        ("swing", || swing::run(true).map(drop)),
        ("windshield_wiper", || windshield_wiper::run(true).map(drop)),
        ("engine", || engine::run(true).map(drop)),
        ("elliptical", || elliptical::run(true).map(drop)),
        ("head_neck", || head_neck::run(true).map(drop)),
        ("sled_test", || sled_test::run(true).map(drop)),
        ("mountain_bike", || mountain_bike::run(true).map(drop)),
    ];
    let mut failed = 0;
    for (name, run) in runs {
        println!("\n=== {name} ===");
        if let Err(e) = run() {
            eprintln!("{name}: {e}");
            failed += 1;
        }
    }
    // An animation of each example's main mechanism, as a page and as an animated SVG.
    let dir = std::path::Path::new("target/showcase");
    println!("\n=== animations ===");
    for (name, animate) in ANIMATIONS {
        let (html, svg) = (dir.join(format!("{name}.html")), dir.join(format!("{name}.svg")));
        let write = || -> Result<usize, Box<dyn std::error::Error>> {
            let animation = animate()?;
            std::fs::create_dir_all(dir)?;
            animation.write_html(&html)?;
            animation.write_svg(&svg)?;
            Ok(animation.len())
        };
        match write() {
            Ok(frames) => println!("{name}: {frames} frames → {} and {}", html.display(), svg.display()),
            Err(e) => {
                eprintln!("{name} (animation): {e}");
                failed += 1;
            }
        }
    }
    if failed > 0 {
        std::process::exit(1);
    }
}
