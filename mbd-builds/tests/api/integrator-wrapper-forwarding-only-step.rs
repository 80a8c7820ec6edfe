use mbd::prelude::*;
use mbd::{Point, System, WorkArrays};

// A wrapper around an integrator that forwards only `step` and `interpolate`: before, it
// compiled, and DOP853's dense output (no `prepare_interpolation`) or generalized-α's state after
// a correction (no `after_correction`) were silently wrong through it. Every method that changes
// results is required, so it does not compile.
struct Counted<I> {
    inner: I,
    steps: u64,
}

impl<T: Real, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Integrator<T, M, NQ, NV, NC, N, NS> for Counted<I>
where
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        self.steps += 1;
        self.inner.step(system, ws, from, t_max, to)
    }
    fn interpolate(&self, m: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        self.inner.interpolate(m, from, to, t, q, v)
    }
}

fn main() {
    let counted = Counted { inner: Dop853::<f64, 3, 3>::default(), steps: 0 };
    println!("{}", counted.steps);
}
