use mbd::prelude::*;

mechanism! {
    Ram {
        body ram { mass: 1.0, inertia: 0.1 }
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ ram[0.0, 0.0] along [1.0, 0.0];
        force ram[0.0, 0.0] = [if ram.x == 0.5 { -100.0 } else { 0.0 }, 0.0];
    }
}
fn main() {}
