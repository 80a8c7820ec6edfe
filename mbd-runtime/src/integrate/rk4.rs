//! Classical fourth-order Runge–Kutta with a fixed step h, on y = (q, v), y' = (B(q) v, v̇):
//!
//! ```text
//! k₁ = f(t, y),  k₂ = f(t + h/2, y + h/2 k₁),  k₃ = f(t + h/2, y + h/2 k₂),  k₄ = f(t + h, y + h k₃)
//! y₊ = y + h/6 (k₁ + 2k₂ + 2k₃ + k₄),  then q₊ normalized
//! ```
//!
//! 4 evaluations of v̇ per step (k₁ is the start point's); the work integrals use the same
//! weights on the stage powers; dense output is cubic Hermite.

use super::{check_step, fixed_step, hermite_state, Integrator, Point, SimulationError, System};
use crate::model::dynamics::ForwardDynamics;
use crate::model::workspace::WorkArrays;
use crate::real::Real;

crate::options::options! {
    /// Options of [`Rk4`], in the scalar type `T` of the mechanism (default `f64`). Build from
    /// [`Default`] and the `with_*` setters: `Rk4::new(Rk4Options::default().with_step(1e-4))`.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Rk4Options<T> {
        /// Step size h (s); the last step before an end time may be shorter. Default 1e-3 s.
        step: T = T::from_f64(1e-3) => with_step,
    }
}

/// Classical fourth-order Runge–Kutta with a fixed step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4<T = f64> {
    /// The step size.
    pub options: Rk4Options<T>,
}

impl<T: Real> Default for Rk4<T> {
    fn default() -> Self {
        Self::new(Rk4Options::new())
    }
}

impl<T: Real> Rk4<T> {
    /// RK4 with the given options.
    pub fn new(options: Rk4Options<T>) -> Self {
        Self { options }
    }
}

impl<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Integrator<T, M, NQ, NV, NC, N, NS> for Rk4<T>
{
    #[inline]
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    // One index runs over the state and its stage derivatives in step.
    #[allow(clippy::needless_range_loop)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        if !(self.options.step > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "Rk4Options::step must be positive" });
        }
        let mech = system.mechanism;
        let (h, t_end) = fixed_step(from.t, self.options.step, t_max);
        let half = h * T::from_f64(0.5);
        let sixth = h / T::from_f64(6.0);
        let two = T::from_f64(2.0);
        let t_half = from.t + half;
        // The start's multipliers (the first guess of Coulomb friction loads, if any), the stage
        // state and the stages' rates, each written whole before it is read.
        let mut dense = ws.dense();
        let [lambda] = dense.vectors.rows_written::<NC, 1>();
        *lambda = from.lambda;
        let [q, qd1, qd2, qd3, qd4] = dense.vectors.rows_written::<NQ, 5>();
        let [v2, v3, v4, vd2, vd3, vd4] = dense.vectors.rows_written::<NV, 6>();
        // k1 = (B(q0) v0, v̇0)
        mech.position_rates(&from.q, &from.v, qd1);
        for i in 0..NQ {
            q[i] = from.q[i] + half * qd1[i];
        }
        for i in 0..NV {
            v2[i] = from.v[i] + half * from.vd[i];
        }
        mech.position_rates(q, v2, qd2);
        let p2 = system.derivatives_in(dense.reborrow(), t_half, q, v2, vd2, lambda)?;
        for i in 0..NQ {
            q[i] = from.q[i] + half * qd2[i];
        }
        for i in 0..NV {
            v3[i] = from.v[i] + half * vd2[i];
        }
        mech.position_rates(q, v3, qd3);
        let p3 = system.derivatives_in(dense.reborrow(), t_half, q, v3, vd3, lambda)?;
        for i in 0..NQ {
            q[i] = from.q[i] + h * qd3[i];
        }
        for i in 0..NV {
            v4[i] = from.v[i] + h * vd3[i];
        }
        mech.position_rates(q, v4, qd4);
        let p4 = system.derivatives_in(dense.reborrow(), t_end, q, v4, vd4, lambda)?;
        for i in 0..NQ {
            to.q[i] = from.q[i] + sixth * (qd1[i] + two * (qd2[i] + qd3[i]) + qd4[i]);
        }
        for i in 0..NV {
            to.v[i] = from.v[i] + sixth * (from.vd[i] + two * (vd2[i] + vd3[i]) + vd4[i]);
        }
        mech.normalize_positions(&mut to.q);
        for k in 0..2 {
            to.work[k] = from.work[k] + sixth * (from.power[k] + two * (p2[k] + p3[k]) + p4[k]);
        }
        to.t = t_end;
        check_step::<T, M, NQ, NV, NC>(from, to)?;
        to.power = system.derivatives_in(dense, to.t, &to.q, &to.v, &mut to.vd, &mut to.lambda)?;
        Ok(())
    }

    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        hermite_state(mechanism, from, to, t, q, v);
    }

    fn prepare_interpolation(
        &mut self,
        _system: &System<'_, M, T>,
        _ws: &mut WorkArrays<T, NV, NC, N, NS>,
        _from: &Point<T, NQ, NV, NC>,
        _to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        // The cubic Hermite interpolant needs the step's ends only.
        Ok(())
    }

    fn restart(&mut self) {
        // A fixed step carries nothing from step to step.
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
