//! What the tests of joint coordinates against body coordinates share (`tests/joint_coordinates.rs`,
//! `tests/spatial_joint_coordinates.rs`).

use mbd::prelude::*;
use mbd::{BodyCoordinates, JointLoads};

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

/// Every joint's reaction on each of its bodies, both ways at the same state (λ of the cut
/// joints from their rows, of the tree's by Newton–Euler over the subtree), and in body
/// coordinates `joint_reaction_at` is `joint_reaction` of D (tolerance as `agree`; the
/// reactions are O(1–100) N).
#[allow(clippy::type_complexity, dead_code)]
pub fn reactions_agree<B, J, const NQB: usize, const NVB: usize, const NCB: usize, const NQJ: usize, const NVJ: usize, const NCJ: usize>(
    b: &B,
    (qb, vb, vdb, lb): (&[f64; NQB], &[f64; NVB], &[f64; NVB], &[f64; NCB]),
    j: &J,
    (q, v, vd, l): (&[f64; NQJ], &[f64; NVJ], &[f64; NVJ], &[f64; NCJ]),
    t: f64,
) where
    B: JointLoads<f64, NQB, NVB, NCB> + Kinematics<f64, NQB, NVB, NCB> + BodyCoordinates,
    J: JointLoads<f64, NQJ, NVJ, NCJ>,
{
    let mut d = [[0.0; NVB]; NCB];
    b.jacobian(qb, t, &mut d);
    assert_eq!(B::JOINTS.len(), J::JOINTS.len());
    for (k, info) in J::JOINTS.iter().enumerate() {
        let by_rows = joint_reaction(b, qb, &d, lb, k).expect("a joint");
        let in_bodies = joint_reaction_at(b, qb, vb, vdb, t, lb, k).expect("a joint");
        let in_joints = joint_reaction_at(j, q, v, vd, t, l, k).expect("a joint");
        assert_eq!((in_joints.joint, in_bodies.joint), (info.name, info.name));
        for (side, (x, y, z)) in
            [("i", (by_rows.on_i, in_bodies.on_i, in_joints.on_i)), ("j", (by_rows.on_j, in_bodies.on_j, in_joints.on_j))]
        {
            let (Some(x), Some(y), Some(z)) = (x, y, z) else {
                assert!(x.is_none() && y.is_none() && z.is_none(), "{}: side {side} is ground in one and not the other", info.name);
                continue;
            };
            for c in 0..3 {
                for (what, a, bb, jj) in [("force", x.force[c], y.force[c], z.force[c]), ("moment", x.moment[c], y.moment[c], z.moment[c])]
                {
                    assert!(close(a, bb), "{}: {what} {c} on side {side}: {a} from D, {bb} from the bodies' loads", info.name);
                    assert!(close(bb, jj), "{}: {what} {c} on side {side}: {bb} in body coordinates, {jj} in joint coordinates", info.name);
                }
            }
        }
    }
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
