// The free spatial pendulum chain of 4 links of `spatial_chain4.rs` in joint coordinates
// (`joint_coordinates;`): each spherical joint carries its link by a quaternion — as MuJoCo's
// ball joints do — so the chain has 16 coordinates, 12 velocities and no constraint rows. The
// statements below are the body-coordinate file's with that one line added.
mbd::mechanism! {
    /// Free spatial pendulum chain of 4 links on spherical joints in joint coordinates (benchmark).
    pub SpatialChain4Joint {
        spatial;
        joint_coordinates;
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
