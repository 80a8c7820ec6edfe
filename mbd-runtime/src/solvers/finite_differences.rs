//! [`FiniteDifferences`]: a mechanism whose derivatives are central differences of its own
//! functions instead of the generated exact ones — what a tool without symbolic derivatives
//! does — so that the same Newton solves (assembly, statics, generalized-α) can be run both ways
//! and what exactness buys compared in accuracy, iterations and time (`mbd-study`).
//!
//! Every derivative is taken along the velocity directions, as the generated ones are: a
//! coordinate perturbation is q ⊕ εe_j ([`Kinematics::integrate_positions`], planar q + εe_j).
//!
//! * ∂h/∂q·B, ∂h/∂v and the Coulomb friction's derivatives: central differences of
//!   [`Dynamics::forces`] and [`Dynamics::friction_forces`], 2 NV evaluations each, with
//!   ε = ∛u·max(1, ‖q‖∞) (‖v‖∞ for ∂/∂v; u the unit roundoff): truncation ε² and rounding u/ε
//!   balanced, about u^(2/3) ≈ 4e-11 relative in f64 (friction: 4 NV evaluations of nothing
//!   for a mechanism without Coulomb friction).
//! * K = ∂(Dᵀλ)/∂q·B: without the generated D, Dᵀλ is itself the gradient of the scalar λᵀΦ
//!   along the velocity directions, so K is a central difference of central differences of Φ
//!   (4 NV² evaluations of Φ, ε = u^(1/4)·max(1, ‖q‖∞), about u^(1/2) ≈ 1e-8 relative).
//! * D = Φ_q B, only with [`FiniteDifferences::constraint_jacobian`]: central differences of Φ
//!   (2 NV evaluations). D is part of the equations (M v̇ − Dᵀλ = h, D v = ν), not only of the
//!   Newton matrices, so by default it stays exact and only the iteration matrices change; with
//!   the flag on, every derivative a Newton solve uses is a difference.
//!
//! Everything else — Φ, ν, γ, h, M, V and the forward-dynamics solve — is the mechanism's own.
//! No work array is larger than O(NQ + NV + NC): the differences are taken a column at a time
//! into the caller's matrix.

use crate::model::body::{BodyFrames, BodyPose, BodyTwist};
use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::model::mechanism::{
    ConstraintForces, CoordinateInfo, Dynamics, ForceInfo, JointInfo, Kinematics, KinematicsHooks, Mechanism, NewtonMatrix, OpCount,
    VelocityInfo,
};
use crate::model::workspace::DenseScratch;
use crate::real::Real;

/// A mechanism with finite-difference derivatives (module docs).
#[derive(Clone, Copy, Debug)]
pub struct FiniteDifferences<'m, M> {
    /// The mechanism whose functions are differenced.
    pub mechanism: &'m M,
    /// Also D = Φ_q B by differences (default: exact).
    pub constraint_jacobian: bool,
}

impl<'m, M> FiniteDifferences<'m, M> {
    /// `mechanism` with differenced ∂h/∂q, ∂h/∂v, friction derivatives and K; D exact.
    pub fn new(mechanism: &'m M) -> Self {
        Self { mechanism, constraint_jacobian: false }
    }

    /// Every derivative by differences, D = Φ_q B included.
    pub fn with_constraint_jacobian(mechanism: &'m M) -> Self {
        Self { mechanism, constraint_jacobian: true }
    }
}

impl<M: Mechanism> Mechanism for FiniteDifferences<'_, M> {
    const NAME: &'static str = M::NAME;
    const BODY_NAMES: &'static [&'static str] = M::BODY_NAMES;
    const COORDINATE_NAMES: &'static [&'static str] = M::COORDINATE_NAMES;
    const VELOCITY_NAMES: &'static [&'static str] = M::VELOCITY_NAMES;
    const COORDINATES: &'static [CoordinateInfo] = M::COORDINATES;
    const VELOCITIES: &'static [VelocityInfo] = M::VELOCITIES;
    const CONSTRAINT_NAMES: &'static [&'static str] = M::CONSTRAINT_NAMES;
    const PARAM_NAMES: &'static [&'static str] = M::PARAM_NAMES;
    const DOF: i32 = M::DOF;
    const JACOBIAN_PATTERN: &'static [(u16, u16)] = M::JACOBIAN_PATTERN;
    const PHI_T_IS_ZERO: bool = M::PHI_T_IS_ZERO;
    const OP_COUNTS: &'static [OpCount] = M::OP_COUNTS;
    const JOINTS: &'static [JointInfo] = M::JOINTS;
    const FORCE_ELEMENTS: &'static [ForceInfo] = M::FORCE_ELEMENTS;
    const EFFECTS: &'static [&'static str] = M::EFFECTS;
    const MODEL_JSON: &'static str = M::MODEL_JSON;
}

/// ∛u and u^(1/4) of the scalar type: the steps of first and nested differences.
fn steps<T: Real>() -> (T, T) {
    (T::EPSILON.powf(T::from_f64(1.0 / 3.0)), T::EPSILON.powf(T::from_f64(0.25)))
}

fn scale<T: Real>(x: &[T]) -> T {
    x.iter().fold(T::ONE, |s, v| s.max(v.abs()))
}

/// Central differences of `f` along each velocity direction at q: column j of `out` (rows from
/// `f`'s output) is (f(q ⊕ εe_j) − f(q ⊕ −εe_j)) / 2ε, written or added.
#[allow(clippy::too_many_arguments)]
fn columns_in_q<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const R: usize>(
    m: &M,
    q: &[T; NQ],
    epsilon: T,
    add: bool,
    mut f: impl FnMut(&[T; NQ], &mut [T; R]),
    out: &mut [[T; NV]; R],
) {
    let (mut plus, mut minus) = ([T::ZERO; R], [T::ZERO; R]);
    for j in 0..NV {
        let mut e = [T::ZERO; NV];
        e[j] = T::ONE;
        let (mut qp, mut qm) = (*q, *q);
        m.integrate_positions(&mut qp, &e, epsilon);
        m.integrate_positions(&mut qm, &e, -epsilon);
        f(&qp, &mut plus);
        f(&qm, &mut minus);
        for (row, (p, n)) in out.iter_mut().zip(plus.iter().zip(&minus)) {
            let value = (*p - *n) / (epsilon + epsilon);
            row[j] = if add { row[j] + value } else { value };
        }
    }
}

/// Dᵀλ at q as the gradient of λᵀΦ along the velocity directions (central differences).
fn constraint_forces<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[T; NQ],
    t: T,
    lambda: &[T; NC],
    epsilon: T,
    out: &mut [T; NV],
) {
    let mut phi = [T::ZERO; NC];
    let mut work = |qq: &[T; NQ]| {
        m.constraints(qq, t, &mut phi);
        phi.iter().zip(lambda).fold(T::ZERO, |s, (p, l)| s + *p * *l)
    };
    for (j, o) in out.iter_mut().enumerate() {
        let mut e = [T::ZERO; NV];
        e[j] = T::ONE;
        let (mut qp, mut qm) = (*q, *q);
        m.integrate_positions(&mut qp, &e, epsilon);
        m.integrate_positions(&mut qm, &e, -epsilon);
        *o = (work(&qp) - work(&qm)) / (epsilon + epsilon);
    }
}

impl<T: Real, M: BodyFrames<T, NQ, NV>, const NQ: usize, const NV: usize> BodyFrames<T, NQ, NV> for FiniteDifferences<'_, M> {
    fn body_pose(&self, body: usize, q: &[T; NQ]) -> Option<BodyPose<T>> {
        self.mechanism.body_pose(body, q)
    }
    fn body_twist(&self, body: usize, q: &[T; NQ], x: &[T; NV]) -> Option<BodyTwist<T>> {
        self.mechanism.body_twist(body, q, x)
    }
    fn body_acceleration(&self, body: usize, q: &[T; NQ], v: &[T; NV], vd: &[T; NV]) -> Option<BodyTwist<T>> {
        self.mechanism.body_acceleration(body, q, v, vd)
    }
    fn add_body_wrench(&self, body: usize, q: &[T; NQ], force: [T; 3], moment: [T; 3], g: &mut [T; NV]) -> bool {
        self.mechanism.add_body_wrench(body, q, force, moment, g)
    }
}

/// The generated solves are not forwarded: the reference takes the dense paths.
impl<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> KinematicsHooks<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
}

impl<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> Kinematics<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
    fn initial_positions(&self) -> [T; NQ] {
        self.mechanism.initial_positions()
    }
    fn initial_velocities(&self) -> [T; NV] {
        self.mechanism.initial_velocities()
    }
    fn position_rates(&self, q: &[T; NQ], v: &[T; NV], qdot: &mut [T; NQ]) {
        self.mechanism.position_rates(q, v, qdot);
    }
    fn integrate_positions(&self, q: &mut [T; NQ], dv: &[T; NV], h: T) {
        self.mechanism.integrate_positions(q, dv, h);
    }
    fn normalize_positions(&self, q: &mut [T; NQ]) {
        self.mechanism.normalize_positions(q);
    }
    fn constraints(&self, q: &[T; NQ], t: T, phi: &mut [T; NC]) {
        self.mechanism.constraints(q, t, phi);
    }
    fn jacobian(&self, q: &[T; NQ], t: T, d: &mut [[T; NV]; NC]) {
        if !self.constraint_jacobian {
            return self.mechanism.jacobian(q, t, d);
        }
        let epsilon = steps::<T>().0 * scale(q);
        columns_in_q(self.mechanism, q, epsilon, false, |qq, phi| self.mechanism.constraints(qq, t, phi), d);
    }
    fn velocity_rhs(&self, q: &[T; NQ], t: T, nu: &mut [T; NC]) {
        self.mechanism.velocity_rhs(q, t, nu);
    }
    fn gamma(&self, q: &[T; NQ], v: &[T; NV], t: T, gamma: &mut [T; NC]) {
        self.mechanism.gamma(q, v, t, gamma);
    }
    fn position_eval(&self, q: &[T; NQ], t: T, phi: &mut [T; NC], d: &mut [[T; NV]; NC]) {
        self.mechanism.position_eval(q, t, phi, d);
        if self.constraint_jacobian {
            self.jacobian(q, t, d);
        }
    }
    fn full_eval(&self, q: &[T; NQ], v: &[T; NV], t: T, phi: &mut [T; NC], d: &mut [[T; NV]; NC], nu: &mut [T; NC], gamma: &mut [T; NC]) {
        self.mechanism.full_eval(q, v, t, phi, d, nu, gamma);
        if self.constraint_jacobian {
            self.jacobian(q, t, d);
        }
    }
}

impl<T: Real, M: Dynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> Dynamics<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
    fn mass_times(&self, q: &[T; NQ], x: &[T; NV], y: &mut [T; NV]) {
        self.mechanism.mass_times(q, x, y);
    }
    fn check_inertia(&self) -> Result<(), crate::model::dynamics::DynamicsError> {
        self.mechanism.check_inertia()
    }
    fn add_mass_matrix(&self, q: &[T; NQ], scale: T, a: &mut [[T; NV]; NV]) {
        self.mechanism.add_mass_matrix(q, scale, a);
    }
    fn add_mass_derivative(&self, q: &[T; NQ], x: &[T; NV], scale: T, a: &mut [[T; NV]; NV]) {
        self.mechanism.add_mass_derivative(q, x, scale, a);
    }
    fn forces(&self, q: &[T; NQ], v: &[T; NV], t: T, h: &mut [T; NV]) {
        self.mechanism.forces(q, v, t, h);
    }
    fn forces_q(&self, q: &[T; NQ], v: &[T; NV], t: T, dh: &mut [[T; NV]; NV]) {
        let epsilon = steps::<T>().0 * scale(q);
        columns_in_q(self.mechanism, q, epsilon, false, |qq, h| self.mechanism.forces(qq, v, t, h), dh);
    }
    fn forces_v(&self, q: &[T; NQ], v: &[T; NV], t: T, dh: &mut [[T; NV]; NV]) {
        let epsilon = steps::<T>().0 * scale(v);
        let (mut plus, mut minus) = ([T::ZERO; NV], [T::ZERO; NV]);
        for j in 0..NV {
            let (mut vp, mut vm) = (*v, *v);
            vp[j] += epsilon;
            vm[j] -= epsilon;
            self.mechanism.forces(q, &vp, t, &mut plus);
            self.mechanism.forces(q, &vm, t, &mut minus);
            for (row, (p, n)) in dh.iter_mut().zip(plus.iter().zip(&minus)) {
                row[j] = (*p - *n) / (epsilon + epsilon);
            }
        }
    }
    fn potential_energy(&self, q: &[T; NQ], t: T) -> T {
        self.mechanism.potential_energy(q, t)
    }
    const SWITCH_NAMES: &'static [&'static str] = M::SWITCH_NAMES;
    const TIME_SWITCHES: usize = M::TIME_SWITCHES;
    fn switching_function(&self, k: usize, q: &[T; NQ], v: &[T; NV], t: T) -> T {
        self.mechanism.switching_function(k, q, v, t)
    }
    fn friction_forces(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], h: &mut [T; NV]) {
        self.mechanism.friction_forces(q, v, t, lambda, h);
    }
    fn friction_derivatives(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], d_q: &mut [[T; NV]; NV], d_v: &mut [[T; NV]; NV]) {
        let friction = |qq: &[T; NQ], vv: &[T; NV], out: &mut [T; NV]| {
            *out = [T::ZERO; NV];
            self.mechanism.friction_forces(qq, vv, t, lambda, out);
        };
        let epsilon = steps::<T>().0 * scale(q);
        columns_in_q(self.mechanism, q, epsilon, true, |qq, out| friction(qq, v, out), d_q);
        let epsilon = steps::<T>().0 * scale(v);
        let (mut plus, mut minus) = ([T::ZERO; NV], [T::ZERO; NV]);
        for j in 0..NV {
            let (mut vp, mut vm) = (*v, *v);
            vp[j] += epsilon;
            vm[j] -= epsilon;
            friction(q, &vp, &mut plus);
            friction(q, &vm, &mut minus);
            for (row, (p, n)) in d_v.iter_mut().zip(plus.iter().zip(&minus)) {
                row[j] += (*p - *n) / (epsilon + epsilon);
            }
        }
    }
    fn friction_multiplier_derivatives(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], d_lambda: &mut [[T; NV]; NC]) {
        let epsilon = steps::<T>().0 * scale(lambda);
        for (r, row) in d_lambda.iter_mut().enumerate() {
            let (mut lp, mut lm) = (*lambda, *lambda);
            lp[r] += epsilon;
            lm[r] -= epsilon;
            let (mut plus, mut minus) = ([T::ZERO; NV], [T::ZERO; NV]);
            self.mechanism.friction_forces(q, v, t, &lp, &mut plus);
            self.mechanism.friction_forces(q, v, t, &lm, &mut minus);
            for (x, (p, n)) in row.iter_mut().zip(plus.iter().zip(&minus)) {
                *x += (*p - *n) / (epsilon + epsilon);
            }
        }
    }
    fn nonconservative_power(&self, q: &[T; NQ], v: &[T; NV], t: T) -> T {
        self.mechanism.nonconservative_power(q, v, t)
    }
}

impl<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> ConstraintForces<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
    fn constraint_force_q(&self, q: &[T; NQ], t: T, lambda: &[T; NC], k: &mut [[T; NV]; NV]) {
        // Differences of Dᵀλ, itself the differences of λᵀΦ (module docs), both with u^(1/4).
        let epsilon = steps::<T>().1 * scale(q);
        let m = self.mechanism;
        columns_in_q(m, q, epsilon, false, |qq, out| constraint_forces(m, qq, t, lambda, epsilon, out), k);
    }
}

impl<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> ForwardDynamics<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
    fn accelerations(
        &self,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        options: &DynamicsOptions<T>,
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<(), DynamicsError> {
        self.mechanism.accelerations(q, v, t, options, vd, lambda)
    }
    fn project_positions_step(&self, q: &mut [T; NQ], t: T, options: &DynamicsOptions<T>) -> Result<T, DynamicsError> {
        self.mechanism.project_positions_step(q, t, options)
    }
    fn project_velocities(&self, q: &[T; NQ], v: &mut [T; NV], t: T, options: &DynamicsOptions<T>) -> Result<T, DynamicsError> {
        self.mechanism.project_velocities(q, v, t, options)
    }
    fn accelerations_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        options: &DynamicsOptions<T>,
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<(), DynamicsError> {
        self.mechanism.accelerations_in(scratch, q, v, t, options, vd, lambda)
    }
    fn project_positions_step_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &mut [T; NQ],
        t: T,
        options: &DynamicsOptions<T>,
    ) -> Result<T, DynamicsError> {
        self.mechanism.project_positions_step_in(scratch, q, t, options)
    }
    fn project_velocities_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &[T; NQ],
        v: &mut [T; NV],
        t: T,
        options: &DynamicsOptions<T>,
    ) -> Result<T, DynamicsError> {
        self.mechanism.project_velocities_in(scratch, q, v, t, options)
    }
}

/// The mechanism's planned pattern, filled from the differences (the provided methods: dense
/// derivatives on the stack, then the pattern's entries; a difference's noise off the pattern
/// is left out).
impl<T: Real, M: NewtonMatrix<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> NewtonMatrix<T, NQ, NV, NC>
    for FiniteDifferences<'_, M>
{
    type NewtonStorage = M::NewtonStorage;
    const NEWTON_PATTERN: crate::linalg::sparse::SparsePattern = M::NEWTON_PATTERN;
    fn newton_storage() -> M::NewtonStorage {
        M::newton_storage()
    }
}
