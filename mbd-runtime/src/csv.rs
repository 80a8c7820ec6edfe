//! Simulation output as CSV (feature `std`): one row per [`Sample`], columns
//! `t, <coordinate>…, <velocity>…, <acceleration>…, lambda <constraint row>…, kinetic, potential,
//! nonconservative_work, constraint_work`, in SI units, named from the mechanism so a
//! spreadsheet or pandas reads it without a legend: q from [`Mechanism::COORDINATE_NAMES`]; v
//! and v̇ from [`Mechanism::VELOCITY_NAMES`], planar as `d/dt crank.x` and `d2/dt2 crank.x`
//! (v = q̇), spatial as `top.wx` and `d/dt top.wx`.

use std::io::{self, Write};

use crate::{Mechanism, Real, Sample};

/// Writes samples as CSV rows; use [`CsvWriter::write`] as (or inside) the output callback of
/// [`crate::simulate`] and [`CsvWriter::finish`] after it for the first I/O error, if any.
pub struct CsvWriter<W: Write> {
    out: W,
    error: Option<io::Error>,
    rows: u64,
}

impl<W: Write> CsvWriter<W> {
    /// A writer that has written the header row for mechanism `M`.
    pub fn new<M: Mechanism>(mut out: W) -> Self {
        let mut header = String::from("t");
        // Planar velocities are the coordinates' rates; spatial ones have names of their own.
        let (velocity, acceleration) = if M::DIMENSION == 3 { ("", "d/dt ") } else { ("d/dt ", "d2/dt2 ") };
        for (prefix, names) in [("", M::COORDINATE_NAMES), (velocity, M::VELOCITY_NAMES), (acceleration, M::VELOCITY_NAMES)] {
            for name in names {
                header.push(',');
                header.push_str(prefix);
                header.push_str(name);
            }
        }
        for name in M::CONSTRAINT_NAMES {
            header.push_str(",lambda ");
            header.push_str(&name.replace(',', ";"));
        }
        header.push_str(",kinetic,potential,nonconservative_work,constraint_work\n");
        let error = out.write_all(header.as_bytes()).err();
        Self { out, error, rows: 0 }
    }

    /// Appends one sample (does nothing after an I/O error).
    pub fn write<T: Real, const NQ: usize, const NV: usize, const NC: usize>(&mut self, s: &Sample<T, NQ, NV, NC>) {
        if self.error.is_some() {
            return;
        }
        let p = &s.point;
        let e = &s.energy;
        let values = core::iter::once(p.t)
            .chain(p.q.iter().copied())
            .chain(p.v.iter().copied())
            .chain(p.vd.iter().copied())
            .chain(p.lambda.iter().copied())
            .chain([e.kinetic, e.potential, e.nonconservative_work, e.constraint_work]);
        let mut line = String::new();
        for (k, v) in values.enumerate() {
            if k > 0 {
                line.push(',');
            }
            line.push_str(&format!("{:e}", v.to_f64()));
        }
        line.push('\n');
        match self.out.write_all(line.as_bytes()) {
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
