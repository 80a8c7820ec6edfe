//! Joint kinds whose constants a sign error would flip unnoticed by every other test (issue 10,
//! item 9): a `rigid` joint's angle and a `revolute_translational` joint's distance, checked
//! against the geometry they promise (docs/formulation.md: φ_j − φ_i = θ; n_jᵀ(r_i − r_j) = L
//! with n_j the axis turned +90°). Assembly converges to 1e-10, so 1e-9 separates the right
//! sign from the wrong one (which is off by 2θ = 0.8 rad or 2L = 0.1 m).
use mbd::prelude::*;

mechanism! {
    /// A crank held at 0.3 rad and a bracket welded to its tip at +0.4 rad to it.
    pub Welded {
        body crank { mass: 1.0, inertia: 0.003, at: [0.1, 0.0, 0.0] }
        body bracket { mass: 0.5, inertia: 0.001, at: [0.3, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        drive crank.phi = 0.3;
        rigid weld: crank[0.1, 0.0] ~ bracket[-0.1, 0.0] { angle: 0.4 };
    }
}

mechanism! {
    /// A crank of 0.2 m pinned to ground whose tip runs in a slot 0.05 m from the x axis: the
    /// slot is the line through the origin along x, the tip held at distance +0.05 m (on the
    /// side of n = (0, 1), the axis turned +90°).
    pub OffsetSlot {
        body crank { mass: 1.0, inertia: 0.003, at: [0.1, 0.0, 0.4] }
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        revolute_translational slot: crank[0.1, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0] { distance: 0.05 };
    }
}

#[test]
fn rigid_joint_angle_has_the_documented_sign() {
    let m = Welded::default();
    let mut ws = Welded::workspace();
    // From a guess with the bracket at the wrong angle and off its place.
    let mut q = m.initial_positions();
    q[5] = -0.3;
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let (crank, bracket) = (Welded::CRANK.phi(&q), Welded::BRACKET.phi(&q));
    assert!((crank - 0.3).abs() < 1e-9, "crank at {crank}");
    assert!((bracket - crank - 0.4).abs() < 1e-9, "φ_bracket − φ_crank = {} (want +0.4)", bracket - crank);
    // The welded points coincide: crank tip = bracket's left end.
    let tip = [0.2 * 0.3f64.cos(), 0.2 * 0.3f64.sin()];
    let left = [q[3] - 0.1 * bracket.cos(), q[4] - 0.1 * bracket.sin()];
    assert!((tip[0] - left[0]).abs() < 1e-9 && (tip[1] - left[1]).abs() < 1e-9, "{tip:?} vs {left:?}");
}

#[test]
fn revolute_translational_distance_has_the_documented_sign() {
    let m = OffsetSlot::default();
    let mut ws = OffsetSlot::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    // The tip (0.2 cos φ, 0.2 sin φ) at y = +0.05: φ = asin(0.25), the branch nearest 0.4 rad.
    let phi = OffsetSlot::CRANK.phi(&q);
    assert!((phi - 0.25f64.asin()).abs() < 1e-9, "crank at {phi} rad, want asin(0.25) = {}", 0.25f64.asin());
    assert!((0.2 * phi.sin() - 0.05).abs() < 1e-9, "tip at y = {}", 0.2 * phi.sin());
}

/// A planar body's mass and moment of inertia by name, as written in the mechanism.
#[test]
fn planar_mass_and_inertia_by_name() {
    let m = Welded::default();
    assert_eq!((m.mass_of(Welded::CRANK), m.inertia_of(Welded::CRANK)), (1.0, 0.003));
    assert_eq!((m.mass_of(Welded::BRACKET), m.inertia_of(Welded::BRACKET)), (0.5, 0.001));
}
