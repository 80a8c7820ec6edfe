//! Work space (issue 10, item 5): no solver keeps an O(N²) array on the stack, so a 120-body
//! mechanism (NV = 360, NC = 240: a 7.8 MB [`Workspace`] on the heap) runs assembly, statics
//! and every integrator with every drift correction on a thread with Rust's default 2 MB stack.
//! Before, generalized-α and statics overflowed it (their (NV + NC)² = 2.9 MB saddle-point
//! matrix alone was on the stack), and minimum-norm assembly, partitioning and inverse dynamics
//! kept NC × NV, NC × NC and NV × NV arrays there.
//!
//! The mechanism: a chain of 120 uniform links, 0.1 m and 0.1 kg each, pinned end to end and to
//! ground, straight and 0.3 rad from hanging (written out by a short Python loop, as the
//! benchmarks' chains are: the DSL cannot repeat structure yet).
use mbd::prelude::*;

mechanism! {
    /// A hanging chain of 120 links.
    pub Chain120 {
        gravity [0.0, -9.81];
        body l0 { mass: 0.1, inertia: 8.333333e-05, at: [0.014776, -0.047767, -1.270796] }
        body l1 { mass: 0.1, inertia: 8.333333e-05, at: [0.044328, -0.143300, -1.270796] }
        body l2 { mass: 0.1, inertia: 8.333333e-05, at: [0.073880, -0.238834, -1.270796] }
        body l3 { mass: 0.1, inertia: 8.333333e-05, at: [0.103432, -0.334368, -1.270796] }
        body l4 { mass: 0.1, inertia: 8.333333e-05, at: [0.132984, -0.429901, -1.270796] }
        body l5 { mass: 0.1, inertia: 8.333333e-05, at: [0.162536, -0.525435, -1.270796] }
        body l6 { mass: 0.1, inertia: 8.333333e-05, at: [0.192088, -0.620969, -1.270796] }
        body l7 { mass: 0.1, inertia: 8.333333e-05, at: [0.221640, -0.716502, -1.270796] }
        body l8 { mass: 0.1, inertia: 8.333333e-05, at: [0.251192, -0.812036, -1.270796] }
        body l9 { mass: 0.1, inertia: 8.333333e-05, at: [0.280744, -0.907570, -1.270796] }
        body l10 { mass: 0.1, inertia: 8.333333e-05, at: [0.310296, -1.003103, -1.270796] }
        body l11 { mass: 0.1, inertia: 8.333333e-05, at: [0.339848, -1.098637, -1.270796] }
        body l12 { mass: 0.1, inertia: 8.333333e-05, at: [0.369400, -1.194171, -1.270796] }
        body l13 { mass: 0.1, inertia: 8.333333e-05, at: [0.398952, -1.289704, -1.270796] }
        body l14 { mass: 0.1, inertia: 8.333333e-05, at: [0.428504, -1.385238, -1.270796] }
        body l15 { mass: 0.1, inertia: 8.333333e-05, at: [0.458056, -1.480772, -1.270796] }
        body l16 { mass: 0.1, inertia: 8.333333e-05, at: [0.487608, -1.576305, -1.270796] }
        body l17 { mass: 0.1, inertia: 8.333333e-05, at: [0.517160, -1.671839, -1.270796] }
        body l18 { mass: 0.1, inertia: 8.333333e-05, at: [0.546712, -1.767373, -1.270796] }
        body l19 { mass: 0.1, inertia: 8.333333e-05, at: [0.576264, -1.862906, -1.270796] }
        body l20 { mass: 0.1, inertia: 8.333333e-05, at: [0.605816, -1.958440, -1.270796] }
        body l21 { mass: 0.1, inertia: 8.333333e-05, at: [0.635368, -2.053973, -1.270796] }
        body l22 { mass: 0.1, inertia: 8.333333e-05, at: [0.664920, -2.149507, -1.270796] }
        body l23 { mass: 0.1, inertia: 8.333333e-05, at: [0.694472, -2.245041, -1.270796] }
        body l24 { mass: 0.1, inertia: 8.333333e-05, at: [0.724025, -2.340574, -1.270796] }
        body l25 { mass: 0.1, inertia: 8.333333e-05, at: [0.753577, -2.436108, -1.270796] }
        body l26 { mass: 0.1, inertia: 8.333333e-05, at: [0.783129, -2.531642, -1.270796] }
        body l27 { mass: 0.1, inertia: 8.333333e-05, at: [0.812681, -2.627175, -1.270796] }
        body l28 { mass: 0.1, inertia: 8.333333e-05, at: [0.842233, -2.722709, -1.270796] }
        body l29 { mass: 0.1, inertia: 8.333333e-05, at: [0.871785, -2.818243, -1.270796] }
        body l30 { mass: 0.1, inertia: 8.333333e-05, at: [0.901337, -2.913776, -1.270796] }
        body l31 { mass: 0.1, inertia: 8.333333e-05, at: [0.930889, -3.009310, -1.270796] }
        body l32 { mass: 0.1, inertia: 8.333333e-05, at: [0.960441, -3.104844, -1.270796] }
        body l33 { mass: 0.1, inertia: 8.333333e-05, at: [0.989993, -3.200377, -1.270796] }
        body l34 { mass: 0.1, inertia: 8.333333e-05, at: [1.019545, -3.295911, -1.270796] }
        body l35 { mass: 0.1, inertia: 8.333333e-05, at: [1.049097, -3.391445, -1.270796] }
        body l36 { mass: 0.1, inertia: 8.333333e-05, at: [1.078649, -3.486978, -1.270796] }
        body l37 { mass: 0.1, inertia: 8.333333e-05, at: [1.108201, -3.582512, -1.270796] }
        body l38 { mass: 0.1, inertia: 8.333333e-05, at: [1.137753, -3.678045, -1.270796] }
        body l39 { mass: 0.1, inertia: 8.333333e-05, at: [1.167305, -3.773579, -1.270796] }
        body l40 { mass: 0.1, inertia: 8.333333e-05, at: [1.196857, -3.869113, -1.270796] }
        body l41 { mass: 0.1, inertia: 8.333333e-05, at: [1.226409, -3.964646, -1.270796] }
        body l42 { mass: 0.1, inertia: 8.333333e-05, at: [1.255961, -4.060180, -1.270796] }
        body l43 { mass: 0.1, inertia: 8.333333e-05, at: [1.285513, -4.155714, -1.270796] }
        body l44 { mass: 0.1, inertia: 8.333333e-05, at: [1.315065, -4.251247, -1.270796] }
        body l45 { mass: 0.1, inertia: 8.333333e-05, at: [1.344617, -4.346781, -1.270796] }
        body l46 { mass: 0.1, inertia: 8.333333e-05, at: [1.374169, -4.442315, -1.270796] }
        body l47 { mass: 0.1, inertia: 8.333333e-05, at: [1.403721, -4.537848, -1.270796] }
        body l48 { mass: 0.1, inertia: 8.333333e-05, at: [1.433273, -4.633382, -1.270796] }
        body l49 { mass: 0.1, inertia: 8.333333e-05, at: [1.462825, -4.728916, -1.270796] }
        body l50 { mass: 0.1, inertia: 8.333333e-05, at: [1.492377, -4.824449, -1.270796] }
        body l51 { mass: 0.1, inertia: 8.333333e-05, at: [1.521929, -4.919983, -1.270796] }
        body l52 { mass: 0.1, inertia: 8.333333e-05, at: [1.551481, -5.015517, -1.270796] }
        body l53 { mass: 0.1, inertia: 8.333333e-05, at: [1.581033, -5.111050, -1.270796] }
        body l54 { mass: 0.1, inertia: 8.333333e-05, at: [1.610585, -5.206584, -1.270796] }
        body l55 { mass: 0.1, inertia: 8.333333e-05, at: [1.640137, -5.302118, -1.270796] }
        body l56 { mass: 0.1, inertia: 8.333333e-05, at: [1.669689, -5.397651, -1.270796] }
        body l57 { mass: 0.1, inertia: 8.333333e-05, at: [1.699241, -5.493185, -1.270796] }
        body l58 { mass: 0.1, inertia: 8.333333e-05, at: [1.728793, -5.588718, -1.270796] }
        body l59 { mass: 0.1, inertia: 8.333333e-05, at: [1.758345, -5.684252, -1.270796] }
        body l60 { mass: 0.1, inertia: 8.333333e-05, at: [1.787897, -5.779786, -1.270796] }
        body l61 { mass: 0.1, inertia: 8.333333e-05, at: [1.817449, -5.875319, -1.270796] }
        body l62 { mass: 0.1, inertia: 8.333333e-05, at: [1.847001, -5.970853, -1.270796] }
        body l63 { mass: 0.1, inertia: 8.333333e-05, at: [1.876553, -6.066387, -1.270796] }
        body l64 { mass: 0.1, inertia: 8.333333e-05, at: [1.906105, -6.161920, -1.270796] }
        body l65 { mass: 0.1, inertia: 8.333333e-05, at: [1.935657, -6.257454, -1.270796] }
        body l66 { mass: 0.1, inertia: 8.333333e-05, at: [1.965209, -6.352988, -1.270796] }
        body l67 { mass: 0.1, inertia: 8.333333e-05, at: [1.994761, -6.448521, -1.270796] }
        body l68 { mass: 0.1, inertia: 8.333333e-05, at: [2.024313, -6.544055, -1.270796] }
        body l69 { mass: 0.1, inertia: 8.333333e-05, at: [2.053865, -6.639589, -1.270796] }
        body l70 { mass: 0.1, inertia: 8.333333e-05, at: [2.083417, -6.735122, -1.270796] }
        body l71 { mass: 0.1, inertia: 8.333333e-05, at: [2.112969, -6.830656, -1.270796] }
        body l72 { mass: 0.1, inertia: 8.333333e-05, at: [2.142521, -6.926190, -1.270796] }
        body l73 { mass: 0.1, inertia: 8.333333e-05, at: [2.172074, -7.021723, -1.270796] }
        body l74 { mass: 0.1, inertia: 8.333333e-05, at: [2.201626, -7.117257, -1.270796] }
        body l75 { mass: 0.1, inertia: 8.333333e-05, at: [2.231178, -7.212790, -1.270796] }
        body l76 { mass: 0.1, inertia: 8.333333e-05, at: [2.260730, -7.308324, -1.270796] }
        body l77 { mass: 0.1, inertia: 8.333333e-05, at: [2.290282, -7.403858, -1.270796] }
        body l78 { mass: 0.1, inertia: 8.333333e-05, at: [2.319834, -7.499391, -1.270796] }
        body l79 { mass: 0.1, inertia: 8.333333e-05, at: [2.349386, -7.594925, -1.270796] }
        body l80 { mass: 0.1, inertia: 8.333333e-05, at: [2.378938, -7.690459, -1.270796] }
        body l81 { mass: 0.1, inertia: 8.333333e-05, at: [2.408490, -7.785992, -1.270796] }
        body l82 { mass: 0.1, inertia: 8.333333e-05, at: [2.438042, -7.881526, -1.270796] }
        body l83 { mass: 0.1, inertia: 8.333333e-05, at: [2.467594, -7.977060, -1.270796] }
        body l84 { mass: 0.1, inertia: 8.333333e-05, at: [2.497146, -8.072593, -1.270796] }
        body l85 { mass: 0.1, inertia: 8.333333e-05, at: [2.526698, -8.168127, -1.270796] }
        body l86 { mass: 0.1, inertia: 8.333333e-05, at: [2.556250, -8.263661, -1.270796] }
        body l87 { mass: 0.1, inertia: 8.333333e-05, at: [2.585802, -8.359194, -1.270796] }
        body l88 { mass: 0.1, inertia: 8.333333e-05, at: [2.615354, -8.454728, -1.270796] }
        body l89 { mass: 0.1, inertia: 8.333333e-05, at: [2.644906, -8.550262, -1.270796] }
        body l90 { mass: 0.1, inertia: 8.333333e-05, at: [2.674458, -8.645795, -1.270796] }
        body l91 { mass: 0.1, inertia: 8.333333e-05, at: [2.704010, -8.741329, -1.270796] }
        body l92 { mass: 0.1, inertia: 8.333333e-05, at: [2.733562, -8.836863, -1.270796] }
        body l93 { mass: 0.1, inertia: 8.333333e-05, at: [2.763114, -8.932396, -1.270796] }
        body l94 { mass: 0.1, inertia: 8.333333e-05, at: [2.792666, -9.027930, -1.270796] }
        body l95 { mass: 0.1, inertia: 8.333333e-05, at: [2.822218, -9.123463, -1.270796] }
        body l96 { mass: 0.1, inertia: 8.333333e-05, at: [2.851770, -9.218997, -1.270796] }
        body l97 { mass: 0.1, inertia: 8.333333e-05, at: [2.881322, -9.314531, -1.270796] }
        body l98 { mass: 0.1, inertia: 8.333333e-05, at: [2.910874, -9.410064, -1.270796] }
        body l99 { mass: 0.1, inertia: 8.333333e-05, at: [2.940426, -9.505598, -1.270796] }
        body l100 { mass: 0.1, inertia: 8.333333e-05, at: [2.969978, -9.601132, -1.270796] }
        body l101 { mass: 0.1, inertia: 8.333333e-05, at: [2.999530, -9.696665, -1.270796] }
        body l102 { mass: 0.1, inertia: 8.333333e-05, at: [3.029082, -9.792199, -1.270796] }
        body l103 { mass: 0.1, inertia: 8.333333e-05, at: [3.058634, -9.887733, -1.270796] }
        body l104 { mass: 0.1, inertia: 8.333333e-05, at: [3.088186, -9.983266, -1.270796] }
        body l105 { mass: 0.1, inertia: 8.333333e-05, at: [3.117738, -10.078800, -1.270796] }
        body l106 { mass: 0.1, inertia: 8.333333e-05, at: [3.147290, -10.174334, -1.270796] }
        body l107 { mass: 0.1, inertia: 8.333333e-05, at: [3.176842, -10.269867, -1.270796] }
        body l108 { mass: 0.1, inertia: 8.333333e-05, at: [3.206394, -10.365401, -1.270796] }
        body l109 { mass: 0.1, inertia: 8.333333e-05, at: [3.235946, -10.460935, -1.270796] }
        body l110 { mass: 0.1, inertia: 8.333333e-05, at: [3.265498, -10.556468, -1.270796] }
        body l111 { mass: 0.1, inertia: 8.333333e-05, at: [3.295050, -10.652002, -1.270796] }
        body l112 { mass: 0.1, inertia: 8.333333e-05, at: [3.324602, -10.747536, -1.270796] }
        body l113 { mass: 0.1, inertia: 8.333333e-05, at: [3.354154, -10.843069, -1.270796] }
        body l114 { mass: 0.1, inertia: 8.333333e-05, at: [3.383706, -10.938603, -1.270796] }
        body l115 { mass: 0.1, inertia: 8.333333e-05, at: [3.413258, -11.034136, -1.270796] }
        body l116 { mass: 0.1, inertia: 8.333333e-05, at: [3.442810, -11.129670, -1.270796] }
        body l117 { mass: 0.1, inertia: 8.333333e-05, at: [3.472362, -11.225204, -1.270796] }
        body l118 { mass: 0.1, inertia: 8.333333e-05, at: [3.501914, -11.320737, -1.270796] }
        body l119 { mass: 0.1, inertia: 8.333333e-05, at: [3.531466, -11.416271, -1.270796] }
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
        revolute l63[0.05, 0.0] ~ l64[-0.05, 0.0];
        revolute l64[0.05, 0.0] ~ l65[-0.05, 0.0];
        revolute l65[0.05, 0.0] ~ l66[-0.05, 0.0];
        revolute l66[0.05, 0.0] ~ l67[-0.05, 0.0];
        revolute l67[0.05, 0.0] ~ l68[-0.05, 0.0];
        revolute l68[0.05, 0.0] ~ l69[-0.05, 0.0];
        revolute l69[0.05, 0.0] ~ l70[-0.05, 0.0];
        revolute l70[0.05, 0.0] ~ l71[-0.05, 0.0];
        revolute l71[0.05, 0.0] ~ l72[-0.05, 0.0];
        revolute l72[0.05, 0.0] ~ l73[-0.05, 0.0];
        revolute l73[0.05, 0.0] ~ l74[-0.05, 0.0];
        revolute l74[0.05, 0.0] ~ l75[-0.05, 0.0];
        revolute l75[0.05, 0.0] ~ l76[-0.05, 0.0];
        revolute l76[0.05, 0.0] ~ l77[-0.05, 0.0];
        revolute l77[0.05, 0.0] ~ l78[-0.05, 0.0];
        revolute l78[0.05, 0.0] ~ l79[-0.05, 0.0];
        revolute l79[0.05, 0.0] ~ l80[-0.05, 0.0];
        revolute l80[0.05, 0.0] ~ l81[-0.05, 0.0];
        revolute l81[0.05, 0.0] ~ l82[-0.05, 0.0];
        revolute l82[0.05, 0.0] ~ l83[-0.05, 0.0];
        revolute l83[0.05, 0.0] ~ l84[-0.05, 0.0];
        revolute l84[0.05, 0.0] ~ l85[-0.05, 0.0];
        revolute l85[0.05, 0.0] ~ l86[-0.05, 0.0];
        revolute l86[0.05, 0.0] ~ l87[-0.05, 0.0];
        revolute l87[0.05, 0.0] ~ l88[-0.05, 0.0];
        revolute l88[0.05, 0.0] ~ l89[-0.05, 0.0];
        revolute l89[0.05, 0.0] ~ l90[-0.05, 0.0];
        revolute l90[0.05, 0.0] ~ l91[-0.05, 0.0];
        revolute l91[0.05, 0.0] ~ l92[-0.05, 0.0];
        revolute l92[0.05, 0.0] ~ l93[-0.05, 0.0];
        revolute l93[0.05, 0.0] ~ l94[-0.05, 0.0];
        revolute l94[0.05, 0.0] ~ l95[-0.05, 0.0];
        revolute l95[0.05, 0.0] ~ l96[-0.05, 0.0];
        revolute l96[0.05, 0.0] ~ l97[-0.05, 0.0];
        revolute l97[0.05, 0.0] ~ l98[-0.05, 0.0];
        revolute l98[0.05, 0.0] ~ l99[-0.05, 0.0];
        revolute l99[0.05, 0.0] ~ l100[-0.05, 0.0];
        revolute l100[0.05, 0.0] ~ l101[-0.05, 0.0];
        revolute l101[0.05, 0.0] ~ l102[-0.05, 0.0];
        revolute l102[0.05, 0.0] ~ l103[-0.05, 0.0];
        revolute l103[0.05, 0.0] ~ l104[-0.05, 0.0];
        revolute l104[0.05, 0.0] ~ l105[-0.05, 0.0];
        revolute l105[0.05, 0.0] ~ l106[-0.05, 0.0];
        revolute l106[0.05, 0.0] ~ l107[-0.05, 0.0];
        revolute l107[0.05, 0.0] ~ l108[-0.05, 0.0];
        revolute l108[0.05, 0.0] ~ l109[-0.05, 0.0];
        revolute l109[0.05, 0.0] ~ l110[-0.05, 0.0];
        revolute l110[0.05, 0.0] ~ l111[-0.05, 0.0];
        revolute l111[0.05, 0.0] ~ l112[-0.05, 0.0];
        revolute l112[0.05, 0.0] ~ l113[-0.05, 0.0];
        revolute l113[0.05, 0.0] ~ l114[-0.05, 0.0];
        revolute l114[0.05, 0.0] ~ l115[-0.05, 0.0];
        revolute l115[0.05, 0.0] ~ l116[-0.05, 0.0];
        revolute l116[0.05, 0.0] ~ l117[-0.05, 0.0];
        revolute l117[0.05, 0.0] ~ l118[-0.05, 0.0];
        revolute l118[0.05, 0.0] ~ l119[-0.05, 0.0];
    }
}

/// Rust's default stack for spawned threads (and the main thread's on many systems).
const DEFAULT_STACK: usize = 2 << 20;

/// Runs `f` on a thread with the default 2 MB stack; an overflow aborts the test binary, so a
/// regression cannot pass silently.
fn on_default_stack<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
    std::thread::Builder::new().stack_size(DEFAULT_STACK).spawn(f).expect("spawn").join().expect("the run panicked")
}

/// Assembly and statics of the chain, and the top pin's reaction.
#[test]
fn statics_and_kinematics_of_120_bodies_on_a_2_mb_stack() {
    on_default_stack(|| {
        let m = Chain120::default();
        let mut ws = Chain120::workspace();
        assert_eq!(Workspace::<f64, 360, 240, 600>::BYTES, 7_838_400, "D twice, D Dᵀ, three NV², the saddle matrix and its rhs");
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the chain assembles");
        // Statics from the tilted chain: it hangs straight down, every link at φ = −π/2 (the
        // verdict is Stable, and the angles agree to the solver's tolerance; 1e-8 rad leaves
        // room for the conditioning of 120 links).
        let mut lambda = [0.0; 240];
        let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the chain hangs");
        assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
        for k in 0..120 {
            let phi = q[3 * k + 2];
            assert!((phi + std::f64::consts::FRAC_PI_2).abs() < 1e-8, "link {k} at φ = {phi}");
        }
        // The pin at the top carries the whole chain's weight, 120 × 0.1 kg × 9.81 m/s² =
        // 117.72 N (λ from the static solve, D as the workspace holds it after inverse
        // dynamics; the chain is not driven, so here D is the generated Jacobian's, on the heap). 1e-9 N: rounding of a sum of 240
        // multipliers of size ≤ 118 N.
        let mut d = vec![[0.0; 360]; 240];
        let d: &mut [[f64; 360]; 240] = d.as_mut_slice().try_into().expect("240 rows");
        m.jacobian(&q, 0.0, d);
        let pin = joint_reaction(&m, &q, d, &lambda, 0).and_then(|r| r.on_j).expect("the top pin acts on l0");
        assert!(pin.force[0].abs() < 1e-9 && (pin.force[1] - 117.72).abs() < 1e-9, "{pin:?}");
    });
}

/// Every integrator with every drift correction, from the tilted chain at rest, for a few
/// steps (the point is the stack, not the motion: a debug build factors the 600-square
/// generalized-α matrix in about a second). Each run must keep the constraints (‖Φ‖∞ below
/// 1e-6 m after 5 ms: the explicit runs' drift is O(h⁵) per step, the corrected ones are held to
/// their correction's tolerance) and stay finite.
#[test]
fn every_integrator_runs_120_bodies_on_a_2_mb_stack() {
    on_default_stack(|| {
        let m = Chain120::default();
        let mut ws = Chain120::workspace();
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the chain assembles");
        let times = [2.5e-3, 5e-3];
        for correction in [Correction::None, Correction::projection(), Correction::partitioning()] {
            let options = SimulationOptions { correction, ..SimulationOptions::default() };
            let check = |name: &str, q: &[f64; 360]| {
                let mut phi = [0.0; 240];
                m.constraints(q, 5e-3, &mut phi);
                let worst = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                assert!(worst < 1e-6, "{name}, {correction:?}: ‖Φ‖∞ = {worst:e}");
            };
            let mut last = [0.0; 360];
            simulate(&m, &mut ws, &mut Rk4::new(1e-3), 0.0, &q, &[0.0; 360], &times, &options, |s| last = s.point.q).expect("RK4");
            check("RK4", &last);
            let mut dopri = Dopri5::new(Dopri5Options::default());
            simulate(&m, &mut ws, &mut dopri, 0.0, &q, &[0.0; 360], &times, &options, |s| last = s.point.q).expect("DOPRI5");
            check("DOPRI5", &last);
            let mut dop853 = Dop853::new(Dop853Options::default());
            simulate(&m, &mut ws, &mut dop853, 0.0, &q, &[0.0; 360], &times, &options, |s| last = s.point.q).expect("DOP853");
            check("DOP853", &last);
            let mut alpha = Chain120::generalized_alpha(GeneralizedAlphaOptions { step: 2.5e-3, ..GeneralizedAlphaOptions::default() });
            simulate(&m, &mut ws, &mut alpha, 0.0, &q, &[0.0; 360], &times, &options, |s| last = s.point.q).expect("generalized-α");
            check("generalized-α", &last);
        }
    });
}
