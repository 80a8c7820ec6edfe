// A free spatial pendulum chain of 4 links, each a bar 0.1 m long and 0.1 kg (inertia of a thin
// rod about its centre, m L²/12 = 8.333e-5 kg·m² across the bar, and 1e-6 kg·m² about its axis, a
// 4.5 mm rod, so that M is regular), on a spherical joint to the previous link and the first to
// ground; gravity 9.81 m/s² along −z (28 coordinates, 24 velocities, 12 constraint rows,
// 12 degrees of freedom). It starts at rest from a horizontal arc: link k points along
// (cos θk, sin θk, 0), θk = 0.2 k rad, so the fall is three-dimensional. The same chain is built
// for MuJoCo by mbd-bench/peers/mujoco_chain.py (nested bodies with ball joints). Generated once
// by a short Python loop and committed as plain DSL.
mbd::mechanism! {
    /// Free spatial pendulum chain of 4 links on spherical joints (benchmark).
    pub SpatialChain4 {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body l0 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.05, 0.0, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.0] }
        body l1 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.14900332889206208, 0.009933466539753062, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.2] }
        body l2 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.24405970748426845, 0.039337850194938656, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.4] }
        body l3 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.3313795379298966, 0.08704089098012296, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.6] }
        point l3.tip = [0.05, 0.0, 0.0];
        spherical ground[0.0, 0.0, 0.0] ~ l0[-0.05, 0.0, 0.0];
        spherical l0[0.05, 0.0, 0.0] ~ l1[-0.05, 0.0, 0.0];
        spherical l1[0.05, 0.0, 0.0] ~ l2[-0.05, 0.0, 0.0];
        spherical l2[0.05, 0.0, 0.0] ~ l3[-0.05, 0.0, 0.0];
    }
}
