//! The scenes' mechanisms (`src/bin/scenes.rs` times them and its tests check what each scene
//! costs): a planar suspension corner and a 13-body vehicle, each with scenes that leave out one
//! effect at a time.
//!
//! They live in this library because the vehicle's five types are the costliest code of the
//! workspace to compile: about 140 s of one core in CI's debug build with clippy's lints
//! (2026-11-28). In the binary they were compiled with its tests, a unit nothing depends on,
//! which cargo started last and ran alone with the other core idle; a library is a dependency,
//! which cargo builds early beside the rest. (`test = false` in Cargo.toml: the library has no
//! tests of its own to compile them again for.)

use mbd::prelude::*;

mechanism! {
    /// A planar double A-arm corner on a rig (the chassis is ground; Nikravesh ch. 8 style, the
    /// linkage of `examples/suspension_dynamics.rs`): coil spring and shock absorber from the lower
    /// arm to the chassis, a linear tyre at the contact patch, viscous friction in the arm pivots.
    pub QuarterCar {
        params { k_s: 30000.0, free_length: 0.61, c_s: 1500.0, k_t: 200000.0, c_t: 100.0, c_pivot: 2.0 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.375, 0.14, 0.0] }
        body upper   { mass: 2.5, inertia: 0.02, at: [0.41, 0.46, 0.0] }
        body knuckle { mass: 18.0, inertia: 0.60, at: [0.62, 0.30, 0.0] }
        revolute lower_pivot: ground[0.20, 0.15] ~ lower[-0.175, 0.01] { viscous: c_pivot };
        revolute upper_pivot: ground[0.30, 0.45] ~ upper[-0.11, -0.01] { viscous: c_pivot };
        revolute lower_ball: lower[0.175, -0.01] ~ knuckle[-0.07, -0.17];
        revolute upper_ball: upper[0.11, 0.01] ~ knuckle[-0.10, 0.17];
        spring coil: lower[0.1, 0.0] ~ ground[0.45, 0.60] { k: k_s, length: free_length };
        damper shock: lower[0.1, 0.0] ~ ground[0.45, 0.60] { c: c_s };
        force tyre: knuckle[0.0, -0.30] = [0.0, k_t * (0.0 - (knuckle.y - 0.3 * cos(knuckle.phi))) - c_t * knuckle.vy];
        scene QuarterCarNoFriction without friction;
        scene QuarterCarNoShock without shock;
        scene QuarterCarNoCoil without coil;
        scene QuarterCarNoTyre without tyre;
        scene QuarterCarNoGravity without gravity;
        scene QuarterCarBare without friction, shock, coil, tyre, gravity;
    }
}

mechanism! {
    /// A vehicle of four double-wishbone corners (the corner of `examples/double_wishbone_3d.rs`,
    /// the right ones its mirror image in y) on a free chassis: lower and upper arms hinged to the
    /// chassis with viscous pivot friction, ball joints to the upright, a tie rod to the chassis,
    /// coil spring and shock absorber from the lower arm to the chassis, and a vertical linear
    /// tyre at the wheel centre. Chassis frame at its centre of mass, 0.55 m above the road.
    pub Vehicle {
        spatial;
        params { k_s: 35000.0, free_length: 0.67, c_s: 3000.0, k_t: 250000.0, c_t: 200.0, radius: 0.3126, c_pivot: 5.0 }
        gravity [0.0, 0.0, -9.81];
        body chassis { mass: 1200.0, inertia: [450.0, 1700.0, 1900.0], at: [0.0, 0.0, 0.55] }
        part corner(x0) {
            body lower { mass: 3.0, inertia: [0.06, 0.01, 0.06], at: [x0, 0.475, 0.14] }
            body upper { mass: 2.0, inertia: [0.02, 0.005, 0.02], at: [x0 - 0.009, 0.505, 0.46] }
            body upright { mass: 15.0, inertia: [0.5, 0.8, 0.5], at: [x0, 0.76, 0.30] }
            revolute lower_pivot: chassis[x0, 0.25, 0.15 - 0.55] along [1.0, 0.0, 0.0]
                ~ lower[0.0, 0.25 - 0.475, 0.01] along [1.0, 0.0, 0.0] { viscous: c_pivot };
            revolute upper_pivot: chassis[x0, 0.35, 0.45 - 0.55] along [1.0, 0.0, 0.0]
                ~ upper[0.009, 0.35 - 0.505, -0.01] along [1.0, 0.0, 0.0] { viscous: c_pivot };
            spherical lower_ball: lower[0.0, 0.70 - 0.475, -0.01] ~ upright[0.0, 0.70 - 0.76, -0.17];
            spherical upper_ball: upper[-0.009, 0.66 - 0.505, 0.01] ~ upright[-0.018, 0.66 - 0.76, 0.17];
            distance tie_rod: chassis[x0 - 0.13, 0.25, 0.15 - 0.55] ~ upright[-0.13, 0.70 - 0.76, -0.17]
                { length: sqrt(0.45^2 + 0.02^2) };
            spring coil: lower[0.0, 0.60 - 0.475, 0.0] ~ chassis[x0, 0.55, 0.70 - 0.55] { k: k_s, length: free_length };
            damper shock: lower[0.0, 0.60 - 0.475, 0.0] ~ chassis[x0, 0.55, 0.70 - 0.55] { c: c_s };
            force tyre: upright[0.0, 0.0, 0.0] = [0.0, 0.0, k_t * (radius - upright.z) - c_t * upright.vz];
        }
        corner front_left(x0: 1.3);
        corner front_right(x0: 1.3) mirrored y;
        corner rear_left(x0: -1.4);
        corner rear_right(x0: -1.4) mirrored y;
        scene VehicleNoFriction without friction;
        scene VehicleNoShock without shock;
        scene VehicleBare without friction, shock, coil, tyre, gravity;
    }
}
