//! [`Plot`]: time histories and x–y plots of named quantities as SVG (feature `plots`, with
//! plotters' SVG backend).
//!
//! Quantities are named as [`crate::CsvWriter`]'s columns, without the units: a coordinate
//! (`"crank.phi"`), a velocity and an acceleration (planar `"d/dt crank.phi"`,
//! `"d2/dt2 slider.x"`; spatial `"top.wx"`, `"d/dt top.wx"`), a multiplier
//! (`"lambda motor: phi"`), an energy (`"kinetic"`, `"potential"`, `"nonconservative_work"`,
//! `"constraint_work"`) — read off a simulation's [`Sample`]s in one call
//! ([`Plot::time_histories`], [`Plot::xy`]); anything else (a point's position, a computed
//! quantity) goes in as its own series of (x, y) pairs ([`Plot::series`]).

use std::fmt;
use std::path::Path;

use plotters::prelude::*;

use crate::integrate::Sample;
use crate::model::mechanism::Mechanism;
use crate::real::Real;

/// A plot of one or more named series of (x, y) points, written as SVG.
#[derive(Clone, Debug, PartialEq)]
pub struct Plot {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<(String, Vec<(f64, f64)>)>,
}

/// Why a plot was not made.
#[derive(Debug)]
#[non_exhaustive]
pub enum PlotError {
    /// A quantity the mechanism does not have.
    UnknownQuantity {
        /// The name given.
        name: String,
        /// The mechanism's.
        mechanism: &'static str,
    },
    /// Drawing or writing the file failed.
    Draw(String),
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlotError::UnknownQuantity { name, mechanism } => write!(
                f,
                "{mechanism} has no quantity `{name}`: name a coordinate (`crank.phi`), a velocity or an acceleration \
                 (`d/dt crank.phi`, `d2/dt2 crank.phi`; spatial `top.wx`, `d/dt top.wx`), a multiplier (`lambda <row>`) or an \
                 energy (`kinetic`, `potential`, `nonconservative_work`, `constraint_work`)"
            ),
            PlotError::Draw(e) => write!(f, "the plot could not be drawn: {e}"),
        }
    }
}

impl std::error::Error for PlotError {}

/// Where a named quantity sits in a [`Sample`].
#[derive(Clone, Copy)]
enum Column {
    Q(usize),
    V(usize),
    Vd(usize),
    Lambda(usize),
    Energy(usize),
}

const ENERGIES: [&str; 4] = ["kinetic", "potential", "nonconservative_work", "constraint_work"];

fn column<M: Mechanism>(name: &str) -> Result<Column, PlotError> {
    let position = |names: &[&str], n: &str| names.iter().position(|&c| c == n);
    // As the CSV header names them (`VelocityInfo::prefix`).
    let velocity = |order: usize| M::VELOCITIES.iter().position(|v| name.strip_prefix(v.prefix::<M>(order)) == Some(v.name));
    let found = if let Some(row) = name.strip_prefix("lambda ") {
        position(M::CONSTRAINT_NAMES, row).map(Column::Lambda)
    } else if let Some(k) = position(&ENERGIES, name) {
        Some(Column::Energy(k))
    } else if let Some(i) = velocity(1) {
        Some(Column::Vd(i))
    } else if let Some(i) = velocity(0) {
        Some(Column::V(i))
    } else {
        position(M::COORDINATE_NAMES, name).map(Column::Q)
    };
    found.ok_or_else(|| PlotError::UnknownQuantity { name: name.to_string(), mechanism: M::NAME })
}

fn value<T: Real, const NQ: usize, const NV: usize, const NC: usize>(s: &Sample<T, NQ, NV, NC>, c: Column) -> f64 {
    let e = &s.energy;
    match c {
        Column::Q(i) => s.point.q[i],
        Column::V(i) => s.point.v[i],
        Column::Vd(i) => s.point.vd[i],
        Column::Lambda(i) => s.point.lambda[i],
        Column::Energy(k) => [e.kinetic, e.potential, e.nonconservative_work, e.constraint_work][k],
    }
    .to_f64()
}

impl Plot {
    /// An empty plot with a title.
    pub fn new(title: impl Into<String>) -> Self {
        Plot { title: title.into(), x_label: String::new(), y_label: String::new(), series: Vec::new() }
    }

    /// With these axis labels (say the units: `"t (s)"`, `"crank.phi (rad)"`).
    pub fn labels(mut self, x: impl Into<String>, y: impl Into<String>) -> Self {
        self.x_label = x.into();
        self.y_label = y.into();
        self
    }

    /// With a series of (x, y) points added.
    pub fn series(mut self, name: impl Into<String>, points: impl IntoIterator<Item = (f64, f64)>) -> Self {
        self.series.push((name.into(), points.into_iter().collect()));
        self
    }

    /// The time histories of named quantities of mechanism `M` (module docs) over `samples`.
    pub fn time_histories<M: Mechanism, T: Real, const NQ: usize, const NV: usize, const NC: usize>(
        title: impl Into<String>,
        samples: &[Sample<T, NQ, NV, NC>],
        names: &[&str],
    ) -> Result<Plot, PlotError> {
        let mut plot = Plot::new(title).labels("t (s)", names.join(", "));
        for &name in names {
            let c = column::<M>(name)?;
            plot = plot.series(name, samples.iter().map(|s| (s.point.t.to_f64(), value(s, c))));
        }
        Ok(plot)
    }

    /// One named quantity of mechanism `M` against another over `samples` (a phase portrait
    /// `"crank.phi"` against `"d/dt crank.phi"`, a point's path from two coordinates).
    pub fn xy<M: Mechanism, T: Real, const NQ: usize, const NV: usize, const NC: usize>(
        title: impl Into<String>,
        samples: &[Sample<T, NQ, NV, NC>],
        x: &str,
        y: &str,
    ) -> Result<Plot, PlotError> {
        let (cx, cy) = (column::<M>(x)?, column::<M>(y)?);
        let points = samples.iter().map(|s| (value(s, cx), value(s, cy)));
        Ok(Plot::new(title).labels(x, y).series(format!("{y} against {x}"), points))
    }

    /// The series (name, points).
    pub fn series_points(&self) -> &[(String, Vec<(f64, f64)>)] {
        &self.series
    }

    /// Writes the plot as an SVG file of 900 × 560 px: one line per series, a legend when
    /// there are several. Non-finite points are left out.
    pub fn write_svg(&self, path: impl AsRef<Path>) -> Result<(), PlotError> {
        self.draw(path.as_ref()).map_err(|e| PlotError::Draw(e.to_string()))
    }

    fn draw(&self, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
        let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for (_, points) in &self.series {
            for &(x, y) in points.iter().filter(finite) {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        // A margin of 5 % around the data, and some height for a constant series.
        let pad = |lo: f64, hi: f64| {
            let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
            (lo - 0.05 * span, hi + 0.05 * span)
        };
        let ((x0, x1), (y0, y1)) = (pad(x0, x1), pad(y0, y1));
        let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(14)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart.configure_mesh().x_desc(&self.x_label).y_desc(&self.y_label).draw()?;
        for (k, (name, points)) in self.series.iter().enumerate() {
            let colour = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(points.iter().filter(finite).copied(), colour.stroke_width(2)))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        }
        if self.series.len() > 1 {
            chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).draw()?;
        }
        root.present()?;
        Ok(())
    }
}
