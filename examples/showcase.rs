//! Runs every example of mbd in turn: the README's first command,
//! `cargo run --release --example showcase`.

#[path = "double_a_arm.rs"]
mod double_a_arm;
#[path = "filmstrip.rs"]
mod filmstrip;
#[path = "four_bar.rs"]
mod four_bar;
#[path = "macpherson.rs"]
mod macpherson;
#[path = "slider_crank.rs"]
mod slider_crank;
#[path = "slider_crank_inverse.rs"]
mod slider_crank_inverse;
#[path = "variable_pendulum.rs"]
mod variable_pendulum;
#[path = "web_cutter.rs"]
mod web_cutter;

fn main() {
    let runs: [(&str, fn() -> Result<(), mbd::KinematicError>); 8] = [
        ("slider_crank", || slider_crank::run(true).map(drop)),
        ("four_bar", || four_bar::run(true).map(drop)),
        ("variable_pendulum", || variable_pendulum::run(true).map(drop)),
        ("filmstrip", || filmstrip::run(true).map(drop)),
        ("web_cutter", || web_cutter::run(true).map(drop)),
        ("double_a_arm", || double_a_arm::run(true).map(drop)),
        ("macpherson", || macpherson::run(true).map(drop)),
        ("slider_crank_inverse", || slider_crank_inverse::run(true).map(drop)),
    ];
    let mut failed = 0;
    for (name, run) in runs {
        println!("\n=== {name} ===");
        if let Err(e) = run() {
            eprintln!("{name}: {e}");
            failed += 1;
        }
    }
    if failed > 0 {
        std::process::exit(1);
    }
}
