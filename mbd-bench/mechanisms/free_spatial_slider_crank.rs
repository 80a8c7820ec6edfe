// The spatial slider-crank of spatial_slider_crank.rs without its driver: free under gravity
// along −y (in the crank's plane), released at rest with the crank at 30° (21 coordinates,
// 18 velocities, 17 constraint rows, 1 degree of freedom) — the forward-dynamics benchmark's
// small spatial mechanism.
mbd::mechanism! {
    /// Free spatial slider-crank under gravity (benchmark).
    pub FreeSpatialSliderCrank {
        spatial;
        params { a: 0.1, len: 0.35, ey: 0.05, ez: 0.08 }
        gravity [0.0, -9.81, 0.0];
        body crank { mass: 1.0, inertia: [1.0e-3, 1.0e-3, 2.0e-3], axis_angle: [0.0, 0.0, 1.0, 0.5236] }
        body rod { mass: 2.0, inertia: [1.0e-4, 0.0205, 0.0205], at: [0.2569, 0.05, 0.04], angles: [0.0, -0.23, 0.0] }
        body slider { mass: 0.5, inertia: [1.0e-4, 1.0e-4, 1.0e-4], at: [0.4272, ey, ez] }
        revolute crankshaft: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        spherical crank[a, 0.0, 0.0] ~ rod[-len / 2.0, 0.0, 0.0];
        universal rod[len / 2.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ slider[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0];
        translational guide: ground[0.0, ey, ez] along [1.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
    }
}
