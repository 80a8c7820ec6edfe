//! Named access to a mechanism's state: what `mechanism!` generates for each body and named
//! point, so that results are read by name (`Engine::CRANK.phi(&q)`,
//! `engine.crank_a().velocity(&q, &v)`) and never by an index into q. A labelled joint gets a
//! constant too, its index into `JOINTS` (`joint_reaction(.., Engine::MOTOR)`).
//!
//! In joint coordinates a body's pose is no entry of q: `Name::BODY` is a [`TreeBody`] and a
//! named point a [`TreePoint`], both read through the generated `BodyFrames` (the tree's poses,
//! twists and accelerations), in three components in the plane too (z = 0).
//!
//! Positions, velocities and accelerations go out as nalgebra types (`Point3`, `Vector3`,
//! `UnitQuaternion`, `Matrix3`; `Point2`, `Vector2` in the plane). The state goes in as arrays
//! of the mechanism's sizes, `&[T; NQ]` and `&[T; NV]`, which the body's type carries
//! (`PlanarBody<NQ>`, `SpatialBody<NQ, NV>`): the state of another mechanism, or a slice too
//! short, does not compile. (A nalgebra vector or a slice of the right length converts with
//! `.as_slice().try_into()`.)

use nalgebra::{Matrix3, Point2, Point3, Quaternion, UnitQuaternion, Vector2, Vector3};

use crate::model::body::{euler_rotation, BodyFrames};
use crate::real::Real;

/// A planar body: coordinates q[3k..3k+3] = (x, y, φ), velocities the same entries of v = q̇.
/// Generated as `Name::BODY`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanarBody<const NQ: usize> {
    /// Its index among the moving bodies.
    pub index: usize,
    /// Its name.
    pub name: &'static str,
}

impl<const NQ: usize> PlanarBody<NQ> {
    /// Body number `index`, named `name`, of a mechanism with NQ coordinates (NQ = NV).
    ///
    /// # Panics
    /// Where its three coordinates do not lie within q (3 index + 3 > NQ): in a `const`, as the
    /// generated `Name::BODY` is, that is a compile error.
    pub const fn new(index: usize, name: &'static str) -> Self {
        assert!(3 * index + 3 <= NQ, "a planar body's three coordinates lie within q");
        PlanarBody { index, name }
    }
    /// x of its centre of mass (m).
    pub fn x<T: Real>(&self, q: &[T; NQ]) -> T {
        q[3 * self.index]
    }
    /// y of its centre of mass (m).
    pub fn y<T: Real>(&self, q: &[T; NQ]) -> T {
        q[3 * self.index + 1]
    }
    /// Its angle φ (rad).
    pub fn phi<T: Real>(&self, q: &[T; NQ]) -> T {
        q[3 * self.index + 2]
    }
    /// Its centre of mass (m).
    pub fn position<T: Real>(&self, q: &[T; NQ]) -> Point2<T> {
        Point2::new(self.x(q), self.y(q))
    }
    /// The velocity of its centre of mass (m/s).
    pub fn velocity<T: Real>(&self, v: &[T; NQ]) -> Vector2<T> {
        Vector2::new(v[3 * self.index], v[3 * self.index + 1])
    }
    /// The acceleration of its centre of mass (m/s²), from the accelerations v̇.
    pub fn acceleration<T: Real>(&self, vd: &[T; NQ]) -> Vector2<T> {
        self.velocity(vd)
    }
    /// Its angular velocity φ̇ (rad/s, counter-clockwise).
    pub fn omega<T: Real>(&self, v: &[T; NQ]) -> T {
        v[3 * self.index + 2]
    }
    /// Its angular acceleration φ̈ (rad/s²) from the accelerations v̇.
    pub fn alpha<T: Real>(&self, vd: &[T; NQ]) -> T {
        vd[3 * self.index + 2]
    }
    /// The point with body-fixed coordinates `local` (m).
    pub fn point<T: Real>(&self, local: [T; 2]) -> PlanarPoint<T, NQ> {
        PlanarPoint { body: *self, local }
    }
}

/// A point fixed on a planar body, by its body-frame coordinates. Generated for each named
/// point as a method `body_point()` of the mechanism (its coordinates may depend on parameters).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarPoint<T, const NQ: usize> {
    /// The body it is on.
    pub body: PlanarBody<NQ>,
    /// Its coordinates in the body frame (m).
    pub local: [T; 2],
}

impl<T: Real, const NQ: usize> PlanarPoint<T, NQ> {
    /// r^P = r + A(φ) s′ (m).
    pub fn position(&self, q: &[T; NQ]) -> Point2<T> {
        let (s, c) = self.body.phi(q).sin_cos();
        let [a, b] = self.local;
        Point2::new(self.body.x(q) + c * a - s * b, self.body.y(q) + s * a + c * b)
    }
    /// ṙ^P = ṙ + φ̇ ∂A/∂φ s′ (m/s).
    pub fn velocity(&self, q: &[T; NQ], v: &[T; NQ]) -> Vector2<T> {
        let arm = self.arm(q);
        let w = self.body.omega(v);
        self.body.velocity(v) + Vector2::new(-w * arm.y, w * arm.x)
    }
    /// r̈^P = r̈ + φ̈ ∂A/∂φ s′ − φ̇² A s′ (m/s²).
    pub fn acceleration(&self, q: &[T; NQ], v: &[T; NQ], vd: &[T; NQ]) -> Vector2<T> {
        let arm = self.arm(q);
        let (w, alpha) = (self.body.omega(v), self.body.alpha(vd));
        let base = Vector2::new(vd[3 * self.body.index], vd[3 * self.body.index + 1]);
        base + Vector2::new(-alpha * arm.y - w * w * arm.x, alpha * arm.x - w * w * arm.y)
    }
    /// A s′: from the centre of mass to the point, global components (m).
    fn arm(&self, q: &[T; NQ]) -> Vector2<T> {
        let (s, c) = self.body.phi(q).sin_cos();
        let [a, b] = self.local;
        Vector2::new(c * a - s * b, s * a + c * b)
    }
}

/// A spatial body: coordinates q[7k..7k+7] = (x, y, z, e0, e1, e2, e3), velocities
/// v[6k..6k+6] = (ẋ, ẏ, ż, ω′x, ω′y, ω′z) with ω′ in the body frame. Generated as `Name::BODY`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpatialBody<const NQ: usize, const NV: usize> {
    /// Its index among the moving bodies.
    pub index: usize,
    /// Its name.
    pub name: &'static str,
}

impl<const NQ: usize, const NV: usize> SpatialBody<NQ, NV> {
    /// Body number `index`, named `name`, of a mechanism with NQ coordinates and NV velocities.
    ///
    /// # Panics
    /// Where its coordinates or velocities do not lie within q and v: in a `const`, as the
    /// generated `Name::BODY` is, that is a compile error.
    pub const fn new(index: usize, name: &'static str) -> Self {
        assert!(7 * index + 7 <= NQ && 6 * index + 6 <= NV, "a spatial body's coordinates lie within q and v");
        SpatialBody { index, name }
    }
    /// Its centre of mass (m).
    pub fn position<T: Real>(&self, q: &[T; NQ]) -> Point3<T> {
        let k = 7 * self.index;
        Point3::new(q[k], q[k + 1], q[k + 2])
    }
    /// Its orientation: the unit quaternion of its Euler parameters (e0 the scalar part).
    pub fn orientation<T: Real>(&self, q: &[T; NQ]) -> UnitQuaternion<T> {
        let [e0, e1, e2, e3] = self.euler_parameters(q);
        UnitQuaternion::new_unchecked(Quaternion::new(e0, e1, e2, e3))
    }
    /// Its rotation matrix A(p): body-frame components → global.
    pub fn rotation<T: Real>(&self, q: &[T; NQ]) -> Matrix3<T> {
        let a = euler_rotation(self.euler_parameters(q));
        Matrix3::from_fn(|r, c| a[r][c])
    }
    /// The velocity of its centre of mass, global (m/s).
    pub fn velocity<T: Real>(&self, v: &[T; NV]) -> Vector3<T> {
        let k = 6 * self.index;
        Vector3::new(v[k], v[k + 1], v[k + 2])
    }
    /// Its angular velocity ω′ in its own frame (rad/s), as v holds it.
    pub fn body_angular_velocity<T: Real>(&self, v: &[T; NV]) -> Vector3<T> {
        let k = 6 * self.index + 3;
        Vector3::new(v[k], v[k + 1], v[k + 2])
    }
    /// Its angular velocity in global components, ω = A ω′ (rad/s).
    pub fn angular_velocity<T: Real>(&self, q: &[T; NQ], v: &[T; NV]) -> Vector3<T> {
        self.rotation(q) * self.body_angular_velocity(v)
    }
    /// The acceleration of its centre of mass, global (m/s²), from v̇.
    pub fn acceleration<T: Real>(&self, vd: &[T; NV]) -> Vector3<T> {
        self.velocity(vd)
    }
    /// Its angular acceleration ω̇′ in its own frame (rad/s²), from v̇.
    pub fn body_angular_acceleration<T: Real>(&self, vd: &[T; NV]) -> Vector3<T> {
        self.body_angular_velocity(vd)
    }
    /// The point with body-fixed coordinates `local` (m).
    pub fn point<T: Real>(&self, local: [T; 3]) -> SpatialPoint<T, NQ, NV> {
        SpatialPoint { body: *self, local }
    }
    fn euler_parameters<T: Real>(&self, q: &[T; NQ]) -> [T; 4] {
        let k = 7 * self.index + 3;
        [q[k], q[k + 1], q[k + 2], q[k + 3]]
    }
}

/// A point fixed on a spatial body, by its body-frame coordinates. Generated for each named
/// point as a method `body_point()` of the mechanism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialPoint<T, const NQ: usize, const NV: usize> {
    /// The body it is on.
    pub body: SpatialBody<NQ, NV>,
    /// Its coordinates in the body frame (m).
    pub local: [T; 3],
}

impl<T: Real, const NQ: usize, const NV: usize> SpatialPoint<T, NQ, NV> {
    /// r^P = r + A s′ (m).
    pub fn position(&self, q: &[T; NQ]) -> Point3<T> {
        self.body.position(q) + self.body.rotation(q) * self.local_vector()
    }
    /// ṙ^P = ṙ + A (ω′ × s′) (m/s).
    pub fn velocity(&self, q: &[T; NQ], v: &[T; NV]) -> Vector3<T> {
        let w = self.body.body_angular_velocity(v);
        self.body.velocity(v) + self.body.rotation(q) * w.cross(&self.local_vector())
    }
    /// r̈^P = r̈ + A (ω̇′ × s′ + ω′ × (ω′ × s′)) (m/s²).
    pub fn acceleration(&self, q: &[T; NQ], v: &[T; NV], vd: &[T; NV]) -> Vector3<T> {
        let (w, wd, s) = (self.body.body_angular_velocity(v), self.body.body_angular_acceleration(vd), self.local_vector());
        self.body.acceleration(vd) + self.body.rotation(q) * (wd.cross(&s) + w.cross(&w.cross(&s)))
    }
    fn local_vector(&self) -> Vector3<T> {
        Vector3::new(self.local[0], self.local[1], self.local[2])
    }
}

/// A body of a mechanism in joint coordinates (`joint_coordinates;`): its pose, twist and
/// acceleration computed from the joint state through the mechanism's `BodyFrames`. Generated
/// as `Name::BODY`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TreeBody {
    /// Its index among the moving bodies.
    pub index: usize,
    /// Its name.
    pub name: &'static str,
}

impl TreeBody {
    /// Body number `index`, named `name`.
    pub const fn new(index: usize, name: &'static str) -> Self {
        TreeBody { index, name }
    }
    /// Its centre of mass (m).
    pub fn position<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize>(&self, m: &M, q: &[T; NQ]) -> Point3<T> {
        let r = self.pose(m, q).position;
        Point3::new(r[0], r[1], r[2])
    }
    /// Its rotation matrix: body-frame components → global.
    pub fn rotation<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize>(&self, m: &M, q: &[T; NQ]) -> Matrix3<T> {
        let a = self.pose(m, q).rotation;
        Matrix3::from_fn(|r, c| a[r][c])
    }
    /// The velocity of its centre of mass and its angular velocity, global (m/s, rad/s).
    pub fn velocity<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        v: &[T; NV],
    ) -> (Vector3<T>, Vector3<T>) {
        let t = m.body_twist(self.index, q, v).expect("a body of this mechanism");
        (Vector3::from(t.velocity), Vector3::from(t.angular_velocity))
    }
    /// The acceleration of its centre of mass and its angular acceleration, global (m/s²,
    /// rad/s²), from the accelerations v̇.
    pub fn acceleration<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        v: &[T; NV],
        vd: &[T; NV],
    ) -> (Vector3<T>, Vector3<T>) {
        let a = m.body_acceleration(self.index, q, v, vd).expect("a body of this mechanism");
        (Vector3::from(a.velocity), Vector3::from(a.angular_velocity))
    }
    /// The point at `local` in its body frame (m): `[x, y]` in the plane, `[x, y, z]` in space
    /// — as [`PlanarBody::point`] and [`SpatialBody::point`] give it in body coordinates, with
    /// the mechanism that places the body. (Named points are also generated as methods,
    /// `m.body_point()`.)
    pub fn point<'m, T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize, const D: usize>(
        &self,
        m: &'m M,
        local: [T; D],
    ) -> TreePoint<'m, M, T, NQ, NV> {
        const { assert!(D == 2 || D == 3, "a point on a body has 2 coordinates in the plane, 3 in space") };
        TreePoint { mechanism: m, body: *self, local: [local[0], local[1], local.get(2).copied().unwrap_or(T::ZERO)] }
    }
    fn pose<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
    ) -> crate::model::body::BodyPose<T> {
        m.body_pose(self.index, q).expect("a body of this mechanism")
    }
}

/// A point fixed on a body of a mechanism in joint coordinates, by its body-frame coordinates
/// (z = 0 in the plane), with the mechanism that places its body. Generated for each named point
/// as a method `body_point()` of the mechanism.
#[derive(Clone, Copy, Debug)]
pub struct TreePoint<'m, M, T, const NQ: usize, const NV: usize> {
    /// The mechanism.
    pub mechanism: &'m M,
    /// The body it is on.
    pub body: TreeBody,
    /// Its coordinates in the body frame (m).
    pub local: [T; 3],
}

impl<M: BodyFrames<T, NQ, NV>, T: Real, const NQ: usize, const NV: usize> TreePoint<'_, M, T, NQ, NV> {
    /// r^P = r + A s′ (m).
    pub fn position(&self, q: &[T; NQ]) -> Point3<T> {
        Point3::from(self.body.pose(self.mechanism, q).point(self.local))
    }
    /// ṙ^P = ṙ + ω × (A s′) (m/s).
    pub fn velocity(&self, q: &[T; NQ], v: &[T; NV]) -> Vector3<T> {
        let (velocity, w) = self.body.velocity(self.mechanism, q, v);
        velocity + w.cross(&self.arm(q))
    }
    /// r̈^P = r̈ + ω̇ × (A s′) + ω × (ω × A s′) (m/s²).
    pub fn acceleration(&self, q: &[T; NQ], v: &[T; NV], vd: &[T; NV]) -> Vector3<T> {
        let arm = self.arm(q);
        let (_, w) = self.body.velocity(self.mechanism, q, v);
        let (acceleration, wd) = self.body.acceleration(self.mechanism, q, v, vd);
        acceleration + wd.cross(&arm) + w.cross(&w.cross(&arm))
    }
    /// A s′, global (m).
    fn arm(&self, q: &[T; NQ]) -> Vector3<T> {
        Vector3::from(self.body.pose(self.mechanism, q).to_global(self.local))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A planar point 0.5 m along x of a body at (1, 2) turned 90° and spinning at 2 rad/s,
    /// accelerating at 3 rad/s²: at (1, 2.5), moving at (−1, 0) m/s, accelerating at
    /// (−1.5, −2) m/s² (tangential α r, centripetal ω² r).
    #[test]
    fn planar_point() {
        let body = PlanarBody::<6>::new(1, "b");
        let q = [0.0, 0.0, 0.0, 1.0, 2.0, core::f64::consts::FRAC_PI_2];
        let (v, vd) = ([0.0, 0.0, 0.0, 0.0, 0.0, 2.0], [0.0, 0.0, 0.0, 0.0, 0.0, 3.0]);
        let p = body.point([0.5, 0.0]);
        // Tolerances: a few ulps of the O(1) values involved (cos 90° = 6e-17).
        assert!((p.position(&q) - Point2::new(1.0, 2.5)).norm() < 1e-15);
        assert!((p.velocity(&q, &v) - Vector2::new(-1.0, 0.0)).norm() < 1e-15);
        assert!((p.acceleration(&q, &v, &vd) - Vector2::new(-1.5, -2.0)).norm() < 1e-15);
        assert_eq!((body.x(&q), body.y(&q), body.omega(&v)), (1.0, 2.0, 2.0));
    }

    /// A spatial body turned 90° about z (p = (cos 45°, 0, 0, sin 45°)) spinning at ω′ = 2 about
    /// its own z: its body x-axis point s′ = (0.5, 0, 0) is at r + (0, 0.5, 0) and moves at
    /// ω × (A s′) = (−1, 0, 0); the quaternion and the rotation matrix agree with nalgebra's.
    #[test]
    fn spatial_point() {
        let body = SpatialBody::<7, 6>::new(0, "b");
        let h = core::f64::consts::FRAC_1_SQRT_2;
        let q = [1.0, 2.0, 3.0, h, 0.0, 0.0, h];
        let v = [0.1, 0.0, 0.0, 0.0, 0.0, 2.0];
        let vd = [0.0; 6];
        let p = body.point([0.5, 0.0, 0.0]);
        assert!((p.position(&q) - Point3::new(1.0, 2.5, 3.0)).norm() < 1e-15);
        assert!((p.velocity(&q, &v) - Vector3::new(0.1 - 1.0, 0.0, 0.0)).norm() < 1e-15);
        // centripetal ω² |s′| = 2 toward the centre: −2 along A s′ = (0, 1, 0)
        assert!((p.acceleration(&q, &v, &vd) - Vector3::new(0.0, -2.0, 0.0)).norm() < 1e-15);
        let nalgebra_rotation = body.orientation(&q).to_rotation_matrix().into_inner();
        assert!((body.rotation(&q) - nalgebra_rotation).norm() < 1e-15);
        assert!((body.angular_velocity(&q, &v) - Vector3::new(0.0, 0.0, 2.0)).norm() < 1e-15);
    }
}
