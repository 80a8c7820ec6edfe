//! Classical fourth-order Runge–Kutta with a fixed step h, on y = (q, q̇), y' = (q̇, q̈):
//!
//! ```text
//! k₁ = f(t, y),  k₂ = f(t + h/2, y + h/2 k₁),  k₃ = f(t + h/2, y + h/2 k₂),  k₄ = f(t + h, y + h k₃)
//! y₊ = y + h/6 (k₁ + 2k₂ + 2k₃ + k₄)
//! ```
//!
//! 4 evaluations of q̈ per step (k₁ is the start point's); the work integrals use the same
//! weights on the stage powers; dense output is cubic Hermite.

use super::{check_step, hermite_state, Integrator, Point, SimulationError, System};
use crate::{ForwardDynamics, Real};

/// Classical fourth-order Runge–Kutta with a fixed step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4<T> {
    /// Step size h (s); the last step before an end time may be shorter. Default 1e-3 s.
    pub step: T,
}

impl<T: Real> Default for Rk4<T> {
    fn default() -> Self {
        Self { step: T::from_f64(1e-3) }
    }
}

impl<T: Real> Rk4<T> {
    /// RK4 with step `step` (s).
    pub fn new(step: T) -> Self {
        Self { step }
    }
}

impl<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize> Integrator<T, M, NQ, NC> for Rk4<T> {
    #[inline]
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NC>,
    ) -> Result<(), SimulationError> {
        if !(self.step > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "Rk4::step must be positive" });
        }
        let h = if from.t + self.step > t_max { t_max - from.t } else { self.step };
        let half = h * T::from_f64(0.5);
        let sixth = h / T::from_f64(6.0);
        let two = T::from_f64(2.0);
        let t_half = from.t + half;
        // The start's multipliers: the first guess of Coulomb friction loads, if any.
        let mut lambda = from.lambda;
        // k1 = (q̇0, q̈0)
        let mut q = [T::ZERO; NQ];
        let mut qd2 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + half * from.qd[i];
            qd2[i] = from.qd[i] + half * from.qdd[i];
        }
        let mut qdd2 = [T::ZERO; NQ];
        let p2 = system.derivatives(t_half, &q, &qd2, &mut qdd2, &mut lambda)?;
        let mut qd3 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + half * qd2[i];
            qd3[i] = from.qd[i] + half * qdd2[i];
        }
        let mut qdd3 = [T::ZERO; NQ];
        let p3 = system.derivatives(t_half, &q, &qd3, &mut qdd3, &mut lambda)?;
        let mut qd4 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + h * qd3[i];
            qd4[i] = from.qd[i] + h * qdd3[i];
        }
        let mut qdd4 = [T::ZERO; NQ];
        let p4 = system.derivatives(from.t + h, &q, &qd4, &mut qdd4, &mut lambda)?;
        for i in 0..NQ {
            to.q[i] = from.q[i] + sixth * (from.qd[i] + two * (qd2[i] + qd3[i]) + qd4[i]);
            to.qd[i] = from.qd[i] + sixth * (from.qdd[i] + two * (qdd2[i] + qdd3[i]) + qdd4[i]);
        }
        for k in 0..2 {
            to.work[k] = from.work[k] + sixth * (from.power[k] + two * (p2[k] + p3[k]) + p4[k]);
        }
        to.t = from.t + h;
        check_step::<T, M, NQ, NC>(from, to)?;
        to.power = system.derivatives(to.t, &to.q, &to.qd, &mut to.qdd, &mut to.lambda)?;
        Ok(())
    }

    fn interpolate(&self, from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T, q: &mut [T; NQ], qd: &mut [T; NQ]) {
        hermite_state(from, to, t, q, qd);
    }
}
