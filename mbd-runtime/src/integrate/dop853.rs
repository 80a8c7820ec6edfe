//! Dormand–Prince 8(5,3) with error control and 7th-order dense output (Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, II.5 and II.10, and Hairer's `DOP853` code): [`Dop853`], for the
//! tight tolerances (rtol 1e-9 … 1e-13) where [`Dopri5`](super::Dopri5)'s fifth order needs
//! many small steps.
//!
//! On y = (q, v), y' = (B(q) v, v̇); each accepted step ends with q normalized. Twelve stages
//! and the derivative at the step's end (FSAL: it starts the next step), so 12 evaluations of v̇
//! per accepted step. The error estimate combines the embedded 5th- and 3rd-order solutions as
//! `DOP853` does: err = h · ‖e₅‖² / √(n (‖e₅‖² + 0.01 ‖e₃‖²)), norms RMS-scaled by
//! atol + rtol·|y|; the next step is h · 0.9 · err^(−1/8), the factor clamped to [1/3, 6] (and not
//! above 1 right after a rejection). The dense output is Hairer's 7th-order interpolant; it costs
//! three more evaluations of v̇, made only for steps with an output time strictly inside
//! ([`Integrator::prepare_interpolation`]).

// The coefficients are quoted with the 30 digits Hairer publishes (so they can be checked
// against the source); the compiler rounds them to f64.
#![allow(clippy::excessive_precision)]

use super::dopri5::{initial_step, MinExt};
use super::stiffness::{StiffnessDetected, StiffnessTest};
use super::{check_step, hermite_state, non_finite, Integrator, Point, SimulationError, System};
use crate::model::dynamics::ForwardDynamics;
use crate::model::workspace::WorkArrays;
use crate::real::Real;

crate::options::options! {
    /// Options of [`Dop853`], in the scalar type `T` of the mechanism (default `f64`): the same
    /// tolerances, step limits and defaults as [`Dopri5Options`](super::Dopri5Options). Build
    /// from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Dop853Options<T> {
        /// Relative tolerance on each coordinate and velocity. Default 1e-8; raised to 16 ε of
        /// the scalar type where it is below (f32: 1.9e-6), since no step resolves less.
        rtol: T = T::from_f64(1e-8) => with_rtol,
        /// Absolute tolerance (m, rad, m/s, rad/s). Default 1e-10; raised likewise to 16 ε.
        atol: T = T::from_f64(1e-10) => with_atol,
        /// First step size (s); 0 chooses one from the initial derivatives (Hairer's rule).
        /// Default 0.
        initial_step: T = T::ZERO => with_initial_step,
        /// Largest step size (s). Default 0.1 s.
        max_step: T = T::from_f64(0.1) => with_max_step,
        /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default
        /// 1e-12 s.
        min_step: T = T::from_f64(1e-12) => with_min_step,
    }
}

impl<T: Real> Dop853Options<T> {
    /// See [`check_step_control`](super::dopri5::check_step_control).
    fn check(&self) -> Result<(), SimulationError> {
        super::dopri5::check_step_control(
            [self.rtol, self.atol, self.max_step, self.min_step],
            [
                "rtol and atol (Dop853Options) must be non-negative, not both zero",
                "Dop853Options::max_step must be positive, min_step non-negative",
            ],
        )
    }
}

/// Stages of a step (`S`) and with the dense output's three (`SD`).
const S: usize = 12;
const SD: usize = 16;

/// Dormand–Prince 8(5,3) with error control and 7th-order dense output (Hairer, Nørsett &
/// Wanner, *Solving ODEs I*, II.10, and Hairer's `DOP853` code). The work integrals use the
/// method's 8th-order weights on the stage powers.
#[derive(Clone, Copy, Debug)]
pub struct Dop853<T, const NQ: usize, const NV: usize> {
    /// Tolerances and step limits.
    pub options: Dop853Options<T>,
    /// The step size the next step will try (s); 0 before the first.
    pub next_step: T,
    /// Accepted steps so far.
    pub accepted: u64,
    /// Rejected steps so far.
    pub rejected: u64,
    /// Evaluations of v̇ so far (the stages of every step tried, and the dense output's).
    pub evaluations: u64,
    // The last accepted step's stage derivatives of q and v (13: the 12 stages and the end
    // point's), then the dense output's three; and its size.
    kq: [[T; NQ]; SD],
    kv: [[T; NV]; SD],
    h: T,
    // Dense output of the last step, once prepared: y(θ) = y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + … ))).
    dense_q: [[T; NQ]; 7],
    dense_v: [[T; NV]; 7],
    dense_ready: bool,
    stiffness: StiffnessTest,
}

impl<T: Real, const NQ: usize, const NV: usize> Dop853<T, NQ, NV> {
    /// A DOP853 integrator with the given options.
    pub fn new(options: Dop853Options<T>) -> Self {
        Self {
            options,
            next_step: T::ZERO,
            accepted: 0,
            rejected: 0,
            evaluations: 0,
            kq: [[T::ZERO; NQ]; SD],
            kv: [[T::ZERO; NV]; SD],
            h: T::ZERO,
            dense_q: [[T::ZERO; NQ]; 7],
            dense_v: [[T::ZERO; NV]; 7],
            dense_ready: false,
            stiffness: StiffnessTest::default(),
        }
    }
}

impl<T: Real, const NQ: usize, const NV: usize> Default for Dop853<T, NQ, NV> {
    fn default() -> Self {
        Self::new(Dop853Options::default())
    }
}

// DOP853's nodes and coefficients (Hairer's `dop853.f`, as transcribed in SciPy's
// `dop853_coefficients.py`): rows 0–11 are the stages, row 12 the 8th-order weights b, rows
// 13–15 the dense output's extra stages.
const C: [f64; SD] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
    1.0,
    0.1,
    0.2,
    0.777777777777777777777777777778,
];

#[rustfmt::skip]
const A: [[f64; SD]; SD] = {
    let mut a = [[0.0; SD]; SD];
    a[1][0] = 5.26001519587677318785587544488e-2;
    a[2][0] = 1.97250569845378994544595329183e-2;
    a[2][1] = 5.91751709536136983633785987549e-2;
    a[3][0] = 2.95875854768068491816892993775e-2;
    a[3][2] = 8.87627564304205475450678981324e-2;
    a[4][0] = 2.41365134159266685502369798665e-1;
    a[4][2] = -8.84549479328286085344864962717e-1;
    a[4][3] = 9.24834003261792003115737966543e-1;
    a[5][0] = 3.7037037037037037037037037037e-2;
    a[5][3] = 1.70828608729473871279604482173e-1;
    a[5][4] = 1.25467687566822425016691814123e-1;
    a[6][0] = 3.7109375e-2;
    a[6][3] = 1.70252211019544039314978060272e-1;
    a[6][4] = 6.02165389804559606850219397283e-2;
    a[6][5] = -1.7578125e-2;
    a[7][0] = 3.70920001185047927108779319836e-2;
    a[7][3] = 1.70383925712239993810214054705e-1;
    a[7][4] = 1.07262030446373284651809199168e-1;
    a[7][5] = -1.53194377486244017527936158236e-2;
    a[7][6] = 8.27378916381402288758473766002e-3;
    a[8][0] = 6.24110958716075717114429577812e-1;
    a[8][3] = -3.36089262944694129406857109825;
    a[8][4] = -8.68219346841726006818189891453e-1;
    a[8][5] = 2.75920996994467083049415600797e1;
    a[8][6] = 2.01540675504778934086186788979e1;
    a[8][7] = -4.34898841810699588477366255144e1;
    a[9][0] = 4.77662536438264365890433908527e-1;
    a[9][3] = -2.48811461997166764192642586468;
    a[9][4] = -5.90290826836842996371446475743e-1;
    a[9][5] = 2.12300514481811942347288949897e1;
    a[9][6] = 1.52792336328824235832596922938e1;
    a[9][7] = -3.32882109689848629194453265587e1;
    a[9][8] = -2.03312017085086261358222928593e-2;
    a[10][0] = -9.3714243008598732571704021658e-1;
    a[10][3] = 5.18637242884406370830023853209;
    a[10][4] = 1.09143734899672957818500254654;
    a[10][5] = -8.14978701074692612513997267357;
    a[10][6] = -1.85200656599969598641566180701e1;
    a[10][7] = 2.27394870993505042818970056734e1;
    a[10][8] = 2.49360555267965238987089396762;
    a[10][9] = -3.0467644718982195003823669022;
    a[11][0] = 2.27331014751653820792359768449;
    a[11][3] = -1.05344954667372501984066689879e1;
    a[11][4] = -2.00087205822486249909675718444;
    a[11][5] = -1.79589318631187989172765950534e1;
    a[11][6] = 2.79488845294199600508499808837e1;
    a[11][7] = -2.85899827713502369474065508674;
    a[11][8] = -8.87285693353062954433549289258;
    a[11][9] = 1.23605671757943030647266201528e1;
    a[11][10] = 6.43392746015763530355970484046e-1;
    a[12][0] = 5.42937341165687622380535766363e-2;
    a[12][5] = 4.45031289275240888144113950566;
    a[12][6] = 1.89151789931450038304281599044;
    a[12][7] = -5.8012039600105847814672114227;
    a[12][8] = 3.1116436695781989440891606237e-1;
    a[12][9] = -1.52160949662516078556178806805e-1;
    a[12][10] = 2.01365400804030348374776537501e-1;
    a[12][11] = 4.47106157277725905176885569043e-2;
    a[13][0] = 5.61675022830479523392909219681e-2;
    a[13][6] = 2.53500210216624811088794765333e-1;
    a[13][7] = -2.46239037470802489917441475441e-1;
    a[13][8] = -1.24191423263816360469010140626e-1;
    a[13][9] = 1.5329179827876569731206322685e-1;
    a[13][10] = 8.20105229563468988491666602057e-3;
    a[13][11] = 7.56789766054569976138603589584e-3;
    a[13][12] = -8.298e-3;
    a[14][0] = 3.18346481635021405060768473261e-2;
    a[14][5] = 2.83009096723667755288322961402e-2;
    a[14][6] = 5.35419883074385676223797384372e-2;
    a[14][7] = -5.49237485713909884646569340306e-2;
    a[14][10] = -1.08347328697249322858509316994e-4;
    a[14][11] = 3.82571090835658412954920192323e-4;
    a[14][12] = -3.40465008687404560802977114492e-4;
    a[14][13] = 1.41312443674632500278074618366e-1;
    a[15][0] = -4.28896301583791923408573538692e-1;
    a[15][5] = -4.69762141536116384314449447206;
    a[15][6] = 7.68342119606259904184240953878;
    a[15][7] = 4.06898981839711007970213554331;
    a[15][8] = 3.56727187455281109270669543021e-1;
    a[15][12] = -1.39902416515901462129418009734e-3;
    a[15][13] = 2.9475147891527723389556272149;
    a[15][14] = -9.15095847217987001081870187138;
    a
};

/// The 8th-order weights (b₁₂ = 0 for the end point's derivative).
const B: [f64; 13] = {
    let mut b = [0.0; 13];
    let mut i = 0;
    while i < S {
        b[i] = A[12][i];
        i += 1;
    }
    b
};

/// b − b̂₃: the 3rd-order error estimate's weights.
const E3: [f64; 13] = {
    let mut e = B;
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
};

/// The 5th-order error estimate's weights.
const E5: [f64; 13] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
    0.0,
];

/// The dense output's last four coefficients, F₃ … F₆ = h Σ_s D[k][s] k_s.
#[rustfmt::skip]
const D: [[f64; SD]; 4] = [
    [-0.84289382761090128651353491142e1, 0.0, 0.0, 0.0, 0.0, 0.56671495351937776962531783590, -0.30689499459498916912797304727e1,
     0.23846676565120698287728149680e1, 0.21170345824450282767155149946e1, -0.87139158377797299206789907490,
     0.22404374302607882758541771650e1, 0.63157877876946881815570249290, -0.88990336451333310820698117400e-1,
     0.18148505520854727256656404962e2, -0.91946323924783554000451984436e1, -0.44360363875948939664310572000e1],
    [0.10427508642579134603413151009e2, 0.0, 0.0, 0.0, 0.0, 0.24228349177525818288430175319e3, 0.16520045171727028198505394887e3,
     -0.37454675472269020279518312152e3, -0.22113666853125306036270938578e2, 0.77334326684722638389603898808e1,
     -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1, 0.15697238121770843886131091075e2,
     -0.31139403219565177677282850411e2, -0.93529243588444783865713862664e1, 0.35816841486394083752465898540e2],
    [0.19985053242002433820987653617e2, 0.0, 0.0, 0.0, 0.0, -0.38703730874935176555105901742e3, -0.18917813819516756882830838328e3,
     0.52780815920542364900561016686e3, -0.11573902539959630126141871134e2, 0.68812326946963000169666922661e1,
     -0.10006050966910838403183860980e1, 0.77771377980534432092869265740, -0.27782057523535084065932004339e1,
     -0.60196695231264120758267380846e2, 0.84320405506677161018159903784e2, 0.11992291136182789328035130030e2],
    [-0.25693933462703749003312586129e2, 0.0, 0.0, 0.0, 0.0, -0.15418974869023643374053993627e3, -0.23152937917604549567536039109e3,
     0.35763911791061412378285349910e3, 0.93405324183624310003907691704e2, -0.37458323136451633156875139351e2,
     0.10409964950896230045147246184e3, 0.29840293426660503123344363579e2, -0.43533456590011143754432175058e2,
     0.96324553959188282948394950600e2, -0.39177261675615439165231486172e2, -0.14972683625798562581422125276e3],
];

/// y₀ + h Σ_{j<s} a_sj k_j for each entry, into `out`.
#[inline]
fn stage_state<T: Real, const N: usize>(y0: &[T; N], k: &[[T; N]; SD], s: usize, h: T, out: &mut [T; N]) {
    for (i, o) in out.iter_mut().enumerate() {
        let mut d = T::ZERO;
        for (j, kj) in k.iter().enumerate().take(s) {
            let a = A[s][j];
            if a != 0.0 {
                d += T::from_f64(a) * kj[i];
            }
        }
        *o = y0[i] + h * d;
    }
}

impl<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Integrator<T, M, NQ, NV, NC, N, NS> for Dop853<T, NQ, NV>
{
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    // One index runs over q (or v) and its stage derivatives, or over a stage's node and row.
    #[allow(clippy::needless_range_loop)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        let o = self.options;
        o.check()?;
        self.dense_ready = false;
        let span = t_max - from.t;
        if !(span > T::ZERO) {
            to.copy_from(from);
            return Ok(());
        }
        let mech = system.mechanism;
        let floor = T::from_f64(16.0) * T::EPSILON;
        let (rtol, atol) = (o.rtol.max(floor), o.atol.max(floor));
        let scale = |y0: T, y1: T| atol + rtol * y0.abs().max(y1.abs());
        let mut kp = [[T::ZERO; 2]; S + 1];
        mech.position_rates(&from.q, &from.v, &mut self.kq[0]);
        self.kv[0] = from.vd;
        kp[0] = from.power;
        if !(self.next_step > T::ZERO) {
            self.next_step = if o.initial_step > T::ZERO { o.initial_step } else { initial_step(from, &self.kq[0], &scale, o.max_step) };
        }
        // The stage state, the last stage's (at t + h like the solution: the stiffness test's)
        // and the multipliers.
        let mut dense = ws.dense();
        let [q, q_last] = dense.vectors.rows::<NQ, 2>();
        let [v, v_last] = dense.vectors.rows::<NV, 2>();
        let lambda = dense.vectors.take::<NC>();
        *lambda = from.lambda;
        let mut rejected_here = false;
        'attempt: loop {
            let mut h = self.next_step.max(o.min_step).min_(o.max_step);
            // Hairer's rule: a step within 1 % of the end goes all the way, so that a run never
            // ends on a sliver left by rounding (ten steps of 0.1 s sum to 0.9999999999999999).
            let last = from.t + T::from_f64(1.01) * h >= t_max;
            if last {
                h = span;
            }
            // Stages 1–11, then the 8th-order solution and its derivative (row 12 of A is b).
            for s in 1..=S {
                stage_state(&from.q, &self.kq, s, h, q);
                stage_state(&from.v, &self.kv, s, h, v);
                if s == S - 1 {
                    *q_last = *q;
                    *v_last = *v;
                }
                mech.position_rates(q, v, &mut self.kq[s]);
                let t_s = if s >= S - 1 { from.t + h } else { from.t + T::from_f64(C[s]) * h };
                self.evaluations += 1;
                match system.derivatives_in(dense.reborrow(), t_s, q, v, &mut self.kv[s], lambda) {
                    Ok(p) => kp[s] = p,
                    // A trial state may be off the manifold far enough to fail the solve:
                    // shrink the step, and report the failure only at the minimum step.
                    Err(e) => {
                        self.rejected += 1;
                        rejected_here = true;
                        self.next_step = h * T::from_f64(0.25);
                        if self.next_step < o.min_step {
                            return Err(e.into());
                        }
                        continue 'attempt;
                    }
                }
            }
            // Error estimate (Hairer's `DOP853`): both embedded errors, scaled, squared, summed.
            let (mut sum5, mut sum3) = (T::ZERO, T::ZERO);
            let mut accumulate = |k: &dyn Fn(usize) -> T, y0: T, y1: T| {
                let (mut e5, mut e3) = (T::ZERO, T::ZERO);
                for s in 0..=S {
                    e5 += T::from_f64(E5[s]) * k(s);
                    e3 += T::from_f64(E3[s]) * k(s);
                }
                let sk = scale(y0, y1);
                sum5 += (e5 / sk) * (e5 / sk);
                sum3 += (e3 / sk) * (e3 / sk);
            };
            for i in 0..NQ {
                accumulate(&|s| self.kq[s][i], from.q[i], q[i]);
            }
            for i in 0..NV {
                accumulate(&|s| self.kv[s][i], from.v[i], v[i]);
            }
            let denominator = sum5 + T::from_f64(0.01) * sum3;
            let n = T::from_f64((NQ + NV).max(1) as f64);
            let error = if denominator > T::ZERO { h * sum5 / (n * denominator).sqrt() } else { T::ZERO };
            let safe = T::from_f64(0.9);
            if error <= T::ONE {
                let e = error.max(T::from_f64(1e-30));
                let mut factor = (safe * e.powf(T::from_f64(-0.125))).max(T::from_f64(1.0 / 3.0)).min_(T::from_f64(6.0));
                if rejected_here {
                    factor = factor.min_(T::ONE);
                }
                if !last || h < self.next_step {
                    self.next_step = h * factor;
                }
                self.accepted += 1;
                self.h = h;
                let (k, k_last) = ([&self.kq[S][..], &self.kv[S][..]], [&self.kq[S - 1][..], &self.kv[S - 1][..]]);
                self.stiffness.observe("DOP853", 6.1, from.t + h, h, [k[0], k[1], k_last[0], k_last[1]], [q, v, q_last, v_last]);
                to.q = *q;
                to.v = *v;
                to.vd = self.kv[S];
                to.lambda = *lambda;
                to.power = kp[S];
                for k in 0..2 {
                    let mut w = T::ZERO;
                    for s in 0..S {
                        w += T::from_f64(B[s]) * kp[s][k];
                    }
                    to.work[k] = from.work[k] + h * w;
                }
                to.t = if last { t_max } else { from.t + h };
                mech.normalize_positions(&mut to.q);
                return check_step::<T, M, NQ, NV, NC>(from, to);
            }
            self.rejected += 1;
            rejected_here = true;
            let e = if error.is_finite() { error } else { T::from_f64(1e10) };
            let factor = (safe * e.powf(T::from_f64(-0.125))).max(T::from_f64(1.0 / 3.0));
            self.next_step = h * factor;
            if self.next_step < o.min_step {
                if let Some(coordinate) = non_finite::<T, M, NQ, NV>(q, v) {
                    return Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate });
                }
                return Err(SimulationError::StepSizeTooSmall { t: from.t.to_f64(), step: self.next_step.to_f64() });
            }
        }
    }

    /// The three extra stages and the 7th-order interpolant of the last step (Hairer's
    /// `DOP853` with dense output), from the stages and the step's unnormalized end (the flow
    /// the stages followed).
    #[allow(clippy::needless_range_loop)] // s indexes the nodes C and the stage arrays alike
    fn prepare_interpolation(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        _to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        if self.dense_ready {
            return Ok(());
        }
        let h = self.h;
        let mech = system.mechanism;
        // The stage state, and the end point as the stages reached it (before normalization):
        // y₀ + h Σ b k.
        let mut scratch = ws.dense();
        let [q, q1] = scratch.vectors.rows::<NQ, 2>();
        let [v, v1] = scratch.vectors.rows::<NV, 2>();
        let lambda = scratch.vectors.take::<NC>();
        *lambda = from.lambda;
        stage_state(&from.q, &self.kq, S, h, q1);
        stage_state(&from.v, &self.kv, S, h, v1);
        for s in S + 1..SD {
            stage_state(&from.q, &self.kq, s, h, q);
            stage_state(&from.v, &self.kv, s, h, v);
            mech.position_rates(q, v, &mut self.kq[s]);
            self.evaluations += 1;
            system.derivatives_in(scratch.reborrow(), from.t + T::from_f64(C[s]) * h, q, v, &mut self.kv[s], lambda)?;
        }
        dense(&from.q, q1, &self.kq, h, &mut self.dense_q);
        dense(&from.v, v1, &self.kv, h, &mut self.dense_v);
        self.dense_ready = true;
        Ok(())
    }

    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        if !self.dense_ready {
            // Not prepared (a caller other than `Simulation::run`): the cubic Hermite interpolant.
            hermite_state(mechanism, from, to, t, q, v);
            return;
        }
        let theta = if self.h > T::ZERO { (t - from.t) / self.h } else { T::ONE };
        evaluate(&from.q, &self.dense_q, theta, q);
        evaluate(&from.v, &self.dense_v, theta, v);
    }

    /// Hairer's test on the last two stages of each accepted step (module `stiffness`).
    fn stiffness(&self) -> Option<StiffnessDetected> {
        self.stiffness.found()
    }

    fn restart(&mut self) {
        self.next_step = T::ZERO;
        self.dense_ready = false;
    }
    fn after_correction(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        // An explicit method goes on from forward dynamics at the corrected state.
        Ok(system.complete_in(ws.dense(), to)?)
    }
}

/// The interpolant's coefficients F₀ … F₆ of one vector y over a step y0 → y1 of size h with
/// stage derivatives k (SciPy's `DOP853._dense_output_impl`, Hairer's `contd8`).
fn dense<T: Real, const N: usize>(y0: &[T; N], y1: &[T; N], k: &[[T; N]; SD], h: T, f: &mut [[T; N]; 7]) {
    let two = T::from_f64(2.0);
    for i in 0..N {
        let delta = y1[i] - y0[i];
        f[0][i] = delta;
        f[1][i] = h * k[0][i] - delta;
        f[2][i] = two * delta - h * (k[S][i] + k[0][i]);
        for (row, d) in D.iter().enumerate() {
            let mut sum = T::ZERO;
            for (s, &c) in d.iter().enumerate() {
                if c != 0.0 {
                    sum += T::from_f64(c) * k[s][i];
                }
            }
            f[3 + row][i] = h * sum;
        }
    }
}

/// y(θ) = y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ + (1−θ)(F₅ + θ F₆)))))).
fn evaluate<T: Real, const N: usize>(y0: &[T; N], f: &[[T; N]; 7], theta: T, out: &mut [T; N]) {
    let one_minus = T::ONE - theta;
    for i in 0..N {
        let mut y = T::ZERO;
        for (k, fk) in f.iter().enumerate().rev() {
            y += fk[i];
            y *= if k % 2 == 0 { theta } else { one_minus };
        }
        out[i] = y0[i] + y;
    }
}
