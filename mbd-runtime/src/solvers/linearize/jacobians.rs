//! The linear model's matrices: exact from the generated derivatives, or by central
//! differences of the forward dynamics along the chart; the inputs' columns.

use super::*;

/// What an input is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Input {
    /// A parameter, by index into [`Linearize::INPUTS`].
    Load(usize),
    /// A driver's acceleration, by its row of Φ.
    Driver(usize),
}

/// The inputs the options name.
pub(super) fn input_kinds<M: Linearize<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    options: &LinearizeOptions,
) -> Result<Vec<Input>, LinearizeError> {
    let is_driver = |j: &&crate::model::mechanism::JointInfo| j.kind.starts_with("drive") && j.rows == 1;
    options
        .inputs
        .iter()
        .map(|&name| {
            if let Some(k) = M::INPUTS.iter().position(|&n| n == name) {
                return Ok(Input::Load(k));
            }
            if let Some(j) = M::JOINTS.iter().filter(is_driver).find(|j| j.name == name) {
                return Ok(Input::Driver(j.first_row as usize));
            }
            let choices = M::INPUTS.iter().copied().chain(M::JOINTS.iter().filter(is_driver).map(|j| j.name)).collect();
            let what = if M::PARAM_NAMES.contains(&name) {
                "input (a parameter that also sets the geometry, the masses or friction)"
            } else {
                "input"
            };
            Err(LinearizeError::UnknownName { what, name: name.to_string(), choices })
        })
        .collect()
}

/// [`Linearizer::linearize`].
pub(super) fn exact<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    options: &LinearizeOptions,
) -> Result<Linearization, LinearizeError>
where
    M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC>,
{
    let (inputs, chart) = prepare(m, q, v, t, options)?;
    let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
    m.accelerations_in(HeapArrays::new().scratch(), q, v, t, &DynamicsOptions::without_stabilization(), &mut vd, &mut lambda)?;

    // The derivatives, dense.
    let (mut a1, mut a2) = (boxed::<NV, NV>(), boxed::<NV, NV>());
    m.add_mass_matrix(q, 1.0, &mut a1);
    let mass = dense(&a1);
    m.forces_q(q, v, t, &mut a1);
    m.forces_v(q, v, t, &mut a2);
    m.friction_derivatives(q, v, t, &lambda, &mut a1, &mut a2);
    let (mut h, h_v) = (dense(&a1), dense(&a2));
    m.constraint_force_q(q, t, &lambda, &mut a1);
    h += dense(&a1);
    // M(q) v̇ − Dᵀλ = h: where M depends on q (joint coordinates) its change at the solved v̇
    // acts as a force, −(∂(M v̇)/∂q) B.
    for row in a1.iter_mut() {
        *row = [0.0; NV];
    }
    m.add_mass_derivative(q, &vd, -1.0, &mut a1);
    h += dense(&a1);
    let (mut g1, mut g2) = (boxed::<NC, NV>(), boxed::<NC, NV>());
    let mut gamma_v_at = |a: &[f64; NV]| {
        m.gamma_derivatives(q, a, t, &mut g1, &mut g2);
        (dense(&g1), dense(&g2))
    };
    // ½ Γ_v(q₀, 0) = ν_q B, and Q(a) = ∂(D a)/∂q B for a = v₀ and v̇₀.
    let (_, gamma_v0) = gamma_v_at(&[0.0; NV]);
    let (gamma_q, gamma_v) = gamma_v_at(v);
    let (q_v, q_a) = if velocities_are_rates::<M>() {
        // Where q̇ = v (in the plane) Q(a)b = Φ_qq(a, b) is symmetric in a and b, so
        // Γ_v(a) = −2 Q(a) − 2 Φ_tq and Q(a) = −½ (Γ_v(a) − Γ_v(0)): two evaluations of γ's
        // derivatives.
        let (_, gamma_va) = gamma_v_at(&vd);
        ((&gamma_v - &gamma_v0) * -0.5, (gamma_va - &gamma_v0) * -0.5)
    } else {
        // In space B(q) makes Q(a)b − Q(b)a = Φ_q [Bb, Ba] ≠ 0: row r is aᵀ K(e_r).
        let (mut q_v, mut q_a) = (DMatrix::zeros(NC, NV), DMatrix::zeros(NC, NV));
        let (v0, a0) = (DVector::from_column_slice(v), DVector::from_column_slice(&vd));
        for &r in &chart.rows {
            let mut unit = [0.0; NC];
            unit[r] = 1.0;
            m.constraint_force_q(q, t, &unit, &mut a1);
            let k = dense(&a1);
            q_v.row_mut(r).copy_from(&(v0.transpose() * &k));
            q_a.row_mut(r).copy_from(&(a0.transpose() * &k));
        }
        (q_v, q_a)
    };
    let g = q_v - gamma_v0 * 0.5;
    let mut h_u = DMatrix::zeros(NV, inputs.len());
    for (j, &input) in inputs.iter().enumerate() {
        if let Input::Load(k) = input {
            let mut column = [0.0; NV];
            m.forces_input(k, q, v, t, &mut column);
            h_u.column_mut(j).copy_from_slice(&column);
        }
    }

    // The saddle-point system [[M, −Dᵀ], [D, 0]] [δv̇; δλ] = [top; bottom] over the independent
    // rows, one column per state and input, solved in the null space: δv̇ = Z s + R bottom with
    // s = M_r⁻¹ Zᵀ (top − M R bottom), and E δv̇ = s is A's row; δλ = Rᵀ (M δv̇ − top).
    let (f, nr, ni) = (chart.independent.len(), chart.rows.len(), inputs.len());
    let pick = |a: &DMatrix<f64>| DMatrix::from_fn(nr, a.ncols(), |i, c| a[(chart.rows[i], c)]);
    let z = &chart.z;
    let correction = &chart.r * pick(&g) * z; // δv = Z w − R G Z y
    let mut top = DMatrix::zeros(NV, 2 * f + ni);
    let mut bottom = DMatrix::zeros(nr, 2 * f + ni);
    top.view_mut((0, 0), (NV, f)).copy_from(&(&h * z - &h_v * &correction));
    bottom.view_mut((0, 0), (nr, f)).copy_from(&(pick(&(&gamma_q - &q_a)) * z - pick(&gamma_v) * &correction));
    top.view_mut((0, f), (NV, f)).copy_from(&(&h_v * z));
    bottom.view_mut((0, f), (nr, f)).copy_from(&(pick(&gamma_v) * z));
    top.view_mut((0, 2 * f), (NV, ni)).copy_from(&h_u);
    for (j, &input) in inputs.iter().enumerate() {
        // A driver's row reads D v̇ = γ_r + u: its acceleration input.
        if let Some(i) = chart.rows.iter().position(|&r| Input::Driver(r) == input) {
            bottom[(i, 2 * f + j)] = 1.0;
        }
    }
    let particular = &chart.r * &bottom;
    let reduced_mass = z.transpose() * &mass * z;
    let s = Cholesky::new(reduced_mass).ok_or(LinearizeError::Singular)?.solve(&(z.transpose() * (&top - &mass * &particular)));
    let mut a = DMatrix::zeros(2 * f, 2 * f);
    if !velocities_are_rates::<M>() {
        let omega_z = omega::<M, NV>(v) * z;
        a.view_mut((0, 0), (f, f)).copy_from(&DMatrix::from_fn(f, f, |i, k| omega_z[(chart.independent[i], k)]));
    }
    a.view_mut((0, f), (f, f)).fill_with_identity();
    a.view_mut((f, 0), (f, 2 * f)).copy_from(&s.columns(0, 2 * f));
    let mut b = DMatrix::zeros(2 * f, ni);
    b.view_mut((f, 0), (f, ni)).copy_from(&s.columns(2 * f, ni));
    let multipliers = if options.outputs.iter().any(|o| matches!(o, Output::Multiplier(_))) {
        let accelerations = z * &s + particular;
        chart.r.transpose() * (&mass * accelerations - &top)
    } else {
        DMatrix::zeros(nr, 2 * f + ni)
    };

    // Outputs.
    let no = options.outputs.len();
    let (mut c, mut dd) = (DMatrix::zeros(no, 2 * f), DMatrix::zeros(no, ni));
    for (o, output) in options.outputs.iter().enumerate() {
        match output {
            Output::Displacement(name) => {
                let i = find("displacement (a velocity direction)", name, M::VELOCITY_NAMES)?;
                c.view_mut((o, 0), (1, f)).copy_from(&z.row(i));
            }
            Output::Velocity(name) => {
                let i = find("velocity", name, M::VELOCITY_NAMES)?;
                c.view_mut((o, 0), (1, f)).copy_from(&(-correction.row(i)));
                c.view_mut((o, f), (1, f)).copy_from(&z.row(i));
            }
            Output::Multiplier(name) => {
                let row = find("constraint row", name, M::CONSTRAINT_NAMES)?;
                if let Some(i) = chart.rows.iter().position(|&r| r == row) {
                    c.row_mut(o).copy_from(&multipliers.view((i, 0), (1, 2 * f)));
                    dd.row_mut(o).copy_from(&multipliers.view((i, 2 * f), (1, ni)));
                }
            }
            Output::Rate { rate, .. } => {
                for k in 0..f {
                    c[(o, k)] = rate(q, z.column(k).as_slice());
                }
            }
        }
    }
    Ok(assemble::<M>((t, q, v), a, b, c, dd, mass, chart, options))
}

/// The model's matrices with the second-order form and the names.
#[allow(clippy::too_many_arguments)]
pub(super) fn assemble<M: Mechanism>(
    (t, q, v): (f64, &[f64], &[f64]),
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    d: DMatrix<f64>,
    mass: DMatrix<f64>,
    chart: Chart,
    options: &LinearizeOptions,
) -> Linearization {
    let f = chart.independent.len();
    let mass_diagonal = mass.diagonal().iter().copied().collect();
    let reduced_mass = chart.z.transpose() * mass * &chart.z;
    let stiffness = -(&reduced_mass * a.view((f, 0), (f, f)));
    let damping = -(&reduced_mass * a.view((f, f), (f, f)));
    let input_forces = &reduced_mass * b.rows(f, f);
    let input_names = options.inputs.iter().map(|n| n.to_string()).collect();
    Linearization {
        t,
        q: q.to_vec(),
        v: v.to_vec(),
        state_names: state_names::<M>(&chart.independent),
        a,
        b,
        c,
        d,
        mass: reduced_mass,
        damping,
        stiffness,
        input_forces,
        basis: chart.z,
        independent: chart.independent,
        input_names,
        output_names: options.outputs.iter().map(Output::name).collect(),
        velocity_names: M::VELOCITY_NAMES,
        mass_diagonal,
    }
}

/// [`Linearizer::finite_differences`].
pub(super) fn finite_differences<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    options: &LinearizeOptions,
) -> Result<Linearization, LinearizeError>
where
    M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC> + Clone,
{
    let (inputs, chart) = prepare(m, q, v, t, options)?;
    let f = chart.independent.len();
    let ni = inputs.len();
    let no = options.outputs.len();
    // The state (y, w) at (q, v): y = 0, w = E v.
    let x0: Vec<f64> = (0..f).map(|_| 0.0).chain(chart.independent.iter().map(|&i| v[i])).collect();
    let u0: Vec<f64> = inputs
        .iter()
        .map(|&input| match input {
            Input::Load(k) => m.input(k),
            Input::Driver(_) => 0.0,
        })
        .collect();
    // ẋ and the outputs at (x, u).
    let mut arrays = HeapArrays::<NV, NC>::new();
    let mut evaluate = |x: &[f64], u: &[f64]| -> Result<(Vec<f64>, Vec<f64>), LinearizeError> {
        let mut model = m.clone();
        let mut offsets = [0.0; NC];
        for (&input, &value) in inputs.iter().zip(u) {
            match input {
                Input::Load(k) => model.set_input(k, value),
                Input::Driver(row) => offsets[row] = value,
            }
        }
        let (qx, delta) = chart.position::<M, NQ, NV, NC>(m, q, t, &x[..f])?;
        let vx = chart.velocity::<M, NQ, NV, NC>(m, &qx, t, &x[f..])?;
        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
        model.accelerations_in(arrays.scratch(), &qx, &vx, t, &DynamicsOptions::without_stabilization(), &mut vd, &mut lambda)?;
        if offsets.iter().any(|&o| o != 0.0) {
            // A driver's acceleration offset: the saddle-point system at this state with γ_r + u
            // (and the joints' friction at the loads just found), solved densely.
            driven_accelerations(&model, &chart, &qx, &vx, t, &offsets, &mut vd, &mut lambda)?;
        }
        let rates = displacement_rates::<M, NQ, NV>(q, &qx, &vx);
        let xdot: Vec<f64> = chart.independent.iter().map(|&i| rates[i]).chain(chart.independent.iter().map(|&i| vd[i])).collect();
        let mut y = Vec::with_capacity(no);
        for output in &options.outputs {
            y.push(match output {
                Output::Displacement(name) => delta[find("displacement (a velocity direction)", name, M::VELOCITY_NAMES)?],
                Output::Velocity(name) => vx[find("velocity", name, M::VELOCITY_NAMES)?],
                Output::Multiplier(name) => lambda[find("constraint row", name, M::CONSTRAINT_NAMES)?],
                Output::Rate { rate, .. } => rate(q, &delta),
            });
        }
        Ok((xdot, y))
    };
    // Central differences along each state, then each input: (ẋ, y) columns.
    let mut columns = Vec::with_capacity(2 * f + ni);
    for k in 0..2 * f + ni {
        let (which, i) = if k < 2 * f { (0, k) } else { (1, k - 2 * f) };
        let mut args = [x0.clone(), u0.clone()];
        let at = args[which][i];
        let h = f64::EPSILON.cbrt() * at.abs().max(1.0);
        args[which][i] = at + h;
        let plus = evaluate(&args[0], &args[1])?;
        args[which][i] = at - h;
        let minus = evaluate(&args[0], &args[1])?;
        let difference = |p: &[f64], m: &[f64]| p.iter().zip(m).map(|(a, b)| (a - b) / (2.0 * h)).collect::<Vec<f64>>();
        columns.push((difference(&plus.0, &minus.0), difference(&plus.1, &minus.1)));
    }
    let a = DMatrix::from_fn(2 * f, 2 * f, |i, k| columns[k].0[i]);
    let b = DMatrix::from_fn(2 * f, ni, |i, k| columns[2 * f + k].0[i]);
    let c = DMatrix::from_fn(no, 2 * f, |i, k| columns[k].1[i]);
    let dd = DMatrix::from_fn(no, ni, |i, k| columns[2 * f + k].1[i]);
    let mut mass = boxed::<NV, NV>();
    m.add_mass_matrix(q, 1.0, &mut mass);
    Ok(assemble::<M>((t, q, v), a, b, c, dd, dense(&mass), chart, options))
}

/// v̇ and λ from [[M, −Dᵀ], [D, 0]] [v̇; λ] = [h + h_f(λ); γ + offsets] over the chart's rows,
/// the friction h_f at the λ passed in.
#[allow(clippy::too_many_arguments)]
pub(super) fn driven_accelerations<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    chart: &Chart,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    offsets: &[f64; NC],
    vd: &mut [f64; NV],
    lambda: &mut [f64; NC],
) -> Result<(), LinearizeError>
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let (mut h, mut gamma) = ([0.0; NV], [0.0; NC]);
    m.forces(q, v, t, &mut h);
    m.friction_forces(q, v, t, lambda, &mut h);
    m.gamma(q, v, t, &mut gamma);
    let (mut mass, mut d) = (boxed::<NV, NV>(), boxed::<NC, NV>());
    m.add_mass_matrix(q, 1.0, &mut mass);
    m.jacobian(q, t, &mut d);
    let nr = chart.rows.len();
    let mut kkt = DMatrix::zeros(NV + nr, NV + nr);
    let mut rhs = DVector::zeros(NV + nr);
    for i in 0..NV {
        rhs[i] = h[i];
        for j in 0..NV {
            kkt[(i, j)] = mass[i][j];
        }
    }
    for (k, &r) in chart.rows.iter().enumerate() {
        rhs[NV + k] = gamma[r] + offsets[r];
        for j in 0..NV {
            kkt[(NV + k, j)] = d[r][j];
            kkt[(j, NV + k)] = -d[r][j];
        }
    }
    let x = kkt.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
    vd.copy_from_slice(x.rows(0, NV).as_slice());
    *lambda = [0.0; NC];
    for (k, &r) in chart.rows.iter().enumerate() {
        lambda[r] = x[NV + k];
    }
    Ok(())
}
