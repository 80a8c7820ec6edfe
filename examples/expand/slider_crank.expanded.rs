// Generated from slider_crank.rs by `MBD_BLESS=1 cargo test -p mbd-macros snapshot`. Do not edit.
/// Slider-crank driven at constant speed (Nikravesh, Planar Multibody Dynamics, ch. 7).
///
/// 3 planar bodies, 9 coordinates and velocities, 9 constraint rows (0 degrees of freedom); D has 23 structural non-zeros of 81.
/**
# Coordinates and velocities

`q[i]` in every `[f64; SliderCrank::NQ]`; planar velocities are their rates, `v[i]` = q̇ᵢ (m/s, rad/s), and v̇, h and the columns of D are indexed the same way.

| i | coordinate | unit |
|---:|---|---|
| 0 | `crank.x` | m |
| 1 | `crank.y` | m |
| 2 | `crank.phi` | rad |
| 3 | `rod.x` | m |
| 4 | `rod.y` | m |
| 5 | `rod.phi` | rad |
| 6 | `slider.x` | m |
| 7 | `slider.y` | m |
| 8 | `slider.phi` | rad |

# Joints, drivers and constraints

In the order of `JOINTS` (the index `joint_reaction` takes) and of their rows in Φ.

| index | joint | kind | rows of Φ |
|---:|---|---|---|
| 0 | `revolute ground~crank` | revolute | 0–1 |
| 1 | `revolute crank~rod` | revolute | 2–3 |
| 2 | `revolute rod~slider` | revolute | 4–5 |
| 3 | `translational slider~ground` | translational | 6–7 |
| 4 | `drive crank.phi` | drive | 8 |

# Constraint rows

`Φ[r]`, and the multiplier `λ[r]`: the reaction of the row, with the sign convention M v̇ − Dᵀλ = h.

| r | row | λ unit |
|---:|---|---|
| 0 | `revolute ground~crank: x` | N |
| 1 | `revolute ground~crank: y` | N |
| 2 | `revolute crank~rod: x` | N |
| 3 | `revolute crank~rod: y` | N |
| 4 | `revolute rod~slider: x` | N |
| 5 | `revolute rod~slider: y` | N |
| 6 | `translational slider~ground: normal` | N |
| 7 | `translational slider~ground: angle` | N·m |
| 8 | `drive crank.phi: phi` | N·m |
*/
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrank {
    ///Parameter `omega` (default 6.283185307179586).
    pub omega: f64,
    ///Parameter `r` (default 0.1).
    pub r: f64,
    ///Parameter `l` (default 0.3).
    pub l: f64,
}
#[allow(clippy::approx_constant)]
impl ::core::default::Default for SliderCrank {
    fn default() -> Self {
        Self {
            omega: 6.283185307179586f64,
            r: 0.1f64,
            l: 0.3f64,
        }
    }
}
#[allow(unused_variables, unused_parens, clippy::approx_constant)]
impl SliderCrank {
    /// Number of moving bodies.
    pub const N_BODIES: usize = 3;
    /// Number of generalized coordinates q (3 per body: x, y, φ).
    pub const NQ: usize = 9;
    /// Number of velocities v (3 per body; planar v = q̇, so NV = NQ).
    pub const NV: usize = 9;
    /// Number of constraint rows (joints, drivers and user constraints).
    pub const NC: usize = 9;
    /// Degrees of freedom: `NV − NC`.
    pub const DOF: i32 = 0i32;
    /// Number of structurally non-zero entries of Φ_q.
    pub const NNZ: usize = 23;
    /// Number of runtime parameters.
    pub const NP: usize = 3;
    /// Scalars of one planned Newton matrix (D's non-zeros and the factors' entries of
    /// [[A, −Dᵀ], [D, 0]], fill included): the last size of this mechanism's
    /// `Workspace`, which statics and generalized-α keep their matrices in.
    pub const NEWTON_STORAGE: usize = 135;
    /// Body `crank`: its coordinates, velocities and points.
    pub const CRANK: ::mbd::PlanarBody<9> = <::mbd::PlanarBody<9>>::new(0, "crank");
    /// Body `rod`: its coordinates, velocities and points.
    pub const ROD: ::mbd::PlanarBody<9> = <::mbd::PlanarBody<9>>::new(1, "rod");
    /// Body `slider`: its coordinates, velocities and points.
    pub const SLIDER: ::mbd::PlanarBody<9> = <::mbd::PlanarBody<9>>::new(2, "slider");
    /// The mass (kg) of a body (`Name::BODY`).
    #[allow(unused_parens, clippy::approx_constant)]
    pub fn mass_of(&self, body: ::mbd::PlanarBody<9>) -> f64 {
        let mut out = [0f64; 3];
        use ::mbd::__private::Elements as _;
        let [__out_0, __out_1, __out_2] = out.window_mut::<0, 3>();
        (*__out_0) = 1f64;
        (*__out_1) = 2f64;
        (*__out_2) = 0.5f64;
        out[body.index]
    }
    /// The moment of inertia J (kg·m²) of a body (`Name::BODY`) about its centre of mass.
    #[allow(unused_parens, clippy::approx_constant)]
    pub fn inertia_of(&self, body: ::mbd::PlanarBody<9>) -> f64 {
        let mut out = [[[0f64; 1]; 1]; 3];
        out[0][0][0] = 0.002f64;
        out[1][0][0] = 0.015f64;
        out[2][0][0] = 0.001f64;
        out[body.index][0][0]
    }
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
    ::mbd::__if_std! {
        #[doc =
        r" The work space every solver takes (its O(N²) arrays: D, the saddle-point"]
        #[doc = r" matrix, NV × NV derivatives, and three planned Newton matrices of"]
        #[doc =
        r" `NEWTON_STORAGE` scalars), zeroed on the heap. Make it once and pass it to"]
        #[doc =
        r" each analysis; without `std`, put a `Workspace::new()` of the same type in a"]
        #[doc = r" `static`."] pub fn workspace() -> ::mbd::workspace::Boxed < f64, 9, 9,
        18, 135 > { ::mbd::Workspace::boxed() }
    }
    /// A generalized-α integrator for this mechanism.
    pub fn generalized_alpha(
        options: ::mbd::GeneralizedAlphaOptions<f64>,
    ) -> ::mbd::GeneralizedAlpha<f64, 9> {
        ::mbd::GeneralizedAlpha::new(options)
    }
    /// The structural non-zeros of Φ_q(q, t), in the order of `JACOBIAN_PATTERN`.
    #[inline]
    pub fn jacobian_values(&self, q: &[f64; 9], t: f64, out: &mut [f64; 23]) {
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v32,
            s_slider,
            c_slider,
            v81,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__out_0, __out_1, __out_2, __out_3, __out_4, __out_5, __out_6, __out_7,
        __out_8, __out_9, __out_10, __out_11, __out_12, __out_13, __out_14, __out_15,
        __out_16, __out_17, __out_18, __out_19, __out_20, __out_21, __out_22] = out
            .window_mut::<0, 23>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v13 = (-(v5 * s_crank));
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v32 = (-(v24 * s_rod));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        (*__out_0) = (-1f64);
        (*__out_1) = v13;
        (*__out_2) = (-1f64);
        (*__out_3) = v10;
        (*__out_4) = 1f64;
        (*__out_5) = v13;
        (*__out_6) = (-1f64);
        (*__out_7) = v32;
        (*__out_8) = 1f64;
        (*__out_9) = v10;
        (*__out_10) = (-1f64);
        (*__out_11) = v29;
        (*__out_12) = 1f64;
        (*__out_13) = v32;
        (*__out_14) = (-1f64);
        (*__out_15) = 1f64;
        (*__out_16) = v29;
        (*__out_17) = (-1f64);
        (*__out_18) = s_slider;
        (*__out_19) = v81;
        (*__out_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__out_21) = v81;
        (*__out_22) = 1f64;
    }
    /// Φ, the structural non-zeros of Φ_q (in the order of `JACOBIAN_PATTERN`), ν and γ in
    /// one evaluation: the sparse twin of `Kinematics::full_eval`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn full_eval_values(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        out: &mut [f64; 23],
        nu: &mut [f64; 9],
        gamma: &mut [f64; 9],
    ) {
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v81,
            v119,
            v126,
            v134,
            v138,
            v141,
            v147,
            v151,
            v152,
            v158,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5, __gamma_6,
        __gamma_7, __gamma_8] = gamma.window_mut::<0, 9>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        let [__out_0, __out_1, __out_2, __out_3, __out_4, __out_5, __out_6, __out_7,
        __out_8, __out_9, __out_10, __out_11, __out_12, __out_13, __out_14, __out_15,
        __out_16, __out_17, __out_18, __out_19, __out_20, __out_21, __out_22] = out
            .window_mut::<0, 23>();
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        v119 = (s_slider * (*__v_8));
        v126 = (c_slider * (*__v_8));
        v134 = (v5 * ((*__v_2) * (c_crank * (*__v_2))));
        v138 = (v5 * ((*__v_2) * (s_crank * (*__v_2))));
        v141 = (v24 * ((*__v_5) * (c_rod * (*__v_5))));
        v147 = (v24 * ((*__v_5) * (s_rod * (*__v_5))));
        v151 = ((*__v_6) * v126);
        v152 = ((*__v_8) * v119);
        v158 = ((*__v_7) * v119);
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
        (*__out_0) = (-1f64);
        (*__out_1) = v13;
        (*__out_2) = (-1f64);
        (*__out_3) = v10;
        (*__out_4) = 1f64;
        (*__out_5) = v13;
        (*__out_6) = (-1f64);
        (*__out_7) = v32;
        (*__out_8) = 1f64;
        (*__out_9) = v10;
        (*__out_10) = (-1f64);
        (*__out_11) = v29;
        (*__out_12) = 1f64;
        (*__out_13) = v32;
        (*__out_14) = (-1f64);
        (*__out_15) = 1f64;
        (*__out_16) = v29;
        (*__out_17) = (-1f64);
        (*__out_18) = s_slider;
        (*__out_19) = v81;
        (*__out_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__out_21) = v81;
        (*__out_22) = 1f64;
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
        (*__gamma_0) = v134;
        (*__gamma_1) = v138;
        (*__gamma_2) = (v134 + v141);
        (*__gamma_3) = (v138 + v147);
        (*__gamma_4) = v141;
        (*__gamma_5) = v147;
        (*__gamma_6) = (-((v151 + (v151 - ((*__q_6) * v152)))
            + (v158
                + <f64 as ::mbd::Real>::fused_mul_add(
                    (*__q_7),
                    ((*__v_8) * v126),
                    v158,
                ))));
        (*__gamma_7) = (-v152);
        (*__gamma_8) = 0f64;
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
    const VELOCITY_NAMES: &'static [&'static str] = &[
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
    const COORDINATES: &'static [::mbd::CoordinateInfo] = &[
        ::mbd::CoordinateInfo {
            name: "crank.x",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "crank.y",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "crank.phi",
            kind: ::mbd::CoordinateKind::Angle,
        },
        ::mbd::CoordinateInfo {
            name: "rod.x",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "rod.y",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "rod.phi",
            kind: ::mbd::CoordinateKind::Angle,
        },
        ::mbd::CoordinateInfo {
            name: "slider.x",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "slider.y",
            kind: ::mbd::CoordinateKind::Length,
        },
        ::mbd::CoordinateInfo {
            name: "slider.phi",
            kind: ::mbd::CoordinateKind::Angle,
        },
    ];
    const VELOCITIES: &'static [::mbd::VelocityInfo] = &[
        ::mbd::VelocityInfo {
            name: "crank.x",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 0,
            },
            displacement: "crank.x",
        },
        ::mbd::VelocityInfo {
            name: "crank.y",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 1,
            },
            displacement: "crank.y",
        },
        ::mbd::VelocityInfo {
            name: "crank.phi",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 2,
            },
            displacement: "crank.phi",
        },
        ::mbd::VelocityInfo {
            name: "rod.x",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 3,
            },
            displacement: "rod.x",
        },
        ::mbd::VelocityInfo {
            name: "rod.y",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 4,
            },
            displacement: "rod.y",
        },
        ::mbd::VelocityInfo {
            name: "rod.phi",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 5,
            },
            displacement: "rod.phi",
        },
        ::mbd::VelocityInfo {
            name: "slider.x",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 6,
            },
            displacement: "slider.x",
        },
        ::mbd::VelocityInfo {
            name: "slider.y",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 7,
            },
            displacement: "slider.y",
        },
        ::mbd::VelocityInfo {
            name: "slider.phi",
            kind: ::mbd::VelocityKind::Rate {
                coordinate: 8,
            },
            displacement: "slider.phi",
        },
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
            function: "forces_v",
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
        ::mbd::OpCount {
            function: "nonconservative_power",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
        ::mbd::OpCount {
            function: "accelerations (evaluation, before the solve)",
            add: 22u32,
            mul: 29u32,
            div: 2u32,
            call: 3u32,
        },
        ::mbd::OpCount {
            function: "newton_matrix (Φ, D and generalized-α's matrix, before the factorization)",
            add: 23u32,
            mul: 21u32,
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
    const FORCE_ELEMENTS: &'static [::mbd::ForceInfo] = &[];
    const BASE_FORCE_OP_COUNTS: &'static [::mbd::OpCount] = &[
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
            function: "forces_v",
            add: 0u32,
            mul: 0u32,
            div: 0u32,
            call: 0u32,
        },
    ];
    const EFFECTS: &'static [&'static str] = &[];
    const CONSTRAINT_UNITS: &'static [&'static str] = &[
        "N",
        "N",
        "N",
        "N",
        "N",
        "N",
        "N",
        "N·m",
        "N·m",
    ];
    #[doc(hidden)]
    const MODEL_JSON: &'static str = "{\"bodies\":[{\"inertia\":[\"num\",0.002],\"mass\":[\"num\",1.0],\"name\":\"crank\",\"q0\":[[\"num\",0.05],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]},{\"inertia\":[\"num\",0.015],\"mass\":[\"num\",2.0],\"name\":\"rod\",\"q0\":[[\"num\",0.25],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]},{\"inertia\":[\"num\",0.001],\"mass\":[\"num\",0.5],\"name\":\"slider\",\"q0\":[[\"num\",0.4],[\"num\",0.0],[\"num\",0.0]],\"qd0\":[[\"num\",0.0],[\"num\",0.0],[\"num\",0.0]]}],\"constraint_rows\":[\"revolute ground~crank: x\",\"revolute ground~crank: y\",\"revolute crank~rod: x\",\"revolute crank~rod: y\",\"revolute rod~slider: x\",\"revolute rod~slider: y\",\"translational slider~ground: normal\",\"translational slider~ground: angle\",\"drive crank.phi: phi\"],\"constraints\":[{\"i\":{\"body\":\"ground\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"j\":{\"body\":\"crank\",\"point\":[[\"div\",[\"neg\",[\"param\",\"r\"]],[\"num\",2.0]],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute ground~crank\"},{\"i\":{\"body\":\"crank\",\"point\":[[\"div\",[\"param\",\"r\"],[\"num\",2.0]],[\"num\",0.0]]},\"j\":{\"body\":\"rod\",\"point\":[[\"div\",[\"neg\",[\"param\",\"l\"]],[\"num\",2.0]],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute crank~rod\"},{\"i\":{\"body\":\"rod\",\"point\":[[\"div\",[\"param\",\"l\"],[\"num\",2.0]],[\"num\",0.0]]},\"j\":{\"body\":\"slider\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"kind\":\"revolute\",\"name\":\"revolute rod~slider\"},{\"i\":{\"axis\":[[\"num\",1.0],[\"num\",0.0]],\"body\":\"slider\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"j\":{\"axis\":[[\"num\",1.0],[\"num\",0.0]],\"body\":\"ground\",\"point\":[[\"num\",0.0],[\"num\",0.0]]},\"kind\":\"translational\",\"name\":\"translational slider~ground\"},{\"body\":\"crank\",\"coordinate\":\"phi\",\"f\":[\"mul\",[\"param\",\"omega\"],[\"t\"]],\"kind\":\"drive\",\"name\":\"drive crank.phi\"}],\"coordinates\":[\"crank.x\",\"crank.y\",\"crank.phi\",\"rod.x\",\"rod.y\",\"rod.phi\",\"slider.x\",\"slider.y\",\"slider.phi\"],\"forces\":[],\"gravity\":null,\"jacobian_pattern\":[[0,0],[0,2],[1,1],[1,2],[2,0],[2,2],[2,3],[2,5],[3,1],[3,2],[3,4],[3,5],[4,3],[4,5],[4,6],[5,4],[5,5],[5,7],[6,6],[6,7],[6,8],[7,8],[8,2]],\"name\":\"SliderCrank\",\"params\":[{\"default\":6.283185307179586,\"name\":\"omega\"},{\"default\":0.1,\"name\":\"r\"},{\"default\":0.3,\"name\":\"l\"}],\"points\":[],\"scalar\":\"f64\",\"vectors\":[]}";
}
impl ::mbd::BodyCoordinates for SliderCrank {}
#[allow(unused_variables, unused_parens, clippy::approx_constant)]
impl ::mbd::Linearize<f64, 9, 9, 9> for SliderCrank {
    const INPUTS: &'static [&'static str] = &[];
    #[inline]
    fn gamma_derivatives(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        gamma_q: &mut [[f64; 9]; 9],
        gamma_v: &mut [[f64; 9]; 9],
    ) {
        for row in gamma_q.iter_mut().chain(gamma_v.iter_mut()) {
            *row = [0f64; 9];
        }
        let (
            v5,
            s_crank,
            c_crank,
            v24,
            s_rod,
            c_rod,
            s_slider,
            c_slider,
            v87,
            v93,
            v98,
            v106,
            v119,
            v126,
            v134,
            v139,
            v141,
            v148,
            v152,
            v160,
            v251,
            v254,
            v259,
            v268,
            v270,
            v272,
            v274,
            v275,
            v277,
            v278,
            v280,
            v285,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v87 = (s_crank * (*__v_2));
        v93 = (c_crank * (*__v_2));
        v98 = (s_rod * (*__v_5));
        v106 = (c_rod * (*__v_5));
        v119 = (s_slider * (*__v_8));
        v126 = (c_slider * (*__v_8));
        v134 = (v5 * ((*__v_2) * v93));
        v139 = (-(v5 * ((*__v_2) * v87)));
        v141 = (v24 * ((*__v_5) * v106));
        v148 = (-(v24 * ((*__v_5) * v98)));
        v152 = ((*__v_8) * v119);
        v160 = ((*__v_8) * v126);
        v251 = (-v160);
        v254 = ((*__v_7) * v126);
        v259 = ((*__v_6) * v119);
        v268 = (v5 * (2f64 * v93));
        v270 = (v5 * (2f64 * v87));
        v272 = (v24 * (2f64 * v106));
        v274 = (v24 * (2f64 * v98));
        v275 = (2f64 * v126);
        v277 = (2f64 * v119);
        v278 = (-v277);
        v280 = (s_slider * (*__v_7));
        v285 = (c_slider * (*__v_6));
        gamma_q[0][2] = v139;
        gamma_q[1][2] = v134;
        gamma_q[2][2] = v139;
        gamma_q[2][5] = v148;
        gamma_q[3][2] = v134;
        gamma_q[3][5] = v141;
        gamma_q[4][5] = v148;
        gamma_q[5][5] = v141;
        gamma_q[6][6] = v152;
        gamma_q[6][7] = v251;
        gamma_q[6][8] = (-((v254 + (v254 - ((*__q_7) * v152)))
            - (v259 + (((*__q_6) * v160) + v259))));
        gamma_q[7][8] = v251;
        gamma_v[0][2] = v268;
        gamma_v[1][2] = v270;
        gamma_v[2][2] = v268;
        gamma_v[2][5] = v272;
        gamma_v[3][2] = v270;
        gamma_v[3][5] = v274;
        gamma_v[4][5] = v272;
        gamma_v[5][5] = v274;
        gamma_v[6][6] = (-v275);
        gamma_v[6][7] = v278;
        gamma_v[6][8] = (-((v280
            + <f64 as ::mbd::Real>::fused_mul_add((*__q_7), v275, v280))
            + (v285 + (v285 - ((*__q_6) * v277)))));
        gamma_v[7][8] = v278;
    }
    #[inline]
    fn forces_input(
        &self,
        k: usize,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        dh: &mut [f64; 9],
    ) {
        *dh = [0f64; 9];
        match k {
            _ => {}
        }
    }
    fn input(&self, k: usize) -> f64 {
        match k {
            _ => 0f64,
        }
    }
    fn set_input(&mut self, k: usize, value: f64) {
        match k {
            _ => {}
        }
    }
}
#[allow(unused_variables, unused_parens, clippy::approx_constant)]
impl ::mbd::ConstraintForces<f64, 9, 9, 9> for SliderCrank {
    #[inline]
    fn constraint_force_q(
        &self,
        q: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        k: &mut [[f64; 9]; 9],
    ) {
        for row in k.iter_mut() {
            *row = [0f64; 9];
        }
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            s_slider,
            c_slider,
            v203,
            v205,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__lambda_0, __lambda_1, __lambda_2, __lambda_3, __lambda_4, __lambda_5,
        __lambda_6, __lambda_7] = lambda.window::<0, 8>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v203 = (s_slider * (*__lambda_6));
        v205 = (c_slider * (*__lambda_6));
        k[2][2] = (-((v12 * (*__lambda_3))
            + ((v10 * (*__lambda_2))
                + ((v12 * (*__lambda_1)) + (v10 * (*__lambda_0))))));
        k[5][5] = (-((v31 * (*__lambda_5))
            + ((v29 * (*__lambda_4))
                + ((v31 * (*__lambda_3)) + (v29 * (*__lambda_2))))));
        k[6][8] = v205;
        k[7][8] = v203;
        k[8][6] = v205;
        k[8][7] = v203;
        k[8][8] = <f64 as ::mbd::Real>::fused_mul_add(
            (*__lambda_6),
            ((c_slider * (*__q_7)) - (s_slider * (*__q_6))),
            (s_slider * (*__lambda_7)),
        );
    }
}
#[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
impl ::mbd::Dynamics<f64, 9, 9, 9> for SliderCrank {
    #[inline]
    fn mass_times(&self, q: &[f64; 9], x: &[f64; 9], y: &mut [f64; 9]) {
        let mut m = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window_mut::<0, 9>();
        (*__m_0) = 1f64;
        (*__m_1) = 1f64;
        (*__m_2) = 0.002f64;
        (*__m_3) = 2f64;
        (*__m_4) = 2f64;
        (*__m_5) = 0.015f64;
        (*__m_6) = 0.5f64;
        (*__m_7) = 0.5f64;
        (*__m_8) = 0.001f64;
        y[0] = m[0] * x[0];
        y[1] = m[1] * x[1];
        y[2] = m[2] * x[2];
        y[3] = m[3] * x[3];
        y[4] = m[4] * x[4];
        y[5] = m[5] * x[5];
        y[6] = m[6] * x[6];
        y[7] = m[7] * x[7];
        y[8] = m[8] * x[8];
    }
    #[inline]
    fn add_mass_matrix(&self, q: &[f64; 9], scale: f64, a: &mut [[f64; 9]; 9]) {
        let mut m = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window_mut::<0, 9>();
        (*__m_0) = 1f64;
        (*__m_1) = 1f64;
        (*__m_2) = 0.002f64;
        (*__m_3) = 2f64;
        (*__m_4) = 2f64;
        (*__m_5) = 0.015f64;
        (*__m_6) = 0.5f64;
        (*__m_7) = 0.5f64;
        (*__m_8) = 0.001f64;
        a[0][0] += scale * m[0];
        a[1][1] += scale * m[1];
        a[2][2] += scale * m[2];
        a[3][3] += scale * m[3];
        a[4][4] += scale * m[4];
        a[5][5] += scale * m[5];
        a[6][6] += scale * m[6];
        a[7][7] += scale * m[7];
        a[8][8] += scale * m[8];
    }
    #[inline]
    fn forces_q(&self, q: &[f64; 9], v: &[f64; 9], t: f64, dh: &mut [[f64; 9]; 9]) {
        for row in dh.iter_mut() {
            *row = [0f64; 9];
        }
    }
    #[inline]
    fn forces_v(&self, q: &[f64; 9], v: &[f64; 9], t: f64, dh: &mut [[f64; 9]; 9]) {
        for row in dh.iter_mut() {
            *row = [0f64; 9];
        }
    }
    #[inline]
    fn forces(&self, q: &[f64; 9], v: &[f64; 9], t: f64, h: &mut [f64; 9]) {
        use ::mbd::__private::Elements as _;
        let [__h_0, __h_1, __h_2, __h_3, __h_4, __h_5, __h_6, __h_7, __h_8] = h
            .window_mut::<0, 9>();
        (*__h_0) = 0f64;
        (*__h_1) = 0f64;
        (*__h_2) = 0f64;
        (*__h_3) = 0f64;
        (*__h_4) = 0f64;
        (*__h_5) = 0f64;
        (*__h_6) = 0f64;
        (*__h_7) = 0f64;
        (*__h_8) = 0f64;
    }
    #[inline]
    fn potential_energy(&self, q: &[f64; 9], t: f64) -> f64 {
        let mut energy = [0f64; 1];
        use ::mbd::__private::Elements as _;
        let [__energy_0] = energy.window_mut::<0, 1>();
        (*__energy_0) = 0f64;
        energy[0]
    }
    #[inline]
    fn friction_forces(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        h: &mut [f64; 9],
    ) {}
    #[inline]
    fn friction_derivatives(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        d_q: &mut [[f64; 9]; 9],
        d_v: &mut [[f64; 9]; 9],
    ) {}
    #[inline]
    fn friction_multiplier_derivatives(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        d_lambda: &mut [[f64; 9]; 9],
    ) {}
    #[inline]
    fn nonconservative_power(&self, q: &[f64; 9], v: &[f64; 9], t: f64) -> f64 {
        let mut power = [0f64; 1];
        use ::mbd::__private::Elements as _;
        let [__power_0] = power.window_mut::<0, 1>();
        (*__power_0) = 0f64;
        power[0]
    }
}
#[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
impl SliderCrank {
    /// LDLᵀ of S = D M⁻¹ Dᵀ over its compile-time pattern; `Err(row)` for a dependent row.
    #[inline(always)]
    fn schur_factor(
        jv: &[f64; 23],
        minv: &[f64; 9],
        tol: f64,
        allow_redundant: bool,
        l: &mut [f64; 18],
        dinv: &mut [f64; 9],
    ) -> ::core::result::Result<(), usize> {
        let mut d = [0f64; 9];
        let exact: f64 = if allow_redundant { 1e2 } else { 1.0 };
        use ::mbd::__private::Elements as _;
        let [__d_0, __d_1, __d_2, __d_3, __d_4, __d_5, __d_6, __d_7, __d_8] = d
            .window_mut::<0, 9>();
        let [__dinv_0, __dinv_1, __dinv_2, __dinv_3, __dinv_4, __dinv_5, __dinv_6,
        __dinv_7, __dinv_8] = dinv.window_mut::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__l_0, __l_1, __l_2, __l_3, __l_4, __l_5, __l_6, __l_7, __l_8, __l_9,
        __l_10, __l_11, __l_12, __l_13, __l_14, __l_15, __l_16, __l_17] = l
            .window_mut::<0, 18>();
        let [__minv_0, __minv_1, __minv_2, __minv_3, __minv_4, __minv_5, __minv_6,
        __minv_7, __minv_8] = minv.window::<0, 9>();
        let skk: f64 = ((*__jv_21) * (*__jv_21) * (*__minv_8));
        let dk: f64 = skk;
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(7);
        };
        (*__d_0) = dk;
        (*__dinv_0) = dik;
        (*__l_0) = (((*__jv_21) * (*__jv_20) * (*__minv_8))) * (*__dinv_0);
        let skk: f64 = ((*__jv_18) * (*__jv_18) * (*__minv_6)
            + (*__jv_19) * (*__jv_19) * (*__minv_7)
            + (*__jv_20) * (*__jv_20) * (*__minv_8));
        let dk: f64 = skk - (*__l_0) * (*__l_0) * (*__d_0);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(6);
        };
        (*__d_1) = dk;
        (*__dinv_1) = dik;
        (*__l_1) = (((*__jv_18) * (*__jv_14) * (*__minv_6))) * (*__dinv_1);
        (*__l_2) = (((*__jv_19) * (*__jv_17) * (*__minv_7))) * (*__dinv_1);
        let skk: f64 = ((*__jv_12) * (*__jv_12) * (*__minv_3)
            + (*__jv_13) * (*__jv_13) * (*__minv_5)
            + (*__jv_14) * (*__jv_14) * (*__minv_6));
        let dk: f64 = skk - (*__l_1) * (*__l_1) * (*__d_1);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(4);
        };
        (*__d_2) = dk;
        (*__dinv_2) = dik;
        (*__l_3) = (((*__jv_16) * (*__jv_13) * (*__minv_5))
            - (*__l_2) * (*__l_1) * (*__d_1)) * (*__dinv_2);
        (*__l_4) = (((*__jv_12) * (*__jv_6) * (*__minv_3)
            + (*__jv_13) * (*__jv_7) * (*__minv_5))) * (*__dinv_2);
        (*__l_5) = (((*__jv_13) * (*__jv_11) * (*__minv_5))) * (*__dinv_2);
        let skk: f64 = ((*__jv_15) * (*__jv_15) * (*__minv_4)
            + (*__jv_16) * (*__jv_16) * (*__minv_5)
            + (*__jv_17) * (*__jv_17) * (*__minv_7));
        let dk: f64 = skk - (*__l_2) * (*__l_2) * (*__d_1)
            - (*__l_3) * (*__l_3) * (*__d_2);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(5);
        };
        (*__d_3) = dk;
        (*__dinv_3) = dik;
        (*__l_6) = (((*__jv_16) * (*__jv_7) * (*__minv_5))
            - (*__l_4) * (*__l_3) * (*__d_2)) * (*__dinv_3);
        (*__l_7) = (((*__jv_15) * (*__jv_10) * (*__minv_4)
            + (*__jv_16) * (*__jv_11) * (*__minv_5)) - (*__l_5) * (*__l_3) * (*__d_2))
            * (*__dinv_3);
        let skk: f64 = ((*__jv_0) * (*__jv_0) * (*__minv_0)
            + (*__jv_1) * (*__jv_1) * (*__minv_2));
        let dk: f64 = skk;
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(0);
        };
        (*__d_4) = dk;
        (*__dinv_4) = dik;
        (*__l_8) = (((*__jv_3) * (*__jv_1) * (*__minv_2))) * (*__dinv_4);
        (*__l_9) = (((*__jv_22) * (*__jv_1) * (*__minv_2))) * (*__dinv_4);
        (*__l_10) = (((*__jv_4) * (*__jv_0) * (*__minv_0)
            + (*__jv_5) * (*__jv_1) * (*__minv_2))) * (*__dinv_4);
        (*__l_11) = (((*__jv_9) * (*__jv_1) * (*__minv_2))) * (*__dinv_4);
        let skk: f64 = ((*__jv_2) * (*__jv_2) * (*__minv_1)
            + (*__jv_3) * (*__jv_3) * (*__minv_2));
        let dk: f64 = skk - (*__l_8) * (*__l_8) * (*__d_4);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(1);
        };
        (*__d_5) = dk;
        (*__dinv_5) = dik;
        (*__l_12) = (((*__jv_22) * (*__jv_3) * (*__minv_2))
            - (*__l_9) * (*__l_8) * (*__d_4)) * (*__dinv_5);
        (*__l_13) = (((*__jv_5) * (*__jv_3) * (*__minv_2))
            - (*__l_10) * (*__l_8) * (*__d_4)) * (*__dinv_5);
        (*__l_14) = (((*__jv_8) * (*__jv_2) * (*__minv_1)
            + (*__jv_9) * (*__jv_3) * (*__minv_2)) - (*__l_11) * (*__l_8) * (*__d_4))
            * (*__dinv_5);
        let skk: f64 = ((*__jv_22) * (*__jv_22) * (*__minv_2));
        let dk: f64 = skk - (*__l_9) * (*__l_9) * (*__d_4)
            - (*__l_12) * (*__l_12) * (*__d_5);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(8);
        };
        (*__d_6) = dk;
        (*__dinv_6) = dik;
        (*__l_15) = (((*__jv_22) * (*__jv_5) * (*__minv_2))
            - (*__l_10) * (*__l_9) * (*__d_4) - (*__l_13) * (*__l_12) * (*__d_5))
            * (*__dinv_6);
        (*__l_16) = (((*__jv_22) * (*__jv_9) * (*__minv_2))
            - (*__l_11) * (*__l_9) * (*__d_4) - (*__l_14) * (*__l_12) * (*__d_5))
            * (*__dinv_6);
        let skk: f64 = ((*__jv_4) * (*__jv_4) * (*__minv_0)
            + (*__jv_5) * (*__jv_5) * (*__minv_2) + (*__jv_6) * (*__jv_6) * (*__minv_3)
            + (*__jv_7) * (*__jv_7) * (*__minv_5));
        let dk: f64 = skk - (*__l_4) * (*__l_4) * (*__d_2)
            - (*__l_6) * (*__l_6) * (*__d_3) - (*__l_10) * (*__l_10) * (*__d_4)
            - (*__l_13) * (*__l_13) * (*__d_5) - (*__l_15) * (*__l_15) * (*__d_6);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(2);
        };
        (*__d_7) = dk;
        (*__dinv_7) = dik;
        (*__l_17) = (((*__jv_9) * (*__jv_5) * (*__minv_2)
            + (*__jv_11) * (*__jv_7) * (*__minv_5)) - (*__l_5) * (*__l_4) * (*__d_2)
            - (*__l_7) * (*__l_6) * (*__d_3) - (*__l_11) * (*__l_10) * (*__d_4)
            - (*__l_14) * (*__l_13) * (*__d_5) - (*__l_16) * (*__l_15) * (*__d_6))
            * (*__dinv_7);
        let skk: f64 = ((*__jv_8) * (*__jv_8) * (*__minv_1)
            + (*__jv_9) * (*__jv_9) * (*__minv_2) + (*__jv_10) * (*__jv_10) * (*__minv_4)
            + (*__jv_11) * (*__jv_11) * (*__minv_5));
        let dk: f64 = skk - (*__l_5) * (*__l_5) * (*__d_2)
            - (*__l_7) * (*__l_7) * (*__d_3) - (*__l_11) * (*__l_11) * (*__d_4)
            - (*__l_14) * (*__l_14) * (*__d_5) - (*__l_16) * (*__l_16) * (*__d_6)
            - (*__l_17) * (*__l_17) * (*__d_7);
        let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(
            skk,
            dk,
            exact,
            tol,
            allow_redundant,
        ) else {
            return ::core::result::Result::Err(3);
        };
        (*__d_8) = dk;
        (*__dinv_8) = dik;
        ::core::result::Result::Ok(())
    }
    /// b ← S⁻¹ b with the factors of `schur_factor`.
    #[inline(always)]
    fn schur_solve(l: &[f64; 18], dinv: &[f64; 9], b: &mut [f64; 9]) {
        use ::mbd::__private::Elements as _;
        let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
            .window_mut::<0, 9>();
        let [__dinv_0, __dinv_1, __dinv_2, __dinv_3, __dinv_4, __dinv_5, __dinv_6,
        __dinv_7, __dinv_8] = dinv.window::<0, 9>();
        let [__l_0, __l_1, __l_2, __l_3, __l_4, __l_5, __l_6, __l_7, __l_8, __l_9,
        __l_10, __l_11, __l_12, __l_13, __l_14, __l_15, __l_16, __l_17] = l
            .window::<0, 18>();
        (*__b_6) -= (*__l_0) * (*__b_7);
        (*__b_4) -= (*__l_1) * (*__b_6);
        (*__b_5) -= (*__l_2) * (*__b_6);
        (*__b_5) -= (*__l_3) * (*__b_4);
        (*__b_1) -= (*__l_8) * (*__b_0);
        (*__b_8) -= (*__l_9) * (*__b_0);
        (*__b_8) -= (*__l_12) * (*__b_1);
        (*__b_2) -= (*__l_4) * (*__b_4);
        (*__b_2) -= (*__l_6) * (*__b_5);
        (*__b_2) -= (*__l_10) * (*__b_0);
        (*__b_2) -= (*__l_13) * (*__b_1);
        (*__b_2) -= (*__l_15) * (*__b_8);
        (*__b_3) -= (*__l_5) * (*__b_4);
        (*__b_3) -= (*__l_7) * (*__b_5);
        (*__b_3) -= (*__l_11) * (*__b_0);
        (*__b_3) -= (*__l_14) * (*__b_1);
        (*__b_3) -= (*__l_16) * (*__b_8);
        (*__b_3) -= (*__l_17) * (*__b_2);
        (*__b_7) *= (*__dinv_0);
        (*__b_6) *= (*__dinv_1);
        (*__b_4) *= (*__dinv_2);
        (*__b_5) *= (*__dinv_3);
        (*__b_0) *= (*__dinv_4);
        (*__b_1) *= (*__dinv_5);
        (*__b_8) *= (*__dinv_6);
        (*__b_2) *= (*__dinv_7);
        (*__b_3) *= (*__dinv_8);
        (*__b_2) -= (*__l_17) * (*__b_3);
        (*__b_8) -= (*__l_15) * (*__b_2);
        (*__b_8) -= (*__l_16) * (*__b_3);
        (*__b_1) -= (*__l_12) * (*__b_8);
        (*__b_1) -= (*__l_13) * (*__b_2);
        (*__b_1) -= (*__l_14) * (*__b_3);
        (*__b_0) -= (*__l_8) * (*__b_1);
        (*__b_0) -= (*__l_9) * (*__b_8);
        (*__b_0) -= (*__l_10) * (*__b_2);
        (*__b_0) -= (*__l_11) * (*__b_3);
        (*__b_5) -= (*__l_6) * (*__b_2);
        (*__b_5) -= (*__l_7) * (*__b_3);
        (*__b_4) -= (*__l_3) * (*__b_5);
        (*__b_4) -= (*__l_4) * (*__b_2);
        (*__b_4) -= (*__l_5) * (*__b_3);
        (*__b_6) -= (*__l_1) * (*__b_4);
        (*__b_6) -= (*__l_2) * (*__b_5);
        (*__b_7) -= (*__l_0) * (*__b_6);
    }
    /// x = D⁻¹ b for a square, regular D from `schur_factor`'s factors of D Dᵀ, refined on
    /// its residual; false where the refinement does not settle.
    #[inline]
    fn constraint_solve(
        jv: &[f64; 23],
        l: &[f64; 18],
        dinv: &[f64; 9],
        rhs: &[f64; 9],
        x: &mut [f64; 9],
    ) -> bool {
        let mut b = *rhs;
        Self::schur_solve(l, dinv, &mut b);
        *x = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
            .window::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__x_0, __x_1, __x_2, __x_3, __x_4, __x_5, __x_6, __x_7, __x_8] = x
            .window_mut::<0, 9>();
        (*__x_0) = ((*__jv_0) * (*__b_0) + (*__jv_4) * (*__b_2));
        (*__x_1) = ((*__jv_2) * (*__b_1) + (*__jv_8) * (*__b_3));
        (*__x_2) = ((*__jv_1) * (*__b_0) + (*__jv_3) * (*__b_1) + (*__jv_5) * (*__b_2)
            + (*__jv_9) * (*__b_3) + (*__jv_22) * (*__b_8));
        (*__x_3) = ((*__jv_6) * (*__b_2) + (*__jv_12) * (*__b_4));
        (*__x_4) = ((*__jv_10) * (*__b_3) + (*__jv_15) * (*__b_5));
        (*__x_5) = ((*__jv_7) * (*__b_2) + (*__jv_11) * (*__b_3) + (*__jv_13) * (*__b_4)
            + (*__jv_16) * (*__b_5));
        (*__x_6) = ((*__jv_14) * (*__b_4) + (*__jv_18) * (*__b_6));
        (*__x_7) = ((*__jv_17) * (*__b_5) + (*__jv_19) * (*__b_6));
        (*__x_8) = ((*__jv_20) * (*__b_6) + (*__jv_21) * (*__b_7));
        ::mbd::__private::refined(
            x,
            |x, dx| {
                let mut b = [0f64; 9];
                use ::mbd::__private::Elements as _;
                let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
                    .window_mut::<0, 9>();
                let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7,
                __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15,
                __jv_16, __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                    .window::<0, 23>();
                let [__rhs_0, __rhs_1, __rhs_2, __rhs_3, __rhs_4, __rhs_5, __rhs_6,
                __rhs_7, __rhs_8] = rhs.window::<0, 9>();
                let [__x_0, __x_1, __x_2, __x_3, __x_4, __x_5, __x_6, __x_7, __x_8] = x
                    .window::<0, 9>();
                (*__b_0) = (*__rhs_0) - ((*__jv_0) * (*__x_0) + (*__jv_1) * (*__x_2));
                (*__b_1) = (*__rhs_1) - ((*__jv_2) * (*__x_1) + (*__jv_3) * (*__x_2));
                (*__b_2) = (*__rhs_2)
                    - ((*__jv_4) * (*__x_0) + (*__jv_5) * (*__x_2) + (*__jv_6) * (*__x_3)
                        + (*__jv_7) * (*__x_5));
                (*__b_3) = (*__rhs_3)
                    - ((*__jv_8) * (*__x_1) + (*__jv_9) * (*__x_2)
                        + (*__jv_10) * (*__x_4) + (*__jv_11) * (*__x_5));
                (*__b_4) = (*__rhs_4)
                    - ((*__jv_12) * (*__x_3) + (*__jv_13) * (*__x_5)
                        + (*__jv_14) * (*__x_6));
                (*__b_5) = (*__rhs_5)
                    - ((*__jv_15) * (*__x_4) + (*__jv_16) * (*__x_5)
                        + (*__jv_17) * (*__x_7));
                (*__b_6) = (*__rhs_6)
                    - ((*__jv_18) * (*__x_6) + (*__jv_19) * (*__x_7)
                        + (*__jv_20) * (*__x_8));
                (*__b_7) = (*__rhs_7) - ((*__jv_21) * (*__x_8));
                (*__b_8) = (*__rhs_8) - ((*__jv_22) * (*__x_2));
                Self::schur_solve(l, dinv, &mut b);
                use ::mbd::__private::Elements as _;
                let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
                    .window::<0, 9>();
                let [__dx_0, __dx_1, __dx_2, __dx_3, __dx_4, __dx_5, __dx_6, __dx_7,
                __dx_8] = dx.window_mut::<0, 9>();
                let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7,
                __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15,
                __jv_16, __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                    .window::<0, 23>();
                (*__dx_0) = ((*__jv_0) * (*__b_0) + (*__jv_4) * (*__b_2));
                (*__dx_1) = ((*__jv_2) * (*__b_1) + (*__jv_8) * (*__b_3));
                (*__dx_2) = ((*__jv_1) * (*__b_0) + (*__jv_3) * (*__b_1)
                    + (*__jv_5) * (*__b_2) + (*__jv_9) * (*__b_3)
                    + (*__jv_22) * (*__b_8));
                (*__dx_3) = ((*__jv_6) * (*__b_2) + (*__jv_12) * (*__b_4));
                (*__dx_4) = ((*__jv_10) * (*__b_3) + (*__jv_15) * (*__b_5));
                (*__dx_5) = ((*__jv_7) * (*__b_2) + (*__jv_11) * (*__b_3)
                    + (*__jv_13) * (*__b_4) + (*__jv_16) * (*__b_5));
                (*__dx_6) = ((*__jv_14) * (*__b_4) + (*__jv_18) * (*__b_6));
                (*__dx_7) = ((*__jv_17) * (*__b_5) + (*__jv_19) * (*__b_6));
                (*__dx_8) = ((*__jv_20) * (*__b_6) + (*__jv_21) * (*__b_7));
            },
        )
    }
    /// x = D⁻ᵀ b for a square, regular D from `schur_factor`'s factors of D Dᵀ, refined
    /// on its residual; false where the refinement does not settle.
    #[inline]
    fn transpose_solve(
        jv: &[f64; 23],
        l: &[f64; 18],
        dinv: &[f64; 9],
        rhs: &[f64; 9],
        x: &mut [f64; 9],
    ) -> bool {
        let mut b = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
            .window_mut::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__rhs_0, __rhs_1, __rhs_2, __rhs_3, __rhs_4, __rhs_5, __rhs_6, __rhs_7,
        __rhs_8] = rhs.window::<0, 9>();
        (*__b_0) = ((*__jv_0) * (*__rhs_0) + (*__jv_1) * (*__rhs_2));
        (*__b_1) = ((*__jv_2) * (*__rhs_1) + (*__jv_3) * (*__rhs_2));
        (*__b_2) = ((*__jv_4) * (*__rhs_0) + (*__jv_5) * (*__rhs_2)
            + (*__jv_6) * (*__rhs_3) + (*__jv_7) * (*__rhs_5));
        (*__b_3) = ((*__jv_8) * (*__rhs_1) + (*__jv_9) * (*__rhs_2)
            + (*__jv_10) * (*__rhs_4) + (*__jv_11) * (*__rhs_5));
        (*__b_4) = ((*__jv_12) * (*__rhs_3) + (*__jv_13) * (*__rhs_5)
            + (*__jv_14) * (*__rhs_6));
        (*__b_5) = ((*__jv_15) * (*__rhs_4) + (*__jv_16) * (*__rhs_5)
            + (*__jv_17) * (*__rhs_7));
        (*__b_6) = ((*__jv_18) * (*__rhs_6) + (*__jv_19) * (*__rhs_7)
            + (*__jv_20) * (*__rhs_8));
        (*__b_7) = ((*__jv_21) * (*__rhs_8));
        (*__b_8) = ((*__jv_22) * (*__rhs_2));
        Self::schur_solve(l, dinv, &mut b);
        *x = b;
        ::mbd::__private::refined(
            x,
            |x, b| {
                let mut w = [0f64; 9];
                use ::mbd::__private::Elements as _;
                let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7,
                __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15,
                __jv_16, __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                    .window::<0, 23>();
                let [__rhs_0, __rhs_1, __rhs_2, __rhs_3, __rhs_4, __rhs_5, __rhs_6,
                __rhs_7, __rhs_8] = rhs.window::<0, 9>();
                let [__w_0, __w_1, __w_2, __w_3, __w_4, __w_5, __w_6, __w_7, __w_8] = w
                    .window_mut::<0, 9>();
                let [__x_0, __x_1, __x_2, __x_3, __x_4, __x_5, __x_6, __x_7, __x_8] = x
                    .window::<0, 9>();
                (*__w_0) = (*__rhs_0) - ((*__jv_0) * (*__x_0) + (*__jv_4) * (*__x_2));
                (*__w_1) = (*__rhs_1) - ((*__jv_2) * (*__x_1) + (*__jv_8) * (*__x_3));
                (*__w_2) = (*__rhs_2)
                    - ((*__jv_1) * (*__x_0) + (*__jv_3) * (*__x_1) + (*__jv_5) * (*__x_2)
                        + (*__jv_9) * (*__x_3) + (*__jv_22) * (*__x_8));
                (*__w_3) = (*__rhs_3) - ((*__jv_6) * (*__x_2) + (*__jv_12) * (*__x_4));
                (*__w_4) = (*__rhs_4) - ((*__jv_10) * (*__x_3) + (*__jv_15) * (*__x_5));
                (*__w_5) = (*__rhs_5)
                    - ((*__jv_7) * (*__x_2) + (*__jv_11) * (*__x_3)
                        + (*__jv_13) * (*__x_4) + (*__jv_16) * (*__x_5));
                (*__w_6) = (*__rhs_6) - ((*__jv_14) * (*__x_4) + (*__jv_18) * (*__x_6));
                (*__w_7) = (*__rhs_7) - ((*__jv_17) * (*__x_5) + (*__jv_19) * (*__x_6));
                (*__w_8) = (*__rhs_8) - ((*__jv_20) * (*__x_6) + (*__jv_21) * (*__x_7));
                use ::mbd::__private::Elements as _;
                let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
                    .window_mut::<0, 9>();
                let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7,
                __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15,
                __jv_16, __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                    .window::<0, 23>();
                let [__w_0, __w_1, __w_2, __w_3, __w_4, __w_5, __w_6, __w_7, __w_8] = w
                    .window::<0, 9>();
                (*__b_0) = ((*__jv_0) * (*__w_0) + (*__jv_1) * (*__w_2));
                (*__b_1) = ((*__jv_2) * (*__w_1) + (*__jv_3) * (*__w_2));
                (*__b_2) = ((*__jv_4) * (*__w_0) + (*__jv_5) * (*__w_2)
                    + (*__jv_6) * (*__w_3) + (*__jv_7) * (*__w_5));
                (*__b_3) = ((*__jv_8) * (*__w_1) + (*__jv_9) * (*__w_2)
                    + (*__jv_10) * (*__w_4) + (*__jv_11) * (*__w_5));
                (*__b_4) = ((*__jv_12) * (*__w_3) + (*__jv_13) * (*__w_5)
                    + (*__jv_14) * (*__w_6));
                (*__b_5) = ((*__jv_15) * (*__w_4) + (*__jv_16) * (*__w_5)
                    + (*__jv_17) * (*__w_7));
                (*__b_6) = ((*__jv_18) * (*__w_6) + (*__jv_19) * (*__w_7)
                    + (*__jv_20) * (*__w_8));
                (*__b_7) = ((*__jv_21) * (*__w_8));
                (*__b_8) = ((*__jv_22) * (*__w_2));
                Self::schur_solve(l, dinv, b);
            },
        )
    }
}
#[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
impl ::mbd::ForwardDynamics<f64, 9, 9, 9> for SliderCrank {
    #[inline]
    fn accelerations(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        options: &::mbd::DynamicsOptions<f64>,
        vd: &mut [f64; 9],
        lambda: &mut [f64; 9],
    ) -> ::core::result::Result<(), ::mbd::DynamicsError> {
        let mut jv = [0f64; 23];
        let mut phi = [0f64; 9];
        let mut nu = [0f64; 9];
        let mut gamma = [0f64; 9];
        let mut h = [0f64; 9];
        let mut m = [0f64; 9];
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v81,
            v119,
            v126,
            v134,
            v138,
            v141,
            v147,
            v151,
            v152,
            v158,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5, __gamma_6,
        __gamma_7, __gamma_8] = gamma.window_mut::<0, 9>();
        let [__h_0, __h_1, __h_2, __h_3, __h_4, __h_5, __h_6, __h_7, __h_8] = h
            .window_mut::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window_mut::<0, 23>();
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window_mut::<0, 9>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        v119 = (s_slider * (*__v_8));
        v126 = (c_slider * (*__v_8));
        v134 = (v5 * ((*__v_2) * (c_crank * (*__v_2))));
        v138 = (v5 * ((*__v_2) * (s_crank * (*__v_2))));
        v141 = (v24 * ((*__v_5) * (c_rod * (*__v_5))));
        v147 = (v24 * ((*__v_5) * (s_rod * (*__v_5))));
        v151 = ((*__v_6) * v126);
        v152 = ((*__v_8) * v119);
        v158 = ((*__v_7) * v119);
        (*__jv_0) = (-1f64);
        (*__jv_1) = v13;
        (*__jv_2) = (-1f64);
        (*__jv_3) = v10;
        (*__jv_4) = 1f64;
        (*__jv_5) = v13;
        (*__jv_6) = (-1f64);
        (*__jv_7) = v32;
        (*__jv_8) = 1f64;
        (*__jv_9) = v10;
        (*__jv_10) = (-1f64);
        (*__jv_11) = v29;
        (*__jv_12) = 1f64;
        (*__jv_13) = v32;
        (*__jv_14) = (-1f64);
        (*__jv_15) = 1f64;
        (*__jv_16) = v29;
        (*__jv_17) = (-1f64);
        (*__jv_18) = s_slider;
        (*__jv_19) = v81;
        (*__jv_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__jv_21) = v81;
        (*__jv_22) = 1f64;
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
        (*__gamma_0) = v134;
        (*__gamma_1) = v138;
        (*__gamma_2) = (v134 + v141);
        (*__gamma_3) = (v138 + v147);
        (*__gamma_4) = v141;
        (*__gamma_5) = v147;
        (*__gamma_6) = (-((v151 + (v151 - ((*__q_6) * v152)))
            + (v158
                + <f64 as ::mbd::Real>::fused_mul_add(
                    (*__q_7),
                    ((*__v_8) * v126),
                    v158,
                ))));
        (*__gamma_7) = (-v152);
        (*__gamma_8) = 0f64;
        (*__h_0) = 0f64;
        (*__h_1) = 0f64;
        (*__h_2) = 0f64;
        (*__h_3) = 0f64;
        (*__h_4) = 0f64;
        (*__h_5) = 0f64;
        (*__h_6) = 0f64;
        (*__h_7) = 0f64;
        (*__h_8) = 0f64;
        (*__m_0) = 1f64;
        (*__m_1) = 1f64;
        (*__m_2) = 0.002f64;
        (*__m_3) = 2f64;
        (*__m_4) = 2f64;
        (*__m_5) = 0.015f64;
        (*__m_6) = 0.5f64;
        (*__m_7) = 0.5f64;
        (*__m_8) = 0.001f64;
        let mut minv = [0f64; 9];
        minv[0] = 1f64 / m[0];
        minv[1] = minv[0];
        minv[2] = 1f64 / m[2];
        minv[3] = 1f64 / m[3];
        minv[4] = minv[3];
        minv[5] = 1f64 / m[5];
        minv[6] = 1f64 / m[6];
        minv[7] = minv[6];
        minv[8] = 1f64 / m[8];
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        if let ::core::result::Result::Err(row) = Self::schur_factor(
            &jv,
            &minv,
            options.pivot_tolerance,
            options.allow_redundant,
            &mut l,
            &mut dinv,
        ) {
            let finite = q
                .iter()
                .chain(jv.iter())
                .chain(m.iter())
                .all(|x| x.is_finite());
            const MASS_BODIES: [u16; 9] = [
                0u16, 0u16, 0u16, 1u16, 1u16, 1u16, 2u16, 2u16, 2u16,
            ];
            return ::core::result::Result::Err(
                ::mbd::DynamicsError::from_pivot::<
                    Self,
                    f64,
                >(t, row, &m[..], &MASS_BODIES, &jv[..], finite, options.allow_redundant),
            );
        }
        let two_alpha = options.baumgarte_alpha + options.baumgarte_alpha;
        let beta2 = options.baumgarte_beta * options.baumgarte_beta;
        use ::mbd::__private::Elements as _;
        let [__h_0, __h_1, __h_2, __h_3, __h_4, __h_5, __h_6, __h_7, __h_8] = h
            .window::<0, 9>();
        let [__minv_0, __minv_1, __minv_2, __minv_3, __minv_4, __minv_5, __minv_6,
        __minv_7, __minv_8] = minv.window::<0, 9>();
        let [__vd_0, __vd_1, __vd_2, __vd_3, __vd_4, __vd_5, __vd_6, __vd_7, __vd_8] = vd
            .window_mut::<0, 9>();
        (*__vd_0) = (*__h_0) * (*__minv_0);
        (*__vd_1) = (*__h_1) * (*__minv_1);
        (*__vd_2) = (*__h_2) * (*__minv_2);
        (*__vd_3) = (*__h_3) * (*__minv_3);
        (*__vd_4) = (*__h_4) * (*__minv_4);
        (*__vd_5) = (*__h_5) * (*__minv_5);
        (*__vd_6) = (*__h_6) * (*__minv_6);
        (*__vd_7) = (*__h_7) * (*__minv_7);
        (*__vd_8) = (*__h_8) * (*__minv_8);
        use ::mbd::__private::Elements as _;
        let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5, __gamma_6,
        __gamma_7, __gamma_8] = gamma.window::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__lambda_0, __lambda_1, __lambda_2, __lambda_3, __lambda_4, __lambda_5,
        __lambda_6, __lambda_7, __lambda_8] = lambda.window_mut::<0, 9>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window::<0, 9>();
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window::<0, 9>();
        let [__v_0, __v_1, __v_2, __v_3, __v_4, __v_5, __v_6, __v_7, __v_8] = v
            .window::<0, 9>();
        let [__vd_0, __vd_1, __vd_2, __vd_3, __vd_4, __vd_5, __vd_6, __vd_7, __vd_8] = vd
            .window::<0, 9>();
        (*__lambda_0) = (*__gamma_0) - ((*__jv_0) * (*__vd_0) + (*__jv_1) * (*__vd_2))
            - two_alpha * (((*__jv_0) * (*__v_0) + (*__jv_1) * (*__v_2)) - (*__nu_0))
            - beta2 * (*__phi_0);
        (*__lambda_1) = (*__gamma_1) - ((*__jv_2) * (*__vd_1) + (*__jv_3) * (*__vd_2))
            - two_alpha * (((*__jv_2) * (*__v_1) + (*__jv_3) * (*__v_2)) - (*__nu_1))
            - beta2 * (*__phi_1);
        (*__lambda_2) = (*__gamma_2)
            - ((*__jv_4) * (*__vd_0) + (*__jv_5) * (*__vd_2) + (*__jv_6) * (*__vd_3)
                + (*__jv_7) * (*__vd_5))
            - two_alpha
                * (((*__jv_4) * (*__v_0) + (*__jv_5) * (*__v_2) + (*__jv_6) * (*__v_3)
                    + (*__jv_7) * (*__v_5)) - (*__nu_2)) - beta2 * (*__phi_2);
        (*__lambda_3) = (*__gamma_3)
            - ((*__jv_8) * (*__vd_1) + (*__jv_9) * (*__vd_2) + (*__jv_10) * (*__vd_4)
                + (*__jv_11) * (*__vd_5))
            - two_alpha
                * (((*__jv_8) * (*__v_1) + (*__jv_9) * (*__v_2) + (*__jv_10) * (*__v_4)
                    + (*__jv_11) * (*__v_5)) - (*__nu_3)) - beta2 * (*__phi_3);
        (*__lambda_4) = (*__gamma_4)
            - ((*__jv_12) * (*__vd_3) + (*__jv_13) * (*__vd_5) + (*__jv_14) * (*__vd_6))
            - two_alpha
                * (((*__jv_12) * (*__v_3) + (*__jv_13) * (*__v_5)
                    + (*__jv_14) * (*__v_6)) - (*__nu_4)) - beta2 * (*__phi_4);
        (*__lambda_5) = (*__gamma_5)
            - ((*__jv_15) * (*__vd_4) + (*__jv_16) * (*__vd_5) + (*__jv_17) * (*__vd_7))
            - two_alpha
                * (((*__jv_15) * (*__v_4) + (*__jv_16) * (*__v_5)
                    + (*__jv_17) * (*__v_7)) - (*__nu_5)) - beta2 * (*__phi_5);
        (*__lambda_6) = (*__gamma_6)
            - ((*__jv_18) * (*__vd_6) + (*__jv_19) * (*__vd_7) + (*__jv_20) * (*__vd_8))
            - two_alpha
                * (((*__jv_18) * (*__v_6) + (*__jv_19) * (*__v_7)
                    + (*__jv_20) * (*__v_8)) - (*__nu_6)) - beta2 * (*__phi_6);
        (*__lambda_7) = (*__gamma_7) - ((*__jv_21) * (*__vd_8))
            - two_alpha * (((*__jv_21) * (*__v_8)) - (*__nu_7)) - beta2 * (*__phi_7);
        (*__lambda_8) = (*__gamma_8) - ((*__jv_22) * (*__vd_2))
            - two_alpha * (((*__jv_22) * (*__v_2)) - (*__nu_8)) - beta2 * (*__phi_8);
        Self::schur_solve(&l, &dinv, lambda);
        use ::mbd::__private::Elements as _;
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__lambda_0, __lambda_1, __lambda_2, __lambda_3, __lambda_4, __lambda_5,
        __lambda_6, __lambda_7, __lambda_8] = lambda.window::<0, 9>();
        let [__minv_0, __minv_1, __minv_2, __minv_3, __minv_4, __minv_5, __minv_6,
        __minv_7, __minv_8] = minv.window::<0, 9>();
        let [__vd_0, __vd_1, __vd_2, __vd_3, __vd_4, __vd_5, __vd_6, __vd_7, __vd_8] = vd
            .window_mut::<0, 9>();
        (*__vd_0)
            += (*__minv_0) * ((*__jv_0) * (*__lambda_0) + (*__jv_4) * (*__lambda_2));
        (*__vd_1)
            += (*__minv_1) * ((*__jv_2) * (*__lambda_1) + (*__jv_8) * (*__lambda_3));
        (*__vd_2)
            += (*__minv_2)
                * ((*__jv_1) * (*__lambda_0) + (*__jv_3) * (*__lambda_1)
                    + (*__jv_5) * (*__lambda_2) + (*__jv_9) * (*__lambda_3)
                    + (*__jv_22) * (*__lambda_8));
        (*__vd_3)
            += (*__minv_3) * ((*__jv_6) * (*__lambda_2) + (*__jv_12) * (*__lambda_4));
        (*__vd_4)
            += (*__minv_4) * ((*__jv_10) * (*__lambda_3) + (*__jv_15) * (*__lambda_5));
        (*__vd_5)
            += (*__minv_5)
                * ((*__jv_7) * (*__lambda_2) + (*__jv_11) * (*__lambda_3)
                    + (*__jv_13) * (*__lambda_4) + (*__jv_16) * (*__lambda_5));
        (*__vd_6)
            += (*__minv_6) * ((*__jv_14) * (*__lambda_4) + (*__jv_18) * (*__lambda_6));
        (*__vd_7)
            += (*__minv_7) * ((*__jv_17) * (*__lambda_5) + (*__jv_19) * (*__lambda_6));
        (*__vd_8)
            += (*__minv_8) * ((*__jv_20) * (*__lambda_6) + (*__jv_21) * (*__lambda_7));
        ::core::result::Result::Ok(())
    }
    #[inline]
    fn project_positions_step(
        &self,
        q: &mut [f64; 9],
        t: f64,
        options: &::mbd::DynamicsOptions<f64>,
    ) -> ::core::result::Result<f64, ::mbd::DynamicsError> {
        let mut jv = [0f64; 23];
        let mut phi = [0f64; 9];
        let mut m = [0f64; 9];
        {
            let q: &[f64; 9] = q;
            let (
                v5,
                s_crank,
                c_crank,
                v10,
                v12,
                v13,
                v24,
                s_rod,
                c_rod,
                v29,
                v31,
                v32,
                s_slider,
                c_slider,
                v81,
            ): (
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
                f64,
            );
            use ::mbd::__private::Elements as _;
            let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
            __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16,
            __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                .window_mut::<0, 23>();
            let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
                .window_mut::<0, 9>();
            let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
            __phi_8] = phi.window_mut::<0, 9>();
            let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
                .window::<0, 9>();
            v5 = (self.r / 2f64);
            (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
            v10 = (v5 * c_crank);
            v12 = (v5 * s_crank);
            v13 = (-v12);
            v24 = (self.l / 2f64);
            (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
            v29 = (v24 * c_rod);
            v31 = (v24 * s_rod);
            v32 = (-v31);
            (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
            v81 = (-c_slider);
            (*__phi_0) = (-((*__q_0) - v10));
            (*__phi_1) = (-((*__q_1) - v12));
            (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
            (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
            (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
            (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
            (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
            (*__phi_7) = (-s_slider);
            (*__phi_8) = ((*__q_2) - (self.omega * t));
            (*__jv_0) = (-1f64);
            (*__jv_1) = v13;
            (*__jv_2) = (-1f64);
            (*__jv_3) = v10;
            (*__jv_4) = 1f64;
            (*__jv_5) = v13;
            (*__jv_6) = (-1f64);
            (*__jv_7) = v32;
            (*__jv_8) = 1f64;
            (*__jv_9) = v10;
            (*__jv_10) = (-1f64);
            (*__jv_11) = v29;
            (*__jv_12) = 1f64;
            (*__jv_13) = v32;
            (*__jv_14) = (-1f64);
            (*__jv_15) = 1f64;
            (*__jv_16) = v29;
            (*__jv_17) = (-1f64);
            (*__jv_18) = s_slider;
            (*__jv_19) = v81;
            (*__jv_20) = <f64 as ::mbd::Real>::fused_mul_add(
                c_slider,
                (*__q_6),
                (s_slider * (*__q_7)),
            );
            (*__jv_21) = v81;
            (*__jv_22) = 1f64;
            (*__m_0) = 1f64;
            (*__m_1) = 1f64;
            (*__m_2) = 0.002f64;
            (*__m_3) = 2f64;
            (*__m_4) = 2f64;
            (*__m_5) = 0.015f64;
            (*__m_6) = 0.5f64;
            (*__m_7) = 0.5f64;
            (*__m_8) = 0.001f64;
        }
        let mut b = phi;
        let (worst, _) = ::mbd::__private::max_abs_finite(&b[..]);
        let mut minv = [0f64; 9];
        minv[0] = 1f64 / m[0];
        minv[1] = minv[0];
        minv[2] = 1f64 / m[2];
        minv[3] = 1f64 / m[3];
        minv[4] = minv[3];
        minv[5] = 1f64 / m[5];
        minv[6] = 1f64 / m[6];
        minv[7] = minv[6];
        minv[8] = 1f64 / m[8];
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        if let ::core::result::Result::Err(row) = Self::schur_factor(
            &jv,
            &minv,
            options.pivot_tolerance,
            options.allow_redundant,
            &mut l,
            &mut dinv,
        ) {
            let finite = q
                .iter()
                .chain(jv.iter())
                .chain(m.iter())
                .all(|x| x.is_finite());
            const MASS_BODIES: [u16; 9] = [
                0u16, 0u16, 0u16, 1u16, 1u16, 1u16, 2u16, 2u16, 2u16,
            ];
            return ::core::result::Result::Err(
                ::mbd::DynamicsError::from_pivot::<
                    Self,
                    f64,
                >(t, row, &m[..], &MASS_BODIES, &jv[..], finite, options.allow_redundant),
            );
        }
        Self::schur_solve(&l, &dinv, &mut b);
        use ::mbd::__private::Elements as _;
        let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
            .window::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__minv_0, __minv_1, __minv_2, __minv_3, __minv_4, __minv_5, __minv_6,
        __minv_7, __minv_8] = minv.window::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window_mut::<0, 9>();
        (*__q_0) -= (*__minv_0) * ((*__jv_0) * (*__b_0) + (*__jv_4) * (*__b_2));
        (*__q_1) -= (*__minv_1) * ((*__jv_2) * (*__b_1) + (*__jv_8) * (*__b_3));
        (*__q_2)
            -= (*__minv_2)
                * ((*__jv_1) * (*__b_0) + (*__jv_3) * (*__b_1) + (*__jv_5) * (*__b_2)
                    + (*__jv_9) * (*__b_3) + (*__jv_22) * (*__b_8));
        (*__q_3) -= (*__minv_3) * ((*__jv_6) * (*__b_2) + (*__jv_12) * (*__b_4));
        (*__q_4) -= (*__minv_4) * ((*__jv_10) * (*__b_3) + (*__jv_15) * (*__b_5));
        (*__q_5)
            -= (*__minv_5)
                * ((*__jv_7) * (*__b_2) + (*__jv_11) * (*__b_3) + (*__jv_13) * (*__b_4)
                    + (*__jv_16) * (*__b_5));
        (*__q_6) -= (*__minv_6) * ((*__jv_14) * (*__b_4) + (*__jv_18) * (*__b_6));
        (*__q_7) -= (*__minv_7) * ((*__jv_17) * (*__b_5) + (*__jv_19) * (*__b_6));
        (*__q_8) -= (*__minv_8) * ((*__jv_20) * (*__b_6) + (*__jv_21) * (*__b_7));
        ::core::result::Result::Ok(worst)
    }
    #[inline]
    fn project_velocities(
        &self,
        q: &[f64; 9],
        v: &mut [f64; 9],
        t: f64,
        options: &::mbd::DynamicsOptions<f64>,
    ) -> ::core::result::Result<f64, ::mbd::DynamicsError> {
        let mut jv = [0f64; 23];
        let mut nu = [0f64; 9];
        let mut m = [0f64; 9];
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v32,
            s_slider,
            c_slider,
            v81,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window_mut::<0, 23>();
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window_mut::<0, 9>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v13 = (-(v5 * s_crank));
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v32 = (-(v24 * s_rod));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        (*__jv_0) = (-1f64);
        (*__jv_1) = v13;
        (*__jv_2) = (-1f64);
        (*__jv_3) = v10;
        (*__jv_4) = 1f64;
        (*__jv_5) = v13;
        (*__jv_6) = (-1f64);
        (*__jv_7) = v32;
        (*__jv_8) = 1f64;
        (*__jv_9) = v10;
        (*__jv_10) = (-1f64);
        (*__jv_11) = v29;
        (*__jv_12) = 1f64;
        (*__jv_13) = v32;
        (*__jv_14) = (-1f64);
        (*__jv_15) = 1f64;
        (*__jv_16) = v29;
        (*__jv_17) = (-1f64);
        (*__jv_18) = s_slider;
        (*__jv_19) = v81;
        (*__jv_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__jv_21) = v81;
        (*__jv_22) = 1f64;
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
        (*__m_0) = 1f64;
        (*__m_1) = 1f64;
        (*__m_2) = 0.002f64;
        (*__m_3) = 2f64;
        (*__m_4) = 2f64;
        (*__m_5) = 0.015f64;
        (*__m_6) = 0.5f64;
        (*__m_7) = 0.5f64;
        (*__m_8) = 0.001f64;
        let mut minv = [0f64; 9];
        minv[0] = 1f64 / m[0];
        minv[1] = minv[0];
        minv[2] = 1f64 / m[2];
        minv[3] = 1f64 / m[3];
        minv[4] = minv[3];
        minv[5] = 1f64 / m[5];
        minv[6] = 1f64 / m[6];
        minv[7] = minv[6];
        minv[8] = 1f64 / m[8];
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        if let ::core::result::Result::Err(row) = Self::schur_factor(
            &jv,
            &minv,
            options.pivot_tolerance,
            options.allow_redundant,
            &mut l,
            &mut dinv,
        ) {
            let finite = q
                .iter()
                .chain(jv.iter())
                .chain(m.iter())
                .all(|x| x.is_finite());
            const MASS_BODIES: [u16; 9] = [
                0u16, 0u16, 0u16, 1u16, 1u16, 1u16, 2u16, 2u16, 2u16,
            ];
            return ::core::result::Result::Err(
                ::mbd::DynamicsError::from_pivot::<
                    Self,
                    f64,
                >(t, row, &m[..], &MASS_BODIES, &jv[..], finite, options.allow_redundant),
            );
        }
        let mut b = [0f64; 9];
        {
            let v: &[f64; 9] = v;
            use ::mbd::__private::Elements as _;
            let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
                .window_mut::<0, 9>();
            let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
            __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16,
            __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
            let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8,
            ] = nu.window::<0, 9>();
            let [__v_0, __v_1, __v_2, __v_3, __v_4, __v_5, __v_6, __v_7, __v_8] = v
                .window::<0, 9>();
            (*__b_0) = ((*__jv_0) * (*__v_0) + (*__jv_1) * (*__v_2)) - (*__nu_0);
            (*__b_1) = ((*__jv_2) * (*__v_1) + (*__jv_3) * (*__v_2)) - (*__nu_1);
            (*__b_2) = ((*__jv_4) * (*__v_0) + (*__jv_5) * (*__v_2)
                + (*__jv_6) * (*__v_3) + (*__jv_7) * (*__v_5)) - (*__nu_2);
            (*__b_3) = ((*__jv_8) * (*__v_1) + (*__jv_9) * (*__v_2)
                + (*__jv_10) * (*__v_4) + (*__jv_11) * (*__v_5)) - (*__nu_3);
            (*__b_4) = ((*__jv_12) * (*__v_3) + (*__jv_13) * (*__v_5)
                + (*__jv_14) * (*__v_6)) - (*__nu_4);
            (*__b_5) = ((*__jv_15) * (*__v_4) + (*__jv_16) * (*__v_5)
                + (*__jv_17) * (*__v_7)) - (*__nu_5);
            (*__b_6) = ((*__jv_18) * (*__v_6) + (*__jv_19) * (*__v_7)
                + (*__jv_20) * (*__v_8)) - (*__nu_6);
            (*__b_7) = ((*__jv_21) * (*__v_8)) - (*__nu_7);
            (*__b_8) = ((*__jv_22) * (*__v_2)) - (*__nu_8);
        }
        let (worst, _) = ::mbd::__private::max_abs_finite(&b[..]);
        Self::schur_solve(&l, &dinv, &mut b);
        use ::mbd::__private::Elements as _;
        let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
            .window::<0, 9>();
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window::<0, 23>();
        let [__minv_0, __minv_1, __minv_2, __minv_3, __minv_4, __minv_5, __minv_6,
        __minv_7, __minv_8] = minv.window::<0, 9>();
        let [__v_0, __v_1, __v_2, __v_3, __v_4, __v_5, __v_6, __v_7, __v_8] = v
            .window_mut::<0, 9>();
        (*__v_0) -= (*__minv_0) * ((*__jv_0) * (*__b_0) + (*__jv_4) * (*__b_2));
        (*__v_1) -= (*__minv_1) * ((*__jv_2) * (*__b_1) + (*__jv_8) * (*__b_3));
        (*__v_2)
            -= (*__minv_2)
                * ((*__jv_1) * (*__b_0) + (*__jv_3) * (*__b_1) + (*__jv_5) * (*__b_2)
                    + (*__jv_9) * (*__b_3) + (*__jv_22) * (*__b_8));
        (*__v_3) -= (*__minv_3) * ((*__jv_6) * (*__b_2) + (*__jv_12) * (*__b_4));
        (*__v_4) -= (*__minv_4) * ((*__jv_10) * (*__b_3) + (*__jv_15) * (*__b_5));
        (*__v_5)
            -= (*__minv_5)
                * ((*__jv_7) * (*__b_2) + (*__jv_11) * (*__b_3) + (*__jv_13) * (*__b_4)
                    + (*__jv_16) * (*__b_5));
        (*__v_6) -= (*__minv_6) * ((*__jv_14) * (*__b_4) + (*__jv_18) * (*__b_6));
        (*__v_7) -= (*__minv_7) * ((*__jv_17) * (*__b_5) + (*__jv_19) * (*__b_6));
        (*__v_8) -= (*__minv_8) * ((*__jv_20) * (*__b_6) + (*__jv_21) * (*__b_7));
        ::core::result::Result::Ok(worst)
    }
}
#[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
#[doc(hidden)]
impl ::mbd::NewtonMatrix<f64, 9, 9, 9> for SliderCrank {
    type NewtonStorage = [f64; 135];
    const NEWTON_PATTERN: ::mbd::SparsePattern = ::mbd::SparsePattern {
        unknown: &[0, 1, 3, 4, 6, 7, 5, 8, 15, 16, 13, 14, 2, 9, 10, 17, 11, 12],
        position: &[0, 1, 12, 2, 3, 6, 4, 5, 7, 13, 14, 16, 17, 10, 11, 8, 9, 15],
        row_start: &[
            0, 3, 6, 9, 12, 16, 20, 25, 32, 39, 44, 54, 64, 70, 77, 84, 90, 101, 112,
        ],
        columns: &[
            0, 13, 16, 1, 14, 17, 2, 10, 16, 3, 11, 17, 4, 7, 8, 10, 5, 7, 8, 11, 6, 10,
            11, 16, 17, 4, 5, 7, 8, 9, 10, 11, 4, 5, 7, 8, 9, 10, 11, 7, 8, 9, 10, 11, 2,
            4, 6, 7, 8, 9, 10, 11, 16, 17, 3, 5, 6, 7, 8, 9, 10, 11, 16, 17, 12, 13, 14,
            15, 16, 17, 0, 12, 13, 14, 15, 16, 17, 1, 12, 13, 14, 15, 16, 17, 12, 13, 14,
            15, 16, 17, 0, 2, 6, 10, 11, 12, 13, 14, 15, 16, 17, 1, 3, 6, 10, 11, 12, 13,
            14, 15, 16, 17,
        ],
        diagonal: &[0, 3, 6, 9, 12, 16, 20, 27, 35, 41, 50, 61, 64, 72, 80, 87, 99, 111],
    };
    #[inline]
    fn newton_storage() -> [f64; 135] {
        [0f64; 135]
    }
    #[inline]
    fn newton_jacobian(
        &self,
        q: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        s: &mut [f64; 135],
        _scratch: ::mbd::DenseScratch<'_, f64, 9, 9>,
    ) {
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v81,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        let [__s_0, __s_1, __s_2, __s_3, __s_4, __s_5, __s_6, __s_7, __s_8, __s_9,
        __s_10, __s_11, __s_12, __s_13, __s_14, __s_15, __s_16, __s_17, __s_18, __s_19,
        __s_20, __s_21, __s_22] = s.window_mut::<0, 23>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
        (*__s_0) = (-1f64);
        (*__s_1) = v13;
        (*__s_2) = (-1f64);
        (*__s_3) = v10;
        (*__s_4) = 1f64;
        (*__s_5) = v13;
        (*__s_6) = (-1f64);
        (*__s_7) = v32;
        (*__s_8) = 1f64;
        (*__s_9) = v10;
        (*__s_10) = (-1f64);
        (*__s_11) = v29;
        (*__s_12) = 1f64;
        (*__s_13) = v32;
        (*__s_14) = (-1f64);
        (*__s_15) = 1f64;
        (*__s_16) = v29;
        (*__s_17) = (-1f64);
        (*__s_18) = s_slider;
        (*__s_19) = v81;
        (*__s_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__s_21) = v81;
        (*__s_22) = 1f64;
    }
    #[inline(never)]
    fn newton_matrix(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        vd: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
        displacement: ::core::option::Option<&[f64; 9]>,
        c_v: f64,
        c_q: f64,
        phi: &mut [f64; 9],
        s: &mut [f64; 135],
        _scratch: ::mbd::DenseScratch<'_, f64, 9, 9>,
    ) {
        for x in s[23..].iter_mut() {
            *x = 0f64;
        }
        let mut m = [0f64; 9];
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v53,
            v54,
            v81,
            v203,
            v205,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__lambda_0, __lambda_1, __lambda_2, __lambda_3, __lambda_4, __lambda_5,
        __lambda_6, __lambda_7] = lambda.window::<0, 8>();
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window_mut::<0, 9>();
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v53 = (s_slider * (*__q_6));
        v54 = (c_slider * (*__q_7));
        v81 = (-c_slider);
        v203 = (s_slider * (*__lambda_6));
        v205 = (c_slider * (*__lambda_6));
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = (v53 - v54);
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
        s[0] = (-1f64);
        s[1] = v13;
        s[2] = (-1f64);
        s[3] = v10;
        s[4] = 1f64;
        s[5] = v13;
        s[6] = (-1f64);
        s[7] = v32;
        s[8] = 1f64;
        s[9] = v10;
        s[10] = (-1f64);
        s[11] = v29;
        s[12] = 1f64;
        s[13] = v32;
        s[14] = (-1f64);
        s[15] = 1f64;
        s[16] = v29;
        s[17] = (-1f64);
        s[18] = s_slider;
        s[19] = v81;
        s[20] = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        s[21] = v81;
        s[22] = 1f64;
        (*__m_0) = 1f64;
        (*__m_1) = 1f64;
        (*__m_2) = 0.002f64;
        (*__m_3) = 2f64;
        (*__m_4) = 2f64;
        (*__m_5) = 0.015f64;
        (*__m_6) = 0.5f64;
        (*__m_7) = 0.5f64;
        (*__m_8) = 0.001f64;
        s[87] = (-((v12 * (*__lambda_3))
            + ((v10 * (*__lambda_2))
                + ((v12 * (*__lambda_1)) + (v10 * (*__lambda_0))))));
        s[43] = (-((v31 * (*__lambda_5))
            + ((v29 * (*__lambda_4))
                + ((v31 * (*__lambda_3)) + (v29 * (*__lambda_2))))));
        s[36] = v205;
        s[40] = v203;
        s[48] = v205;
        s[49] = v203;
        s[50] = <f64 as ::mbd::Real>::fused_mul_add(
            (*__lambda_6),
            (v54 - v53),
            (s_slider * (*__lambda_7)),
        );
        use ::mbd::__private::Elements as _;
        let [__m_0, __m_1, __m_2, __m_3, __m_4, __m_5, __m_6, __m_7, __m_8] = m
            .window::<0, 9>();
        s[23] = (*__m_0);
        s[26] = (*__m_1);
        s[87] = (*__m_2) - c_q * s[87];
        s[29] = (*__m_3);
        s[32] = (*__m_4);
        s[43] = (*__m_5) - c_q * s[43];
        s[35] = (*__m_6);
        s[36] *= -c_q;
        s[39] = (*__m_7);
        s[40] *= -c_q;
        s[48] *= -c_q;
        s[49] *= -c_q;
        s[50] = (*__m_8) - c_q * s[50];
        s[24] = -s[0];
        s[93] = s[0];
        s[88] = -s[1];
        s[94] = s[1];
        s[27] = -s[2];
        s[100] = s[2];
        s[89] = -s[3];
        s[101] = s[3];
        s[25] = -s[4];
        s[113] = s[4];
        s[91] = -s[5];
        s[118] = s[5];
        s[31] = -s[6];
        s[114] = s[6];
        s[46] = -s[7];
        s[115] = s[7];
        s[28] = -s[8];
        s[124] = s[8];
        s[92] = -s[9];
        s[129] = s[9];
        s[34] = -s[10];
        s[125] = s[10];
        s[47] = -s[11];
        s[126] = s[11];
        s[30] = -s[12];
        s[67] = s[12];
        s[44] = -s[13];
        s[69] = s[13];
        s[38] = -s[14];
        s[68] = s[14];
        s[33] = -s[15];
        s[77] = s[15];
        s[45] = -s[16];
        s[79] = s[16];
        s[42] = -s[17];
        s[78] = s[17];
        s[37] = -s[18];
        s[55] = s[18];
        s[41] = -s[19];
        s[56] = s[19];
        s[51] = -s[20];
        s[57] = s[20];
        s[52] = -s[21];
        s[62] = s[21];
        s[90] = -s[22];
        s[107] = s[22];
    }
    fn newton_factor(
        s: &mut [f64; 135],
        tolerance: f64,
        allow_redundant: bool,
        dropped: &mut [bool; 9],
    ) -> ::core::result::Result<f64, ::mbd::LinalgError> {
        let mut smallest = 1f64;
        let mut inverse = [0f64; 18];
        {
            let scale = 0f64.max(s[23].abs()).max(s[24].abs()).max(s[25].abs());
            let pivot = s[23];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                0,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[0] = 1f64 / pivot;
                s[23] = inverse[0];
            } else {
                for x in s[23..26].iter_mut() {
                    *x = 0f64;
                }
                s[23] = 1f64;
                inverse[0] = 1f64;
            }
        }
        {
            let scale = 0f64.max(s[26].abs()).max(s[27].abs()).max(s[28].abs());
            let pivot = s[26];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                1,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[1] = 1f64 / pivot;
                s[26] = inverse[1];
            } else {
                for x in s[26..29].iter_mut() {
                    *x = 0f64;
                }
                s[26] = 1f64;
                inverse[1] = 1f64;
            }
        }
        {
            let scale = 0f64.max(s[29].abs()).max(s[30].abs()).max(s[31].abs());
            let pivot = s[29];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                3,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[2] = 1f64 / pivot;
                s[29] = inverse[2];
            } else {
                for x in s[29..32].iter_mut() {
                    *x = 0f64;
                }
                s[29] = 1f64;
                inverse[2] = 1f64;
            }
        }
        {
            let scale = 0f64.max(s[32].abs()).max(s[33].abs()).max(s[34].abs());
            let pivot = s[32];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                4,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[3] = 1f64 / pivot;
                s[32] = inverse[3];
            } else {
                for x in s[32..35].iter_mut() {
                    *x = 0f64;
                }
                s[32] = 1f64;
                inverse[3] = 1f64;
            }
        }
        {
            let scale = 0f64
                .max(s[35].abs())
                .max(s[36].abs())
                .max(s[37].abs())
                .max(s[38].abs());
            let pivot = s[35];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                6,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[4] = 1f64 / pivot;
                s[35] = inverse[4];
            } else {
                for x in s[35..39].iter_mut() {
                    *x = 0f64;
                }
                s[35] = 1f64;
                inverse[4] = 1f64;
            }
        }
        {
            let scale = 0f64
                .max(s[39].abs())
                .max(s[40].abs())
                .max(s[41].abs())
                .max(s[42].abs());
            let pivot = s[39];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                7,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[5] = 1f64 / pivot;
                s[39] = inverse[5];
            } else {
                for x in s[39..43].iter_mut() {
                    *x = 0f64;
                }
                s[39] = 1f64;
                inverse[5] = 1f64;
            }
        }
        {
            let scale = 0f64
                .max(s[43].abs())
                .max(s[44].abs())
                .max(s[45].abs())
                .max(s[46].abs())
                .max(s[47].abs());
            let pivot = s[43];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                5,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[6] = 1f64 / pivot;
                s[43] = inverse[6];
            } else {
                for x in s[43..48].iter_mut() {
                    *x = 0f64;
                }
                s[43] = 1f64;
                inverse[6] = 1f64;
            }
        }
        {
            let scale = 0f64
                .max(s[48].abs())
                .max(s[49].abs())
                .max(s[50].abs())
                .max(s[51].abs())
                .max(s[52].abs());
            {
                let l = s[48] * inverse[4];
                s[48] = l;
                s[50] -= l * s[36];
                s[51] -= l * s[37];
                s[53] -= l * s[38];
            }
            {
                let l = s[49] * inverse[5];
                s[49] = l;
                s[50] -= l * s[40];
                s[51] -= l * s[41];
                s[54] -= l * s[42];
            }
            let pivot = s[50];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                8,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[7] = 1f64 / pivot;
                s[50] = inverse[7];
            } else {
                for x in s[48..55].iter_mut() {
                    *x = 0f64;
                }
                s[50] = 1f64;
                inverse[7] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[55] * s[55] * s[35].abs() + s[56] * s[56] * s[39].abs()
                + s[57] * s[57] * s[50].abs();
            {
                let l = s[55] * inverse[4];
                s[55] = l;
                s[57] -= l * s[36];
                s[58] -= l * s[37];
                s[60] -= l * s[38];
            }
            {
                let l = s[56] * inverse[5];
                s[56] = l;
                s[57] -= l * s[40];
                s[58] -= l * s[41];
                s[61] -= l * s[42];
            }
            {
                let l = s[57] * inverse[7];
                s[57] = l;
                s[58] -= l * s[51];
                s[59] -= l * s[52];
                s[60] -= l * s[53];
                s[61] -= l * s[54];
            }
            let pivot = s[58];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                15,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[8] = 1f64 / pivot;
                s[58] = inverse[8];
            } else {
                for x in s[55..62].iter_mut() {
                    *x = 0f64;
                }
                s[58] = 1f64;
                inverse[8] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[62] * s[62] * s[50].abs();
            {
                let l = s[62] * inverse[7];
                s[62] = l;
                s[63] -= l * s[51];
                s[64] -= l * s[52];
                s[65] -= l * s[53];
                s[66] -= l * s[54];
            }
            {
                let l = s[63] * inverse[8];
                s[63] = l;
                s[64] -= l * s[59];
                s[65] -= l * s[60];
                s[66] -= l * s[61];
            }
            let pivot = s[64];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                16,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[9] = 1f64 / pivot;
                s[64] = inverse[9];
            } else {
                for x in s[62..67].iter_mut() {
                    *x = 0f64;
                }
                s[64] = 1f64;
                inverse[9] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[67] * s[67] * s[29].abs() + s[68] * s[68] * s[35].abs()
                + s[69] * s[69] * s[43].abs();
            {
                let l = s[67] * inverse[2];
                s[67] = l;
                s[73] -= l * s[30];
                s[75] -= l * s[31];
            }
            {
                let l = s[68] * inverse[4];
                s[68] = l;
                s[70] -= l * s[36];
                s[71] -= l * s[37];
                s[73] -= l * s[38];
            }
            {
                let l = s[69] * inverse[6];
                s[69] = l;
                s[73] -= l * s[44];
                s[74] -= l * s[45];
                s[75] -= l * s[46];
                s[76] -= l * s[47];
            }
            {
                let l = s[70] * inverse[7];
                s[70] = l;
                s[71] -= l * s[51];
                s[72] -= l * s[52];
                s[73] -= l * s[53];
                s[74] -= l * s[54];
            }
            {
                let l = s[71] * inverse[8];
                s[71] = l;
                s[72] -= l * s[59];
                s[73] -= l * s[60];
                s[74] -= l * s[61];
            }
            {
                let l = s[72] * inverse[9];
                s[72] = l;
                s[73] -= l * s[65];
                s[74] -= l * s[66];
            }
            let pivot = s[73];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                13,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[10] = 1f64 / pivot;
                s[73] = inverse[10];
            } else {
                for x in s[67..77].iter_mut() {
                    *x = 0f64;
                }
                s[73] = 1f64;
                inverse[10] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[77] * s[77] * s[32].abs() + s[78] * s[78] * s[39].abs()
                + s[79] * s[79] * s[43].abs();
            {
                let l = s[77] * inverse[3];
                s[77] = l;
                s[84] -= l * s[33];
                s[86] -= l * s[34];
            }
            {
                let l = s[78] * inverse[5];
                s[78] = l;
                s[80] -= l * s[40];
                s[81] -= l * s[41];
                s[84] -= l * s[42];
            }
            {
                let l = s[79] * inverse[6];
                s[79] = l;
                s[83] -= l * s[44];
                s[84] -= l * s[45];
                s[85] -= l * s[46];
                s[86] -= l * s[47];
            }
            {
                let l = s[80] * inverse[7];
                s[80] = l;
                s[81] -= l * s[51];
                s[82] -= l * s[52];
                s[83] -= l * s[53];
                s[84] -= l * s[54];
            }
            {
                let l = s[81] * inverse[8];
                s[81] = l;
                s[82] -= l * s[59];
                s[83] -= l * s[60];
                s[84] -= l * s[61];
            }
            {
                let l = s[82] * inverse[9];
                s[82] = l;
                s[83] -= l * s[65];
                s[84] -= l * s[66];
            }
            {
                let l = s[83] * inverse[10];
                s[83] = l;
                s[84] -= l * s[74];
                s[85] -= l * s[75];
                s[86] -= l * s[76];
            }
            let pivot = s[84];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                14,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[11] = 1f64 / pivot;
                s[84] = inverse[11];
            } else {
                for x in s[77..87].iter_mut() {
                    *x = 0f64;
                }
                s[84] = 1f64;
                inverse[11] = 1f64;
            }
        }
        {
            let scale = 0f64
                .max(s[87].abs())
                .max(s[88].abs())
                .max(s[89].abs())
                .max(s[90].abs())
                .max(s[91].abs())
                .max(s[92].abs());
            let pivot = s[87];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                2,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[12] = 1f64 / pivot;
                s[87] = inverse[12];
            } else {
                for x in s[87..93].iter_mut() {
                    *x = 0f64;
                }
                s[87] = 1f64;
                inverse[12] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[93] * s[93] * s[23].abs() + s[94] * s[94] * s[87].abs();
            {
                let l = s[93] * inverse[0];
                s[93] = l;
                s[95] -= l * s[24];
                s[98] -= l * s[25];
            }
            {
                let l = s[94] * inverse[12];
                s[94] = l;
                s[95] -= l * s[88];
                s[96] -= l * s[89];
                s[97] -= l * s[90];
                s[98] -= l * s[91];
                s[99] -= l * s[92];
            }
            let pivot = s[95];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                9,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[13] = 1f64 / pivot;
                s[95] = inverse[13];
            } else {
                for x in s[93..100].iter_mut() {
                    *x = 0f64;
                }
                s[95] = 1f64;
                inverse[13] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[100] * s[100] * s[26].abs()
                + s[101] * s[101] * s[87].abs();
            {
                let l = s[100] * inverse[1];
                s[100] = l;
                s[103] -= l * s[27];
                s[106] -= l * s[28];
            }
            {
                let l = s[101] * inverse[12];
                s[101] = l;
                s[102] -= l * s[88];
                s[103] -= l * s[89];
                s[104] -= l * s[90];
                s[105] -= l * s[91];
                s[106] -= l * s[92];
            }
            {
                let l = s[102] * inverse[13];
                s[102] = l;
                s[103] -= l * s[96];
                s[104] -= l * s[97];
                s[105] -= l * s[98];
                s[106] -= l * s[99];
            }
            let pivot = s[103];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                10,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[14] = 1f64 / pivot;
                s[103] = inverse[14];
            } else {
                for x in s[100..107].iter_mut() {
                    *x = 0f64;
                }
                s[103] = 1f64;
                inverse[14] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[107] * s[107] * s[87].abs();
            {
                let l = s[107] * inverse[12];
                s[107] = l;
                s[108] -= l * s[88];
                s[109] -= l * s[89];
                s[110] -= l * s[90];
                s[111] -= l * s[91];
                s[112] -= l * s[92];
            }
            {
                let l = s[108] * inverse[13];
                s[108] = l;
                s[109] -= l * s[96];
                s[110] -= l * s[97];
                s[111] -= l * s[98];
                s[112] -= l * s[99];
            }
            {
                let l = s[109] * inverse[14];
                s[109] = l;
                s[110] -= l * s[104];
                s[111] -= l * s[105];
                s[112] -= l * s[106];
            }
            let pivot = s[110];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                17,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[15] = 1f64 / pivot;
                s[110] = inverse[15];
            } else {
                for x in s[107..113].iter_mut() {
                    *x = 0f64;
                }
                s[110] = 1f64;
                inverse[15] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[113] * s[113] * s[23].abs()
                + s[114] * s[114] * s[29].abs() + s[115] * s[115] * s[43].abs()
                + s[118] * s[118] * s[87].abs();
            {
                let l = s[113] * inverse[0];
                s[113] = l;
                s[119] -= l * s[24];
                s[122] -= l * s[25];
            }
            {
                let l = s[114] * inverse[2];
                s[114] = l;
                s[116] -= l * s[30];
                s[122] -= l * s[31];
            }
            {
                let l = s[115] * inverse[6];
                s[115] = l;
                s[116] -= l * s[44];
                s[117] -= l * s[45];
                s[122] -= l * s[46];
                s[123] -= l * s[47];
            }
            {
                let l = s[116] * inverse[10];
                s[116] = l;
                s[117] -= l * s[74];
                s[122] -= l * s[75];
                s[123] -= l * s[76];
            }
            {
                let l = s[117] * inverse[11];
                s[117] = l;
                s[122] -= l * s[85];
                s[123] -= l * s[86];
            }
            {
                let l = s[118] * inverse[12];
                s[118] = l;
                s[119] -= l * s[88];
                s[120] -= l * s[89];
                s[121] -= l * s[90];
                s[122] -= l * s[91];
                s[123] -= l * s[92];
            }
            {
                let l = s[119] * inverse[13];
                s[119] = l;
                s[120] -= l * s[96];
                s[121] -= l * s[97];
                s[122] -= l * s[98];
                s[123] -= l * s[99];
            }
            {
                let l = s[120] * inverse[14];
                s[120] = l;
                s[121] -= l * s[104];
                s[122] -= l * s[105];
                s[123] -= l * s[106];
            }
            {
                let l = s[121] * inverse[15];
                s[121] = l;
                s[122] -= l * s[111];
                s[123] -= l * s[112];
            }
            let pivot = s[122];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                11,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[16] = 1f64 / pivot;
                s[122] = inverse[16];
            } else {
                for x in s[113..124].iter_mut() {
                    *x = 0f64;
                }
                s[122] = 1f64;
                inverse[16] = 1f64;
            }
        }
        {
            let scale = 0f64 + s[124] * s[124] * s[26].abs()
                + s[125] * s[125] * s[32].abs() + s[126] * s[126] * s[43].abs()
                + s[129] * s[129] * s[87].abs();
            {
                let l = s[124] * inverse[1];
                s[124] = l;
                s[131] -= l * s[27];
                s[134] -= l * s[28];
            }
            {
                let l = s[125] * inverse[3];
                s[125] = l;
                s[128] -= l * s[33];
                s[134] -= l * s[34];
            }
            {
                let l = s[126] * inverse[6];
                s[126] = l;
                s[127] -= l * s[44];
                s[128] -= l * s[45];
                s[133] -= l * s[46];
                s[134] -= l * s[47];
            }
            {
                let l = s[127] * inverse[10];
                s[127] = l;
                s[128] -= l * s[74];
                s[133] -= l * s[75];
                s[134] -= l * s[76];
            }
            {
                let l = s[128] * inverse[11];
                s[128] = l;
                s[133] -= l * s[85];
                s[134] -= l * s[86];
            }
            {
                let l = s[129] * inverse[12];
                s[129] = l;
                s[130] -= l * s[88];
                s[131] -= l * s[89];
                s[132] -= l * s[90];
                s[133] -= l * s[91];
                s[134] -= l * s[92];
            }
            {
                let l = s[130] * inverse[13];
                s[130] = l;
                s[131] -= l * s[96];
                s[132] -= l * s[97];
                s[133] -= l * s[98];
                s[134] -= l * s[99];
            }
            {
                let l = s[131] * inverse[14];
                s[131] = l;
                s[132] -= l * s[104];
                s[133] -= l * s[105];
                s[134] -= l * s[106];
            }
            {
                let l = s[132] * inverse[15];
                s[132] = l;
                s[133] -= l * s[111];
                s[134] -= l * s[112];
            }
            {
                let l = s[133] * inverse[16];
                s[133] = l;
                s[134] -= l * s[123];
            }
            let pivot = s[134];
            if ::mbd::__private::pivot(
                pivot,
                scale,
                12,
                9,
                tolerance,
                allow_redundant,
                dropped,
                &mut smallest,
            )? {
                inverse[17] = 1f64 / pivot;
                s[134] = inverse[17];
            } else {
                for x in s[124..135].iter_mut() {
                    *x = 0f64;
                }
                s[134] = 1f64;
                inverse[17] = 1f64;
            }
        }
        ::core::result::Result::Ok(smallest)
    }
    fn newton_solve(s: &[f64; 135], b: &mut [f64]) {
        if let ::core::result::Result::Ok(b) = <&mut [f64; 18]>::try_from(&mut *b) {
            b[8] -= s[48] * b[6];
            b[8] -= s[49] * b[7];
            b[15] -= s[55] * b[6];
            b[15] -= s[56] * b[7];
            b[15] -= s[57] * b[8];
            b[16] -= s[62] * b[8];
            b[16] -= s[63] * b[15];
            b[13] -= s[67] * b[3];
            b[13] -= s[68] * b[6];
            b[13] -= s[69] * b[5];
            b[13] -= s[70] * b[8];
            b[13] -= s[71] * b[15];
            b[13] -= s[72] * b[16];
            b[14] -= s[77] * b[4];
            b[14] -= s[78] * b[7];
            b[14] -= s[79] * b[5];
            b[14] -= s[80] * b[8];
            b[14] -= s[81] * b[15];
            b[14] -= s[82] * b[16];
            b[14] -= s[83] * b[13];
            b[9] -= s[93] * b[0];
            b[9] -= s[94] * b[2];
            b[10] -= s[100] * b[1];
            b[10] -= s[101] * b[2];
            b[10] -= s[102] * b[9];
            b[17] -= s[107] * b[2];
            b[17] -= s[108] * b[9];
            b[17] -= s[109] * b[10];
            b[11] -= s[113] * b[0];
            b[11] -= s[114] * b[3];
            b[11] -= s[115] * b[5];
            b[11] -= s[116] * b[13];
            b[11] -= s[117] * b[14];
            b[11] -= s[118] * b[2];
            b[11] -= s[119] * b[9];
            b[11] -= s[120] * b[10];
            b[11] -= s[121] * b[17];
            b[12] -= s[124] * b[1];
            b[12] -= s[125] * b[4];
            b[12] -= s[126] * b[5];
            b[12] -= s[127] * b[13];
            b[12] -= s[128] * b[14];
            b[12] -= s[129] * b[2];
            b[12] -= s[130] * b[9];
            b[12] -= s[131] * b[10];
            b[12] -= s[132] * b[17];
            b[12] -= s[133] * b[11];
            b[12] *= s[134];
            b[11] = (b[11] - s[123] * b[12]) * s[122];
            b[17] = (b[17] - s[111] * b[11] - s[112] * b[12]) * s[110];
            b[10] = (b[10] - s[104] * b[17] - s[105] * b[11] - s[106] * b[12]) * s[103];
            b[9] = (b[9] - s[96] * b[10] - s[97] * b[17] - s[98] * b[11] - s[99] * b[12])
                * s[95];
            b[2] = (b[2] - s[88] * b[9] - s[89] * b[10] - s[90] * b[17] - s[91] * b[11]
                - s[92] * b[12]) * s[87];
            b[14] = (b[14] - s[85] * b[11] - s[86] * b[12]) * s[84];
            b[13] = (b[13] - s[74] * b[14] - s[75] * b[11] - s[76] * b[12]) * s[73];
            b[16] = (b[16] - s[65] * b[13] - s[66] * b[14]) * s[64];
            b[15] = (b[15] - s[59] * b[16] - s[60] * b[13] - s[61] * b[14]) * s[58];
            b[8] = (b[8] - s[51] * b[15] - s[52] * b[16] - s[53] * b[13] - s[54] * b[14])
                * s[50];
            b[5] = (b[5] - s[44] * b[13] - s[45] * b[14] - s[46] * b[11] - s[47] * b[12])
                * s[43];
            b[7] = (b[7] - s[40] * b[8] - s[41] * b[15] - s[42] * b[14]) * s[39];
            b[6] = (b[6] - s[36] * b[8] - s[37] * b[15] - s[38] * b[13]) * s[35];
            b[4] = (b[4] - s[33] * b[14] - s[34] * b[12]) * s[32];
            b[3] = (b[3] - s[30] * b[13] - s[31] * b[11]) * s[29];
            b[1] = (b[1] - s[27] * b[10] - s[28] * b[12]) * s[26];
            b[0] = (b[0] - s[24] * b[9] - s[25] * b[11]) * s[23];
        } else {
            ::mbd::sparse::solve(&Self::NEWTON_PATTERN, &s[23..], b);
        }
    }
}
#[allow(unused_variables)]
impl ::mbd::BodyFrames<f64, 9, 9> for SliderCrank {
    #[inline]
    fn body_pose(
        &self,
        body: usize,
        q: &[f64; 9],
    ) -> ::core::option::Option<::mbd::BodyPose<f64>> {
        if body >= 3 {
            return ::core::option::Option::None;
        }
        let k = 3 * body;
        ::core::option::Option::Some(::mbd::BodyPose::planar(q[k], q[k + 1], q[k + 2]))
    }
    #[inline]
    fn body_twist(
        &self,
        body: usize,
        q: &[f64; 9],
        x: &[f64; 9],
    ) -> ::core::option::Option<::mbd::BodyTwist<f64>> {
        if body >= 3 {
            return ::core::option::Option::None;
        }
        let k = 3 * body;
        ::core::option::Option::Some(::mbd::BodyTwist {
            velocity: [x[k], x[k + 1], <f64 as ::mbd::Real>::ZERO],
            angular_velocity: [
                <f64 as ::mbd::Real>::ZERO,
                <f64 as ::mbd::Real>::ZERO,
                x[k + 2],
            ],
        })
    }
    #[inline]
    fn body_acceleration(
        &self,
        body: usize,
        q: &[f64; 9],
        v: &[f64; 9],
        vd: &[f64; 9],
    ) -> ::core::option::Option<::mbd::BodyTwist<f64>> {
        ::mbd::BodyFrames::body_twist(self, body, q, vd)
    }
    #[inline]
    fn add_body_wrench(
        &self,
        body: usize,
        q: &[f64; 9],
        force: [f64; 3],
        moment: [f64; 3],
        g: &mut [f64; 9],
    ) -> bool {
        if body >= 3 {
            return false;
        }
        let k = 3 * body;
        g[k] += force[0];
        g[k + 1] += force[1];
        g[k + 2] += moment[2];
        true
    }
}
#[allow(unused_variables, unused_mut, unused_parens, clippy::approx_constant)]
impl ::mbd::JointLoads<f64, 9, 9, 9> for SliderCrank {
    fn constraint_wrench(
        &self,
        body: usize,
        q: &[f64; 9],
        t: f64,
        lambda: &[f64; 9],
    ) -> ::core::option::Option<::mbd::BodyWrench<f64>> {
        if body >= 3 {
            return ::core::option::Option::None;
        }
        let mut out = [[[0f64; 3]; 2]; 3];
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            s_slider,
            c_slider,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__lambda_0, __lambda_1, __lambda_2, __lambda_3, __lambda_4, __lambda_5,
        __lambda_6, __lambda_7, __lambda_8] = lambda.window::<0, 9>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        out[0][0][0] = ((*__lambda_2) - (*__lambda_0));
        out[0][0][1] = ((*__lambda_3) - (*__lambda_1));
        out[0][1][2] = (<f64 as ::mbd::Real>::fused_mul_add(
            v10,
            (*__lambda_3),
            (((v10 * (*__lambda_1)) - (v12 * (*__lambda_0))) - (v12 * (*__lambda_2))),
        ) + (*__lambda_8));
        out[1][0][0] = ((*__lambda_4) - (*__lambda_2));
        out[1][0][1] = ((*__lambda_5) - (*__lambda_3));
        out[1][1][2] = <f64 as ::mbd::Real>::fused_mul_add(
            v29,
            (*__lambda_5),
            (((v29 * (*__lambda_3)) - (v31 * (*__lambda_2))) - (v31 * (*__lambda_4))),
        );
        out[2][0][0] = ((s_slider * (*__lambda_6)) - (*__lambda_4));
        out[2][0][1] = (-((*__lambda_5) + (c_slider * (*__lambda_6))));
        out[2][1][2] = ((<f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        ) * (*__lambda_6)) - (c_slider * (*__lambda_7)));
        ::core::option::Option::Some(::mbd::BodyWrench {
            force: out[body][0],
            moment: out[body][1],
        })
    }
}
#[allow(unused_variables, unused_parens, clippy::approx_constant)]
impl ::mbd::__private::KinematicsHooks<f64, 9, 9, 9> for SliderCrank {
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn sparse_position_solve(
        &self,
        q: &mut [f64; 9],
        t: f64,
        tolerance: f64,
        pivot_tolerance: f64,
        max_iterations: u32,
        reuse: f64,
        max_step: f64,
        phi: &mut [f64; 9],
        step: &mut [f64; 9],
    ) -> ::core::option::Option<(::mbd::PositionStep, u32, u32)> {
        let mut jv = [0f64; 23];
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        let mut newton = ::mbd::__private::Newton::new(
            tolerance,
            max_iterations,
            reuse,
            max_step,
        );
        let (v5, v24, v59): (f64, f64, f64);
        v5 = (self.r / 2f64);
        v24 = (self.l / 2f64);
        v59 = (self.omega * t);
        loop {
            {
                let q: &[f64; 9] = q;
                let (
                    s_crank,
                    c_crank,
                    v10,
                    v12,
                    v13,
                    s_rod,
                    c_rod,
                    v29,
                    v31,
                    v32,
                    s_slider,
                    c_slider,
                    v81,
                ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
                use ::mbd::__private::Elements as _;
                let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6,
                __phi_7, __phi_8] = phi.window_mut::<0, 9>();
                let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
                    .window::<0, 9>();
                (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
                v10 = (v5 * c_crank);
                v12 = (v5 * s_crank);
                v13 = (-v12);
                (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
                v29 = (v24 * c_rod);
                v31 = (v24 * s_rod);
                v32 = (-v31);
                (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
                (*__phi_0) = (-((*__q_0) - v10));
                (*__phi_1) = (-((*__q_1) - v12));
                (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
                (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
                (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
                (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
                (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
                (*__phi_7) = (-s_slider);
                (*__phi_8) = ((*__q_2) - v59);
                match newton.after_residual(phi) {
                    ::mbd::__private::NewtonNext::Stop(end) => {
                        return ::core::option::Option::Some(newton.end(end));
                    }
                    ::mbd::__private::NewtonNext::Factor => {
                        use ::mbd::__private::Elements as _;
                        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6,
                        __jv_7, __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13,
                        __jv_14, __jv_15, __jv_16, __jv_17, __jv_18, __jv_19, __jv_20,
                        __jv_21, __jv_22] = jv.window_mut::<0, 23>();
                        let [__q_6, __q_7] = q.window::<6, 2>();
                        v81 = (-c_slider);
                        (*__jv_0) = (-1f64);
                        (*__jv_1) = v13;
                        (*__jv_2) = (-1f64);
                        (*__jv_3) = v10;
                        (*__jv_4) = 1f64;
                        (*__jv_5) = v13;
                        (*__jv_6) = (-1f64);
                        (*__jv_7) = v32;
                        (*__jv_8) = 1f64;
                        (*__jv_9) = v10;
                        (*__jv_10) = (-1f64);
                        (*__jv_11) = v29;
                        (*__jv_12) = 1f64;
                        (*__jv_13) = v32;
                        (*__jv_14) = (-1f64);
                        (*__jv_15) = 1f64;
                        (*__jv_16) = v29;
                        (*__jv_17) = (-1f64);
                        (*__jv_18) = s_slider;
                        (*__jv_19) = v81;
                        (*__jv_20) = <f64 as ::mbd::Real>::fused_mul_add(
                            c_slider,
                            (*__q_6),
                            (s_slider * (*__q_7)),
                        );
                        (*__jv_21) = v81;
                        (*__jv_22) = 1f64;
                        if Self::schur_factor(
                                &jv,
                                &[1f64; 9],
                                pivot_tolerance,
                                false,
                                &mut l,
                                &mut dinv,
                            )
                            .is_err()
                        {
                            return ::core::option::Option::Some(
                                newton.end(::mbd::PositionStep::Singular),
                            );
                        }
                        newton.factored();
                    }
                    ::mbd::__private::NewtonNext::Reuse => {}
                }
                let mut b = *phi;
                Self::schur_solve(&l, &dinv, &mut b);
                *step = [0f64; 9];
                use ::mbd::__private::Elements as _;
                let [__b_0, __b_1, __b_2, __b_3, __b_4, __b_5, __b_6, __b_7, __b_8] = b
                    .window::<0, 9>();
                let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7,
                __jv_8, __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15,
                __jv_16, __jv_17, __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv
                    .window::<0, 23>();
                let [__step_0, __step_1, __step_2, __step_3, __step_4, __step_5,
                __step_6, __step_7, __step_8] = step.window_mut::<0, 9>();
                (*__step_0) = -((*__jv_0) * (*__b_0) + (*__jv_4) * (*__b_2));
                (*__step_1) = -((*__jv_2) * (*__b_1) + (*__jv_8) * (*__b_3));
                (*__step_2) = -((*__jv_1) * (*__b_0) + (*__jv_3) * (*__b_1)
                    + (*__jv_5) * (*__b_2) + (*__jv_9) * (*__b_3)
                    + (*__jv_22) * (*__b_8));
                (*__step_3) = -((*__jv_6) * (*__b_2) + (*__jv_12) * (*__b_4));
                (*__step_4) = -((*__jv_10) * (*__b_3) + (*__jv_15) * (*__b_5));
                (*__step_5) = -((*__jv_7) * (*__b_2) + (*__jv_11) * (*__b_3)
                    + (*__jv_13) * (*__b_4) + (*__jv_16) * (*__b_5));
                (*__step_6) = -((*__jv_14) * (*__b_4) + (*__jv_18) * (*__b_6));
                (*__step_7) = -((*__jv_17) * (*__b_5) + (*__jv_19) * (*__b_6));
                (*__step_8) = -((*__jv_20) * (*__b_6) + (*__jv_21) * (*__b_7));
            }
            if !newton.accept_step(step) {
                return ::core::option::Option::Some(
                    newton.end(::mbd::PositionStep::Step),
                );
            }
            ::mbd::Kinematics::integrate_positions(self, q, step, 1f64);
        }
    }
    #[inline]
    fn sparse_velocity_acceleration(
        &self,
        q: &[f64; 9],
        t: f64,
        pivot_tolerance: f64,
        v: &mut [f64; 9],
        vd: &mut [f64; 9],
    ) -> bool {
        let mut jv = [0f64; 23];
        let mut nu = [0f64; 9];
        let mut gamma = [0f64; 9];
        let (v5, v24): (f64, f64);
        v5 = (self.r / 2f64);
        v24 = (self.l / 2f64);
        let (
            s_crank,
            c_crank,
            v10,
            v13,
            s_rod,
            c_rod,
            v29,
            v32,
            s_slider,
            c_slider,
            v81,
            v119,
            v126,
            v134,
            v138,
            v141,
            v147,
            v151,
            v152,
            v158,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__jv_0, __jv_1, __jv_2, __jv_3, __jv_4, __jv_5, __jv_6, __jv_7, __jv_8,
        __jv_9, __jv_10, __jv_11, __jv_12, __jv_13, __jv_14, __jv_15, __jv_16, __jv_17,
        __jv_18, __jv_19, __jv_20, __jv_21, __jv_22] = jv.window_mut::<0, 23>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v13 = (-(v5 * s_crank));
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v32 = (-(v24 * s_rod));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        (*__jv_0) = (-1f64);
        (*__jv_1) = v13;
        (*__jv_2) = (-1f64);
        (*__jv_3) = v10;
        (*__jv_4) = 1f64;
        (*__jv_5) = v13;
        (*__jv_6) = (-1f64);
        (*__jv_7) = v32;
        (*__jv_8) = 1f64;
        (*__jv_9) = v10;
        (*__jv_10) = (-1f64);
        (*__jv_11) = v29;
        (*__jv_12) = 1f64;
        (*__jv_13) = v32;
        (*__jv_14) = (-1f64);
        (*__jv_15) = 1f64;
        (*__jv_16) = v29;
        (*__jv_17) = (-1f64);
        (*__jv_18) = s_slider;
        (*__jv_19) = v81;
        (*__jv_20) = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        (*__jv_21) = v81;
        (*__jv_22) = 1f64;
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        if Self::schur_factor(&jv, &[1f64; 9], pivot_tolerance, false, &mut l, &mut dinv)
            .is_err()
        {
            return false;
        }
        if !Self::constraint_solve(&jv, &l, &dinv, &nu, v) {
            return false;
        }
        {
            let v: &[f64; 9] = v;
            use ::mbd::__private::Elements as _;
            let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5,
            __gamma_6, __gamma_7, __gamma_8] = gamma.window_mut::<0, 9>();
            let [__q_6, __q_7] = q.window::<6, 2>();
            let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
            v119 = (s_slider * (*__v_8));
            v126 = (c_slider * (*__v_8));
            v134 = (v5 * ((*__v_2) * (c_crank * (*__v_2))));
            v138 = (v5 * ((*__v_2) * (s_crank * (*__v_2))));
            v141 = (v24 * ((*__v_5) * (c_rod * (*__v_5))));
            v147 = (v24 * ((*__v_5) * (s_rod * (*__v_5))));
            v151 = ((*__v_6) * v126);
            v152 = ((*__v_8) * v119);
            v158 = ((*__v_7) * v119);
            (*__gamma_0) = v134;
            (*__gamma_1) = v138;
            (*__gamma_2) = (v134 + v141);
            (*__gamma_3) = (v138 + v147);
            (*__gamma_4) = v141;
            (*__gamma_5) = v147;
            (*__gamma_6) = (-((v151 + (v151 - ((*__q_6) * v152)))
                + (v158
                    + <f64 as ::mbd::Real>::fused_mul_add(
                        (*__q_7),
                        ((*__v_8) * v126),
                        v158,
                    ))));
            (*__gamma_7) = (-v152);
            (*__gamma_8) = 0f64;
        }
        Self::constraint_solve(&jv, &l, &dinv, &gamma, vd)
    }
    #[inline]
    fn sparse_multipliers(
        &self,
        q: &[f64; 9],
        t: f64,
        pivot_tolerance: f64,
        b: &[f64; 9],
        lambda: &mut [f64; 9],
    ) -> bool {
        let mut jv = [0f64; 23];
        self.jacobian_values(q, t, &mut jv);
        let mut l = [0f64; 18];
        let mut dinv = [0f64; 9];
        if Self::schur_factor(&jv, &[1f64; 9], pivot_tolerance, false, &mut l, &mut dinv)
            .is_err()
        {
            return false;
        }
        Self::transpose_solve(&jv, &l, &dinv, b, lambda)
    }
}
#[allow(unused_variables, unused_parens, clippy::approx_constant)]
impl ::mbd::Kinematics<f64, 9, 9, 9> for SliderCrank {
    #[inline]
    fn initial_positions(&self) -> [f64; 9] {
        let mut q = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window_mut::<0, 9>();
        (*__q_0) = 0.05f64;
        (*__q_1) = 0f64;
        (*__q_2) = 0f64;
        (*__q_3) = 0.25f64;
        (*__q_4) = 0f64;
        (*__q_5) = 0f64;
        (*__q_6) = 0.4f64;
        (*__q_7) = 0f64;
        (*__q_8) = 0f64;
        q
    }
    #[inline]
    fn initial_velocities(&self) -> [f64; 9] {
        let mut v = [0f64; 9];
        use ::mbd::__private::Elements as _;
        let [__v_0, __v_1, __v_2, __v_3, __v_4, __v_5, __v_6, __v_7, __v_8] = v
            .window_mut::<0, 9>();
        (*__v_0) = 0f64;
        (*__v_1) = 0f64;
        (*__v_2) = 0f64;
        (*__v_3) = 0f64;
        (*__v_4) = 0f64;
        (*__v_5) = 0f64;
        (*__v_6) = 0f64;
        (*__v_7) = 0f64;
        (*__v_8) = 0f64;
        v
    }
    #[inline]
    fn position_rates(&self, q: &[f64; 9], v: &[f64; 9], qdot: &mut [f64; 9]) {
        *qdot = *v;
    }
    #[inline]
    fn integrate_positions(&self, q: &mut [f64; 9], dv: &[f64; 9], h: f64) {
        for i in 0..9 {
            q[i] += h * dv[i];
        }
    }
    #[inline]
    fn normalize_positions(&self, q: &mut [f64; 9]) {}
    #[inline]
    fn constraints(&self, q: &[f64; 9], t: f64, phi: &mut [f64; 9]) {
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            s_slider,
            c_slider,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
    }
    #[inline]
    fn jacobian(&self, q: &[f64; 9], t: f64, d: &mut [[f64; 9]; 9]) {
        for row in d.iter_mut() {
            *row = [0f64; 9];
        }
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v32,
            s_slider,
            c_slider,
            v81,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v13 = (-(v5 * s_crank));
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v32 = (-(v24 * s_rod));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
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
        d[6][7] = v81;
        d[6][8] = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        d[7][8] = v81;
        d[8][2] = 1f64;
    }
    #[inline]
    fn velocity_rhs(&self, q: &[f64; 9], t: f64, nu: &mut [f64; 9]) {
        use ::mbd::__private::Elements as _;
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
    }
    #[inline]
    fn gamma(&self, q: &[f64; 9], v: &[f64; 9], t: f64, gamma: &mut [f64; 9]) {
        let (
            v5,
            s_crank,
            c_crank,
            v24,
            s_rod,
            c_rod,
            s_slider,
            c_slider,
            v119,
            v126,
            v134,
            v138,
            v141,
            v147,
            v151,
            v152,
            v158,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5, __gamma_6,
        __gamma_7, __gamma_8] = gamma.window_mut::<0, 9>();
        let [__q_2, _, _, __q_5, __q_6, __q_7, __q_8] = q.window::<2, 7>();
        let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v119 = (s_slider * (*__v_8));
        v126 = (c_slider * (*__v_8));
        v134 = (v5 * ((*__v_2) * (c_crank * (*__v_2))));
        v138 = (v5 * ((*__v_2) * (s_crank * (*__v_2))));
        v141 = (v24 * ((*__v_5) * (c_rod * (*__v_5))));
        v147 = (v24 * ((*__v_5) * (s_rod * (*__v_5))));
        v151 = ((*__v_6) * v126);
        v152 = ((*__v_8) * v119);
        v158 = ((*__v_7) * v119);
        (*__gamma_0) = v134;
        (*__gamma_1) = v138;
        (*__gamma_2) = (v134 + v141);
        (*__gamma_3) = (v138 + v147);
        (*__gamma_4) = v141;
        (*__gamma_5) = v147;
        (*__gamma_6) = (-((v151 + (v151 - ((*__q_6) * v152)))
            + (v158
                + <f64 as ::mbd::Real>::fused_mul_add(
                    (*__q_7),
                    ((*__v_8) * v126),
                    v158,
                ))));
        (*__gamma_7) = (-v152);
        (*__gamma_8) = 0f64;
    }
    #[inline]
    fn position_eval(
        &self,
        q: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        d: &mut [[f64; 9]; 9],
    ) {
        for row in d.iter_mut() {
            *row = [0f64; 9];
        }
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v81,
        ): (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);
        use ::mbd::__private::Elements as _;
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
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
        d[6][7] = v81;
        d[6][8] = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        d[7][8] = v81;
        d[8][2] = 1f64;
    }
    #[inline]
    fn full_eval(
        &self,
        q: &[f64; 9],
        v: &[f64; 9],
        t: f64,
        phi: &mut [f64; 9],
        d: &mut [[f64; 9]; 9],
        nu: &mut [f64; 9],
        gamma: &mut [f64; 9],
    ) {
        for row in d.iter_mut() {
            *row = [0f64; 9];
        }
        let (
            v5,
            s_crank,
            c_crank,
            v10,
            v12,
            v13,
            v24,
            s_rod,
            c_rod,
            v29,
            v31,
            v32,
            s_slider,
            c_slider,
            v81,
            v119,
            v126,
            v134,
            v138,
            v141,
            v147,
            v151,
            v152,
            v158,
        ): (
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
            f64,
        );
        use ::mbd::__private::Elements as _;
        let [__gamma_0, __gamma_1, __gamma_2, __gamma_3, __gamma_4, __gamma_5, __gamma_6,
        __gamma_7, __gamma_8] = gamma.window_mut::<0, 9>();
        let [__nu_0, __nu_1, __nu_2, __nu_3, __nu_4, __nu_5, __nu_6, __nu_7, __nu_8] = nu
            .window_mut::<0, 9>();
        let [__phi_0, __phi_1, __phi_2, __phi_3, __phi_4, __phi_5, __phi_6, __phi_7,
        __phi_8] = phi.window_mut::<0, 9>();
        let [__q_0, __q_1, __q_2, __q_3, __q_4, __q_5, __q_6, __q_7, __q_8] = q
            .window::<0, 9>();
        let [__v_2, _, _, __v_5, __v_6, __v_7, __v_8] = v.window::<2, 7>();
        v5 = (self.r / 2f64);
        (s_crank, c_crank) = <f64 as ::mbd::Real>::sin_cos((*__q_2));
        v10 = (v5 * c_crank);
        v12 = (v5 * s_crank);
        v13 = (-v12);
        v24 = (self.l / 2f64);
        (s_rod, c_rod) = <f64 as ::mbd::Real>::sin_cos((*__q_5));
        v29 = (v24 * c_rod);
        v31 = (v24 * s_rod);
        v32 = (-v31);
        (s_slider, c_slider) = <f64 as ::mbd::Real>::sin_cos((*__q_8));
        v81 = (-c_slider);
        v119 = (s_slider * (*__v_8));
        v126 = (c_slider * (*__v_8));
        v134 = (v5 * ((*__v_2) * (c_crank * (*__v_2))));
        v138 = (v5 * ((*__v_2) * (s_crank * (*__v_2))));
        v141 = (v24 * ((*__v_5) * (c_rod * (*__v_5))));
        v147 = (v24 * ((*__v_5) * (s_rod * (*__v_5))));
        v151 = ((*__v_6) * v126);
        v152 = ((*__v_8) * v119);
        v158 = ((*__v_7) * v119);
        (*__phi_0) = (-((*__q_0) - v10));
        (*__phi_1) = (-((*__q_1) - v12));
        (*__phi_2) = ((v10 + (*__q_0)) - ((*__q_3) - v29));
        (*__phi_3) = ((v12 + (*__q_1)) - ((*__q_4) - v31));
        (*__phi_4) = ((v29 + (*__q_3)) - (*__q_6));
        (*__phi_5) = ((v31 + (*__q_4)) - (*__q_7));
        (*__phi_6) = ((s_slider * (*__q_6)) - (c_slider * (*__q_7)));
        (*__phi_7) = (-s_slider);
        (*__phi_8) = ((*__q_2) - (self.omega * t));
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
        d[6][7] = v81;
        d[6][8] = <f64 as ::mbd::Real>::fused_mul_add(
            c_slider,
            (*__q_6),
            (s_slider * (*__q_7)),
        );
        d[7][8] = v81;
        d[8][2] = 1f64;
        (*__nu_0) = 0f64;
        (*__nu_1) = 0f64;
        (*__nu_2) = 0f64;
        (*__nu_3) = 0f64;
        (*__nu_4) = 0f64;
        (*__nu_5) = 0f64;
        (*__nu_6) = 0f64;
        (*__nu_7) = 0f64;
        (*__nu_8) = self.omega;
        (*__gamma_0) = v134;
        (*__gamma_1) = v138;
        (*__gamma_2) = (v134 + v141);
        (*__gamma_3) = (v138 + v147);
        (*__gamma_4) = v141;
        (*__gamma_5) = v147;
        (*__gamma_6) = (-((v151 + (v151 - ((*__q_6) * v152)))
            + (v158
                + <f64 as ::mbd::Real>::fused_mul_add(
                    (*__q_7),
                    ((*__v_8) * v126),
                    v158,
                ))));
        (*__gamma_7) = (-v152);
        (*__gamma_8) = 0f64;
    }
}
