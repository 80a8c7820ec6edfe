// A free pendulum chain of 16 links, each 0.1 m long and 0.1 kg, pinned end to end and to
// ground, hanging under gravity from a horizontal start (48 coordinates, 32 constraint rows,
// 16 degrees of freedom). Generated once by a short Python loop and committed as plain DSL.
mbd::mechanism! {
    /// Free pendulum chain of 16 links (benchmark).
    pub PendulumChain16 {
        gravity [0.0, -9.81];
        body l0 { mass: 0.1, inertia: 8.3333e-5, at: [0.05, 0.0, 0.0] }
        body l1 { mass: 0.1, inertia: 8.3333e-5, at: [0.15, 0.0, 0.0] }
        body l2 { mass: 0.1, inertia: 8.3333e-5, at: [0.25, 0.0, 0.0] }
        body l3 { mass: 0.1, inertia: 8.3333e-5, at: [0.35, 0.0, 0.0] }
        body l4 { mass: 0.1, inertia: 8.3333e-5, at: [0.45, 0.0, 0.0] }
        body l5 { mass: 0.1, inertia: 8.3333e-5, at: [0.55, 0.0, 0.0] }
        body l6 { mass: 0.1, inertia: 8.3333e-5, at: [0.65, 0.0, 0.0] }
        body l7 { mass: 0.1, inertia: 8.3333e-5, at: [0.75, 0.0, 0.0] }
        body l8 { mass: 0.1, inertia: 8.3333e-5, at: [0.85, 0.0, 0.0] }
        body l9 { mass: 0.1, inertia: 8.3333e-5, at: [0.95, 0.0, 0.0] }
        body l10 { mass: 0.1, inertia: 8.3333e-5, at: [1.05, 0.0, 0.0] }
        body l11 { mass: 0.1, inertia: 8.3333e-5, at: [1.15, 0.0, 0.0] }
        body l12 { mass: 0.1, inertia: 8.3333e-5, at: [1.25, 0.0, 0.0] }
        body l13 { mass: 0.1, inertia: 8.3333e-5, at: [1.35, 0.0, 0.0] }
        body l14 { mass: 0.1, inertia: 8.3333e-5, at: [1.45, 0.0, 0.0] }
        body l15 { mass: 0.1, inertia: 8.3333e-5, at: [1.55, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ l0[-0.05, 0.0];
        revolute l0[0.05, 0.0] ~ l1[-0.05, 0.0];
        revolute l1[0.05, 0.0] ~ l2[-0.05, 0.0];
        revolute l2[0.05, 0.0] ~ l3[-0.05, 0.0];
        revolute l3[0.05, 0.0] ~ l4[-0.05, 0.0];
        revolute l4[0.05, 0.0] ~ l5[-0.05, 0.0];
        revolute l5[0.05, 0.0] ~ l6[-0.05, 0.0];
        revolute l6[0.05, 0.0] ~ l7[-0.05, 0.0];
        revolute l7[0.05, 0.0] ~ l8[-0.05, 0.0];
        revolute l8[0.05, 0.0] ~ l9[-0.05, 0.0];
        revolute l9[0.05, 0.0] ~ l10[-0.05, 0.0];
        revolute l10[0.05, 0.0] ~ l11[-0.05, 0.0];
        revolute l11[0.05, 0.0] ~ l12[-0.05, 0.0];
        revolute l12[0.05, 0.0] ~ l13[-0.05, 0.0];
        revolute l13[0.05, 0.0] ~ l14[-0.05, 0.0];
        revolute l14[0.05, 0.0] ~ l15[-0.05, 0.0];
    }
}
