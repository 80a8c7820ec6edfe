//! Angles in a documented range at the end of a static solve: each angle wrapped into
//! (−π, π] and each quaternion to e0 ≥ 0 where that changes neither Φ nor h.

use super::iterate::{max_abs, Iterate};
use super::StaticSolver;
use crate::model::mechanism::{CoordinateKind, NewtonMatrix, VelocityKind};
use crate::model::workspace::DenseScratch;
use crate::real::Real;

impl<T: Real> StaticSolver<T> {
    /// Wraps each angle coordinate into (−π, π] and flips each quaternion to e0 ≥ 0,
    /// where that leaves Φ and h unchanged (to the tolerance plus the rounding of the shift,
    /// bounded by the shift's size times the largest entry of D's or H's column); then
    /// normalizes.
    pub(super) fn wrap_angles<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        s: &mut M::NewtonStorage,
        mut dense: DenseScratch<'_, T, NV, NC>,
    ) where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let tol = self.options.tolerance;
        let (phi, h) = (it.phi, it.h);
        let [zero_v, h1] = dense.vectors.rows::<NV, 2>();
        let phi1 = dense.vectors.take::<NC>();
        let candidate = dense.vectors.take::<NQ>();
        let mut unchanged = |candidate: &[T; NQ], d_scale: T, h_scale: T| {
            m.newton_jacobian(candidate, t, phi1, s, dense.reborrow());
            m.forces(candidate, zero_v, t, h1);
            phi.iter().zip(phi1.iter()).all(|(a, b)| (*a - *b).abs() <= tol + d_scale)
                && h.iter().zip(h1.iter()).all(|(a, b)| (*a - *b).abs() <= tol + h_scale)
        };
        let rounding = T::from_f64(16.0) * T::EPSILON;
        for (i, coordinate) in M::COORDINATES.iter().enumerate().take(NQ) {
            match coordinate.kind {
                CoordinateKind::Angle => {
                    // The column of D and of h that moves this angle: its rate's.
                    let Some(k) = M::VELOCITIES.iter().position(|v| v.kind == VelocityKind::Rate { coordinate: i as u16 }) else {
                        continue;
                    };
                    let wrapped = T::from_f64(wrap_angle(q[i].to_f64()));
                    if wrapped == q[i] {
                        continue;
                    }
                    let shift = rounding * (q[i].abs() + T::from_f64(2.0 * core::f64::consts::PI));
                    *candidate = *q;
                    candidate[i] = wrapped;
                    if unchanged(candidate, shift * it.d_columns[k], shift * it.h_columns[k]) {
                        *q = *candidate;
                    }
                }
                CoordinateKind::Quaternion { part: 0 } if i + 3 < NQ && q[i] < T::ZERO => {
                    // p and −p are one rotation: Φ and h do not change at all.
                    *candidate = *q;
                    for x in candidate[i..i + 4].iter_mut() {
                        *x = -*x;
                    }
                    if unchanged(candidate, rounding * max_abs(phi).0, rounding * max_abs(h).0) {
                        *q = *candidate;
                    }
                }
                _ => {}
            }
        }
        m.normalize_positions(q);
    }
}

/// Wraps an angle into (−π, π].
pub(super) fn wrap_angle(phi: f64) -> f64 {
    let turn = 2.0 * core::f64::consts::PI;
    let mut wrapped = phi - turn * libm::round(phi / turn);
    if wrapped <= -core::f64::consts::PI {
        wrapped += turn;
    } else if wrapped > core::f64::consts::PI {
        wrapped -= turn;
    }
    wrapped
}

#[cfg(test)]
mod tests {
    use super::wrap_angle;

    #[test]
    fn angles_wrap_into_the_half_open_interval() {
        use core::f64::consts::PI;
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert!((wrap_angle(7.0) - (7.0 - 2.0 * PI)).abs() < 1e-15);
        assert!((wrap_angle(-7.0) - (-7.0 + 2.0 * PI)).abs() < 1e-15);
        assert_eq!(wrap_angle(0.25), 0.25);
    }
}
