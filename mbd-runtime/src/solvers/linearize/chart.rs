//! The chart of the linear model: the independent velocities' displacements δ_I, the dependent
//! ones that keep Φ = 0, and the names and rotation rates (Ω) of the states.

use super::*;

/// The chart at a state: which velocities are independent, and the basis that goes with them.
pub(super) struct Chart {
    /// Independent velocities.
    pub(super) independent: Vec<usize>,
    /// Dependent velocities (as many as `rows`).
    pub(super) dependent: Vec<usize>,
    /// The independent constraint rows.
    pub(super) rows: Vec<usize>,
    /// Z (NV × f).
    pub(super) z: DMatrix<f64>,
    /// R (NV × rows): R_D = D_D⁻¹ over the independent rows, R_I = 0.
    pub(super) r: DMatrix<f64>,
}

impl Chart {
    /// Full pivoting on D with each row scaled to its largest entry; the columns of `forced`
    /// never pivot (they stay independent).
    pub(super) fn new(d: &DMatrix<f64>, forced: &[usize], tolerance: f64) -> Result<Chart, LinearizeError> {
        let (nc, nv) = d.shape();
        let mut work = d.clone();
        for mut row in work.row_iter_mut() {
            let scale = row.amax();
            if scale > 0.0 {
                row /= scale;
            }
        }
        let (mut rows, mut dependent) = (Vec::new(), Vec::new());
        let (mut row_used, mut column_used) = (vec![false; nc], vec![false; nv]);
        for &c in forced {
            column_used[c] = true;
        }
        loop {
            let mut best = (tolerance, None);
            for r in (0..nc).filter(|&r| !row_used[r]) {
                for c in (0..nv).filter(|&c| !column_used[c]) {
                    if work[(r, c)].abs() > best.0 {
                        best = (work[(r, c)].abs(), Some((r, c)));
                    }
                }
            }
            let Some((pr, pc)) = best.1 else { break };
            row_used[pr] = true;
            column_used[pc] = true;
            for r in (0..nc).filter(|&r| !row_used[r]) {
                let factor = work[(r, pc)] / work[(pr, pc)];
                if factor != 0.0 {
                    for c in 0..nv {
                        work[(r, c)] -= factor * work[(pr, c)];
                    }
                }
            }
            rows.push(pr);
            dependent.push(pc);
        }
        let independent: Vec<usize> = (0..nv).filter(|c| !dependent.contains(c)).collect();
        let dd = DMatrix::from_fn(rows.len(), rows.len(), |i, j| d[(rows[i], dependent[j])]);
        let di = DMatrix::from_fn(rows.len(), independent.len(), |i, j| d[(rows[i], independent[j])]);
        let lu = dd.lu();
        let inverse = lu.try_inverse().ok_or(LinearizeError::Singular)?;
        let zd = -(&inverse * di);
        let mut z = DMatrix::zeros(nv, independent.len());
        let mut r = DMatrix::zeros(nv, rows.len());
        for (k, &c) in independent.iter().enumerate() {
            z[(c, k)] = 1.0;
        }
        for (i, &c) in dependent.iter().enumerate() {
            z.row_mut(c).copy_from(&zd.row(i));
            r.row_mut(c).copy_from(&inverse.row(i));
        }
        Ok(Chart { independent, dependent, rows, z, r })
    }

    /// The chart at q₀ for the options: named independent velocities, or pivoting.
    pub(super) fn choose<M: Mechanism>(d: &DMatrix<f64>, options: &LinearizeOptions) -> Result<Chart, LinearizeError> {
        let free = Chart::new(d, &[], options.rank_tolerance)?;
        if options.independent.is_empty() {
            return Ok(free);
        }
        let forced = options.independent.iter().map(|n| find("velocity", n, M::VELOCITY_NAMES)).collect::<Result<Vec<_>, _>>()?;
        if forced.len() != free.independent.len() {
            return Err(LinearizeError::BadIndependent {
                reason: format!(
                    "{} named, but the mechanism has {} degrees of freedom at this state (e.g. {})",
                    forced.len(),
                    free.independent.len(),
                    free.independent.iter().map(|&i| M::VELOCITY_NAMES[i]).collect::<Vec<_>>().join(", ")
                ),
            });
        }
        let chart = Chart::new(d, &forced, options.rank_tolerance)?;
        if chart.rows.len() < free.rows.len() {
            let missing = free.rows.iter().find(|r| !chart.rows.contains(r)).copied().unwrap_or(0);
            return Err(LinearizeError::BadIndependent {
                reason: format!(
                    "{} cannot all be independent: with them given, the other velocities cannot satisfy the constraint row `{}`",
                    options.independent.join(", "),
                    M::CONSTRAINT_NAMES.get(missing).copied().unwrap_or("?")
                ),
            });
        }
        Ok(chart)
    }
}

/// Checks that (q, v) is on the manifold; returns D.
// `!(x <= tolerance)` on purpose: a NaN fails too.
/// Ω = ∂δ̇/∂δ: −½[ω₀′×] on the rotation of each body whose orientation is a quaternion, 0 on
/// everything else (module docs; 0 in the plane).
pub(super) fn omega<M: Mechanism, const NV: usize>(v: &[f64; NV]) -> DMatrix<f64> {
    let mut o = DMatrix::zeros(NV, NV);
    for b in angular_triples::<M>().filter(|&b| b + 3 <= NV) {
        let w = [v[b], v[b + 1], v[b + 2]];
        // −½ [w×]: [w×] = [[0, −w3, w2], [w3, 0, −w1], [−w2, w1, 0]]
        let cross = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
        for r in 0..3 {
            for c in 0..3 {
                o[(b + r, b + c)] = -0.5 * cross[r][c];
            }
        }
    }
    o
}

/// The first index into v of each body-frame angular velocity ω′ (its x′ component; y′ and z′
/// follow).
pub(super) fn angular_triples<M: Mechanism>() -> impl Iterator<Item = usize> {
    M::VELOCITIES.iter().enumerate().filter_map(|(i, v)| matches!(v.kind, VelocityKind::Angular { axis: 0, .. }).then_some(i))
}

/// Names of the states: displacements (`"crank.phi"`, `"top.x"`, `"top.rx"`), then rates
/// (`"crank.phi_dot"` for a velocity named as its coordinate, else the velocity's own name,
/// `"top.wx"`).
pub(super) fn state_names<M: Mechanism>(independent: &[usize]) -> Vec<String> {
    let position = |i: usize| M::VELOCITIES[i].displacement.to_string();
    let rate = |i: usize| {
        let v = &M::VELOCITIES[i];
        if v.is_named_rate::<M>() {
            format!("{}_dot", v.name)
        } else {
            v.name.to_string()
        }
    };
    independent.iter().map(|&i| position(i)).chain(independent.iter().map(|&i| rate(i))).collect()
}

impl Chart {
    /// q₀ ⊕ δ with δ_I = y and δ_D such that Φ = 0 (Newton, D_D at the current q); returns q
    /// and δ.
    pub(super) fn position<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q0: &[f64; NQ],
        t: f64,
        y: &[f64],
    ) -> Result<([f64; NQ], [f64; NV]), LinearizeError>
    where
        M: ForwardDynamics<f64, NQ, NV, NC>,
    {
        let mut delta = [0.0; NV];
        for (&i, &value) in self.independent.iter().zip(y) {
            delta[i] = value;
        }
        let mut d = boxed::<NC, NV>();
        let mut phi = [0.0; NC];
        for _ in 0..50 {
            let mut q = *q0;
            m.integrate_positions(&mut q, &delta, 1.0);
            m.position_eval(&q, t, &mut phi, &mut d);
            let residual = self.rows.iter().fold(0.0f64, |a, &r| a.max(phi[r].abs()));
            if residual <= 1e-15 * (1.0 + q.iter().fold(0.0f64, |a, b| a.max(b.abs()))) {
                return Ok((q, delta));
            }
            let dd = DMatrix::from_fn(self.rows.len(), self.rows.len(), |i, j| d[self.rows[i]][self.dependent[j]]);
            let rhs = DVector::from_fn(self.rows.len(), |i, _| -phi[self.rows[i]]);
            let step = dd.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
            for (&c, &s) in self.dependent.iter().zip(step.iter()) {
                delta[c] += s;
            }
        }
        let worst = self.rows.iter().copied().max_by(|&a, &b| phi[a].abs().total_cmp(&phi[b].abs())).unwrap_or(0);
        Err(LinearizeError::NotAssembled { row: M::CONSTRAINT_NAMES[worst], value: phi[worst] })
    }

    /// v with v_I = w and D v = ν at q.
    pub(super) fn velocity<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &[f64; NQ],
        t: f64,
        w: &[f64],
    ) -> Result<[f64; NV], LinearizeError>
    where
        M: ForwardDynamics<f64, NQ, NV, NC>,
    {
        let mut d = boxed::<NC, NV>();
        let mut nu = [0.0; NC];
        m.jacobian(q, t, &mut d);
        m.velocity_rhs(q, t, &mut nu);
        let mut v = [0.0; NV];
        for (&i, &value) in self.independent.iter().zip(w) {
            v[i] = value;
        }
        let dd = DMatrix::from_fn(self.rows.len(), self.rows.len(), |i, j| d[self.rows[i]][self.dependent[j]]);
        let rhs = DVector::from_fn(self.rows.len(), |i, _| {
            let r = self.rows[i];
            nu[r] - self.independent.iter().map(|&c| d[r][c] * v[c]).sum::<f64>()
        });
        if self.rows.is_empty() {
            // No constraint (a tree in joint coordinates): v is w (nalgebra's LU solve of a
            // 0 × 0 system underflows an index).
            return Ok(v);
        }
        let vd = dd.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
        for (&c, &value) in self.dependent.iter().zip(vd.iter()) {
            v[c] = value;
        }
        Ok(v)
    }
}

/// δ̇ at q = q₀ ⊕ δ moving with v: v for a rate; for each body-frame angular velocity ω′, the
/// rate of the chart's rotation vector θ = 2 p_v / p_s, p = e₀* ⊗ e, from ṗ = ½ p ⊗ (0, ω′), e the
/// body's quaternion.
pub(super) fn displacement_rates<M: Mechanism, const NQ: usize, const NV: usize>(
    q0: &[f64; NQ],
    q: &[f64; NQ],
    v: &[f64; NV],
) -> [f64; NV] {
    let mut rates = *v;
    for b in angular_triples::<M>().filter(|&b| b + 3 <= NV) {
        let VelocityKind::Angular { quaternion, .. } = M::VELOCITIES[b].kind else { continue };
        let c = quaternion as usize;
        if c + 4 > NQ {
            continue;
        }
        let (e0, e) = (&q0[c..c + 4], &q[c..c + 4]);
        // p = conj(e0) ⊗ e
        let p = quaternion_product([e0[0], -e0[1], -e0[2], -e0[3]], [e[0], e[1], e[2], e[3]]);
        let w = &v[b..b + 3];
        let pd = quaternion_product(p, [0.0, w[0], w[1], w[2]]).map(|x| 0.5 * x);
        for a in 0..3 {
            rates[b + a] = 2.0 * (pd[a + 1] * p[0] - p[a + 1] * pd[0]) / (p[0] * p[0]);
        }
    }
    rates
}

pub(super) fn quaternion_product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}
