//! Analysis output as CSV (feature `std`): one row per [`Sample`] of a simulation, columns
//! `t, <coordinate>…, <velocity>…, <acceleration>…, lambda <constraint row>…, kinetic, potential,
//! nonconservative_work, constraint_work`; or, from [`CsvWriter::states`], one row per state of a
//! kinematic sweep, an inverse-dynamics run or a sequence of static equilibria, the same columns
//! without the energies. In SI units, named from the mechanism so a
//! spreadsheet or pandas reads it without a legend: q from [`Mechanism::COORDINATE_NAMES`]; v
//! and v̇ from [`Mechanism::VELOCITY_NAMES`], planar as `d/dt crank.x` and `d2/dt2 crank.x`
//! (v = q̇), spatial as `top.wx` and `d/dt top.wx`. Each header carries its unit: `crank.x (m)`,
//! `d/dt crank.phi (rad/s)`, `lambda revolute crank~rod: x (N)`, `lambda drive crank.phi: phi
//! (N·m)` (a user constraint's multiplier has the unit of force its row's unit calls for, which the
//! header leaves out).

use std::io::{self, Write};

use crate::integrate::Sample;
use crate::model::mechanism::Mechanism;
use crate::real::Real;

/// Writes samples as CSV rows; use [`CsvWriter::write`] as (or inside) the output callback of
/// [`crate::Simulation`] and [`CsvWriter::finish`] after it for the first I/O error, if any.
///
/// Rows are formatted straight into `out` (give it a `BufWriter` for a file): nothing is
/// allocated per row.
pub struct CsvWriter<W: Write> {
    out: W,
    error: Option<io::Error>,
    rows: u64,
    /// Whether the rows end with the four energy columns.
    energies: bool,
}

impl<W: Write> CsvWriter<W> {
    /// A writer for a simulation's samples that has written the header row for mechanism `M`.
    /// Its two work columns are 0 unless the run tracks work
    /// ([`SimulationOptions::track_work`](crate::SimulationOptions::track_work)).
    pub fn new<M: Mechanism>(out: W) -> Self {
        Self::with_header::<M>(out, true)
    }

    /// A writer for states without energies — a kinematic sweep, inverse dynamics (λ holds the
    /// driver forces and joint reactions), static equilibria — that has written the header row
    /// for mechanism `M`; rows by [`CsvWriter::write_state`].
    pub fn states<M: Mechanism>(out: W) -> Self {
        Self::with_header::<M>(out, false)
    }

    fn with_header<M: Mechanism>(mut out: W, energies: bool) -> Self {
        let mut header = String::from("t (s)");
        let mut column = |name: &str, unit: &str| {
            header.push(',');
            header.push_str(name);
            if !unit.is_empty() {
                header.push_str(" (");
                header.push_str(unit);
                header.push(')');
            }
        };
        for c in M::COORDINATES {
            column(c.name, c.kind.unit(0));
        }
        for order in 0..2 {
            for v in M::VELOCITIES {
                column(&format!("{}{}", v.prefix::<M>(order), v.name), v.unit::<M>(order));
            }
        }
        for (i, name) in M::CONSTRAINT_NAMES.iter().enumerate() {
            header.push_str(",lambda ");
            header.push_str(&name.replace(',', ";"));
            if let Some(&unit) = M::CONSTRAINT_UNITS.get(i).filter(|unit| !unit.is_empty()) {
                header.push_str(" (");
                header.push_str(unit);
                header.push(')');
            }
        }
        if energies {
            header.push_str(",kinetic (J),potential (J),nonconservative_work (J),constraint_work (J)");
        }
        header.push('\n');
        let error = out.write_all(header.as_bytes()).err();
        Self { out, error, rows: 0, energies }
    }

    /// Appends one sample (does nothing after an I/O error). A writer from
    /// [`CsvWriter::states`] leaves the energies out.
    pub fn write<T: Real, const NQ: usize, const NV: usize, const NC: usize>(&mut self, s: &Sample<T, NQ, NV, NC>) {
        let p = &s.point;
        let e = &s.energy;
        let energies = [e.kinetic, e.potential, e.nonconservative_work, e.constraint_work];
        self.row(p.t, &p.q, &p.v, &p.vd, &p.lambda, Some(&energies));
    }

    /// Appends one state: time (s), coordinates, velocities, accelerations and multipliers
    /// (does nothing after an I/O error). A writer from [`CsvWriter::new`] leaves its energy
    /// columns empty.
    pub fn write_state<T: Real>(&mut self, t: T, q: &[T], v: &[T], vd: &[T], lambda: &[T]) {
        self.row(t, q, v, vd, lambda, None);
    }

    fn row<T: Real>(&mut self, t: T, q: &[T], v: &[T], vd: &[T], lambda: &[T], energies: Option<&[T; 4]>) {
        if self.error.is_some() {
            return;
        }
        let out = &mut self.out;
        let mut result = write!(out, "{:e}", t.to_f64());
        for x in q.iter().chain(v).chain(vd).chain(lambda) {
            result = result.and_then(|()| write!(out, ",{:e}", x.to_f64()));
        }
        if self.energies {
            match energies {
                Some(e) => {
                    for x in e {
                        result = result.and_then(|()| write!(out, ",{:e}", x.to_f64()));
                    }
                }
                None => result = result.and_then(|()| out.write_all(b",,,,")),
            }
        }
        match result.and_then(|()| out.write_all(b"\n")) {
            Ok(()) => self.rows += 1,
            Err(e) => self.error = Some(e),
        }
    }

    /// Flushes; returns the number of rows written or the first I/O error.
    pub fn finish(mut self) -> io::Result<u64> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.flush()?;
        Ok(self.rows)
    }
}
