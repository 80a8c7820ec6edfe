//! The spanning tree of a mechanism in joint coordinates (`joint_coordinates;`; Nikravesh ch. 9,
//! Wallrapp 2.6.2): which joints carry the bodies from ground by their relative coordinates,
//! and which are cut and stay as rows of Φ (loop closures).
//!
//! The joint graph has ground and the bodies as nodes and each joint with a relative-coordinate
//! form (`elements::Relative`: revolute, translational, rigid; in space also cylindrical and
//! spherical) as an edge. The tree keeps the joints that cut the fewest rows: a maximum-weight
//! spanning forest by Kruskal's rule, each joint weighted by the rows it would have (3 or 6 − its
//! velocities), ties kept in declaration order — so of equals the later-declared joint is cut.
//! Every other joint, driver and user constraint keeps its rows. A body with no path to ground
//! floats on a free joint (x, y, φ in the plane; r, p and (ṙ, ω′) in space, as in body
//! coordinates; the first-declared body of its group, relative to ground). Coordinates and
//! velocities are numbered body by body in declaration order: body k's link owns
//! q[first..first + count] and v[first_v..first_v + count_v].
//!
//! Each body's pose and twist as functions of (q, v) are built parent by parent: [`planar`],
//! [`spatial`].

use std::collections::{BTreeSet, VecDeque};

use crate::elements::{Relative, SpatialKind};
use crate::frames::Builder;
use crate::model::{BodyRef, Space};
use crate::sym::Id;

pub mod planar;
pub mod spatial;

/// How one body hangs from its parent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Link {
    pub parent: BodyRef,
    /// The joint (index into `Model::constraints`) that carries it; `None`: a free joint.
    pub joint: Option<usize>,
    /// Whether the body is its joint's first (i) side, so the parent is the second (j).
    pub reversed: bool,
    /// Its coordinates are q[first..first + count], its velocities v[first_v..first_v + count_v].
    pub first: usize,
    pub count: usize,
    pub first_v: usize,
    pub count_v: usize,
}

impl Link {
    /// Where a unit quaternion starts among the link's coordinates, and so its angular velocity
    /// among its velocities: a free spatial body's (after r), a spherical joint's (all of them).
    pub fn quaternion(&self) -> Option<usize> {
        match (self.count, self.count_v) {
            (7, 6) => Some(3),
            (4, 3) => Some(0),
            _ => None,
        }
    }
}

/// The spanning tree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tree {
    /// One link per moving body, in declaration order.
    pub links: Vec<Link>,
    /// The bodies, each after its parent.
    pub order: Vec<usize>,
    /// The joints the tree carries (their rows are not in Φ).
    pub joints: BTreeSet<usize>,
    /// The numbers of coordinates and of velocities (equal in the plane, where v = q̇).
    pub nq: usize,
    pub nv: usize,
}

/// A joint's numbers of coordinates and velocities in the tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counts {
    pub q: usize,
    pub v: usize,
}

/// A joint the tree may carry: its index into `Model::constraints`, its bodies (i, j) and its
/// coordinates and velocities.
pub type Candidate = (usize, [BodyRef; 2], Counts);

/// What a joint coordinate measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoordinateKind {
    Length,
    Angle,
    /// Part 0–3 of a unit quaternion (Euler parameters).
    Quaternion(u8),
}

/// How a velocity relates to the coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VelocityKind {
    /// The rate of coordinate i.
    Rate(usize),
    /// An angular velocity component in the frame of the quaternion at q[quaternion..+4].
    Angular { quaternion: usize, axis: u8 },
}

/// A free body's coordinates and velocities: x, y, φ in the plane; r, p and ṙ, ω′ in space.
fn free(space: Space) -> Counts {
    match space {
        Space::Planar => Counts { q: 3, v: 3 },
        Space::Spatial => Counts { q: 7, v: 6 },
    }
}

/// One body's frame along the tree, as functions of (q, v): its pose (x, y, φ; or r, p), its
/// twist as body coordinates have it (ẋ, ẏ, φ̇; or ṙ, ω′ in its own frame), and its twist in
/// global components (ṙ, ω), of which each link's screws are the partials by its velocities.
pub struct TreeFrame {
    pub pose: Vec<Id>,
    pub twist: Vec<Id>,
    pub global: Vec<Id>,
    /// The twist's rate at constant v (J̇ v, as `twist` holds the twist) where the tree builds it
    /// by recursion (in space); `None`: the twist's derivative along q̇ (in the plane).
    pub bias: Option<Vec<Id>>,
    /// Where the articulated-body solve takes the link (in space); `None`: at the body's centre
    /// of mass with the screws of `global` (in the plane).
    pub articulation: Option<Articulation>,
}

/// A link as the articulated-body solve takes it (`formulation::joint`, `Kinematics::mass_solve`):
/// at a point where its screws have structural zeros — the joint point on the child, where a
/// turn has no linear part; a free body's centre of mass — and with angular velocities given in
/// the body's frame turned to global axes, where a ball joint's or a free body's screws are unit
/// vectors. Then U = I^A S and D = Sᵀ I^A S are entries of I^A, and I^a = I^A − U D⁻¹ Uᵀ has
/// the unit screws' rows and columns exactly zero (I^a S = 0).
#[derive(Clone, Debug)]
pub struct Articulation {
    /// The point, global.
    pub origin: Vec<Id>,
    /// Each velocity's screw (ṙ, ω) at `origin`, global, in the basis below.
    pub screws: Vec<Vec<Id>>,
    /// (m, A): the link's velocities m..m + 3 are angular velocity components in the body's
    /// frame, turned to global ones by the rotation A (v_global = A v; orthogonal, so the
    /// generalized forces turn alike and back by Aᵀ).
    pub rotated: Option<(usize, [[Id; 3]; 3])>,
}

/// Every body's frame, bodies in declaration order.
pub fn frames(b: &mut Builder, tree: &Tree) -> Vec<TreeFrame> {
    match b.model.space {
        Space::Planar => planar::frames(b, tree),
        Space::Spatial => spatial::frames(b, tree),
    }
}

/// The initial joint coordinates and velocities from the bodies' `at:` poses and velocities.
pub fn initial(b: &mut Builder, tree: &Tree) -> (Vec<Id>, Vec<Id>) {
    match b.model.space {
        Space::Planar => planar::initial(b, tree),
        Space::Spatial => spatial::initial(b, tree),
    }
}

/// The tree of `bodies` moving bodies over the candidate joints.
pub fn plan(bodies: usize, candidates: &[Candidate], space: Space) -> Tree {
    let node = |b: BodyRef| match b {
        BodyRef::Ground => 0,
        BodyRef::Body(k) => k + 1,
    };
    // Kruskal: the joints with the most rows first, ties in declaration order.
    let mut by_weight: Vec<&Candidate> = candidates.iter().filter(|(_, [i, j], _)| i != j).collect();
    by_weight.sort_by_key(|&&(index, _, counts)| (counts.v, index));
    let mut root: Vec<usize> = (0..=bodies).collect();
    fn find(root: &mut [usize], mut x: usize) -> usize {
        while root[x] != x {
            root[x] = root[root[x]];
            x = root[x];
        }
        x
    }
    let mut kept: Vec<&Candidate> = Vec::new();
    for &candidate in &by_weight {
        let [i, j] = candidate.1;
        let (a, b) = (find(&mut root, node(i)), find(&mut root, node(j)));
        if a != b {
            root[a] = b;
            kept.push(candidate);
        }
    }
    // Orient from ground, then from the first-declared body of each floating group.
    let mut links: Vec<Option<Link>> = vec![None; bodies];
    let mut order = Vec::with_capacity(bodies);
    let mut queue = VecDeque::new();
    let mut reached = vec![false; bodies + 1];
    reached[0] = true;
    queue.push_back(BodyRef::Ground);
    let mut next_free = 0;
    loop {
        while let Some(parent) = queue.pop_front() {
            for &&(index, [i, j], count) in &kept {
                let (child, reversed) = if i == parent {
                    (j, false)
                } else if j == parent {
                    (i, true)
                } else {
                    continue;
                };
                let BodyRef::Body(k) = child else { continue };
                if reached[k + 1] {
                    continue;
                }
                reached[k + 1] = true;
                links[k] = Some(Link { parent, joint: Some(index), reversed, first: 0, count: count.q, first_v: 0, count_v: count.v });
                order.push(k);
                queue.push_back(child);
            }
        }
        while next_free < bodies && reached[next_free + 1] {
            next_free += 1;
        }
        if next_free == bodies {
            break;
        }
        let k = next_free;
        reached[k + 1] = true;
        let count = free(space);
        links[k] =
            Some(Link { parent: BodyRef::Ground, joint: None, reversed: false, first: 0, count: count.q, first_v: 0, count_v: count.v });
        order.push(k);
        queue.push_back(BodyRef::Body(k));
    }
    let (mut nq, mut nv) = (0, 0);
    let links: Vec<Link> = links
        .into_iter()
        .map(|link| {
            let mut link = link.expect("every body is reached: from ground or as the root of its group");
            (link.first, link.first_v) = (nq, nv);
            nq += link.count;
            nv += link.count_v;
            link
        })
        .collect();
    let joints = kept.iter().map(|&&(index, _, _)| index).collect();
    Tree { links, order, joints, nq, nv }
}

impl Tree {
    /// Each coordinate's name and kind: a revolute joint's `"pin.angle"`, a translational
    /// joint's `"slide.stroke"`, a cylindrical joint's both, a spherical joint's quaternion
    /// `"ball.e0"` … `"ball.e3"`, a floating body's `"float.x"`, `"float.y"`, `"float.phi"` (in
    /// space `"float.x"` … `"float.z"`, `"float.e0"` … `"float.e3"`).
    pub fn coordinate_names(&self, model: &crate::model::Model) -> Vec<(String, CoordinateKind)> {
        let mut names = Vec::with_capacity(self.nq);
        let quaternion = |names: &mut Vec<(String, CoordinateKind)>, owner: &str| {
            names.extend((0..4).map(|part| (format!("{owner}.e{part}"), CoordinateKind::Quaternion(part as u8))));
        };
        for (k, link) in self.links.iter().enumerate() {
            match link.joint {
                None => {
                    let body = &model.bodies[k].name;
                    let lengths: &[&str] = if model.space == Space::Planar { &["x", "y"] } else { &["x", "y", "z"] };
                    names.extend(lengths.iter().map(|c| (format!("{body}.{c}"), CoordinateKind::Length)));
                    match model.space {
                        Space::Planar => names.push((format!("{body}.phi"), CoordinateKind::Angle)),
                        Space::Spatial => quaternion(&mut names, &body.to_string()),
                    }
                }
                Some(index) => {
                    let joint = &model.constraints[index];
                    let name = &joint.name;
                    let (angle, stroke) = match joint.kind.relative() {
                        Some(Relative::Revolute { .. }) => (true, false),
                        Some(Relative::Translational { .. }) => (false, true),
                        Some(Relative::Spatial { kind, .. }) => match kind {
                            SpatialKind::Revolute => (true, false),
                            SpatialKind::Translational => (false, true),
                            SpatialKind::Cylindrical => (true, true),
                            SpatialKind::Spherical => {
                                quaternion(&mut names, name);
                                (false, false)
                            }
                            SpatialKind::Rigid => (false, false),
                        },
                        Some(Relative::Rigid { .. }) | None => (false, false),
                    };
                    if angle {
                        names.push((format!("{name}.angle"), CoordinateKind::Angle));
                    }
                    if stroke {
                        names.push((format!("{name}.stroke"), CoordinateKind::Length));
                    }
                }
            }
        }
        names
    }

    /// Each velocity's name, kind and the name of its displacement (`VelocityInfo`): the rate
    /// of its coordinate where v = q̇ (named as the coordinate), else an angular velocity in
    /// the body's (free) or the child's (spherical) frame, `"ball.wx"` with displacement
    /// `"ball.rx"`; a free spatial body's ṙ is `"float.vx"` … .
    pub fn velocity_names(&self, model: &crate::model::Model) -> Vec<(String, VelocityKind, String)> {
        let coordinates = self.coordinate_names(model);
        let mut names = Vec::with_capacity(self.nv);
        for link in &self.links {
            let own = &coordinates[link.first..link.first + link.count];
            let quaternion = own.iter().position(|(_, kind)| matches!(kind, CoordinateKind::Quaternion(_)));
            for (c, (name, _)) in own.iter().enumerate() {
                match quaternion {
                    Some(e0) if c >= e0 => {
                        if c < e0 + 3 {
                            let owner = name.rsplit_once('.').map_or(name.as_str(), |(owner, _)| owner);
                            let axis = ["x", "y", "z"][c - e0];
                            let kind = VelocityKind::Angular { quaternion: link.first + e0, axis: (c - e0) as u8 };
                            names.push((format!("{owner}.w{axis}"), kind, format!("{owner}.r{axis}")));
                        }
                    }
                    Some(_) => {
                        // a free spatial body's ṙ: named as its velocity, the rate of its position
                        let (owner, axis) = name.rsplit_once('.').expect("a free body's coordinate is `body.c`");
                        names.push((format!("{owner}.v{axis}"), VelocityKind::Rate(link.first + c), name.clone()));
                    }
                    None => names.push((name.clone(), VelocityKind::Rate(link.first + c), name.clone())),
                }
            }
        }
        names
    }

    /// The body whose link owns velocity `i`.
    pub fn body_of_velocity(&self, i: usize) -> usize {
        self.links.iter().position(|l| (l.first_v..l.first_v + l.count_v).contains(&i)).unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: BodyRef = BodyRef::Ground;
    const ONE: Counts = Counts { q: 1, v: 1 };
    const NONE: Counts = Counts { q: 0, v: 0 };
    fn b(k: usize) -> BodyRef {
        BodyRef::Body(k)
    }

    /// An open chain declared from its tip: the links point back to ground, each body after its
    /// parent, coordinates by body.
    #[test]
    fn chain_from_ground() {
        let tree = plan(3, &[(0, [b(1), b(2)], ONE), (1, [b(0), b(1)], ONE), (2, [G, b(0)], ONE)], Space::Planar);
        let parents: Vec<(BodyRef, Option<usize>, bool)> = tree.links.iter().map(|l| (l.parent, l.joint, l.reversed)).collect();
        assert_eq!(parents, [(G, Some(2), false), (b(0), Some(1), false), (b(1), Some(0), false)]);
        assert_eq!(tree.order, [0, 1, 2]);
        assert_eq!((tree.nq, tree.joints.len()), (3, 3));
        // a joint declared child ~ parent is reversed
        let tree = plan(1, &[(0, [b(0), G], ONE)], Space::Planar);
        assert_eq!((tree.links[0].parent, tree.links[0].reversed), (G, true));
    }

    /// The slider-crank's loop (crank, rod, slider; four joints of two rows): the last-declared
    /// of equals is cut; a rigid joint (three rows) is kept over a revolute one.
    #[test]
    fn loop_cuts_the_later_joint_of_equals() {
        let joints = [(0, [G, b(0)], ONE), (1, [b(0), b(1)], ONE), (2, [b(1), b(2)], ONE), (3, [G, b(2)], ONE)];
        let tree = plan(3, &joints, Space::Planar);
        assert_eq!(tree.joints, BTreeSet::from([0, 1, 2]));
        let tree = plan(1, &[(0, [G, b(0)], ONE), (1, [G, b(0)], NONE)], Space::Planar);
        assert_eq!((tree.joints, tree.nq), (BTreeSet::from([1]), 0));
    }

    /// A body on no candidate joint floats on a free joint; so does the first-declared body of a
    /// group joined to ground only by cut joints' rows, its partners hanging from it.
    #[test]
    fn floating_groups_get_a_free_joint() {
        let tree = plan(3, &[(0, [b(2), b(1)], ONE)], Space::Planar);
        let links: Vec<(BodyRef, Option<usize>, usize, usize)> = tree.links.iter().map(|l| (l.parent, l.joint, l.first, l.count)).collect();
        assert_eq!(links, [(G, None, 0, 3), (G, None, 3, 3), (b(1), Some(0), 6, 1)]);
        assert_eq!(tree.order, [0, 1, 2]);
    }

    /// In space a ball joint (4 coordinates, 3 velocities, 3 rows) is cut before a revolute
    /// joint (1 and 1, 5 rows) that closes the same loop; a free body gets r, p and ṙ, ω′; q and
    /// v are numbered body by body, and each link says where its quaternion starts.
    #[test]
    fn spatial_links_count_coordinates_and_velocities_apart() {
        const BALL: Counts = Counts { q: 4, v: 3 };
        let tree = plan(3, &[(0, [G, b(0)], ONE), (1, [b(0), b(1)], BALL), (2, [G, b(1)], ONE)], Space::Spatial);
        assert_eq!(tree.joints, BTreeSet::from([0, 2]), "the ball joint closes the loop and is cut");
        let tree = plan(3, &[(0, [G, b(0)], BALL), (1, [b(0), b(1)], ONE)], Space::Spatial);
        let links: Vec<(usize, usize, usize, usize, Option<usize>)> =
            tree.links.iter().map(|l| (l.first, l.count, l.first_v, l.count_v, l.quaternion())).collect();
        assert_eq!(links, [(0, 4, 0, 3, Some(0)), (4, 1, 3, 1, None), (5, 7, 4, 6, Some(3))]);
        assert_eq!((tree.nq, tree.nv, tree.links[2].joint), (12, 10, None));
    }
}
