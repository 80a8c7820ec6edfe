use mbd::mechanism;

mechanism! {
    PinFriction {
        body rod { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0] { coulomb: 0.2 };
    }
}

fn main() {}
