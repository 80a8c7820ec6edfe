//! What a formulation is to the runtime: which coordinates and velocities it has
//! ([`Coordinates::descriptors`]), how q moves with v (`position_rates`, `integrate_positions`,
//! `normalize_positions`) and each body's pose and twist (`mbd::BodyFrames`). The elements never
//! see this; they build on body frames (`frames`).

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::emit::{real, usize_lit, Emitter, Output};
use crate::formulation::Formulation;
use crate::model::{Coord, Model, Space, Vel};

/// How body frames depend on the generalized coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// Planar body coordinates (Nikravesh ch. 7): body k owns q[3k..3k+3] = (x, y, φ), the
    /// origin of its frame (its centre of mass) and its angle; B = I, so v = q̇.
    PlanarBody,
    /// Spatial body coordinates (docs/formulation.md, "Spatial bodies"): body k owns
    /// q[7k..7k+7] = (r, p), its centre of mass and Euler parameters, and v[6k..6k+6] = (ṙ, ω′)
    /// with ω′ in the body frame; q̇ = B(q) v with ṗ = ½ Lᵀ(p) ω′.
    SpatialBody,
    /// Planar joint coordinates (Nikravesh ch. 9; `joint_coordinates;`): the relative
    /// coordinates of a spanning tree of the joints (`tree`) — a revolute joint's angle
    /// θ = φ_j − φ_i, a translational joint's stroke s = u_iᵀ(r^P_j − r^P_i), a floating body's
    /// x, y, φ — and v = q̇. Each body's pose is a function of them, built along the tree.
    PlanarJoint,
    /// Spatial joint coordinates (Wallrapp 2.6.2; `joint_coordinates;` with `spatial;`): the
    /// tree's angles and strokes, spherical joints' quaternions (with relative angular
    /// velocities in the child's frame) and free bodies' (r, p) with (ṙ, ω′); q̇ = B(q) v
    /// (`tree::spatial`).
    SpatialJoint,
}

impl Coordinates {
    /// The formulation of a model: its space's body coordinates, or joint coordinates.
    pub fn of(model: &Model) -> Self {
        match (model.space, &model.tree) {
            (Space::Planar, Some(_)) => Coordinates::PlanarJoint,
            (Space::Planar, None) => Coordinates::PlanarBody,
            (Space::Spatial, Some(_)) => Coordinates::SpatialJoint,
            (Space::Spatial, None) => Coordinates::SpatialBody,
        }
    }

    /// Coordinates per moving body, in body coordinates (joint coordinates have no such
    /// layout: `Tree::links` says which coordinates carry which body).
    pub fn per_body(self) -> usize {
        match self {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => 3,
            Coordinates::SpatialBody | Coordinates::SpatialJoint => 7,
        }
    }

    /// Velocities per moving body, in body coordinates.
    pub fn velocities_per_body(self) -> usize {
        match self {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => 3,
            Coordinates::SpatialBody | Coordinates::SpatialJoint => 6,
        }
    }

    /// Whether these are joint coordinates (a tree's).
    pub fn is_joint(self) -> bool {
        matches!(self, Coordinates::PlanarJoint | Coordinates::SpatialJoint)
    }

    /// The runtime's descriptors of every coordinate and velocity of `model` in this formulation
    /// (`Mechanism::COORDINATES`, `Mechanism::VELOCITIES`): what each one is, so that no analysis
    /// reads it from a name or a place in q. Planar velocities are named as their coordinates
    /// (v = q̇); spatial ones `"top.vx"`, ..., `"top.wz"`.
    pub fn descriptors(self, model: &Model) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let (mut coordinates, mut velocities) = (Vec::new(), Vec::new());
        if let Some(tree) = &model.tree {
            use crate::tree::{CoordinateKind, VelocityKind};
            for (name, kind) in tree.coordinate_names(model) {
                let kind = match kind {
                    CoordinateKind::Angle => quote!(Angle),
                    CoordinateKind::Length => quote!(Length),
                    CoordinateKind::Quaternion(part) => {
                        let part = Literal::u8_unsuffixed(part);
                        quote!(Quaternion { part: #part })
                    }
                };
                coordinates.push(quote!(::mbd::CoordinateInfo { name: #name, kind: ::mbd::CoordinateKind::#kind }));
            }
            for (name, kind, displacement) in tree.velocity_names(model) {
                let kind = match kind {
                    VelocityKind::Rate(at) => {
                        let at = Literal::u16_unsuffixed(at as u16);
                        quote!(Rate { coordinate: #at })
                    }
                    VelocityKind::Angular { quaternion, axis } => {
                        let (e0, a) = (Literal::u16_unsuffixed(quaternion as u16), Literal::u8_unsuffixed(axis));
                        quote!(Angular { quaternion: #e0, axis: #a })
                    }
                };
                velocities.push(quote!(::mbd::VelocityInfo { name: #name, kind: ::mbd::VelocityKind::#kind, displacement: #displacement }));
            }
            return (coordinates, velocities);
        }
        for (k, body) in model.bodies.iter().enumerate() {
            let name = |c: &str| format!("{}.{c}", body.name);
            let first = (k * self.per_body()) as u16;
            for c in model.space.coordinates() {
                let kind = match c {
                    Coord::X | Coord::Y | Coord::Z => quote!(Length),
                    Coord::Phi => quote!(Angle),
                    Coord::E0 | Coord::E1 | Coord::E2 | Coord::E3 => {
                        let part = Literal::u8_unsuffixed((c.index() - 3) as u8);
                        quote!(Quaternion { part: #part })
                    }
                };
                let n = name(c.name());
                coordinates.push(quote!(::mbd::CoordinateInfo { name: #n, kind: ::mbd::CoordinateKind::#kind }));
            }
            for v in model.space.velocities() {
                let (own, kind, displacement) = match (self, v) {
                    (Coordinates::PlanarJoint | Coordinates::SpatialJoint, _) => {
                        unreachable!("joint coordinates are described by the tree, above")
                    }
                    (Coordinates::PlanarBody, _) => {
                        let c = model.space.coordinates()[v.index()];
                        let at = Literal::u16_unsuffixed(first + c.index() as u16);
                        (name(c.name()), quote!(Rate { coordinate: #at }), name(c.name()))
                    }
                    (Coordinates::SpatialBody, Vel::Wx | Vel::Wy | Vel::Wz) => {
                        let axis = v.index() - 3;
                        let (e0, a) = (Literal::u16_unsuffixed(first + 3), Literal::u8_unsuffixed(axis as u8));
                        (name(v.name()), quote!(Angular { quaternion: #e0, axis: #a }), name(&format!("r{}", ["x", "y", "z"][axis])))
                    }
                    (Coordinates::SpatialBody, _) => {
                        let c = model.space.coordinates()[v.index()];
                        let at = Literal::u16_unsuffixed(first + c.index() as u16);
                        (name(v.name()), quote!(Rate { coordinate: #at }), name(c.name()))
                    }
                };
                velocities.push(quote!(::mbd::VelocityInfo { name: #own, kind: ::mbd::VelocityKind::#kind, displacement: #displacement }));
            }
        }
        (coordinates, velocities)
    }

    /// The body whose motion velocity `i` is (an index among the moving bodies); in joint
    /// coordinates the body its joint carries.
    pub fn body_of_velocity(self, m: &Model, i: usize) -> usize {
        match &m.tree {
            Some(tree) => tree.body_of_velocity(i),
            None => i / self.velocities_per_body(),
        }
    }

    /// The velocity map's code: `position_rates` (q̇ = B(q) v), `integrate_positions` (q ⊕ h dv)
    /// and `normalize_positions`. Planar: B = I and nothing to normalize. Spatial: ṗ = ½ Lᵀ(p) ω′
    /// for each quaternion (each body's; in joint coordinates each free body's and spherical
    /// joint's), q̇ = v for the rest (docs/formulation.md), then p ← p/|p|.
    pub fn position_updates(self, m: &Model, e: &Emitter) -> TokenStream {
        let real = real(m.scalar);
        if m.space == crate::model::Space::Planar {
            let n = usize_lit(m.tree.as_ref().map_or(3 * m.bodies.len(), |tree| tree.nq));
            return quote! {
                #[inline]
                fn position_rates(&self, q: &[#real; #n], v: &[#real; #n], qdot: &mut [#real; #n]) {
                    *qdot = *v;
                }
                #[inline]
                fn integrate_positions(&self, q: &mut [#real; #n], dv: &[#real; #n], h: #real) {
                    for i in 0..#n {
                        q[i] += h * dv[i];
                    }
                }
                #[inline]
                fn normalize_positions(&self, q: &mut [#real; #n]) {}
            };
        }
        let (half, one) = (e.literal(0.5), e.literal(1.0));
        // (coordinate, velocity) pairs with q̇_i = v_j, and (e0's coordinate, ω′'s first
        // velocity) of each quaternion: per body in body coordinates, per free body and
        // spherical joint in joint coordinates
        type Pairs = Vec<(usize, usize)>;
        let (rates, quaternions): (Pairs, Pairs) = match &m.tree {
            None => (
                (0..m.bodies.len()).flat_map(|k| (0..3).map(move |c| (7 * k + c, 6 * k + c))).collect(),
                (0..m.bodies.len()).map(|k| (7 * k + 3, 6 * k + 3)).collect(),
            ),
            Some(tree) => {
                let (mut rates, mut quaternions) = (Vec::new(), Vec::new());
                for link in &tree.links {
                    let at = link.quaternion().unwrap_or(link.count);
                    rates.extend((0..at).map(|c| (link.first + c, link.first_v + c)));
                    if at < link.count {
                        quaternions.push((link.first + at, link.first_v + at));
                    }
                }
                (rates, quaternions)
            }
        };
        let (nq, nv) = (usize_lit(self.nq(m)), usize_lit(self.nv(m)));
        let pair = |(a, b): (usize, usize)| {
            let (a, b) = (usize_lit(a), usize_lit(b));
            quote!((#a, #b))
        };
        let (n_rates, n_quaternions) = (usize_lit(rates.len()), usize_lit(quaternions.len()));
        let (rates, quaternions): (Vec<_>, Vec<_>) = (rates.into_iter().map(pair).collect(), quaternions.into_iter().map(pair).collect());
        quote! {
            #[inline]
            fn position_rates(&self, q: &[#real; #nq], v: &[#real; #nv], qdot: &mut [#real; #nq]) {
                const RATES: [(usize, usize); #n_rates] = [#(#rates),*];
                const QUATERNIONS: [(usize, usize); #n_quaternions] = [#(#quaternions),*];
                for (i, j) in RATES {
                    qdot[i] = v[j];
                }
                for (r, w) in QUATERNIONS {
                    let (e0, e1, e2, e3) = (q[r], q[r + 1], q[r + 2], q[r + 3]);
                    let (wx, wy, wz) = (v[w], v[w + 1], v[w + 2]);
                    qdot[r] = #half * (-e1 * wx - e2 * wy - e3 * wz);
                    qdot[r + 1] = #half * (e0 * wx - e3 * wy + e2 * wz);
                    qdot[r + 2] = #half * (e3 * wx + e0 * wy - e1 * wz);
                    qdot[r + 3] = #half * (-e2 * wx + e1 * wy + e0 * wz);
                }
            }
            #[inline]
            fn integrate_positions(&self, q: &mut [#real; #nq], dv: &[#real; #nv], h: #real) {
                let mut rates = [<#real as ::mbd::Real>::ZERO; #nq];
                ::mbd::Kinematics::position_rates(self, q, dv, &mut rates);
                for i in 0..#nq {
                    q[i] += h * rates[i];
                }
                ::mbd::Kinematics::normalize_positions(self, q);
            }
            #[inline]
            fn normalize_positions(&self, q: &mut [#real; #nq]) {
                const QUATERNIONS: [(usize, usize); #n_quaternions] = [#(#quaternions),*];
                for (p, _) in QUATERNIONS {
                    let norm = <#real as ::mbd::Real>::sqrt(q[p] * q[p] + q[p + 1] * q[p + 1] + q[p + 2] * q[p + 2] + q[p + 3] * q[p + 3]);
                    let scale = #one / norm;
                    for i in p..p + 4 {
                        q[i] *= scale;
                    }
                }
            }
        }
    }

    /// The numbers of coordinates and velocities of a model.
    pub fn nq(self, m: &Model) -> usize {
        m.tree.as_ref().map_or(self.per_body() * m.bodies.len(), |tree| tree.nq)
    }

    pub fn nv(self, m: &Model) -> usize {
        m.tree.as_ref().map_or(self.velocities_per_body() * m.bodies.len(), |tree| tree.nv)
    }

    /// `mbd::BodyFrames` for mechanism `name`: each body's pose, its twist J_b x, its
    /// acceleration and J_bᵀ of a wrench. In body coordinates J_b selects the body's velocities,
    /// its angular part turned to global components (spatial ω = A ω′), and J̇_b v = 0 (planar:
    /// J_b is constant; spatial: d(A ω′)/dt = A ω̇′ + A ω̃′ ω′ = A ω̇′).
    pub fn body_frames(self, m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
        let name = &m.name;
        let real = real(m.scalar);
        let nb = usize_lit(m.bodies.len());
        let (nq, nv) = (usize_lit(self.per_body() * m.bodies.len()), usize_lit(self.velocities_per_body() * m.bodies.len()));
        let zero = quote!(<#real as ::mbd::Real>::ZERO);
        let (pose, twist, wrench) = match self {
            Coordinates::PlanarJoint | Coordinates::SpatialJoint => return joint_body_frames(m, f, e),
            Coordinates::PlanarBody => (
                quote!(let k = 3 * body; ::core::option::Option::Some(::mbd::BodyPose::planar(q[k], q[k + 1], q[k + 2]))),
                quote! {
                    let k = 3 * body;
                    ::core::option::Option::Some(::mbd::BodyTwist { velocity: [x[k], x[k + 1], #zero], angular_velocity: [#zero, #zero, x[k + 2]] })
                },
                quote! {
                    let k = 3 * body;
                    g[k] += force[0];
                    g[k + 1] += force[1];
                    g[k + 2] += moment[2];
                },
            ),
            Coordinates::SpatialBody => (
                quote! {
                    let k = 7 * body;
                    ::core::option::Option::Some(::mbd::BodyPose::spatial([q[k], q[k + 1], q[k + 2]], [q[k + 3], q[k + 4], q[k + 5], q[k + 6]]))
                },
                quote! {
                    let pose = ::mbd::BodyFrames::body_pose(self, body, q)?;
                    let w = 6 * body;
                    ::core::option::Option::Some(::mbd::BodyTwist {
                        velocity: [x[w], x[w + 1], x[w + 2]],
                        angular_velocity: pose.to_global([x[w + 3], x[w + 4], x[w + 5]]),
                    })
                },
                quote! {
                    let n = ::mbd::BodyPose::spatial([#zero; 3], [q[7 * body + 3], q[7 * body + 4], q[7 * body + 5], q[7 * body + 6]]).to_body(moment);
                    let w = 6 * body;
                    for a in 0..3 {
                        g[w + a] += force[a];
                        g[w + 3 + a] += n[a];
                    }
                },
            ),
        };
        quote! {
            #[allow(unused_variables)]
            impl ::mbd::BodyFrames<#real, #nq, #nv> for #name {
                #[inline]
                fn body_pose(&self, body: usize, q: &[#real; #nq]) -> ::core::option::Option<::mbd::BodyPose<#real>> {
                    if body >= #nb {
                        return ::core::option::Option::None;
                    }
                    #pose
                }
                #[inline]
                fn body_twist(&self, body: usize, q: &[#real; #nq], x: &[#real; #nv]) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                    if body >= #nb {
                        return ::core::option::Option::None;
                    }
                    #twist
                }
                #[inline]
                fn body_acceleration(
                    &self,
                    body: usize,
                    q: &[#real; #nq],
                    v: &[#real; #nv],
                    vd: &[#real; #nv],
                ) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                    ::mbd::BodyFrames::body_twist(self, body, q, vd)
                }
                #[inline]
                fn add_body_wrench(&self, body: usize, q: &[#real; #nq], force: [#real; 3], moment: [#real; 3], g: &mut [#real; #nv]) -> bool {
                    if body >= #nb {
                        return false;
                    }
                    #wrench
                    true
                }
            }
        }
    }
}

/// `mbd::BodyFrames` in joint coordinates, from the frames' nodes (`FrameNodes`): every body's
/// pose, twist and twist rate evaluated at once (O(N) for a chain, the subexpressions of the
/// recursion shared) and the one asked for returned; J_bᵀ of a wrench by the tree's backward
/// pass with the other bodies' wrenches zero (O(N) code; `formulation::joint`).
fn joint_body_frames(m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
    let name = &m.name;
    let real = real(m.scalar);
    let nb = usize_lit(m.bodies.len());
    let (nq, nv) = (usize_lit(f.nq), usize_lit(f.nv));
    let zero = quote!(<#real as ::mbd::Real>::ZERO);
    let spatial = m.space == crate::model::Space::Spatial;
    let all = |array: &str, pick: &dyn Fn(&crate::formulation::FrameNodes) -> &[crate::sym::Id]| -> TokenStream {
        let array = proc_macro2::Ident::new(array, proc_macro2::Span::call_site());
        let outputs: Vec<Output> = f
            .frames
            .iter()
            .enumerate()
            .flat_map(|(k, frame)| {
                let k = usize_lit(k);
                let array = array.clone();
                pick(frame).iter().enumerate().map(move |(c, &node)| {
                    let c = usize_lit(c);
                    Output { target: quote!(#array[#k][#c]), node }
                })
            })
            .collect();
        e.body(&outputs).0
    };
    let poses = all("poses", &|frame| &frame.pose);
    let twists = all("twists", &|frame| &frame.twist);
    let biases = all("biases", &|frame| &frame.bias);
    // Σ_b J_bᵀ w_b over every body's wrench w_b = dir[nw b..nw (b + 1)], one backward pass.
    let wrench = f.tree.as_ref().map(|terms| e.body(&crate::emit::vector_outputs("out", &terms.wrench)).0);
    let (n_pose, n_twist) = if spatial { (7, 6) } else { (3, 3) };
    let n_wrench = usize_lit(n_twist * m.bodies.len());
    let table = |array: TokenStream, n: usize| {
        let n = usize_lit(n);
        quote!(let mut #array = [[#zero; #n]; #nb];)
    };
    let (pose_table, twist_table, bias_table) =
        (table(quote!(poses), n_pose), table(quote!(twists), n_twist), table(quote!(biases), n_twist));
    let twist_of = |x: TokenStream| {
        quote! {
            #[allow(clippy::redundant_locals)]
            let v = #x;
            #twist_table
            #twists
            let t = twists[body];
        }
    };
    let (twist_x, twist_vd) = (twist_of(quote!(x)), twist_of(quote!(vd)));
    // the twist t (+ the bias b) as a BodyTwist: ω′ turned to global components in space
    let (pose_out, twist_out, acceleration_out, wrench_in) = if spatial {
        (
            quote!(::mbd::BodyPose::spatial([p[0], p[1], p[2]], [p[3], p[4], p[5], p[6]])),
            quote! {
                let pose = ::mbd::BodyFrames::body_pose(self, body, q)?;
                ::mbd::BodyTwist { velocity: [t[0], t[1], t[2]], angular_velocity: pose.to_global([t[3], t[4], t[5]]) }
            },
            quote! {
                let pose = ::mbd::BodyFrames::body_pose(self, body, q)?;
                ::mbd::BodyTwist {
                    velocity: [t[0] + b[0], t[1] + b[1], t[2] + b[2]],
                    angular_velocity: pose.to_global([t[3] + b[3], t[4] + b[4], t[5] + b[5]]),
                }
            },
            quote!([force[0], force[1], force[2], moment[0], moment[1], moment[2]]),
        )
    } else {
        (
            quote!(::mbd::BodyPose::planar(p[0], p[1], p[2])),
            quote!(::mbd::BodyTwist { velocity: [t[0], t[1], #zero], angular_velocity: [#zero, #zero, t[2]] }),
            quote!(::mbd::BodyTwist { velocity: [t[0] + b[0], t[1] + b[1], #zero], angular_velocity: [#zero, #zero, t[2] + b[2]] }),
            quote!([force[0], force[1], moment[2]]),
        )
    };
    let nw = usize_lit(n_twist);
    quote! {
        #[allow(unused_variables, unused_mut, unused_parens, clippy::approx_constant)]
        impl ::mbd::BodyFrames<#real, #nq, #nv> for #name {
            #[inline]
            fn body_pose(&self, body: usize, q: &[#real; #nq]) -> ::core::option::Option<::mbd::BodyPose<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #pose_table
                #poses
                let p = poses[body];
                ::core::option::Option::Some(#pose_out)
            }
            #[inline]
            fn body_twist(&self, body: usize, q: &[#real; #nq], x: &[#real; #nv]) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #twist_x
                ::core::option::Option::Some({ #twist_out })
            }
            #[inline]
            fn body_acceleration(
                &self,
                body: usize,
                q: &[#real; #nq],
                v: &[#real; #nv],
                vd: &[#real; #nv],
            ) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #bias_table
                #biases
                let b = biases[body];
                #twist_vd
                ::core::option::Option::Some({ #acceleration_out })
            }
            #[inline]
            fn add_body_wrench(&self, body: usize, q: &[#real; #nq], force: [#real; 3], moment: [#real; 3], g: &mut [#real; #nv]) -> bool {
                if body >= #nb {
                    return false;
                }
                let mut dir = [#zero; #n_wrench];
                dir[#nw * body..#nw * (body + 1)].copy_from_slice(&#wrench_in);
                let mut out = [#zero; #nv];
                #wrench
                for (g, out) in g.iter_mut().zip(&out) {
                    *g += *out;
                }
                true
            }
        }
    }
}
