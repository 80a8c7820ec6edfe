// A free pendulum chain of 4 links, each 0.1 m long and 0.1 kg, pinned end to end and to
// ground, hanging under gravity from a horizontal start (12 coordinates, 8 constraint rows,
// 4 degrees of freedom). Generated once by a short Python loop and committed as plain DSL.
mbd::mechanism! {
    /// Free pendulum chain of 4 links (benchmark).
    pub PendulumChain4 {
        gravity [0.0, -9.81];
        body l0 { mass: 0.1, inertia: 8.3333e-5, at: [0.05, 0.0, 0.0] }
        body l1 { mass: 0.1, inertia: 8.3333e-5, at: [0.15, 0.0, 0.0] }
        body l2 { mass: 0.1, inertia: 8.3333e-5, at: [0.25, 0.0, 0.0] }
        body l3 { mass: 0.1, inertia: 8.3333e-5, at: [0.35, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ l0[-0.05, 0.0];
        revolute l0[0.05, 0.0] ~ l1[-0.05, 0.0];
        revolute l1[0.05, 0.0] ~ l2[-0.05, 0.0];
        revolute l2[0.05, 0.0] ~ l3[-0.05, 0.0];
    }
}
