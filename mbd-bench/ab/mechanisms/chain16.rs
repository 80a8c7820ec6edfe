// A chain of 16 links, each 0.1 m long, pinned end to end and to ground; every joint angle is
// driven, so the chain is kinematically determined (48 coordinates, 48 constraint rows).
// Generated once by a short Python loop and committed as plain DSL, so it reads like any user's
// mechanism.
mbd::mechanism! {
    /// Chain of 16 driven links (benchmark).
    pub Chain16 {
        body l0 { mass: 0.1, inertia: 1.0e-4, at: [0.05, 0.0, 0.0] }
        body l1 { mass: 0.1, inertia: 1.0e-4, at: [0.15, 0.0, 0.0] }
        body l2 { mass: 0.1, inertia: 1.0e-4, at: [0.25, 0.0, 0.0] }
        body l3 { mass: 0.1, inertia: 1.0e-4, at: [0.35, 0.0, 0.0] }
        body l4 { mass: 0.1, inertia: 1.0e-4, at: [0.45, 0.0, 0.0] }
        body l5 { mass: 0.1, inertia: 1.0e-4, at: [0.55, 0.0, 0.0] }
        body l6 { mass: 0.1, inertia: 1.0e-4, at: [0.65, 0.0, 0.0] }
        body l7 { mass: 0.1, inertia: 1.0e-4, at: [0.75, 0.0, 0.0] }
        body l8 { mass: 0.1, inertia: 1.0e-4, at: [0.85, 0.0, 0.0] }
        body l9 { mass: 0.1, inertia: 1.0e-4, at: [0.95, 0.0, 0.0] }
        body l10 { mass: 0.1, inertia: 1.0e-4, at: [1.05, 0.0, 0.0] }
        body l11 { mass: 0.1, inertia: 1.0e-4, at: [1.15, 0.0, 0.0] }
        body l12 { mass: 0.1, inertia: 1.0e-4, at: [1.25, 0.0, 0.0] }
        body l13 { mass: 0.1, inertia: 1.0e-4, at: [1.35, 0.0, 0.0] }
        body l14 { mass: 0.1, inertia: 1.0e-4, at: [1.45, 0.0, 0.0] }
        body l15 { mass: 0.1, inertia: 1.0e-4, at: [1.55, 0.0, 0.0] }
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
        drive l0.phi = 0.5 * sin(t);
        drive angle(l0, l1) = 0.1 * sin(t + 1.0);
        drive angle(l1, l2) = 0.1 * sin(t + 2.0);
        drive angle(l2, l3) = 0.1 * sin(t + 3.0);
        drive angle(l3, l4) = 0.1 * sin(t + 4.0);
        drive angle(l4, l5) = 0.1 * sin(t + 5.0);
        drive angle(l5, l6) = 0.1 * sin(t + 6.0);
        drive angle(l6, l7) = 0.1 * sin(t + 7.0);
        drive angle(l7, l8) = 0.1 * sin(t + 8.0);
        drive angle(l8, l9) = 0.1 * sin(t + 9.0);
        drive angle(l9, l10) = 0.1 * sin(t + 10.0);
        drive angle(l10, l11) = 0.1 * sin(t + 11.0);
        drive angle(l11, l12) = 0.1 * sin(t + 12.0);
        drive angle(l12, l13) = 0.1 * sin(t + 13.0);
        drive angle(l13, l14) = 0.1 * sin(t + 14.0);
        drive angle(l14, l15) = 0.1 * sin(t + 15.0);
    }
}
