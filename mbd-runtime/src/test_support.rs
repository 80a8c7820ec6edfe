//! Test doubles with NQ ≠ NV, written by hand: a rod pinned at one end whose orientation is the
//! unit complex number (c, s) = (cos φ, sin φ), the planar analogue of Euler parameters
//! (docs/formulation.md, "Spatial bodies"). No generated mechanism has NQ ≠ NV yet; these
//! exercise the solvers' velocity-space paths.
//!
//! q = (x, y, c, s), v = (vx, vy, ω), q̇ = B(q) v with ċ = −s ω, ṡ = c ω; (c, s) is divided by
//! its norm after every position update. The centre of mass is at distance L from the pin at the
//! origin: the body point (−L, 0) stays there,
//!
//! ```text
//! Φ = r + A (−L, 0) = (x − L c, y − L s),   D = Φ_q B = [[1, 0, L s], [0, 1, −L c]],
//! γ = −𝒟(𝒟Φ) = (−L c ω², −L s ω²),         K = ∂(Dᵀλ)/∂q · B: K₂₂ = L (c λ₀ + s λ₁).
//! ```
//!
//! [`UnitPendulum`] swings free under gravity (NC = 2, with its dynamics); [`DrivenUnitPendulum`]
//! adds the driver sin(φ − Ωt) = s cos Ωt − c sin Ωt (NC = 3), whose D row is
//! (0, 0, c cos Ωt + s sin Ωt), ν = Ω (c cos Ωt + s sin Ωt) and γ = (ω − Ω)² (s cos Ωt − c sin Ωt).

use crate::linalg::{lu_factor, lu_solve_in_place, LuWork};
use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::model::mechanism::{ConstraintForces, Dynamics, Kinematics, KinematicsHooks, Mechanism, OpCount};
use crate::model::mechanism::{CoordinateInfo, CoordinateKind, VelocityInfo, VelocityKind};

/// Distance from the pin to the centre of mass (m).
pub(crate) const LENGTH: f64 = 0.5;
/// Mass (kg).
pub(crate) const MASS: f64 = 2.0;
/// Moment of inertia about the centre of mass (kg·m²).
pub(crate) const INERTIA: f64 = 0.05;
/// Gravity, along −y (m/s²).
pub(crate) const GRAVITY: f64 = 9.81;

/// q̇ = B(q) v.
fn rates(q: &[f64; 4], v: &[f64; 3]) -> [f64; 4] {
    [v[0], v[1], -q[3] * v[2], q[2] * v[2]]
}

/// (c, s) divided by its norm.
fn normalize(q: &mut [f64; 4]) {
    let norm = (q[2] * q[2] + q[3] * q[3]).sqrt();
    q[2] /= norm;
    q[3] /= norm;
}

/// q ← q + h B(q) dv, normalized.
fn integrate(q: &mut [f64; 4], dv: &[f64; 3], h: f64) {
    let r = rates(q, dv);
    for (x, d) in q.iter_mut().zip(r) {
        *x += h * d;
    }
    normalize(q);
}

/// The pin's rows: Φ and D.
fn pin(q: &[f64; 4]) -> ([f64; 2], [[f64; 3]; 2]) {
    let [x, y, c, s] = *q;
    ([x - LENGTH * c, y - LENGTH * s], [[1.0, 0.0, LENGTH * s], [0.0, 1.0, -LENGTH * c]])
}

/// The pin's γ.
fn pin_gamma(q: &[f64; 4], v: &[f64; 3]) -> [f64; 2] {
    let w2 = v[2] * v[2];
    [-LENGTH * q[2] * w2, -LENGTH * q[3] * w2]
}

const COORDINATES: &[&str] = &["rod.x", "rod.y", "rod.c", "rod.s"];
const VELOCITIES: &[&str] = &["rod.vx", "rod.vy", "rod.w"];
const COORDINATE_INFO: &[CoordinateInfo] = &[
    CoordinateInfo { name: "rod.x", kind: CoordinateKind::Length },
    CoordinateInfo { name: "rod.y", kind: CoordinateKind::Length },
    CoordinateInfo { name: "rod.c", kind: CoordinateKind::Number },
    CoordinateInfo { name: "rod.s", kind: CoordinateKind::Number },
];
const VELOCITY_INFO: &[VelocityInfo] = &[
    VelocityInfo { name: "rod.vx", kind: VelocityKind::Rate { coordinate: 0 }, displacement: "rod.x" },
    VelocityInfo { name: "rod.vy", kind: VelocityKind::Rate { coordinate: 1 }, displacement: "rod.y" },
    VelocityInfo { name: "rod.w", kind: VelocityKind::Other { angular: true }, displacement: "rod.phi" },
];

/// The free pendulum: NQ = 4, NV = 3, NC = 2.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct UnitPendulum;

impl Mechanism for UnitPendulum {
    const NAME: &'static str = "UnitPendulum";
    const BODY_NAMES: &'static [&'static str] = &["rod"];
    const COORDINATE_NAMES: &'static [&'static str] = COORDINATES;
    const VELOCITY_NAMES: &'static [&'static str] = VELOCITIES;
    const COORDINATES: &'static [CoordinateInfo] = COORDINATE_INFO;
    const VELOCITIES: &'static [VelocityInfo] = VELOCITY_INFO;
    const CONSTRAINT_NAMES: &'static [&'static str] = &["pin: x", "pin: y"];
    const PARAM_NAMES: &'static [&'static str] = &[];
    const DOF: i32 = 1;
    const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[(0, 0), (0, 2), (1, 1), (1, 2)];
    const PHI_T_IS_ZERO: bool = true;
    const OP_COUNTS: &'static [OpCount] = &[];
    const MODEL_JSON: &'static str = "{}";
}

impl KinematicsHooks<f64, 4, 3, 2> for UnitPendulum {}

impl Kinematics<f64, 4, 3, 2> for UnitPendulum {
    /// Horizontal, at rest.
    fn initial_positions(&self) -> [f64; 4] {
        [LENGTH, 0.0, 1.0, 0.0]
    }
    fn initial_velocities(&self) -> [f64; 3] {
        [0.0; 3]
    }
    fn position_rates(&self, q: &[f64; 4], v: &[f64; 3], qdot: &mut [f64; 4]) {
        *qdot = rates(q, v);
    }
    fn integrate_positions(&self, q: &mut [f64; 4], dv: &[f64; 3], h: f64) {
        integrate(q, dv, h);
    }
    fn normalize_positions(&self, q: &mut [f64; 4]) {
        normalize(q);
    }
    fn constraints(&self, q: &[f64; 4], _t: f64, phi: &mut [f64; 2]) {
        *phi = pin(q).0;
    }
    fn jacobian(&self, q: &[f64; 4], _t: f64, d: &mut [[f64; 3]; 2]) {
        *d = pin(q).1;
    }
    fn velocity_rhs(&self, _q: &[f64; 4], _t: f64, nu: &mut [f64; 2]) {
        *nu = [0.0; 2];
    }
    fn gamma(&self, q: &[f64; 4], v: &[f64; 3], _t: f64, gamma: &mut [f64; 2]) {
        *gamma = pin_gamma(q, v);
    }
    fn position_eval(&self, q: &[f64; 4], _t: f64, phi: &mut [f64; 2], d: &mut [[f64; 3]; 2]) {
        (*phi, *d) = pin(q);
    }
    fn full_eval(
        &self,
        q: &[f64; 4],
        v: &[f64; 3],
        t: f64,
        phi: &mut [f64; 2],
        d: &mut [[f64; 3]; 2],
        nu: &mut [f64; 2],
        gamma: &mut [f64; 2],
    ) {
        self.position_eval(q, t, phi, d);
        self.velocity_rhs(q, t, nu);
        self.gamma(q, v, t, gamma);
    }
}

/// diag(m, m, J).
const MASSES: [f64; 3] = [MASS, MASS, INERTIA];

impl Dynamics<f64, 4, 3, 2> for UnitPendulum {
    fn mass_times(&self, _q: &[f64; 4], x: &[f64; 3], y: &mut [f64; 3]) {
        *y = core::array::from_fn(|i| MASSES[i] * x[i]);
    }
    fn add_mass_matrix(&self, _q: &[f64; 4], scale: f64, a: &mut [[f64; 3]; 3]) {
        for (i, m) in MASSES.iter().enumerate() {
            a[i][i] += scale * m;
        }
    }
    fn forces(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64, h: &mut [f64; 3]) {
        *h = [0.0, -MASS * GRAVITY, 0.0];
    }
    fn forces_q(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64, dh: &mut [[f64; 3]; 3]) {
        *dh = [[0.0; 3]; 3];
    }
    fn forces_v(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64, dh: &mut [[f64; 3]; 3]) {
        *dh = [[0.0; 3]; 3];
    }
    fn potential_energy(&self, q: &[f64; 4], _t: f64) -> f64 {
        MASS * GRAVITY * q[1]
    }
    fn friction_forces(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64, _lambda: &[f64; 2], _h: &mut [f64; 3]) {}
    fn friction_derivatives(
        &self,
        _q: &[f64; 4],
        _v: &[f64; 3],
        _t: f64,
        _lambda: &[f64; 2],
        _d_q: &mut [[f64; 3]; 3],
        _d_v: &mut [[f64; 3]; 3],
    ) {
    }
    fn friction_multiplier_derivatives(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64, _lambda: &[f64; 2], _d_lambda: &mut [[f64; 3]; 2]) {}
    /// Gravity is conservative: vᵀh + dV/dt = −m g v_y + m g ẏ = 0.
    fn nonconservative_power(&self, _q: &[f64; 4], _v: &[f64; 3], _t: f64) -> f64 {
        0.0
    }
}

impl ConstraintForces<f64, 4, 3, 2> for UnitPendulum {
    fn constraint_force_q(&self, q: &[f64; 4], _t: f64, lambda: &[f64; 2], k: &mut [[f64; 3]; 3]) {
        *k = [[0.0; 3]; 3];
        k[2][2] = LENGTH * (q[2] * lambda[0] + q[3] * lambda[1]);
    }
}

/// S = D M⁻¹ Dᵀ (2 × 2) and the solve S x = b, by Cramer's rule.
fn schur_solve(d: &[[f64; 3]; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let s = |r: usize, k: usize| (0..3).map(|i| d[r][i] * d[k][i] / MASSES[i]).sum::<f64>();
    let (a, o, e) = (s(0, 0), s(0, 1), s(1, 1));
    let det = a * e - o * o;
    (det.abs() > 1e-12 * a.abs().max(e.abs())).then(|| [(e * b[0] - o * b[1]) / det, (a * b[1] - o * b[0]) / det])
}

/// M⁻¹ Dᵀ x.
fn minv_dt(d: &[[f64; 3]; 2], x: [f64; 2]) -> [f64; 3] {
    core::array::from_fn(|i| (d[0][i] * x[0] + d[1][i] * x[1]) / MASSES[i])
}

fn dependent(t: f64) -> DynamicsError {
    DynamicsError::DependentConstraint { t, row: "pin: y" }
}

impl ForwardDynamics<f64, 4, 3, 2> for UnitPendulum {
    /// The dense saddle-point solve [[M, −Dᵀ], [D, 0]] [v̇; λ] = [h; γ*].
    fn accelerations(
        &self,
        q: &[f64; 4],
        v: &[f64; 3],
        t: f64,
        options: &DynamicsOptions<f64>,
        vd: &mut [f64; 3],
        lambda: &mut [f64; 2],
    ) -> Result<(), DynamicsError> {
        let (phi, d) = pin(q);
        let gamma = pin_gamma(q, v);
        let mut h = [0.0; 3];
        self.forces(q, v, t, &mut h);
        let mut a = [[0.0; 5]; 5];
        let mut b = [0.0; 5];
        for i in 0..3 {
            a[i][i] = MASSES[i];
            b[i] = h[i];
            for r in 0..2 {
                a[i][3 + r] = -d[r][i];
                a[3 + r][i] = d[r][i];
            }
        }
        for r in 0..2 {
            let dv: f64 = (0..3).map(|i| d[r][i] * v[i]).sum();
            b[3 + r] = gamma[r] - 2.0 * options.baumgarte_alpha * dv - options.baumgarte_beta * options.baumgarte_beta * phi[r];
        }
        let (mut pivots, mut columns, mut scale) = ([0; 5], [0; 5], [0.0; 5]);
        lu_factor(&mut a, 1e-14, LuWork { pivots: &mut pivots, columns: &mut columns, scale: &mut scale }).map_err(|_| dependent(t))?;
        lu_solve_in_place(&a, &pivots, &mut b);
        *vd = [b[0], b[1], b[2]];
        *lambda = [b[3], b[4]];
        Ok(())
    }

    fn project_positions_step(&self, q: &mut [f64; 4], t: f64, _options: &DynamicsOptions<f64>) -> Result<f64, DynamicsError> {
        let (phi, d) = pin(q);
        let x = schur_solve(&d, phi).ok_or(dependent(t))?;
        let step = minv_dt(&d, x).map(|s| -s);
        integrate(q, &step, 1.0);
        Ok(phi[0].abs().max(phi[1].abs()))
    }

    fn project_velocities(&self, q: &[f64; 4], v: &mut [f64; 3], t: f64, _options: &DynamicsOptions<f64>) -> Result<f64, DynamicsError> {
        let (_, d) = pin(q);
        let violation: [f64; 2] = core::array::from_fn(|r| (0..3).map(|i| d[r][i] * v[i]).sum());
        let x = schur_solve(&d, violation).ok_or(dependent(t))?;
        for (vi, correction) in v.iter_mut().zip(minv_dt(&d, x)) {
            *vi -= correction;
        }
        Ok(violation[0].abs().max(violation[1].abs()))
    }
}

/// The pendulum driven at the angular speed Ω (rad/s): NQ = 4, NV = 3, NC = 3.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DrivenUnitPendulum {
    /// Ω (rad/s).
    pub omega: f64,
}

impl Mechanism for DrivenUnitPendulum {
    const NAME: &'static str = "DrivenUnitPendulum";
    const BODY_NAMES: &'static [&'static str] = &["rod"];
    const COORDINATE_NAMES: &'static [&'static str] = COORDINATES;
    const VELOCITY_NAMES: &'static [&'static str] = VELOCITIES;
    const COORDINATES: &'static [CoordinateInfo] = COORDINATE_INFO;
    const VELOCITIES: &'static [VelocityInfo] = VELOCITY_INFO;
    const CONSTRAINT_NAMES: &'static [&'static str] = &["pin: x", "pin: y", "drive: angle"];
    const PARAM_NAMES: &'static [&'static str] = &["omega"];
    const DOF: i32 = 0;
    const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[(0, 0), (0, 2), (1, 1), (1, 2), (2, 2)];
    const PHI_T_IS_ZERO: bool = false;
    const OP_COUNTS: &'static [OpCount] = &[];
    const MODEL_JSON: &'static str = "{}";
}

impl DrivenUnitPendulum {
    /// Φ and D.
    fn rows(&self, q: &[f64; 4], t: f64) -> ([f64; 3], [[f64; 3]; 3]) {
        let ((pin_phi, pin_d), (sf, cf)) = (pin(q), (self.omega * t).sin_cos());
        let (c, s) = (q[2], q[3]);
        ([pin_phi[0], pin_phi[1], s * cf - c * sf], [pin_d[0], pin_d[1], [0.0, 0.0, c * cf + s * sf]])
    }
}

impl KinematicsHooks<f64, 4, 3, 3> for DrivenUnitPendulum {}

impl Kinematics<f64, 4, 3, 3> for DrivenUnitPendulum {
    fn initial_positions(&self) -> [f64; 4] {
        UnitPendulum.initial_positions()
    }
    fn initial_velocities(&self) -> [f64; 3] {
        [0.0; 3]
    }
    fn position_rates(&self, q: &[f64; 4], v: &[f64; 3], qdot: &mut [f64; 4]) {
        *qdot = rates(q, v);
    }
    fn integrate_positions(&self, q: &mut [f64; 4], dv: &[f64; 3], h: f64) {
        integrate(q, dv, h);
    }
    fn normalize_positions(&self, q: &mut [f64; 4]) {
        normalize(q);
    }
    fn constraints(&self, q: &[f64; 4], t: f64, phi: &mut [f64; 3]) {
        *phi = self.rows(q, t).0;
    }
    fn jacobian(&self, q: &[f64; 4], t: f64, d: &mut [[f64; 3]; 3]) {
        *d = self.rows(q, t).1;
    }
    fn velocity_rhs(&self, q: &[f64; 4], t: f64, nu: &mut [f64; 3]) {
        let (sf, cf) = (self.omega * t).sin_cos();
        *nu = [0.0, 0.0, self.omega * (q[2] * cf + q[3] * sf)];
    }
    fn gamma(&self, q: &[f64; 4], v: &[f64; 3], t: f64, gamma: &mut [f64; 3]) {
        let (sf, cf) = (self.omega * t).sin_cos();
        let [gx, gy] = pin_gamma(q, v);
        let slip = v[2] - self.omega;
        *gamma = [gx, gy, slip * slip * (q[3] * cf - q[2] * sf)];
    }
    fn position_eval(&self, q: &[f64; 4], t: f64, phi: &mut [f64; 3], d: &mut [[f64; 3]; 3]) {
        (*phi, *d) = self.rows(q, t);
    }
    fn full_eval(
        &self,
        q: &[f64; 4],
        v: &[f64; 3],
        t: f64,
        phi: &mut [f64; 3],
        d: &mut [[f64; 3]; 3],
        nu: &mut [f64; 3],
        gamma: &mut [f64; 3],
    ) {
        self.position_eval(q, t, phi, d);
        self.velocity_rhs(q, t, nu);
        self.gamma(q, v, t, gamma);
    }
}

/// The Newton matrix dense, in the order v̇ then λ (every multiplier after the velocities).
impl crate::model::mechanism::NewtonMatrix<f64, 4, 3, 2> for UnitPendulum {
    type NewtonStorage = [f64; 4 + 25];
    const NEWTON_PATTERN: crate::linalg::sparse::SparsePattern = crate::linalg::sparse::SparsePattern {
        unknown: &[0, 1, 2, 3, 4],
        position: &[0, 1, 2, 3, 4],
        row_start: &[0, 5, 10, 15, 20, 25],
        columns: &[0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 0, 1, 2, 3, 4],
        diagonal: &[0, 6, 12, 18, 24],
    };
    fn newton_storage() -> Self::NewtonStorage {
        [0.0; 29]
    }
}
