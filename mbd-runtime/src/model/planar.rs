//! Kinematics of points and vectors on planar bodies, for reading results (positions, velocities
//! and accelerations of points of interest) in body coordinates `q[3k..3k+3] = (x, y, φ)`.

use crate::real::Real;

/// Global position r^P = r_k + A(φ_k) s'^P of the point with body-fixed coordinates `local` (m)
/// on body `body` (its index among the moving bodies).
///
/// Returns `None` when `body` has no coordinates in `q`.
pub fn point_position<T: Real>(q: &[T], body: usize, local: [T; 2]) -> Option<[T; 2]> {
    let (x, y, phi) = (*q.get(3 * body)?, *q.get(3 * body + 1)?, *q.get(3 * body + 2)?);
    let (s, c) = phi.sin_cos();
    Some([x + c * local[0] - s * local[1], y + s * local[0] + c * local[1]])
}

/// Global velocity ṙ^P = ṙ_k + φ̇_k B(φ_k) s'^P of a body-fixed point (m/s), where
/// B = dA/dφ = [[−sin φ, −cos φ], [cos φ, −sin φ]].
pub fn point_velocity<T: Real>(q: &[T], v: &[T], body: usize, local: [T; 2]) -> Option<[T; 2]> {
    let phi = *q.get(3 * body + 2)?;
    let (vx, vy, w) = (*v.get(3 * body)?, *v.get(3 * body + 1)?, *v.get(3 * body + 2)?);
    let (s, c) = phi.sin_cos();
    let (bx, by) = (-s * local[0] - c * local[1], c * local[0] - s * local[1]);
    Some([vx + w * bx, vy + w * by])
}

/// Global acceleration r̈^P = r̈_k + φ̈_k B s'^P − φ̇_k² A s'^P of a body-fixed point (m/s²).
pub fn point_acceleration<T: Real>(q: &[T], v: &[T], vd: &[T], body: usize, local: [T; 2]) -> Option<[T; 2]> {
    let phi = *q.get(3 * body + 2)?;
    let w = *v.get(3 * body + 2)?;
    let (ax, ay, alpha) = (*vd.get(3 * body)?, *vd.get(3 * body + 1)?, *vd.get(3 * body + 2)?);
    let (s, c) = phi.sin_cos();
    let (rx, ry) = (c * local[0] - s * local[1], s * local[0] + c * local[1]);
    Some([ax - alpha * ry - w * w * rx, ay + alpha * rx - w * w * ry])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point 0.5 m along the x-axis of a body spinning at ω = 2 rad/s about its fixed origin:
    /// speed ω·0.5 = 1 m/s, centripetal acceleration ω²·0.5 = 2 m/s² toward the origin.
    #[test]
    fn spinning_body() {
        let q = [0.0, 0.0, core::f64::consts::FRAC_PI_2];
        let v = [0.0, 0.0, 2.0];
        let vd = [0.0; 3];
        let p = point_position(&q, 0, [0.5, 0.0]).unwrap();
        let pv = point_velocity(&q, &v, 0, [0.5, 0.0]).unwrap();
        let a = point_acceleration(&q, &v, &vd, 0, [0.5, 0.0]).unwrap();
        // Tolerances: a few ulps of the O(1) values involved.
        assert!((p[0]).abs() < 1e-15 && (p[1] - 0.5).abs() < 1e-15);
        assert!((pv[0] + 1.0).abs() < 1e-15 && pv[1].abs() < 1e-15);
        assert!(a[0].abs() < 1e-15 && (a[1] + 2.0).abs() < 1e-15);
        assert!(point_position(&q, 1, [0.0, 0.0]).is_none());
    }
}
