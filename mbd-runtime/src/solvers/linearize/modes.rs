//! What a linear model gives: its modes, stability, transfer and output, as text and JSON.

use super::*;

/// Relative size below which a real part counts as 0 in [`Linearization::stability`] and an
/// imaginary part makes no oscillation in [`Linearization::modes`]: of the largest |s|.
pub(super) const ZERO_EIGENVALUE: f64 = 1e-9;

impl Linearization {
    /// Degrees of freedom f of the model (A is 2f × 2f).
    pub fn dof(&self) -> usize {
        self.independent.len()
    }

    /// The eigenvalues of A.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        if self.a.is_empty() {
            return Vec::new();
        }
        match nalgebra::Schur::try_new(self.a.clone(), f64::EPSILON, 10_000) {
            Some(schur) => schur.complex_eigenvalues().iter().copied().collect(),
            None => vec![Complex::new(f64::NAN, f64::NAN); self.a.nrows()],
        }
    }

    /// Whether the second-order form is undamped and symmetric (D_r = 0, K_r = K_rᵀ to
    /// rounding, no rotation term in A₁₁): then the modes are real.
    fn undamped(&self) -> bool {
        let f = self.dof();
        let scale = self.stiffness.amax().max(f64::MIN_POSITIVE);
        self.damping.amax() == 0.0
            && self.a.view((0, 0), (f, f)).amax() == 0.0
            && (&self.stiffness - self.stiffness.transpose()).amax() <= 1e-9 * scale
    }

    /// The modes, by natural frequency (module docs): one per oscillation (a conjugate pair of
    /// eigenvalues) and one per real eigenvalue.
    pub fn modes(&self) -> Vec<Mode> {
        if self.dof() == 0 {
            return Vec::new();
        }
        let mut modes = match self.undamped_modes() {
            Some(modes) => modes,
            None => {
                let eigenvalues = self.eigenvalues();
                let scale = eigenvalues.iter().fold(0.0f64, |a, s| a.max(s.modulus()));
                // one of each conjugate pair: Im s ≥ 0
                eigenvalues
                    .iter()
                    .filter(|s| s.re.is_finite() && s.im >= -ZERO_EIGENVALUE * scale)
                    .map(|&s| self.damped_mode(s, scale))
                    .collect()
            }
        };
        modes.sort_by(|a, b| a.natural_frequency.total_cmp(&b.natural_frequency));
        modes
    }

    /// Undamped modes from the symmetric problem K_r φ = ω² M_r φ, when the model is undamped
    /// (`None` otherwise): M_r = L Lᵀ, (L⁻¹ K_r L⁻ᵀ) x = ω² x, φ = L⁻ᵀ x.
    fn undamped_modes(&self) -> Option<Vec<Mode>> {
        let f = self.dof();
        if !self.undamped() {
            return None;
        }
        let li = Cholesky::new(self.mass.clone())?.l().try_inverse()?;
        let k = &li * &self.stiffness * li.transpose();
        let eigen = SymmetricEigen::new((&k + k.transpose()) * 0.5);
        let modes = eigen
            .eigenvalues
            .iter()
            .enumerate()
            .map(|(j, &w2)| {
                let phi = li.transpose() * eigen.eigenvectors.column(j);
                let shape: Vec<Complex<f64>> = (&self.basis * &phi).iter().map(|&x| Complex::new(x, 0.0)).collect();
                let s = if w2 >= 0.0 { Complex::new(0.0, w2.sqrt()) } else { Complex::new((-w2).sqrt(), 0.0) };
                self.mode(s, shape)
            })
            .collect::<Vec<_>>();
        debug_assert_eq!(modes.len(), f);
        Some(modes)
    }

    /// The mode of eigenvalue s of A (`scale` the largest |s|) by inverse iteration, s' a hair
    /// off s so that the matrix is regular: on the pencil s'² − s' A₂₂ − A₂₁ (f × f) for y when
    /// A₁₁ = 0 (ẏ = w), else on A − s' (2f × 2f).
    fn damped_mode(&self, s: Complex<f64>, scale: f64) -> Mode {
        let f = self.dof();
        let s = if s.im.abs() <= ZERO_EIGENVALUE * scale { Complex::new(s.re, 0.0) } else { s };
        let complex = |m: DMatrix<f64>| m.map(|x| Complex::new(x, 0.0));
        let second_order = self.a.view((0, 0), (f, f)).amax() == 0.0;
        let shift = s + Complex::new(1e-10 * scale.max(1e-300), 1e-10 * scale.max(1e-300));
        let n = if second_order { f } else { 2 * f };
        let mut shifted = if second_order {
            let (a21, a22) = (complex(self.a.view((f, 0), (f, f)).into_owned()), complex(self.a.view((f, f), (f, f)).into_owned()));
            -(a21 + a22 * shift)
        } else {
            -complex(self.a.clone())
        };
        let diagonal = if second_order { shift * shift } else { shift };
        for i in 0..n {
            shifted[(i, i)] += diagonal;
        }
        let lu = shifted.lu();
        let mut x = DVector::from_element(n, Complex::new(1.0, 0.0));
        for _ in 0..3 {
            if let Some(next) = lu.solve(&x) {
                let norm = next.norm();
                if norm.is_finite() && norm > 0.0 {
                    x = next / Complex::new(norm, 0.0);
                }
            }
        }
        let shape: Vec<Complex<f64>> =
            (0..self.basis.nrows()).map(|i| (0..f).fold(Complex::new(0.0, 0.0), |acc, k| acc + x[k] * self.basis[(i, k)])).collect();
        self.mode(s, shape)
    }

    /// A mode of eigenvalue s and (unscaled) shape.
    fn mode(&self, s: Complex<f64>, mut shape: Vec<Complex<f64>>) -> Mode {
        let weight = |i: usize| self.mass_diagonal.get(i).map_or(1.0, |m| m.abs().sqrt());
        let (k, _) =
            shape
                .iter()
                .enumerate()
                .fold((0, 0.0), |best, (i, &x)| if x.modulus() * weight(i) > best.1 { (i, x.modulus() * weight(i)) } else { best });
        let largest = shape.get(k).copied().unwrap_or(Complex::new(0.0, 0.0));
        if largest.modulus() > 0.0 {
            for x in &mut shape {
                *x /= largest;
            }
        }
        let norm = s.modulus();
        let tau = 2.0 * core::f64::consts::PI;
        Mode {
            eigenvalue: s,
            natural_frequency: norm / tau,
            damped_frequency: s.im.abs() / tau,
            // + 0.0: an undamped mode's −0 prints as 0
            damping_ratio: if norm > 0.0 { -s.re / norm + 0.0 } else { 0.0 },
            shape,
            dominant: self.velocity_names.get(k).copied().unwrap_or("?"),
        }
    }

    /// Whether the motion about the state is stable, from the eigenvalues of A: a real part
    /// within 1e-9 of the largest |s| counts as 0.
    pub fn stability(&self) -> LinearStability {
        if self.dof() == 0 {
            return LinearStability::Determined;
        }
        let (eigenvalues, undamped) = match self.undamped_modes() {
            Some(modes) => (modes.iter().map(|m| m.eigenvalue).collect::<Vec<_>>(), Some(modes)),
            None => (self.eigenvalues(), None),
        };
        let scale = eigenvalues.iter().fold(0.0f64, |a, s| a.max(s.modulus()));
        let band = ZERO_EIGENVALUE * scale;
        let Some(&worst) = eigenvalues.iter().max_by(|a, b| a.re.total_cmp(&b.re)) else {
            return LinearStability::Asymptotic { decay: f64::INFINITY };
        };
        if worst.re > band {
            // The shape only of the mode that grows fastest.
            let direction = match &undamped {
                Some(modes) => modes.iter().find(|m| m.eigenvalue == worst).map_or("?", |m| m.dominant),
                None => self.damped_mode(worst, scale).dominant,
            };
            LinearStability::Unstable { growth: worst.re, direction }
        } else if worst.re >= -band {
            LinearStability::Marginal
        } else {
            LinearStability::Asymptotic { decay: -worst.re }
        }
    }

    /// The model as JSON: `{"t", "q", "v", "states", "inputs", "outputs", "velocities",
    /// "independent", "A", "B", "C", "D", "M_r", "D_r", "K_r", "B_r", "Z"}` — the state
    /// linearized about, the names (`"independent"`: the velocities the states are), the matrices
    /// as arrays of rows (Z: NV × f, rows named by `"velocities"`).
    pub fn to_json(&self) -> String {
        let names = |n: &mut dyn Iterator<Item = String>| format!("[{}]", n.map(|s| format!("{s:?}")).collect::<Vec<_>>().join(", "));
        let numbers = |x: &[f64]| format!("[{}]", x.iter().map(|x| json_number(*x)).collect::<Vec<_>>().join(", "));
        let matrix = |m: &DMatrix<f64>| {
            let rows: Vec<String> = m.row_iter().map(|r| numbers(&r.iter().copied().collect::<Vec<_>>())).collect();
            format!("[{}]", rows.join(", "))
        };
        let strings = |n: &[String]| names(&mut n.iter().cloned());
        format!(
            "{{\"t\": {}, \"q\": {}, \"v\": {}, \"states\": {}, \"inputs\": {}, \"outputs\": {}, \"velocities\": {}, \"independent\": {}, \
             \"A\": {}, \"B\": {}, \"C\": {}, \"D\": {}, \"M_r\": {}, \"D_r\": {}, \"K_r\": {}, \"B_r\": {}, \"Z\": {}}}",
            json_number(self.t),
            numbers(&self.q),
            numbers(&self.v),
            strings(&self.state_names),
            strings(&self.input_names),
            strings(&self.output_names),
            names(&mut self.velocity_names.iter().map(|n| n.to_string())),
            names(&mut self.independent.iter().map(|&i| self.velocity_names.get(i).copied().unwrap_or("?").to_string())),
            matrix(&self.a),
            matrix(&self.b),
            matrix(&self.c),
            matrix(&self.d),
            matrix(&self.mass),
            matrix(&self.damping),
            matrix(&self.stiffness),
            matrix(&self.input_forces),
            matrix(&self.basis),
        )
    }

    /// Writes `A.csv`, `B.csv`, `C.csv`, `D.csv`, the second-order form's `M_r.csv`, `D_r.csv`,
    /// `K_r.csv`, `B_r.csv` and the basis `Z.csv` into `dir` (created if missing): a header of
    /// column names (states, inputs, independent displacements) after an empty corner, then one
    /// row per state, output, displacement or velocity, its name first. Full precision (`{:e}`
    /// round-trips). Needs `std`.
    #[cfg(feature = "std")]
    pub fn write_csv(&self, dir: &Path) -> io::Result<()> {
        std::fs::create_dir_all(dir)?;
        let write = |file: &str, m: &DMatrix<f64>, rows: &[String], columns: &[String]| -> io::Result<()> {
            let mut out = io::BufWriter::new(std::fs::File::create(dir.join(file))?);
            writeln!(out, "\"\",{}", columns.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(","))?;
            for (name, row) in rows.iter().zip(m.row_iter()) {
                writeln!(out, "{name:?},{}", row.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(","))?;
            }
            out.flush()
        };
        let f = self.dof();
        let positions = &self.state_names[..f];
        let velocities: Vec<String> = self.velocity_names.iter().map(|n| n.to_string()).collect();
        write("A.csv", &self.a, &self.state_names, &self.state_names)?;
        write("B.csv", &self.b, &self.state_names, &self.input_names)?;
        write("C.csv", &self.c, &self.output_names, &self.state_names)?;
        write("D.csv", &self.d, &self.output_names, &self.input_names)?;
        write("M_r.csv", &self.mass, positions, positions)?;
        write("D_r.csv", &self.damping, positions, positions)?;
        write("K_r.csv", &self.stiffness, positions, positions)?;
        write("B_r.csv", &self.input_forces, positions, &self.input_names)?;
        write("Z.csv", &self.basis, &velocities, positions)
    }
}

/// A JSON number (`null` for NaN and infinities, which JSON cannot hold).
pub(super) fn json_number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:e}")
    } else {
        "null".to_string()
    }
}
