// Issue 39's case (A), a stiff spinning linkage: the study's slider-crank with a 2 kg·m²
// flywheel turning at 5 rev/s (31.4 rad/s), whose piston carries a 0.1 kg follower on a short
// guide, held 2 cm ahead of it by a stiff spring-damper (1e7 N/m, 2 200 N·s/m). The follower's
// mode against the piston, √(k/m) ≈ 1e4 rad/s, is overdamped (damping ratio about 1.1 on the
// follower alone, more where the piston is light): its eigenvalues are real, the fastest about
// −1.6e4 1/s at the start (`linearize`; checked in tests/integrators.rs), within the issue's
// 1e4 ± 2×. 10 s under gravity.
mbd::mechanism! {
    /// A flywheel slider-crank whose piston carries a follower on a stiff, overdamped
    /// spring-damper (issue 39, case A).
    pub StiffFlywheel {
        params { k: 1.0e7, c: 2200.0 }
        gravity [0.0, -9.81];
        body crank    { mass: 5.0, inertia: 2.0, at: [0.0, 0.0, 0.0], velocity: [0.0, 0.0, 31.41592653589793] }
        body rod      { mass: 0.8, inertia: 3.0e-3, at: [0.15, 0.0, 0.0] }
        body piston   { mass: 0.5, inertia: 1.0e-4, at: [0.25, 0.0, 0.0] }
        body follower { mass: 0.1, inertia: 1.0e-5, at: [0.27, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute crankpin: crank[0.05, 0.0] ~ rod[-0.1, 0.0];
        revolute wristpin: rod[0.1, 0.0] ~ piston[0.0, 0.0];
        translational bore: piston[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        translational guide: follower[0.0, 0.0] along [1.0, 0.0] ~ piston[0.0, 0.0] along [1.0, 0.0];
        spring mount: piston[0.0, 0.0] ~ follower[0.0, 0.0] { k: k, length: 0.02, c: c };
    }
}
