// A free pendulum chain of 64 links, each 0.1 m long and 0.1 kg, pinned end to end and to
// ground, hanging under gravity from a horizontal start (192 coordinates, 128 constraint rows,
// 64 degrees of freedom). Generated once by a short Python loop and committed as plain DSL.
mbd::mechanism! {
    /// Free pendulum chain of 64 links (benchmark).
    pub PendulumChain64 {
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
        body l16 { mass: 0.1, inertia: 8.3333e-5, at: [1.65, 0.0, 0.0] }
        body l17 { mass: 0.1, inertia: 8.3333e-5, at: [1.75, 0.0, 0.0] }
        body l18 { mass: 0.1, inertia: 8.3333e-5, at: [1.85, 0.0, 0.0] }
        body l19 { mass: 0.1, inertia: 8.3333e-5, at: [1.95, 0.0, 0.0] }
        body l20 { mass: 0.1, inertia: 8.3333e-5, at: [2.05, 0.0, 0.0] }
        body l21 { mass: 0.1, inertia: 8.3333e-5, at: [2.15, 0.0, 0.0] }
        body l22 { mass: 0.1, inertia: 8.3333e-5, at: [2.25, 0.0, 0.0] }
        body l23 { mass: 0.1, inertia: 8.3333e-5, at: [2.35, 0.0, 0.0] }
        body l24 { mass: 0.1, inertia: 8.3333e-5, at: [2.45, 0.0, 0.0] }
        body l25 { mass: 0.1, inertia: 8.3333e-5, at: [2.55, 0.0, 0.0] }
        body l26 { mass: 0.1, inertia: 8.3333e-5, at: [2.65, 0.0, 0.0] }
        body l27 { mass: 0.1, inertia: 8.3333e-5, at: [2.75, 0.0, 0.0] }
        body l28 { mass: 0.1, inertia: 8.3333e-5, at: [2.85, 0.0, 0.0] }
        body l29 { mass: 0.1, inertia: 8.3333e-5, at: [2.95, 0.0, 0.0] }
        body l30 { mass: 0.1, inertia: 8.3333e-5, at: [3.05, 0.0, 0.0] }
        body l31 { mass: 0.1, inertia: 8.3333e-5, at: [3.15, 0.0, 0.0] }
        body l32 { mass: 0.1, inertia: 8.3333e-5, at: [3.25, 0.0, 0.0] }
        body l33 { mass: 0.1, inertia: 8.3333e-5, at: [3.35, 0.0, 0.0] }
        body l34 { mass: 0.1, inertia: 8.3333e-5, at: [3.45, 0.0, 0.0] }
        body l35 { mass: 0.1, inertia: 8.3333e-5, at: [3.55, 0.0, 0.0] }
        body l36 { mass: 0.1, inertia: 8.3333e-5, at: [3.65, 0.0, 0.0] }
        body l37 { mass: 0.1, inertia: 8.3333e-5, at: [3.75, 0.0, 0.0] }
        body l38 { mass: 0.1, inertia: 8.3333e-5, at: [3.85, 0.0, 0.0] }
        body l39 { mass: 0.1, inertia: 8.3333e-5, at: [3.95, 0.0, 0.0] }
        body l40 { mass: 0.1, inertia: 8.3333e-5, at: [4.05, 0.0, 0.0] }
        body l41 { mass: 0.1, inertia: 8.3333e-5, at: [4.15, 0.0, 0.0] }
        body l42 { mass: 0.1, inertia: 8.3333e-5, at: [4.25, 0.0, 0.0] }
        body l43 { mass: 0.1, inertia: 8.3333e-5, at: [4.35, 0.0, 0.0] }
        body l44 { mass: 0.1, inertia: 8.3333e-5, at: [4.45, 0.0, 0.0] }
        body l45 { mass: 0.1, inertia: 8.3333e-5, at: [4.55, 0.0, 0.0] }
        body l46 { mass: 0.1, inertia: 8.3333e-5, at: [4.65, 0.0, 0.0] }
        body l47 { mass: 0.1, inertia: 8.3333e-5, at: [4.75, 0.0, 0.0] }
        body l48 { mass: 0.1, inertia: 8.3333e-5, at: [4.85, 0.0, 0.0] }
        body l49 { mass: 0.1, inertia: 8.3333e-5, at: [4.95, 0.0, 0.0] }
        body l50 { mass: 0.1, inertia: 8.3333e-5, at: [5.05, 0.0, 0.0] }
        body l51 { mass: 0.1, inertia: 8.3333e-5, at: [5.15, 0.0, 0.0] }
        body l52 { mass: 0.1, inertia: 8.3333e-5, at: [5.25, 0.0, 0.0] }
        body l53 { mass: 0.1, inertia: 8.3333e-5, at: [5.35, 0.0, 0.0] }
        body l54 { mass: 0.1, inertia: 8.3333e-5, at: [5.45, 0.0, 0.0] }
        body l55 { mass: 0.1, inertia: 8.3333e-5, at: [5.55, 0.0, 0.0] }
        body l56 { mass: 0.1, inertia: 8.3333e-5, at: [5.65, 0.0, 0.0] }
        body l57 { mass: 0.1, inertia: 8.3333e-5, at: [5.75, 0.0, 0.0] }
        body l58 { mass: 0.1, inertia: 8.3333e-5, at: [5.85, 0.0, 0.0] }
        body l59 { mass: 0.1, inertia: 8.3333e-5, at: [5.95, 0.0, 0.0] }
        body l60 { mass: 0.1, inertia: 8.3333e-5, at: [6.05, 0.0, 0.0] }
        body l61 { mass: 0.1, inertia: 8.3333e-5, at: [6.15, 0.0, 0.0] }
        body l62 { mass: 0.1, inertia: 8.3333e-5, at: [6.25, 0.0, 0.0] }
        body l63 { mass: 0.1, inertia: 8.3333e-5, at: [6.35, 0.0, 0.0] }
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
        revolute l15[0.05, 0.0] ~ l16[-0.05, 0.0];
        revolute l16[0.05, 0.0] ~ l17[-0.05, 0.0];
        revolute l17[0.05, 0.0] ~ l18[-0.05, 0.0];
        revolute l18[0.05, 0.0] ~ l19[-0.05, 0.0];
        revolute l19[0.05, 0.0] ~ l20[-0.05, 0.0];
        revolute l20[0.05, 0.0] ~ l21[-0.05, 0.0];
        revolute l21[0.05, 0.0] ~ l22[-0.05, 0.0];
        revolute l22[0.05, 0.0] ~ l23[-0.05, 0.0];
        revolute l23[0.05, 0.0] ~ l24[-0.05, 0.0];
        revolute l24[0.05, 0.0] ~ l25[-0.05, 0.0];
        revolute l25[0.05, 0.0] ~ l26[-0.05, 0.0];
        revolute l26[0.05, 0.0] ~ l27[-0.05, 0.0];
        revolute l27[0.05, 0.0] ~ l28[-0.05, 0.0];
        revolute l28[0.05, 0.0] ~ l29[-0.05, 0.0];
        revolute l29[0.05, 0.0] ~ l30[-0.05, 0.0];
        revolute l30[0.05, 0.0] ~ l31[-0.05, 0.0];
        revolute l31[0.05, 0.0] ~ l32[-0.05, 0.0];
        revolute l32[0.05, 0.0] ~ l33[-0.05, 0.0];
        revolute l33[0.05, 0.0] ~ l34[-0.05, 0.0];
        revolute l34[0.05, 0.0] ~ l35[-0.05, 0.0];
        revolute l35[0.05, 0.0] ~ l36[-0.05, 0.0];
        revolute l36[0.05, 0.0] ~ l37[-0.05, 0.0];
        revolute l37[0.05, 0.0] ~ l38[-0.05, 0.0];
        revolute l38[0.05, 0.0] ~ l39[-0.05, 0.0];
        revolute l39[0.05, 0.0] ~ l40[-0.05, 0.0];
        revolute l40[0.05, 0.0] ~ l41[-0.05, 0.0];
        revolute l41[0.05, 0.0] ~ l42[-0.05, 0.0];
        revolute l42[0.05, 0.0] ~ l43[-0.05, 0.0];
        revolute l43[0.05, 0.0] ~ l44[-0.05, 0.0];
        revolute l44[0.05, 0.0] ~ l45[-0.05, 0.0];
        revolute l45[0.05, 0.0] ~ l46[-0.05, 0.0];
        revolute l46[0.05, 0.0] ~ l47[-0.05, 0.0];
        revolute l47[0.05, 0.0] ~ l48[-0.05, 0.0];
        revolute l48[0.05, 0.0] ~ l49[-0.05, 0.0];
        revolute l49[0.05, 0.0] ~ l50[-0.05, 0.0];
        revolute l50[0.05, 0.0] ~ l51[-0.05, 0.0];
        revolute l51[0.05, 0.0] ~ l52[-0.05, 0.0];
        revolute l52[0.05, 0.0] ~ l53[-0.05, 0.0];
        revolute l53[0.05, 0.0] ~ l54[-0.05, 0.0];
        revolute l54[0.05, 0.0] ~ l55[-0.05, 0.0];
        revolute l55[0.05, 0.0] ~ l56[-0.05, 0.0];
        revolute l56[0.05, 0.0] ~ l57[-0.05, 0.0];
        revolute l57[0.05, 0.0] ~ l58[-0.05, 0.0];
        revolute l58[0.05, 0.0] ~ l59[-0.05, 0.0];
        revolute l59[0.05, 0.0] ~ l60[-0.05, 0.0];
        revolute l60[0.05, 0.0] ~ l61[-0.05, 0.0];
        revolute l61[0.05, 0.0] ~ l62[-0.05, 0.0];
        revolute l62[0.05, 0.0] ~ l63[-0.05, 0.0];
    }
}
