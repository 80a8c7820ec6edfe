//! CasADi-generated C functions of the benchmark mechanisms, callable from Rust, so criterion can
//! time them beside mbd's generated functions in the same run on the same machine.
//!
//! Kinematics (`slider_crank`, `chain16`; `python -m mbd_oracle.codegen SAMPLES.json PREFIX OUT.c`):
//! `phi(q, t, p)`, `jac(q, t, p)` (the Jacobian's structural non-zeros, column-major) and
//! `gamma(q, qd, t, p)`.
//!
//! Forward dynamics (`free_slider_crank`, `pendulum_chain16`; `python -m mbd_oracle.codegen
//! --dynamics SAMPLES.json PREFIX OUT.c`): `fd_schur(q, qd, t, p, [α, β])` and
//! `fd_qr(q, qd, t, p, [α, β])`, both returning [q̈; λ] of M q̈ − Φ_qᵀλ = h, Φ_q q̈ = γ − 2α(Φ_q q̇ − ν)
//! − β²Φ: the first through the Schur complement Φ_q M⁻¹ Φ_qᵀ factored symbolically by CasADi
//! (straight-line code), the second through CasADi's sparse numeric QR of the KKT matrix.
//! The same files hold the force functions and the Newton-matrix fill (issue 41): `mx(q, x, p)`
//! = M x, `h(q, qd, t, p)`, `h_q` and `h_v` (∂h/∂q and ∂h/∂q̇ as sparse matrices: their structural
//! non-zeros, column-major; none where h is gravity alone), and `newton(q, qd, t, p, λ, [c_v,
//! c_q])` with three outputs, Φ, Φ_q's non-zeros and the sparse A = M − c_v ∂h/∂q̇ − c_q (∂h/∂q +
//! K), K = ∂(Φ_qᵀλ)/∂q: what mbd's `newton_matrix` evaluates into its planned storage.
//! [`CasadiFunction::output_pattern`] reads a sparse output's pattern.
//! The samples files come from `cargo test --test oracle` (`target/oracle/samples/`).
//!
//! Spatial mechanisms (`mechanisms/*.rs`; `casadi/generate_spatial.sh` regenerates their C from
//! the oracle's spatial rebuild of each `MODEL_JSON`): kinematics (`spatial_slider_crank`,
//! `spatial_chain16`) `phi(q, t, p)`, `jac(q, t, p)` (the non-zeros of D = Φ_q B on mbd's
//! `JACOBIAN_PATTERN`, column-major) and `gamma(q, v, t, p)`; forward dynamics
//! (`free_spatial_slider_crank`, `spatial_chain16_dynamics`) `fd_schur(q, v, t, p, [α, β])` and
//! `fd_qr(q, v, t, p, [α, β])` returning [v̇; λ], as above with M = blockdiag(m I₃, J′) and D in
//! place of Φ_q; and the force functions and Newton fill in velocity space (∂h/∂q·B, ∂h/∂v,
//! K = ∂(Dᵀλ)/∂q·B, D's non-zeros on mbd's pattern). q has 7 entries per body (x, y, z, e0..e3), v has 6 (ṙ global, ω′ body frame).
//!
//! The comparison with MuJoCo (`benches/vs_mujoco.rs`) needs none of this: it runs MuJoCo from
//! its own Python environment (`peers/`) and times mbd's RK4 step beside it.
//!
//! Each function has CasADi's standard C interface: `f(arg, res, iw, w, mem)` with the work-space
//! sizes reported by `f_work`. [`CasadiFunction`] queries those sizes once and owns the work
//! space, so a call allocates nothing.

pub mod roofline;

use std::os::raw::c_int;

type CasadiInt = i64;
type Eval = unsafe extern "C" fn(*const *const f64, *const *mut f64, *mut CasadiInt, *mut f64, c_int) -> c_int;
type Work = unsafe extern "C" fn(*mut CasadiInt, *mut CasadiInt, *mut CasadiInt, *mut CasadiInt) -> c_int;
type Sparsity = unsafe extern "C" fn(CasadiInt) -> *const CasadiInt;

/// One CasADi-generated function with its work space.
pub struct CasadiFunction {
    eval: Eval,
    sparsity: Sparsity,
    arg: Vec<*const f64>,
    res: Vec<*mut f64>,
    iw: Vec<CasadiInt>,
    w: Vec<f64>,
}

impl CasadiFunction {
    fn new(eval: Eval, work: Work, sparsity: Sparsity) -> Self {
        let (mut sz_arg, mut sz_res, mut sz_iw, mut sz_w) = (0, 0, 0, 0);
        // SAFETY: the generated `_work` function only writes the four sizes.
        let status = unsafe { work(&mut sz_arg, &mut sz_res, &mut sz_iw, &mut sz_w) };
        assert_eq!(status, 0, "CasADi work-size query failed");
        CasadiFunction {
            eval,
            sparsity,
            arg: vec![std::ptr::null(); sz_arg as usize],
            res: vec![std::ptr::null_mut(); sz_res as usize],
            iw: vec![0; sz_iw as usize],
            w: vec![0.0; sz_w as usize],
        }
    }

    /// Evaluates with the given inputs (dense vectors in CasADi's input order) into `out`.
    ///
    /// The caller passes inputs and an output of the sizes the function was generated for.
    pub fn call(&mut self, inputs: &[&[f64]], out: &mut [f64]) {
        for (slot, input) in self.arg.iter_mut().zip(inputs) {
            *slot = input.as_ptr();
        }
        self.res[0] = out.as_mut_ptr();
        // SAFETY: argument and result pointers point at buffers of the generated sizes, and the
        // work arrays have the sizes the function reported.
        let status = unsafe { (self.eval)(self.arg.as_ptr(), self.res.as_ptr(), self.iw.as_mut_ptr(), self.w.as_mut_ptr(), 0) };
        debug_assert_eq!(status, 0);
    }

    /// Evaluates with the given inputs into one buffer per output (of the generated sizes).
    pub fn call_outputs(&mut self, inputs: &[&[f64]], outputs: &mut [&mut [f64]]) {
        for (slot, input) in self.arg.iter_mut().zip(inputs) {
            *slot = input.as_ptr();
        }
        for (slot, output) in self.res.iter_mut().zip(outputs.iter_mut()) {
            *slot = output.as_mut_ptr();
        }
        // SAFETY: as in `call`, for every output.
        let status = unsafe { (self.eval)(self.arg.as_ptr(), self.res.as_ptr(), self.iw.as_mut_ptr(), self.w.as_mut_ptr(), 0) };
        debug_assert_eq!(status, 0);
    }

    /// The (row, column) of each value of output `i`, in the order the function writes them
    /// (CasADi's compressed columns: column-major), and the output's (rows, columns).
    pub fn output_pattern(&self, i: usize) -> (Vec<(usize, usize)>, (usize, usize)) {
        // SAFETY: the generated function returns a pointer to its static compressed-column
        // pattern [rows, columns, column starts (columns + 1), row of each non-zero] — or
        // [rows, columns, 1] for a dense output (a column start is 0 first otherwise) — or null
        // for an output it does not have.
        unsafe {
            let p = (self.sparsity)(i as CasadiInt);
            assert!(!p.is_null(), "no output {i}");
            let (rows, columns) = (*p as usize, *p.add(1) as usize);
            if *p.add(2) == 1 {
                return ((0..columns).flat_map(|c| (0..rows).map(move |r| (r, c))).collect(), (rows, columns));
            }
            let start = |c: usize| *p.add(2 + c) as usize;
            let mut pattern = Vec::new();
            for c in 0..columns {
                for k in start(c)..start(c + 1) {
                    pattern.push((*p.add(3 + columns + k) as usize, c));
                }
            }
            (pattern, (rows, columns))
        }
    }
}

macro_rules! casadi_functions {
    ($($module:ident: $($name:ident = $f:ident / $w:ident),*;)*) => {
        extern "C" {
            $($(fn $f(arg: *const *const f64, res: *const *mut f64, iw: *mut CasadiInt, w: *mut f64, mem: c_int) -> c_int;
                fn $w(a: *mut CasadiInt, r: *mut CasadiInt, iw: *mut CasadiInt, w: *mut CasadiInt) -> c_int;)*)*
        }
        $(
            /// The CasADi-generated functions of one mechanism (see the crate documentation).
            pub mod $module {
                $(
                    /// A CasADi-generated function (see the crate documentation).
                    pub fn $name() -> super::CasadiFunction {
                        extern "C" {
                            #[link_name = concat!(stringify!($f), "_sparsity_out")]
                            fn sparsity(i: super::CasadiInt) -> *const super::CasadiInt;
                        }
                        super::CasadiFunction::new(super::$f, super::$w, sparsity)
                    }
                )*
            }
        )*
    };
}

casadi_functions! {
    slider_crank: phi = slider_crank_phi / slider_crank_phi_work, jac = slider_crank_jac / slider_crank_jac_work,
        gamma = slider_crank_gamma / slider_crank_gamma_work;
    chain16: phi = chain16_phi / chain16_phi_work, jac = chain16_jac / chain16_jac_work, gamma = chain16_gamma / chain16_gamma_work;
    free_slider_crank: fd_schur = free_slider_crank_fd_schur / free_slider_crank_fd_schur_work,
        fd_qr = free_slider_crank_fd_qr / free_slider_crank_fd_qr_work,
        mx = free_slider_crank_mx / free_slider_crank_mx_work,
        h = free_slider_crank_h / free_slider_crank_h_work,
        h_q = free_slider_crank_h_q / free_slider_crank_h_q_work,
        h_v = free_slider_crank_h_qd / free_slider_crank_h_qd_work,
        newton = free_slider_crank_newton / free_slider_crank_newton_work;
    pendulum_chain16: fd_schur = pendulum_chain16_fd_schur / pendulum_chain16_fd_schur_work,
        fd_qr = pendulum_chain16_fd_qr / pendulum_chain16_fd_qr_work,
        mx = pendulum_chain16_mx / pendulum_chain16_mx_work,
        h = pendulum_chain16_h / pendulum_chain16_h_work,
        h_q = pendulum_chain16_h_q / pendulum_chain16_h_q_work,
        h_v = pendulum_chain16_h_qd / pendulum_chain16_h_qd_work,
        newton = pendulum_chain16_newton / pendulum_chain16_newton_work;
    spatial_slider_crank: phi = spatial_slider_crank_phi / spatial_slider_crank_phi_work,
        jac = spatial_slider_crank_jac / spatial_slider_crank_jac_work,
        gamma = spatial_slider_crank_gamma / spatial_slider_crank_gamma_work;
    spatial_chain16: phi = spatial_chain16_phi / spatial_chain16_phi_work, jac = spatial_chain16_jac / spatial_chain16_jac_work,
        gamma = spatial_chain16_gamma / spatial_chain16_gamma_work;
    free_spatial_slider_crank: fd_schur = free_spatial_slider_crank_fd_schur / free_spatial_slider_crank_fd_schur_work,
        fd_qr = free_spatial_slider_crank_fd_qr / free_spatial_slider_crank_fd_qr_work,
        mx = free_spatial_slider_crank_mx / free_spatial_slider_crank_mx_work,
        h = free_spatial_slider_crank_h / free_spatial_slider_crank_h_work,
        h_q = free_spatial_slider_crank_h_q / free_spatial_slider_crank_h_q_work,
        h_v = free_spatial_slider_crank_h_v / free_spatial_slider_crank_h_v_work,
        newton = free_spatial_slider_crank_newton / free_spatial_slider_crank_newton_work;
    spatial_chain16_dynamics: fd_schur = spatial_chain16_fd_schur / spatial_chain16_fd_schur_work,
        fd_qr = spatial_chain16_fd_qr / spatial_chain16_fd_qr_work,
        mx = spatial_chain16_mx / spatial_chain16_mx_work,
        h = spatial_chain16_h / spatial_chain16_h_work,
        h_q = spatial_chain16_h_q / spatial_chain16_h_q_work,
        h_v = spatial_chain16_h_v / spatial_chain16_h_v_work,
        newton = spatial_chain16_newton / spatial_chain16_newton_work;
}

/// The CasADi counterparts of a mechanism's force functions and Newton-matrix fill (issue 41),
/// made by [`force_functions!`].
pub struct ForceFunctions {
    /// M(q) x.
    pub mx: CasadiFunction,
    /// h(q, v, t).
    pub h: CasadiFunction,
    /// ∂h/∂q (·B), its non-zeros.
    pub h_q: CasadiFunction,
    /// ∂h/∂v, its non-zeros.
    pub h_v: CasadiFunction,
    /// (Φ, D, A) of the Newton matrix.
    pub newton: CasadiFunction,
}

/// The [`ForceFunctions`] of one of the forward-dynamics modules: `force_functions!(pendulum_chain16)`.
#[macro_export]
macro_rules! force_functions {
    ($module:ident) => {
        $crate::ForceFunctions {
            mx: $crate::$module::mx(),
            h: $crate::$module::h(),
            h_q: $crate::$module::h_q(),
            h_v: $crate::$module::h_v(),
            newton: $crate::$module::newton(),
        }
    };
}
