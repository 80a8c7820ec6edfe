// A free spatial pendulum chain of 16 links, each a bar 0.1 m long and 0.1 kg (inertia of a thin
// rod about its centre, m L²/12 = 8.333e-5 kg·m² across the bar, and 1e-6 kg·m² about its axis, a
// 4.5 mm rod, so that M is regular), on a spherical joint to the previous link and the first to
// ground; gravity 9.81 m/s² along −z (112 coordinates, 96 velocities, 48 constraint rows,
// 48 degrees of freedom). It starts at rest from a horizontal arc: link k points along
// (cos θk, sin θk, 0), θk = 0.2 k rad, so the fall is three-dimensional. The same chain is built
// for MuJoCo by mbd-bench/peers/mujoco_chain.py (nested bodies with ball joints). Generated once
// by a short Python loop and committed as plain DSL.
mbd::mechanism! {
    /// Free spatial pendulum chain of 16 links on spherical joints (benchmark).
    pub SpatialChain16 {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body l0 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.05, 0.0, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.0] }
        body l1 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.14900332889206208, 0.009933466539753062, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.2] }
        body l2 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.24405970748426845, 0.039337850194938656, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.4] }
        body l3 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.3313795379298966, 0.08704089098012296, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.6] }
        body l4 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.40748165414273885, 0.1511408191948509, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.8] }
        body l5 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.46933210490350413, 0.22908217298022185, 0.0], axis_angle: [0.0, 0.0, 1.0, 1.0] }
        body l6 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.5144651079207448, 0.317757676518978, 0.0], axis_angle: [0.0, 0.0, 1.0, 1.2] }
        body l7 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.5410813527895905, 0.41363211731676236, 0.0], axis_angle: [0.0, 0.0, 1.0, 1.4] }
        body l8 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.548119733819538, 0.5128832839682607, 0.0], axis_angle: [0.0, 0.0, 1.0, 1.6] }
        body l9 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.5352996529698193, 0.6115543456642456, 0.0], axis_angle: [0.0, 0.0, 1.0, 1.8] }
        body l10 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.5031322064078078, 0.7057115985494394, 0.0], axis_angle: [0.0, 0.0, 1.0, 2.0] }
        body l11 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.45289980871768337, 0.791601290081703, 0.0], axis_angle: [0.0, 0.0, 1.0, 2.2] }
        body l12 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.3866050670778538, 0.86579926930024, 0.0], axis_angle: [0.0, 0.0, 1.0, 2.4] }
        body l13 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.30689094363234415, 0.9253474969188707, 0.0], axis_angle: [0.0, 0.0, 1.0, 2.6] }
        body l14 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.21693538893046388, 0.9678719730177391, 0.0], axis_angle: [0.0, 0.0, 1.0, 2.8] }
        body l15 { mass: 0.1, inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5], at: [0.12032464706700868, 0.9916773809285278, 0.0], axis_angle: [0.0, 0.0, 1.0, 3.0] }
        point l15.tip = [0.05, 0.0, 0.0];
        spherical ground[0.0, 0.0, 0.0] ~ l0[-0.05, 0.0, 0.0];
        spherical l0[0.05, 0.0, 0.0] ~ l1[-0.05, 0.0, 0.0];
        spherical l1[0.05, 0.0, 0.0] ~ l2[-0.05, 0.0, 0.0];
        spherical l2[0.05, 0.0, 0.0] ~ l3[-0.05, 0.0, 0.0];
        spherical l3[0.05, 0.0, 0.0] ~ l4[-0.05, 0.0, 0.0];
        spherical l4[0.05, 0.0, 0.0] ~ l5[-0.05, 0.0, 0.0];
        spherical l5[0.05, 0.0, 0.0] ~ l6[-0.05, 0.0, 0.0];
        spherical l6[0.05, 0.0, 0.0] ~ l7[-0.05, 0.0, 0.0];
        spherical l7[0.05, 0.0, 0.0] ~ l8[-0.05, 0.0, 0.0];
        spherical l8[0.05, 0.0, 0.0] ~ l9[-0.05, 0.0, 0.0];
        spherical l9[0.05, 0.0, 0.0] ~ l10[-0.05, 0.0, 0.0];
        spherical l10[0.05, 0.0, 0.0] ~ l11[-0.05, 0.0, 0.0];
        spherical l11[0.05, 0.0, 0.0] ~ l12[-0.05, 0.0, 0.0];
        spherical l12[0.05, 0.0, 0.0] ~ l13[-0.05, 0.0, 0.0];
        spherical l13[0.05, 0.0, 0.0] ~ l14[-0.05, 0.0, 0.0];
        spherical l14[0.05, 0.0, 0.0] ~ l15[-0.05, 0.0, 0.0];
    }
}
