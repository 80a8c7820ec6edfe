//! One side of the A/B comparison: the project's planar benchmark calls (`benches/kinematics.rs`,
//! `benches/dynamics.rs`), each behind its own `#[inline(never)]` function, for one version of
//! `mbd`. The six packages `sides/{base,head}{1,2,3}` all build this file, each against its own
//! `mbd` (see `../Cargo.toml`); the driver links all six and times them interleaved.
//!
//! The feature `nv` selects the API with a separate velocity dimension (`Point<T, NQ, NV, NC>`,
//! `Point::v`, `Dopri5<T, NQ, NV>`, `Kinematics<T, NQ, NV, NC>`); without it, the earlier API
//! (`Point<T, NQ, NC>`, `Point::qd`, `Dopri5<T, NQ>`). Planar mechanisms have NV = NQ, so both
//! compute the same thing from the same state.
//!
//! The feature `workspace` (which implies `nv`) selects the API of e12cd84 and later: every solver
//! takes the caller's `&mut Workspace<T, NV, NC, N>` as its second argument and `Integrator` has
//! a sixth parameter N = NV + NC. Each case allocates its work spaces (`Name::workspace()`, a
//! `Box`) once, when the case is made, never inside the timed loop; without the feature the same
//! code passes a `&mut ()` that the call ignores, so both sides time the same loop.
#![allow(clippy::too_many_arguments)]

use std::hint::black_box;

/// One timed call: `run(n)` makes the call `n` times; `output()` is what one call wrote, for
/// checking that both sides compute the same numbers.
pub struct Case {
    /// `mechanism/call`, the same on both sides.
    pub name: String,
    /// Makes the call `n` times.
    pub run: Box<dyn FnMut(u64)>,
    /// Makes the call once and returns everything it wrote.
    pub output: Box<dyn FnMut() -> Vec<f64>>,
}

/// An operation count of one generated function, as the mechanism's `OP_COUNTS` gives it.
#[derive(Clone, Debug)]
pub struct Ops {
    /// Mechanism name (`Mechanism::NAME`).
    pub mechanism: &'static str,
    /// Generated function.
    pub function: &'static str,
    /// Additions and subtractions.
    pub add: u32,
    /// Multiplications.
    pub mul: u32,
    /// Divisions.
    pub div: u32,
    /// Calls (sin, cos, sqrt …).
    pub call: u32,
}

#[cfg(feature = "nv")]
macro_rules! nv {
    ($ty:ty) => {
        <$ty>::NV
    };
}
#[cfg(not(feature = "nv"))]
macro_rules! nv {
    ($ty:ty) => {
        <$ty>::NQ
    };
}
#[cfg(feature = "nv")]
macro_rules! point_ty {
    ($nq:ident, $nv:ident, $nc:ident) => { mbd::Point<f64, $nq, $nv, $nc> };
}
#[cfg(not(feature = "nv"))]
macro_rules! point_ty {
    ($nq:ident, $nv:ident, $nc:ident) => { mbd::Point<f64, $nq, $nc> };
}
#[cfg(feature = "nv")]
macro_rules! dopri_ty {
    ($nq:ident, $nv:ident) => { mbd::Dopri5<f64, $nq, $nv> };
}
#[cfg(not(feature = "nv"))]
macro_rules! dopri_ty {
    ($nq:ident, $nv:ident) => { mbd::Dopri5<f64, $nq> };
}
/// Any integrator of a mechanism `M` (a stand-in for `mbd::Integrator`, whose parameters differ
/// between the APIs; N = NV + NC is used only with `workspace`).
#[cfg(feature = "storage")]
pub trait Step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>:
    mbd::Integrator<f64, M, NQ, NV, NC, N, NS>
{
}
#[cfg(feature = "storage")]
impl<I: mbd::Integrator<f64, M, NQ, NV, NC, N, NS>, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Step<M, NQ, NV, NC, N, NS> for I
{
}
#[cfg(all(feature = "workspace", not(feature = "storage")))]
pub trait Step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>: mbd::Integrator<f64, M, NQ, NV, NC, N> {}
#[cfg(all(feature = "workspace", not(feature = "storage")))]
impl<I: mbd::Integrator<f64, M, NQ, NV, NC, N>, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Step<M, NQ, NV, NC, N, NS> for I
{
}
/// Any integrator of a mechanism `M` (a stand-in for `mbd::Integrator`, whose parameters differ
/// between the APIs; N = NV + NC is used only with `workspace`).
#[cfg(all(feature = "nv", not(feature = "workspace")))]
pub trait Step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>: mbd::Integrator<f64, M, NQ, NV, NC> {}
#[cfg(all(feature = "nv", not(feature = "workspace")))]
impl<I: mbd::Integrator<f64, M, NQ, NV, NC>, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Step<M, NQ, NV, NC, N, NS> for I
{
}
/// Any integrator of a mechanism `M` (a stand-in for `mbd::Integrator`, whose parameters differ
/// between the APIs; N = NV + NC is used only with `workspace`).
#[cfg(not(feature = "nv"))]
pub trait Step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>: mbd::Integrator<f64, M, NQ, NC> {}
#[cfg(not(feature = "nv"))]
impl<I: mbd::Integrator<f64, M, NQ, NC>, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Step<M, NQ, NV, NC, N, NS> for I
{
}
/// The work space of a mechanism with NV velocities and NC constraints, N = NV + NC: what every
/// solver takes with `workspace`; `()` without (the solvers then keep it themselves).
#[cfg(feature = "storage")]
macro_rules! ws_ty {
    ($nv:expr, $nc:expr, $n:expr, $ns:expr) => { mbd::Workspace<f64, { $nv }, { $nc }, { $n }, { $ns }> };
}
#[cfg(all(feature = "workspace", not(feature = "storage")))]
macro_rules! ws_ty {
    ($nv:expr, $nc:expr, $n:expr, $ns:expr) => { mbd::Workspace<f64, { $nv }, { $nc }, { $n }> };
}
#[cfg(not(feature = "workspace"))]
macro_rules! ws_ty {
    ($nv:expr, $nc:expr, $n:expr, $ns:expr) => { () };
}
/// The planned Newton matrix's storage of mechanism `$ty` where the work space holds it (the
/// runtime after 2026-11-26), 0 before.
#[cfg(feature = "storage")]
macro_rules! ns {
    ($ty:ty) => { <$ty>::NEWTON_STORAGE };
}
#[cfg(not(feature = "storage"))]
macro_rules! ns {
    ($ty:ty) => { 0 };
}
#[cfg(feature = "workspace")]
pub type Ws<const NV: usize, const NC: usize, const N: usize> = mbd::Workspace<f64, NV, NC, N>;
/// The work space of a mechanism with NV velocities and NC constraints, N = NV + NC: what every
/// solver takes with `workspace`; `()` without (the solvers then keep it themselves).
#[cfg(not(feature = "workspace"))]
pub type Ws<const NV: usize, const NC: usize, const N: usize> = ();
/// A zeroed work space on the heap: `Name::workspace()` with `workspace`.
#[cfg(feature = "workspace")]
macro_rules! new_ws {
    ($ty:ty) => {
        <$ty>::workspace()
    };
}
#[cfg(not(feature = "workspace"))]
macro_rules! new_ws {
    ($ty:ty) => {
        Box::new(())
    };
}
/// `ws_call!(recv.method(first, ws, rest…))`: with `workspace`, the call as written; without, the
/// call without `ws` (not evaluated).
#[cfg(feature = "workspace")]
macro_rules! ws_call {
    ($recv:expr, $method:ident($first:expr, $ws:expr, $($rest:expr),*)) => {
        $recv.$method($first, $ws, $($rest),*)
    };
}
#[cfg(not(feature = "workspace"))]
macro_rules! ws_call {
    ($recv:expr, $method:ident($first:expr, $ws:expr, $($rest:expr),*)) => {{
        let _ = &$ws;
        $recv.$method($first, $($rest),*)
    }};
}
#[cfg(feature = "nv")]
macro_rules! vel {
    ($p:expr) => {
        $p.v
    };
}
#[cfg(not(feature = "nv"))]
macro_rules! vel {
    ($p:expr) => {
        $p.qd
    };
}

mod slider_crank {
    include!("../mechanisms/slider_crank.rs");
}
mod chain16 {
    include!("../mechanisms/chain16.rs");
}
mod free_slider_crank {
    include!("../mechanisms/free_slider_crank.rs");
}
mod chains {
    include!("../mechanisms/pendulum_chain4.rs");
    include!("../mechanisms/pendulum_chain16.rs");
    include!("../mechanisms/pendulum_chain64.rs");
}

fn case(name: String, run: impl FnMut(u64) + 'static, output: impl FnMut() -> Vec<f64> + 'static) -> Case {
    Case { name, run: Box::new(run), output: Box::new(output) }
}

fn flat<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> Vec<f64> {
    a.iter().flatten().copied().collect()
}

/// The calls of `benches/kinematics.rs` for one mechanism, from the same state (assembled at
/// t = 0.37 s, velocities solved).
macro_rules! kinematic_cases {
    ($modname:ident, $label:literal, $ty:ty) => {
        mod $modname {
            use super::*;
            #[allow(unused_imports)]
            use mbd::{KinematicSolver, Kinematics, Mechanism};
            type M = $ty;
            const NQ: usize = <M>::NQ;
            const NC: usize = <M>::NC;
            const NNZ: usize = <M>::NNZ;
            const NV: usize = nv!(M);
            const NS: usize = ns!(M);
            type W = ws_ty!(NV, NC, NV + NC, NS);
            type Q = [f64; NQ];
            type C = [f64; NC];

            #[inline(never)]
            fn constraints(m: &M, q: &Q, t: f64, phi: &mut C) {
                m.constraints(q, t, phi)
            }
            #[inline(never)]
            fn jacobian(m: &M, q: &Q, t: f64, d: &mut [[f64; NQ]; NC]) {
                m.jacobian(q, t, d)
            }
            #[inline(never)]
            fn jacobian_values(m: &M, q: &Q, t: f64, values: &mut [f64; NNZ]) {
                m.jacobian_values(q, t, values)
            }
            #[inline(never)]
            fn velocity_rhs(m: &M, q: &Q, t: f64, nu: &mut C) {
                m.velocity_rhs(q, t, nu)
            }
            #[inline(never)]
            fn gamma(m: &M, q: &Q, qd: &Q, t: f64, gamma: &mut C) {
                m.gamma(q, qd, t, gamma)
            }
            #[inline(never)]
            fn three_calls(m: &M, q: &Q, qd: &Q, t: f64, phi: &mut C, values: &mut [f64; NNZ], gamma: &mut C) {
                m.constraints(black_box(q), black_box(t), phi);
                m.jacobian_values(black_box(q), black_box(t), values);
                m.gamma(black_box(q), black_box(qd), black_box(t), gamma);
            }
            #[inline(never)]
            fn full_eval_values(m: &M, q: &Q, qd: &Q, t: f64, phi: &mut C, values: &mut [f64; NNZ], nu: &mut C, gamma: &mut C) {
                m.full_eval_values(q, qd, t, phi, values, nu, gamma)
            }
            #[inline(never)]
            fn full_eval(m: &M, q: &Q, qd: &Q, t: f64, phi: &mut C, d: &mut [[f64; NQ]; NC], nu: &mut C, gamma: &mut C) {
                m.full_eval(q, qd, t, phi, d, nu, gamma)
            }
            /// One step of a kinematic sweep: Newton from the previous position at t + 1 ms.
            #[inline(never)]
            fn position_solve(solver: &KinematicSolver, m: &M, ws: &mut W, q: &Q, t: f64) -> Q {
                let mut qn = *q;
                ws_call!(solver, solve_position(m, ws, &mut qn, t)).expect("converges");
                qn
            }

            pub fn cases(out: &mut Vec<Case>) {
                let m = <M>::default();
                let solver = KinematicSolver::default();
                let t0 = 0.37;
                let mut q = m.initial_positions();
                let mut ws = new_ws!(M);
                ws_call!(solver, assemble(&m, &mut *ws, &mut q, t0)).expect("the benchmark mechanism assembles");
                let mut qd = [0.0; NQ];
                ws_call!(solver, solve_velocity(&m, &mut *ws, &q, t0, &mut qd)).expect("velocity solve");
                let m: &'static M = Box::leak(Box::new(m));
                let solver: &'static KinematicSolver = Box::leak(Box::new(solver));
                let n = |call: &str| format!("{}/{}", $label, call);
                // `add!(name, |r, phi, d, nu, g, v, ws| call => output)`: the call writes into fresh
                // work arrays (Φ, dense Φ_q, ν, γ, Φ_q values) and returns r; `output` is what
                // one call produced, for the cross-check. `ws` is a work space of its own for each
                // closure, allocated here, outside the timed loop.
                macro_rules! add {
                    ($call:expr, |$r:ident, $phi:ident, $d:ident, $nu:ident, $g:ident, $v:ident, $ws:ident| $body:expr => $ret:expr) => {{
                        #[allow(unused_mut, unused_variables)]
                        let (mut ws_run, mut ws_out) = (new_ws!(M), new_ws!(M));
                        #[allow(unused_mut, unused_variables)]
                        let run = move |k: u64| {
                            let $ws: &mut W = &mut ws_run;
                            let (mut $phi, mut $d, mut $nu, mut $g, mut $v) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC], [0.0; NC], [0.0; NNZ]);
                            for _ in 0..k {
                                let $r = $body;
                                black_box((&$r, &$phi, &$d, &$nu, &$g, &$v));
                            }
                        };
                        #[allow(unused_mut, unused_variables)]
                        let output = move || {
                            let $ws: &mut W = &mut ws_out;
                            let (mut $phi, mut $d, mut $nu, mut $g, mut $v) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC], [0.0; NC], [0.0; NNZ]);
                            let $r = $body;
                            $ret
                        };
                        out.push(case(n($call), run, output));
                    }};
                }
                add!("constraints", |r, phi, d, nu, g, v, ws| constraints(black_box(m), black_box(&q), black_box(t0), &mut phi) => phi.to_vec());
                add!("jacobian (dense)", |r, phi, d, nu, g, v, ws| jacobian(black_box(m), black_box(&q), black_box(t0), &mut d) => flat(&d));
                add!("jacobian_values (sparse)", |r, phi, d, nu, g, v, ws| jacobian_values(black_box(m), black_box(&q), black_box(t0), &mut v) => v.to_vec());
                add!("velocity_rhs", |r, phi, d, nu, g, v, ws| velocity_rhs(black_box(m), black_box(&q), black_box(t0), &mut nu) => nu.to_vec());
                add!("gamma", |r, phi, d, nu, g, v, ws| gamma(black_box(m), black_box(&q), black_box(&qd), black_box(t0), &mut g) => g.to_vec());
                add!("three calls: constraints + jacobian_values + gamma",
                    |r, phi, d, nu, g, v, ws| three_calls(black_box(m), &q, &qd, t0, &mut phi, &mut v, &mut g) => [&phi[..], &v[..], &g[..]].concat());
                add!("full_eval_values (fused)",
                    |r, phi, d, nu, g, v, ws| full_eval_values(black_box(m), black_box(&q), black_box(&qd), black_box(t0), &mut phi, &mut v, &mut nu, &mut g)
                    => [&phi[..], &v[..], &nu[..], &g[..]].concat());
                add!("full_eval (fused, dense)",
                    |r, phi, d, nu, g, v, ws| full_eval(black_box(m), black_box(&q), black_box(&qd), black_box(t0), &mut phi, &mut d, &mut nu, &mut g)
                    => [&phi[..], &flat(&d)[..], &nu[..], &g[..]].concat());
                add!("position solve, t + 1 ms",
                    |r, phi, d, nu, g, v, ws| position_solve(black_box(solver), black_box(m), ws, black_box(&q), black_box(t0 + 1e-3)) => r.to_vec());
            }
        }
    };
}

/// The calls of `benches/dynamics.rs` for one mechanism: from the assembled state at rest, 50 RK4
/// steps of 1 ms, then each call from that moving state.
macro_rules! dynamic_cases {
    ($modname:ident, $label:literal, $ty:ty) => {
        mod $modname {
            use super::*;
            #[allow(unused_imports)]
            use mbd::{
                DynamicsOptions, ForwardDynamics, GeneralizedAlphaOptions, Integrator, KinematicSolver, Kinematics, Mechanism, Rk4, System,
            };
            type M = $ty;
            const NQ: usize = <M>::NQ;
            const NV: usize = nv!(M);
            const NC: usize = <M>::NC;
            const N: usize = NV + NC;
            const NS: usize = ns!(M);
            type W = ws_ty!(NV, NC, N, NS);
            type P = point_ty!(NQ, NV, NC);

            #[inline(never)]
            fn accelerations(m: &M, p: &P, options: &DynamicsOptions<f64>, vd: &mut [f64; NV], lambda: &mut [f64; NC]) {
                m.accelerations(&p.q, &vel!(p), p.t, options, vd, lambda).expect("forward dynamics")
            }
            #[inline(never)]
            fn rk4_step(rk4: &mut Rk4<f64>, system: &System<'_, M, f64>, ws: &mut W, p: &P, next: &mut P) {
                ws_call!(rk4, step(system, ws, p, f64::INFINITY, next)).expect("step");
            }
            #[inline(never)]
            fn dopri5_step(dopri: &mut dopri_ty!(NQ, NV), system: &System<'_, M, f64>, ws: &mut W, p: &P, next: &mut P) {
                dopri.next_step = 1e-3;
                ws_call!(dopri, step(system, ws, p, f64::INFINITY, next)).expect("step");
            }
            #[inline(never)]
            fn alpha_step<I: Step<M, NQ, NV, NC, N, NS>>(alpha: &mut I, system: &System<'_, M, f64>, ws: &mut W, p: &P, next: &mut P) {
                ws_call!(alpha, step(system, ws, p, f64::INFINITY, next)).expect("step");
            }

            fn state(p: &P) -> Vec<f64> {
                [&[p.t][..], &p.q[..], &vel!(p)[..], &p.lambda[..]].concat()
            }

            pub fn cases(out: &mut Vec<Case>) {
                let n = |call: &str| format!("{}/{}", $label, call);
                let m: &'static M = Box::leak(Box::new(<M>::default()));
                let mut q = m.initial_positions();
                let mut ws = new_ws!(M);
                ws_call!(KinematicSolver::default(), assemble(m, &mut *ws, &mut q, 0.0)).expect("the benchmark mechanism assembles");
                let system: &'static System<'static, M, f64> = Box::leak(Box::new(System::new(m)));
                let from: P = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
                // Start from a moving state: 0.05 s into the fall.
                let mut rk4 = Rk4::default(); // h = 1 ms, on both sides
                let mut p = from;
                let mut next = from;
                for _ in 0..50 {
                    ws_call!(rk4, step(system, &mut *ws, &p, f64::INFINITY, &mut next)).expect("step");
                    p = next;
                }
                let options = DynamicsOptions::default();
                {
                    let acc = move || {
                        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
                        accelerations(black_box(m), black_box(&p), black_box(&options), &mut vd, &mut lambda);
                        [&vd[..], &lambda[..]].concat()
                    };
                    let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
                    out.push(case(
                        n("accelerations (right-hand side)"),
                        move |k| {
                            for _ in 0..k {
                                accelerations(black_box(m), black_box(&p), black_box(&options), &mut vd, &mut lambda);
                                black_box((&vd, &lambda));
                            }
                        },
                        acc,
                    ));
                }
                {
                    let (mut r1, mut r2, mut n1, mut n2) = (rk4, rk4, next, next);
                    let (mut w1, mut w2) = (new_ws!(M), new_ws!(M));
                    out.push(case(
                        n("RK4 step, h = 1 ms"),
                        move |k| {
                            for _ in 0..k {
                                rk4_step(&mut r1, black_box(system), &mut w1, black_box(&p), &mut n1);
                                black_box(&n1);
                            }
                        },
                        move || {
                            rk4_step(&mut r2, system, &mut w2, &p, &mut n2);
                            state(&n2)
                        },
                    ));
                }
                {
                    let mut dopri = <dopri_ty!(NQ, NV)>::default();
                    dopri.next_step = 1e-3;
                    dopri.options.max_step = 1e-3;
                    let (mut d1, mut d2, mut n1, mut n2) = (dopri, dopri, next, next);
                    let (mut w1, mut w2) = (new_ws!(M), new_ws!(M));
                    out.push(case(
                        n("DOPRI5 step, h = 1 ms"),
                        move |k| {
                            for _ in 0..k {
                                dopri5_step(&mut d1, black_box(system), &mut w1, black_box(&p), &mut n1);
                                black_box(&n1);
                            }
                        },
                        move || {
                            dopri5_step(&mut d2, system, &mut w2, &p, &mut n2);
                            state(&n2)
                        },
                    ));
                }
                if NQ <= 48 {
                    let mut a1 = <M>::generalized_alpha(GeneralizedAlphaOptions::default());
                    let mut a2 = <M>::generalized_alpha(GeneralizedAlphaOptions::default());
                    let (mut n1, mut n2) = (next, next);
                    let (mut w1, mut w2) = (new_ws!(M), new_ws!(M));
                    out.push(case(
                        n("generalized-α step, h = 1 ms"),
                        move |k| {
                            for _ in 0..k {
                                alpha_step(&mut a1, black_box(system), &mut w1, black_box(&p), &mut n1);
                                black_box(&n1);
                            }
                        },
                        move || {
                            alpha_step(&mut a2, system, &mut w2, &p, &mut n2);
                            state(&n2)
                        },
                    ));
                }
            }
        }
    };
}

kinematic_cases!(k_slider_crank, "slider_crank", crate::slider_crank::SliderCrank);
kinematic_cases!(k_chain16, "chain16", crate::chain16::Chain16);
dynamic_cases!(d_free_slider_crank, "free_slider_crank", crate::free_slider_crank::FreeSliderCrank);
dynamic_cases!(d_pendulum_chain4, "pendulum_chain4", crate::chains::PendulumChain4);
dynamic_cases!(d_pendulum_chain16, "pendulum_chain16", crate::chains::PendulumChain16);
dynamic_cases!(d_pendulum_chain64, "pendulum_chain64", crate::chains::PendulumChain64);

/// Every case of this side, in a fixed order (the same on both sides).
pub fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    k_slider_crank::cases(&mut out);
    k_chain16::cases(&mut out);
    d_free_slider_crank::cases(&mut out);
    d_pendulum_chain4::cases(&mut out);
    d_pendulum_chain16::cases(&mut out);
    d_pendulum_chain64::cases(&mut out);
    out
}

/// The generated functions' operation counts of every mechanism timed here.
pub fn op_counts() -> Vec<Ops> {
    use mbd::Mechanism;
    fn of<M: Mechanism>(out: &mut Vec<Ops>) {
        for o in M::OP_COUNTS {
            out.push(Ops { mechanism: M::NAME, function: o.function, add: o.add, mul: o.mul, div: o.div, call: o.call });
        }
    }
    let mut out = Vec::new();
    of::<slider_crank::SliderCrank>(&mut out);
    of::<chain16::Chain16>(&mut out);
    of::<free_slider_crank::FreeSliderCrank>(&mut out);
    of::<chains::PendulumChain4>(&mut out);
    of::<chains::PendulumChain16>(&mut out);
    of::<chains::PendulumChain64>(&mut out);
    out
}
