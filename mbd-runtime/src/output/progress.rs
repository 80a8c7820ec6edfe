//! A progress bar for long runs (feature `progress`, on by default), drawn by indicatif on
//! standard error — and only when standard error is a terminal, so logs and CI output stay clean.
//!
//! A simulation's bar runs over simulated time; a kinematic sweep's or a study's over a count:
//!
//! ```text
//! let times: Vec<f64> = (0..=10_000).map(|k| k as f64 * 1e-3).collect();
//! let progress = Progress::over(&times);
//! Simulation::new(&m, &mut Dopri5::default()).start(0.0, &q, &v).times(&times).run(&mut ws, progress.track(|sample| {
//!     // your own output, as without the bar
//! }))?;
//!
//! let progress = Progress::count(times.len() as u64);
//! solver.sweep(&m, &mut ws, &mut q, &times, |t, q, v, vd| { progress.inc(); /* ... */ })?;
//! ```
//!
//! A call that does not move the bar costs a comparison; one that does (at most once per thousandth
//! of the interval) formats its text; indicatif redraws at most 20 times a second.
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::integrate::Sample;
use crate::real::Real;

/// Steps of a bar over time: its position is the fraction of the interval done, in thousandths.
const TIME_STEPS: u64 = 1000;

/// A progress bar over simulated time or over a count of items. Finished when dropped.
pub struct Progress {
    bar: ProgressBar,
    /// Of a bar over time: its start and length (s); `None` for a count.
    interval: Option<(f64, f64)>,
}

impl Progress {
    /// A bar over simulated time from `t0` to `t_end` (s), moved by [`Progress::at`] and showing
    /// "t = 0.25 s of 1 s".
    pub fn time(t0: f64, t_end: f64) -> Self {
        let bar = ProgressBar::new(TIME_STEPS);
        bar.set_style(Self::style("{elapsed_precise} [{bar:40}] {msg} (eta {eta})"));
        let progress = Progress { bar, interval: Some((t0, t_end - t0)) };
        progress.at(t0);
        progress
    }

    /// A bar over the output times of a run, from the first to the last (empty: over nothing).
    pub fn over<T: Real>(times: &[T]) -> Self {
        let first = times.first().map_or(0.0, |t| t.to_f64());
        Self::time(first, times.last().map_or(first, |t| t.to_f64()))
    }

    /// A bar over `n` items (the points of a sweep, the runs of a study), moved by
    /// [`Progress::inc`] and showing "k/n".
    pub fn count(n: u64) -> Self {
        let bar = ProgressBar::new(n);
        bar.set_style(Self::style("{elapsed_precise} [{bar:40}] {pos}/{len} {msg} (eta {eta})"));
        Progress { bar, interval: None }
    }

    fn style(template: &str) -> ProgressStyle {
        // the templates above are valid: a failure here is a typo in this file
        ProgressStyle::with_template(template).expect("a valid template").progress_chars("=> ")
    }

    /// The same bar drawn nowhere (tests, or a run whose terminal should stay quiet).
    pub fn hidden(self) -> Self {
        self.bar.set_draw_target(ProgressDrawTarget::hidden());
        self
    }

    /// Moves a bar over time to `t` (s); clamped to its interval. Does nothing to a count.
    pub fn at(&self, t: f64) {
        let Some((t0, span)) = self.interval else { return };
        let done = if span > 0.0 { ((t - t0) / span).clamp(0.0, 1.0) } else { 1.0 };
        let position = (done * TIME_STEPS as f64).round() as u64;
        // its text is formatted only when the bar moves: at most once per thousandth
        if position != self.bar.position() || t == t0 {
            self.bar.set_position(position);
            self.bar.set_message(format!("t = {} s of {} s", Self::seconds(t), Self::seconds(t0 + span)));
        }
    }

    /// A time to as many digits as tell it apart on a bar: 4 significant.
    fn seconds(t: f64) -> String {
        format!("{}", format!("{t:.4e}").parse::<f64>().unwrap_or(t))
    }

    /// One more item done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// Sets the text after the bar (a count's label: "sweep points").
    pub fn message(&self, text: impl Into<String>) {
        self.bar.set_message(text.into());
    }

    /// How far the bar is, in [0, 1].
    pub fn fraction(&self) -> f64 {
        let length = self.bar.length().unwrap_or(0);
        if length == 0 {
            1.0
        } else {
            self.bar.position() as f64 / length as f64
        }
    }

    /// A callback for [`Simulation::run`](crate::Simulation::run) that moves the bar to each sample's time, then hands the
    /// sample to `output` and returns what it returns (so `ControlFlow::Break` still stops the
    /// run).
    pub fn track<'a, T: Real, R, const NQ: usize, const NV: usize, const NC: usize>(
        &'a self,
        mut output: impl FnMut(&Sample<T, NQ, NV, NC>) -> R + 'a,
    ) -> impl FnMut(&Sample<T, NQ, NV, NC>) -> R + 'a {
        move |sample| {
            self.at(sample.point.t.to_f64());
            output(sample)
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish();
    }
}
