// Issue 39's case (C), the heavy-top benchmark (Brüls, Cardona & Arnold 2012): 15 kg, its
// centre of mass 1 m along its symmetry axis y′ from a fixed point, J = diag(0.234375, 0.46875,
// 0.234375) kg·m² about the centre of mass, started at R = I with ω′ = (0, 150, −4.61538) rad/s
// (the centre of mass at ω × (0, 1, 0) = (4.61538, 0, 0) m/s), gravity 9.81 m/s² along −z, 2 s.
mbd::mechanism! {
    /// The heavy-top benchmark (issue 39, case C).
    pub HeavyTop {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body top { mass: 15.0, inertia: [0.234375, 0.46875, 0.234375], at: [0.0, 1.0, 0.0], velocity: [4.61538, 0.0, 0.0], omega: [0.0, 150.0, -4.61538] }
        spherical ground[0.0, 0.0, 0.0] ~ top[0.0, -1.0, 0.0];
    }
}
