// A spatial slider-crank (RSUP): the crank turns about z at the origin, driven at ω; a rod with
// mass, on a spherical joint at the crank pin and a universal joint at the slider (whose cross
// fixes the rod's spin about its own axis); the slider runs along x on a guide offset by
// (ey, ez) from the crank's plane (21 coordinates, 18 velocities, 18 constraint rows with the
// driver, 0 degrees of freedom) — the kinematics benchmark's small spatial mechanism.
mbd::mechanism! {
    /// Driven spatial slider-crank (benchmark).
    pub SpatialSliderCrank {
        spatial;
        params { a: 0.1, len: 0.35, ey: 0.05, ez: 0.08, omega: 3.0 }
        body crank { mass: 1.0, inertia: [1.0e-3, 1.0e-3, 2.0e-3] }
        body rod { mass: 2.0, inertia: [1.0e-4, 0.0205, 0.0205], at: [0.2685, 0.025, 0.04], angles: [0.147, -0.23, 0.0] }
        body slider { mass: 0.5, inertia: [1.0e-4, 1.0e-4, 1.0e-4], at: [0.437, ey, ez] }
        revolute crankshaft: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        spherical crank[a, 0.0, 0.0] ~ rod[-len / 2.0, 0.0, 0.0];
        universal rod[len / 2.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ slider[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0];
        translational guide: ground[0.0, ey, ez] along [1.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        drive crankshaft.angle = omega * t;
    }
}
