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
//! The samples files come from `cargo test --test oracle` (`target/oracle/samples/`).
//!
//! Spatial mechanisms (`mechanisms/*.rs`; `casadi/generate_spatial.sh` regenerates their C from
//! the oracle's spatial rebuild of each `MODEL_JSON`): kinematics (`spatial_slider_crank`,
//! `spatial_chain16`) `phi(q, t, p)`, `jac(q, t, p)` (the non-zeros of D = Φ_q B on mbd's
//! `JACOBIAN_PATTERN`, column-major) and `gamma(q, v, t, p)`; forward dynamics
//! (`free_spatial_slider_crank`, `spatial_chain16_dynamics`) `fd_schur(q, v, t, p, [α, β])` and
//! `fd_qr(q, v, t, p, [α, β])` returning [v̇; λ], as above with M = blockdiag(m I₃, J′) and D in
//! place of Φ_q. q has 7 entries per body (x, y, z, e0..e3), v has 6 (ṙ global, ω′ body frame).
//!
//! The comparison with MuJoCo (`benches/vs_mujoco.rs`) needs none of this: it runs MuJoCo from
//! its own Python environment (`peers/`) and times mbd's RK4 step beside it.
//!
//! Each function has CasADi's standard C interface: `f(arg, res, iw, w, mem)` with the work-space
//! sizes reported by `f_work`. [`CasadiFunction`] queries those sizes once and owns the work
//! space, so a call allocates nothing.

use std::os::raw::c_int;

type CasadiInt = i64;
type Eval = unsafe extern "C" fn(*const *const f64, *const *mut f64, *mut CasadiInt, *mut f64, c_int) -> c_int;
type Work = unsafe extern "C" fn(*mut CasadiInt, *mut CasadiInt, *mut CasadiInt, *mut CasadiInt) -> c_int;

/// One CasADi-generated function with its work space.
pub struct CasadiFunction {
    eval: Eval,
    arg: Vec<*const f64>,
    res: Vec<*mut f64>,
    iw: Vec<CasadiInt>,
    w: Vec<f64>,
}

impl CasadiFunction {
    fn new(eval: Eval, work: Work) -> Self {
        let (mut sz_arg, mut sz_res, mut sz_iw, mut sz_w) = (0, 0, 0, 0);
        // SAFETY: the generated `_work` function only writes the four sizes.
        let status = unsafe { work(&mut sz_arg, &mut sz_res, &mut sz_iw, &mut sz_w) };
        assert_eq!(status, 0, "CasADi work-size query failed");
        CasadiFunction {
            eval,
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
                        super::CasadiFunction::new(super::$f, super::$w)
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
        fd_qr = free_slider_crank_fd_qr / free_slider_crank_fd_qr_work;
    pendulum_chain16: fd_schur = pendulum_chain16_fd_schur / pendulum_chain16_fd_schur_work,
        fd_qr = pendulum_chain16_fd_qr / pendulum_chain16_fd_qr_work;
    spatial_slider_crank: phi = spatial_slider_crank_phi / spatial_slider_crank_phi_work,
        jac = spatial_slider_crank_jac / spatial_slider_crank_jac_work,
        gamma = spatial_slider_crank_gamma / spatial_slider_crank_gamma_work;
    spatial_chain16: phi = spatial_chain16_phi / spatial_chain16_phi_work, jac = spatial_chain16_jac / spatial_chain16_jac_work,
        gamma = spatial_chain16_gamma / spatial_chain16_gamma_work;
    free_spatial_slider_crank: fd_schur = free_spatial_slider_crank_fd_schur / free_spatial_slider_crank_fd_schur_work,
        fd_qr = free_spatial_slider_crank_fd_qr / free_spatial_slider_crank_fd_qr_work;
    spatial_chain16_dynamics: fd_schur = spatial_chain16_fd_schur / spatial_chain16_fd_schur_work,
        fd_qr = spatial_chain16_fd_qr / spatial_chain16_fd_qr_work;
}
