// Generated from slider_crank.rs by `MBD_BLESS=1 cargo test -p mbd-macros snapshot`. Do not edit.
/// Slider-crank driven at constant speed (Nikravesh, Planar Multibody Dynamics, ch. 7).
///
/// 3 bodies, 9 coordinates, 9 constraint rows (0 degrees of freedom); Φ_q has 23 structural non-zeros of 81.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrank {
    ///Parameter `omega` (default 6.283185307179586).
    pub omega: f64,
    ///Parameter `r` (default 0.1).
    pub r: f64,
    ///Parameter `l` (default 0.3).
    pub l: f64,
}
impl ::core::default::Default for SliderCrank {
    fn default() -> Self {
        Self {
            omega: 6.283185307179586f64,
            r: 0.1f64,
            l: 0.3f64,
        }
    }
}
#[allow(unused_variables, unused_parens, clippy::all)]
impl SliderCrank {
    /// Number of moving bodies.
    pub const N_BODIES: usize = 3;
    /// Number of generalized coordinates (3 per body).
    pub const NQ: usize = 9;
    /// Number of constraint rows (joints, drivers and user constraints).
    pub const NC: usize = 9;
    /// Degrees of freedom: `NQ − NC`.
    pub const DOF: i32 = 0i32;
    /// Number of structurally non-zero entries of Φ_q.
    pub const NNZ: usize = 23;
    /// Number of runtime parameters.
    pub const NP: usize = 3;
    /// Parameter values in declaration order (see `PARAM_NAMES`).
    pub fn params(&self) -> [f64; 3] {
        [self.omega, self.r, self.l]
    }
    /// A mechanism with the given parameter values, in declaration order.
    pub fn from_params(p: [f64; 3]) -> Self {
        Self {
            omega: p[0],
            r: p[1],
            l: p[2],
        }
    }
    /// Work space for solvers that factor the (NQ + NC)-square saddle-point matrix
    /// [[K, Φ_qᵀ], [Φ_q, 0]] (static equilibrium).
    pub fn kkt_workspace() -> ::mbd::KktWorkspace<f64, 18> {
        ::mbd::KktWorkspace::new()
    }
    /// The structural non-zeros of Φ_q(q, t), in the order of `JACOBIAN_PATTERN`.
    #[inline]
    pub fn jacobian_values(&self, q: &[f64; 9], t: f64, out: &mut [f64; 23]) {
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v13: f64 = (-(v5 * s_crank));
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v32: f64 = (-(v24 * s_rod));
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v72: f64 = (-c_slider);
        out[0] = (-1f64);
        out[1] = v13;
        out[2] = (-1f64);
        out[3] = v10;
        out[4] = 1f64;
        out[5] = v13;
        out[6] = (-1f64);
        out[7] = v32;
        out[8] = 1f64;
        out[9] = v10;
        out[10] = (-1f64);
        out[11] = v29;
        out[12] = 1f64;
        out[13] = v32;
        out[14] = (-1f64);
        out[15] = 1f64;
        out[16] = v29;
        out[17] = (-1f64);
        out[18] = s_slider;
        out[19] = v72;
        out[20] = ((s_slider * q[7]) + (c_slider * q[6]));
        out[21] = v72;
        out[22] = 1f64;
    }
    /// Φ, the structural non-zeros of Φ_q (in the order of `JACOBIAN_PATTERN`), ν and γ in
    /// one evaluation: the sparse twin of `Kinematics::full_eval`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn full_eval_values(
        &self,
        q: &[f64; 9],
        qd: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        out: &mut [f64; 23],
        nu: &mut [f64; 9],
        gamma: &mut [f64; 9],
    ) {
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v12: f64 = (v5 * s_crank);
        let v13: f64 = (-v12);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v31: f64 = (v24 * s_rod);
        let v32: f64 = (-v31);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v72: f64 = (-c_slider);
        let v119: f64 = (s_slider * qd[8]);
        let v126: f64 = (c_slider * qd[8]);
        let v134: f64 = (v5 * (qd[2] * (c_crank * qd[2])));
        let v138: f64 = (v5 * (qd[2] * (s_crank * qd[2])));
        let v141: f64 = (v24 * (qd[5] * (c_rod * qd[5])));
        let v147: f64 = (v24 * (qd[5] * (s_rod * qd[5])));
        let v151: f64 = (qd[6] * v126);
        let v152: f64 = (qd[8] * v119);
        let v158: f64 = (qd[7] * v119);
        phi[0] = (-(q[0] - v10));
        phi[1] = (-(q[1] - v12));
        phi[2] = ((v10 + q[0]) - (q[3] - v29));
        phi[3] = ((v12 + q[1]) - (q[4] - v31));
        phi[4] = ((v29 + q[3]) - q[6]);
        phi[5] = ((v31 + q[4]) - q[7]);
        phi[6] = ((s_slider * q[6]) - (c_slider * q[7]));
        phi[7] = (-s_slider);
        phi[8] = (q[2] - (self.omega * t));
        out[0] = (-1f64);
        out[1] = v13;
        out[2] = (-1f64);
        out[3] = v10;
        out[4] = 1f64;
        out[5] = v13;
        out[6] = (-1f64);
        out[7] = v32;
        out[8] = 1f64;
        out[9] = v10;
        out[10] = (-1f64);
        out[11] = v29;
        out[12] = 1f64;
        out[13] = v32;
        out[14] = (-1f64);
        out[15] = 1f64;
        out[16] = v29;
        out[17] = (-1f64);
        out[18] = s_slider;
        out[19] = v72;
        out[20] = ((s_slider * q[7]) + (c_slider * q[6]));
        out[21] = v72;
        out[22] = 1f64;
        nu[0] = 0f64;
        nu[1] = 0f64;
        nu[2] = 0f64;
        nu[3] = 0f64;
        nu[4] = 0f64;
        nu[5] = 0f64;
        nu[6] = 0f64;
        nu[7] = 0f64;
        nu[8] = self.omega;
        gamma[0] = v134;
        gamma[1] = v138;
        gamma[2] = (v134 + v141);
        gamma[3] = (v138 + v147);
        gamma[4] = v141;
        gamma[5] = v147;
        gamma[6] = (-((v151 + (v151 - (q[6] * v152)))
            + (v158 + (v158 + (q[7] * (qd[8] * v126))))));
        gamma[7] = (-v152);
        gamma[8] = 0f64;
    }
}
impl ::mbd::Mechanism for SliderCrank {
    const NAME: &'static str = "SliderCrank";
    const BODY_NAMES: &'static [&'static str] = &["crank", "rod", "slider"];
    const COORDINATE_NAMES: &'static [&'static str] = &[
        "crank.x",
        "crank.y",
        "crank.phi",
        "rod.x",
        "rod.y",
        "rod.phi",
        "slider.x",
        "slider.y",
        "slider.phi",
    ];
    const CONSTRAINT_NAMES: &'static [&'static str] = &[
        "revolute ground~crank: x",
        "revolute ground~crank: y",
        "revolute crank~rod: x",
        "revolute crank~rod: y",
        "revolute rod~slider: x",
        "revolute rod~slider: y",
        "translational slider~ground: normal",
        "translational slider~ground: angle",
        "drive crank.phi: phi",
    ];
    const PARAM_NAMES: &'static [&'static str] = &["omega", "r", "l"];
    const DOF: i32 = 0i32;
    const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[
        (0u16, 0u16),
        (0u16, 2u16),
        (1u16, 1u16),
        (1u16, 2u16),
        (2u16, 0u16),
        (2u16, 2u16),
        (2u16, 3u16),
        (2u16, 5u16),
        (3u16, 1u16),
        (3u16, 2u16),
        (3u16, 4u16),
        (3u16, 5u16),
        (4u16, 3u16),
        (4u16, 5u16),
        (4u16, 6u16),
        (5u16, 4u16),
        (5u16, 5u16),
        (5u16, 7u16),
        (6u16, 6u16),
        (6u16, 7u16),
        (6u16, 8u16),
        (7u16, 8u16),
        (8u16, 2u16),
    ];
    const PHI_T_IS_ZERO: bool = false;
    const OP_COUNTS: &'static [::mbd::OpCount] = &[
        ::mbd::OpCount {
            function: "constraints",
            add: 14u32,
            mul: 7u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "jacobian",
            add: 1u32,
            mul: 6u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "jacobian_values",
            add: 1u32,
            mul: 6u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "velocity_rhs",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "gamma",
            add: 7u32,
            mul: 20u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "position_eval",
            add: 15u32,
            mul: 9u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "full_eval",
            add: 22u32,
            mul: 29u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "full_eval_values",
            add: 22u32,
            mul: 29u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "forces",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "forces_q",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "forces_qd",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "potential_energy",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "constraint_force_q",
            add: 8u32,
            mul: 18u32,
            div: 2u32,
            call: 3u32,
        },
    ];
    const JOINTS: &'static [::mbd::JointInfo] = &[
        ::mbd::JointInfo {
            name: "revolute ground~crank",
            kind: "revolute",
            first_row: 0u16,
            rows: 2u16,
            body_i: ::core::option::Option::None,
            body_j: ::core::option::Option::Some(0u16),
        },
        ::mbd::JointInfo {
            name: "revolute crank~rod",
            kind: "revolute",
            first_row: 2u16,
            rows: 2u16,
            body_i: ::core::option::Option::Some(0u16),
            body_j: ::core::option::Option::Some(1u16),
        },
        ::mbd::JointInfo {
            name: "revolute rod~slider",
            kind: "revolute",
            first_row: 4u16,
            rows: 2u16,
            body_i: ::core::option::Option::Some(1u16),
            body_j: ::core::option::Option::Some(2u16),
        },
        ::mbd::JointInfo {
            name: "translational slider~ground",
            kind: "translational",
            first_row: 6u16,
            rows: 2u16,
            body_i: ::core::option::Option::Some(2u16),
            body_j: ::core::option::Option::None,
        },
        ::mbd::JointInfo {
            name: "drive crank.phi",
            kind: "drive",
            first_row: 8u16,
            rows: 1u16,
            body_i: ::core::option::Option::Some(0u16),
            body_j: ::core::option::Option::None,
        },
    ];
    const EFFECTS: &'static [&'static str] = &[];
    const MODEL_JSON: &'static str = "{\"bodies\":[{\"inertia\":[\"num\",0.002],\"mass\":[\"num\",1.0],\"name\":\"crank\",\"q0\":[[\"num\",0.05],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]},{\"inertia\":[\"num\",0.015],\"mass\":[\"num\",2.0],\"name\":\"rod\",\"q0\":[[\"num\",0.25],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]},{\"inertia\":[\"num\",0.001],\"mass\":[\"num\",0.5],\"name\":\"slider\",\"q0\":[[\"num\",0.4],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]}],\"constraint_rows\":[\"revolute ground~crank: x\",\"revolute ground~crank: y\",\"revolute crank~rod: x\",\"revolute crank~rod: y\",\"revolute rod~slider: x\",\"revolute rod~slider: y\",\"translational slider~ground: normal\",\"translational slider~ground: angle\",\"drive crank.phi: phi\"],\"constraints\":[{\"i\":{\"body\":\"ground\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"j\":{\"body\":\"crank\",\"point\":[[\"div\",[\"neg\",[\"param\",\"r\"]],[\"num\",2.0]],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute ground~crank\"},{\"i\":{\"body\":\"crank\",\"point\":[[\"div\",[\"param\",\"r\"],[\"num\",2.0]],[\"num\",0.0]]},\"j\":{\"body\":\"rod\",\"point\":[[\"div\",[\"neg\",[\"param\",\"l\"]],[\"num\",2.0]],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute crank~rod\"},{\"i\":{\"body\":\"rod\",\"point\":[[\"div\",[\"param\",\"l\"],[\"num\",2.0]],[\"num\",0.0]]},\"j\":{\"body\":\"slider\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute rod~slider\"},{\"i\":{\"axis\":[[\"num\",1.0],[\"num\",0.0]],\"body\":\"slider\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"j\":{\"axis\":[[\"num\",1.0],[\"num\",0.0]],\"body\":\"ground\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"kind\":\"translational\",\"name\":\"translational slider~ground\"},{\"body\":\"crank\",\"coordinate\":\"phi\",\"f\":[\"mul\",[\"param\",\"omega\"],[\"t\"]],\"kind\":\"drive\",\"name\":\"drive crank.phi\"}],\"coordinates\":[\"crank.x\",\"crank.y\",\"crank.phi\",\"rod.x\",\"rod.y\",\"rod.phi\",\"slider.x\",\"slider.y\",\"slider.phi\"],\"forces\":[],\"gravity\":null,\"jacobian_pattern\":[[0,0],[0,2],[1,1],[1,2],[2,0],[2,2],[2,3],[2,5],[3,1],[3,2],[3,4],[3,5],[4,3],[4,5],[4,6],[5,4],[5,5],[5,7],[6,6],[6,7],[6,8],[7,8],[8,2]],\"name\":\"SliderCrank\",\"params\":[{\"default\":6.283185307179586,\"name\":\"omega\"},{\"default\":0.1,\"name\":\"r\"},{\"default\":0.3,\"name\":\"l\"}],\"points\":[],\"scalar\":\"f64\",\"vectors\":[]}";
}
#[allow(unused_variables, unused_parens, clippy::all)]
impl ::mbd::ConstraintForces<f64, 9, 9> for SliderCrank {
    #[inline]
    fn constraint_force_q(
        &self,
        q: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        k: &mut [[f64; 9]; 9],
    ) {
        *k = [[0f64; 9]; 9];
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v12: f64 = (v5 * s_crank);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v31: f64 = (v24 * s_rod);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v203: f64 = (s_slider * lambda[6]);
        let v205: f64 = (c_slider * lambda[6]);
        k[2][2] = (-((v12 * lambda[3])
            + ((v10 * lambda[2]) + ((v12 * lambda[1]) + (v10 * lambda[0])))));
        k[5][5] = (-((v31 * lambda[5])
            + ((v29 * lambda[4]) + ((v31 * lambda[3]) + (v29 * lambda[2])))));
        k[6][8] = v205;
        k[7][8] = v203;
        k[8][6] = v205;
        k[8][7] = v203;
        k[8][8] = ((s_slider * lambda[7])
            + (lambda[6] * ((c_slider * q[7]) - (s_slider * q[6]))));
    }
}
#[allow(unused_variables, unused_parens, clippy::all)]
impl ::mbd::Dynamics<f64, 9, 9> for SliderCrank {
    #[inline]
    fn mass_diagonal(&self) -> [f64; 9] {
        let mut m = [0f64; 9];
        m[0] = 1f64;
        m[1] = 1f64;
        m[2] = 0.002f64;
        m[3] = 2f64;
        m[4] = 2f64;
        m[5] = 0.015f64;
        m[6] = 0.5f64;
        m[7] = 0.5f64;
        m[8] = 0.001f64;
        m
    }
    #[inline]
    fn forces(&self, q: &[f64; 9], qd: &[f64; 9], t: f64, h: &mut [f64; 9]) {
        h[0] = 0f64;
        h[1] = 0f64;
        h[2] = 0f64;
        h[3] = 0f64;
        h[4] = 0f64;
        h[5] = 0f64;
        h[6] = 0f64;
        h[7] = 0f64;
        h[8] = 0f64;
    }
    #[inline]
    fn forces_q(&self, q: &[f64; 9], qd: &[f64; 9], t: f64, dh: &mut [[f64; 9]; 9]) {
        *dh = [[0f64; 9]; 9];
    }
    #[inline]
    fn forces_qd(&self, q: &[f64; 9], qd: &[f64; 9], t: f64, dh: &mut [[f64; 9]; 9]) {
        *dh = [[0f64; 9]; 9];
    }
    #[inline]
    fn potential_energy(&self, q: &[f64; 9], t: f64) -> f64 {
        let mut energy = [0f64; 1];
        energy[0] = 0f64;
        energy[0]
    }
}
#[allow(unused_variables, unused_parens, clippy::all)]
impl ::mbd::Kinematics<f64, 9, 9> for SliderCrank {
    #[inline]
    fn initial_positions(&self) -> [f64; 9] {
        let mut q = [0f64; 9];
        q[0] = 0.05f64;
        q[1] = 0f64;
        q[2] = 0f64;
        q[3] = 0.25f64;
        q[4] = 0f64;
        q[5] = 0f64;
        q[6] = 0.4f64;
        q[7] = 0f64;
        q[8] = 0f64;
        q
    }
    #[inline]
    fn initial_velocities(&self) -> [f64; 9] {
        let mut qd = [0f64; 9];
        qd[0] = 0f64;
        qd[1] = 0f64;
        qd[2] = 0f64;
        qd[3] = 0f64;
        qd[4] = 0f64;
        qd[5] = 0f64;
        qd[6] = 0f64;
        qd[7] = 0f64;
        qd[8] = 0f64;
        qd
    }
    #[inline]
    fn constraints(&self, q: &[f64; 9], t: f64, phi: &mut [f64; 9]) {
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v12: f64 = (v5 * s_crank);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v31: f64 = (v24 * s_rod);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        phi[0] = (-(q[0] - v10));
        phi[1] = (-(q[1] - v12));
        phi[2] = ((v10 + q[0]) - (q[3] - v29));
        phi[3] = ((v12 + q[1]) - (q[4] - v31));
        phi[4] = ((v29 + q[3]) - q[6]);
        phi[5] = ((v31 + q[4]) - q[7]);
        phi[6] = ((s_slider * q[6]) - (c_slider * q[7]));
        phi[7] = (-s_slider);
        phi[8] = (q[2] - (self.omega * t));
    }
    #[inline]
    fn jacobian(&self, q: &[f64; 9], t: f64, d: &mut [[f64; 9]; 9]) {
        *d = [[0f64; 9]; 9];
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v13: f64 = (-(v5 * s_crank));
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v32: f64 = (-(v24 * s_rod));
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v72: f64 = (-c_slider);
        d[0][0] = (-1f64);
        d[0][2] = v13;
        d[1][1] = (-1f64);
        d[1][2] = v10;
        d[2][0] = 1f64;
        d[2][2] = v13;
        d[2][3] = (-1f64);
        d[2][5] = v32;
        d[3][1] = 1f64;
        d[3][2] = v10;
        d[3][4] = (-1f64);
        d[3][5] = v29;
        d[4][3] = 1f64;
        d[4][5] = v32;
        d[4][6] = (-1f64);
        d[5][4] = 1f64;
        d[5][5] = v29;
        d[5][7] = (-1f64);
        d[6][6] = s_slider;
        d[6][7] = v72;
        d[6][8] = ((s_slider * q[7]) + (c_slider * q[6]));
        d[7][8] = v72;
        d[8][2] = 1f64;
    }
    #[inline]
    fn velocity_rhs(&self, q: &[f64; 9], t: f64, nu: &mut [f64; 9]) {
        nu[0] = 0f64;
        nu[1] = 0f64;
        nu[2] = 0f64;
        nu[3] = 0f64;
        nu[4] = 0f64;
        nu[5] = 0f64;
        nu[6] = 0f64;
        nu[7] = 0f64;
        nu[8] = self.omega;
    }
    #[inline]
    fn gamma(&self, q: &[f64; 9], qd: &[f64; 9], t: f64, gamma: &mut [f64; 9]) {
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v119: f64 = (s_slider * qd[8]);
        let v126: f64 = (c_slider * qd[8]);
        let v134: f64 = (v5 * (qd[2] * (c_crank * qd[2])));
        let v138: f64 = (v5 * (qd[2] * (s_crank * qd[2])));
        let v141: f64 = (v24 * (qd[5] * (c_rod * qd[5])));
        let v147: f64 = (v24 * (qd[5] * (s_rod * qd[5])));
        let v151: f64 = (qd[6] * v126);
        let v152: f64 = (qd[8] * v119);
        let v158: f64 = (qd[7] * v119);
        gamma[0] = v134;
        gamma[1] = v138;
        gamma[2] = (v134 + v141);
        gamma[3] = (v138 + v147);
        gamma[4] = v141;
        gamma[5] = v147;
        gamma[6] = (-((v151 + (v151 - (q[6] * v152)))
            + (v158 + (v158 + (q[7] * (qd[8] * v126))))));
        gamma[7] = (-v152);
        gamma[8] = 0f64;
    }
    #[inline]
    fn position_eval(
        &self,
        q: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        d: &mut [[f64; 9]; 9],
    ) {
        *d = [[0f64; 9]; 9];
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v12: f64 = (v5 * s_crank);
        let v13: f64 = (-v12);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v31: f64 = (v24 * s_rod);
        let v32: f64 = (-v31);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v72: f64 = (-c_slider);
        phi[0] = (-(q[0] - v10));
        phi[1] = (-(q[1] - v12));
        phi[2] = ((v10 + q[0]) - (q[3] - v29));
        phi[3] = ((v12 + q[1]) - (q[4] - v31));
        phi[4] = ((v29 + q[3]) - q[6]);
        phi[5] = ((v31 + q[4]) - q[7]);
        phi[6] = ((s_slider * q[6]) - (c_slider * q[7]));
        phi[7] = (-s_slider);
        phi[8] = (q[2] - (self.omega * t));
        d[0][0] = (-1f64);
        d[0][2] = v13;
        d[1][1] = (-1f64);
        d[1][2] = v10;
        d[2][0] = 1f64;
        d[2][2] = v13;
        d[2][3] = (-1f64);
        d[2][5] = v32;
        d[3][1] = 1f64;
        d[3][2] = v10;
        d[3][4] = (-1f64);
        d[3][5] = v29;
        d[4][3] = 1f64;
        d[4][5] = v32;
        d[4][6] = (-1f64);
        d[5][4] = 1f64;
        d[5][5] = v29;
        d[5][7] = (-1f64);
        d[6][6] = s_slider;
        d[6][7] = v72;
        d[6][8] = ((s_slider * q[7]) + (c_slider * q[6]));
        d[7][8] = v72;
        d[8][2] = 1f64;
    }
    #[inline]
    fn full_eval(
        &self,
        q: &[f64; 9],
        qd: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        d: &mut [[f64; 9]; 9],
        nu: &mut [f64; 9],
        gamma: &mut [f64; 9],
    ) {
        *d = [[0f64; 9]; 9];
        let v5: f64 = (self.r / 2f64);
        let (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos(q[2]);
        let v10: f64 = (v5 * c_crank);
        let v12: f64 = (v5 * s_crank);
        let v13: f64 = (-v12);
        let v24: f64 = (self.l / 2f64);
        let (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos(q[5]);
        let v29: f64 = (v24 * c_rod);
        let v31: f64 = (v24 * s_rod);
        let v32: f64 = (-v31);
        let (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos(q[8]);
        let v72: f64 = (-c_slider);
        let v119: f64 = (s_slider * qd[8]);
        let v126: f64 = (c_slider * qd[8]);
        let v134: f64 = (v5 * (qd[2] * (c_crank * qd[2])));
        let v138: f64 = (v5 * (qd[2] * (s_crank * qd[2])));
        let v141: f64 = (v24 * (qd[5] * (c_rod * qd[5])));
        let v147: f64 = (v24 * (qd[5] * (s_rod * qd[5])));
        let v151: f64 = (qd[6] * v126);
        let v152: f64 = (qd[8] * v119);
        let v158: f64 = (qd[7] * v119);
        phi[0] = (-(q[0] - v10));
        phi[1] = (-(q[1] - v12));
        phi[2] = ((v10 + q[0]) - (q[3] - v29));
        phi[3] = ((v12 + q[1]) - (q[4] - v31));
        phi[4] = ((v29 + q[3]) - q[6]);
        phi[5] = ((v31 + q[4]) - q[7]);
        phi[6] = ((s_slider * q[6]) - (c_slider * q[7]));
        phi[7] = (-s_slider);
        phi[8] = (q[2] - (self.omega * t));
        d[0][0] = (-1f64);
        d[0][2] = v13;
        d[1][1] = (-1f64);
        d[1][2] = v10;
        d[2][0] = 1f64;
        d[2][2] = v13;
        d[2][3] = (-1f64);
        d[2][5] = v32;
        d[3][1] = 1f64;
        d[3][2] = v10;
        d[3][4] = (-1f64);
        d[3][5] = v29;
        d[4][3] = 1f64;
        d[4][5] = v32;
        d[4][6] = (-1f64);
        d[5][4] = 1f64;
        d[5][5] = v29;
        d[5][7] = (-1f64);
        d[6][6] = s_slider;
        d[6][7] = v72;
        d[6][8] = ((s_slider * q[7]) + (c_slider * q[6]));
        d[7][8] = v72;
        d[8][2] = 1f64;
        nu[0] = 0f64;
        nu[1] = 0f64;
        nu[2] = 0f64;
        nu[3] = 0f64;
        nu[4] = 0f64;
        nu[5] = 0f64;
        nu[6] = 0f64;
        nu[7] = 0f64;
        nu[8] = self.omega;
        gamma[0] = v134;
        gamma[1] = v138;
        gamma[2] = (v134 + v141);
        gamma[3] = (v138 + v147);
        gamma[4] = v141;
        gamma[5] = v147;
        gamma[6] = (-((v151 + (v151 - (q[6] * v152)))
            + (v158 + (v158 + (q[7] * (qd[8] * v126))))));
        gamma[7] = (-v152);
        gamma[8] = 0f64;
    }
}
