//! What the tests of joint coordinates against body coordinates share (`tests/joint_coordinates.rs`,
//! `tests/spatial_joint_coordinates.rs`).

use mbd::prelude::*;

/// Whether a and b agree to 1e-10 relative to max(1, |a|, |b|): both formulations evaluate exact
/// symbolic derivatives of the same geometry and solve well-conditioned systems (masses
/// 0.2–2 kg, lengths 0.1–1 m, cond ≲ 1e4), so values agree to rounding times the condition; a
/// wrong term is O(0.1) or more.
pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-10 * a.abs().max(b.abs()).max(1.0)
}

/// A state of the joint mechanism on its constraints: `q` moved onto Φ = 0 and `v` onto
/// D v = ν by the mass-weighted projections.
pub fn on_constraints<J: ForwardDynamics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    j: &J,
    q: &mut [f64; NQ],
    v: &mut [f64; NV],
    t: f64,
) {
    let options = DynamicsOptions::default();
    for _ in 0..30 {
        if j.project_positions_step(q, t, &options).expect("a regular position") < 1e-13 {
            break;
        }
    }
    j.project_velocities(q, v, t, &options).expect("a regular position");
    let mut phi = [0.0; NC];
    j.constraints(q, t, &mut phi);
    assert!(phi.iter().all(|x| x.abs() < 1e-12), "{}: the projection reached Φ = {phi:?}", J::NAME);
}

/// The same statements as a body-coordinate and a joint-coordinate mechanism:
/// `both_ways! { /// doc  BodyName, JointName { statements } }`.
macro_rules! both_ways {
    ($(#[$doc:meta])* $body:ident, $joint:ident { $($statements:tt)* }) => {
        ::mbd::mechanism! { $(#[$doc])* pub $body { $($statements)* } }
        ::mbd::mechanism! { $(#[$doc])* pub $joint { joint_coordinates; $($statements)* } }
    };
}
#[allow(unused_imports)]
pub(crate) use both_ways;
