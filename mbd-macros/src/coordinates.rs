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
}

impl Coordinates {
    /// The formulation of a model: its space's body coordinates, or joint coordinates.
    pub fn of(model: &Model) -> Self {
        match (model.space, &model.tree) {
            (Space::Planar, Some(_)) => Coordinates::PlanarJoint,
            (Space::Planar, None) => Coordinates::PlanarBody,
            (Space::Spatial, _) => Coordinates::SpatialBody,
        }
    }

    /// Coordinates per moving body, in body coordinates (joint coordinates have no such
    /// layout: `Tree::links` says which coordinates carry which body).
    pub fn per_body(self) -> usize {
        match self {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => 3,
            Coordinates::SpatialBody => 7,
        }
    }

    /// Velocities per moving body, in body coordinates.
    pub fn velocities_per_body(self) -> usize {
        match self {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => 3,
            Coordinates::SpatialBody => 6,
        }
    }

    /// The runtime's descriptors of every coordinate and velocity of `model` in this formulation
    /// (`Mechanism::COORDINATES`, `Mechanism::VELOCITIES`): what each one is, so that no analysis
    /// reads it from a name or a place in q. Planar velocities are named as their coordinates
    /// (v = q̇); spatial ones `"top.vx"`, ..., `"top.wz"`.
    pub fn descriptors(self, model: &Model) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let (mut coordinates, mut velocities) = (Vec::new(), Vec::new());
        if let Some(tree) = &model.tree {
            for (i, (name, angle)) in tree.coordinate_names(model).into_iter().enumerate() {
                let kind = if angle { quote!(Angle) } else { quote!(Length) };
                let at = Literal::u16_unsuffixed(i as u16);
                coordinates.push(quote!(::mbd::CoordinateInfo { name: #name, kind: ::mbd::CoordinateKind::#kind }));
                velocities.push(
                    quote!(::mbd::VelocityInfo { name: #name, kind: ::mbd::VelocityKind::Rate { coordinate: #at }, displacement: #name }),
                );
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
                    (Coordinates::PlanarJoint, _) => unreachable!("joint coordinates are described by the tree, above"),
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
            Some(tree) => tree.body_of_coordinate(i),
            None => i / self.velocities_per_body(),
        }
    }

    /// The velocity map's code: `position_rates` (q̇ = B(q) v), `integrate_positions` (q ⊕ h dv)
    /// and `normalize_positions`. Planar: B = I and nothing to normalize. Spatial, per body:
    /// ṙ = v_r, ṗ = ½ Lᵀ(p) ω′ (docs/formulation.md), then p ← p/|p|.
    pub fn position_updates(self, m: &Model, e: &Emitter) -> TokenStream {
        let real = real(m.scalar);
        let (nq, nv) = (usize_lit(7 * m.bodies.len()), usize_lit(6 * m.bodies.len()));
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
        let nb = usize_lit(m.bodies.len());
        quote! {
            #[inline]
            fn position_rates(&self, q: &[#real; #nq], v: &[#real; #nv], qdot: &mut [#real; #nq]) {
                for k in 0..#nb {
                    let (r, w) = (7 * k, 6 * k);
                    let (e0, e1, e2, e3) = (q[r + 3], q[r + 4], q[r + 5], q[r + 6]);
                    let (wx, wy, wz) = (v[w + 3], v[w + 4], v[w + 5]);
                    qdot[r] = v[w];
                    qdot[r + 1] = v[w + 1];
                    qdot[r + 2] = v[w + 2];
                    qdot[r + 3] = #half * (-e1 * wx - e2 * wy - e3 * wz);
                    qdot[r + 4] = #half * (e0 * wx - e3 * wy + e2 * wz);
                    qdot[r + 5] = #half * (e3 * wx + e0 * wy - e1 * wz);
                    qdot[r + 6] = #half * (-e2 * wx + e1 * wy + e0 * wz);
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
                for k in 0..#nb {
                    let p = 7 * k + 3;
                    let norm = <#real as ::mbd::Real>::sqrt(q[p] * q[p] + q[p + 1] * q[p + 1] + q[p + 2] * q[p + 2] + q[p + 3] * q[p + 3]);
                    let scale = #one / norm;
                    for i in p..p + 4 {
                        q[i] *= scale;
                    }
                }
            }
        }
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
            Coordinates::PlanarJoint => return joint_body_frames(m, f, e),
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
    let n = usize_lit(f.nq);
    let zero = quote!(<#real as ::mbd::Real>::ZERO);
    let all = |array: &str, pick: &dyn Fn(&crate::formulation::FrameNodes) -> [crate::sym::Id; 3]| -> TokenStream {
        let array = proc_macro2::Ident::new(array, proc_macro2::Span::call_site());
        let outputs: Vec<Output> = f
            .frames
            .iter()
            .enumerate()
            .flat_map(|(k, frame)| {
                let k = usize_lit(k);
                let array = array.clone();
                pick(frame).into_iter().enumerate().map(move |(c, node)| {
                    let c = usize_lit(c);
                    Output { target: quote!(#array[#k][#c]), node }
                })
            })
            .collect();
        e.body(&outputs).0
    };
    let poses = all("poses", &|frame| frame.pose);
    let twists = all("twists", &|frame| frame.twist);
    let biases = all("biases", &|frame| frame.bias);
    // Σ_b J_bᵀ w_b over every body's wrench w_b = dir[3b..3b + 3], one backward pass.
    let wrench = f.tree.as_ref().map(|terms| e.body(&crate::emit::vector_outputs("out", &terms.wrench)).0);
    let n_wrench = usize_lit(3 * m.bodies.len());
    let table = |array: TokenStream| quote!(let mut #array = [[#zero; 3]; #nb];);
    let (pose_table, twist_table, bias_table) = (table(quote!(poses)), table(quote!(twists)), table(quote!(biases)));
    let twist_of = |x: TokenStream| {
        quote! {
            #[allow(clippy::redundant_locals)]
            let v = #x;
            #twist_table
            #twists
            let [vx, vy, w] = twists[body];
        }
    };
    let (twist_x, twist_vd) = (twist_of(quote!(x)), twist_of(quote!(vd)));
    quote! {
        #[allow(unused_variables, unused_mut, unused_parens, clippy::approx_constant)]
        impl ::mbd::BodyFrames<#real, #n, #n> for #name {
            #[inline]
            fn body_pose(&self, body: usize, q: &[#real; #n]) -> ::core::option::Option<::mbd::BodyPose<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #pose_table
                #poses
                let [x, y, phi] = poses[body];
                ::core::option::Option::Some(::mbd::BodyPose::planar(x, y, phi))
            }
            #[inline]
            fn body_twist(&self, body: usize, q: &[#real; #n], x: &[#real; #n]) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #twist_x
                ::core::option::Option::Some(::mbd::BodyTwist { velocity: [vx, vy, #zero], angular_velocity: [#zero, #zero, w] })
            }
            #[inline]
            fn body_acceleration(
                &self,
                body: usize,
                q: &[#real; #n],
                v: &[#real; #n],
                vd: &[#real; #n],
            ) -> ::core::option::Option<::mbd::BodyTwist<#real>> {
                if body >= #nb {
                    return ::core::option::Option::None;
                }
                #bias_table
                #biases
                let [bx, by, bw] = biases[body];
                #twist_vd
                ::core::option::Option::Some(::mbd::BodyTwist { velocity: [vx + bx, vy + by, #zero], angular_velocity: [#zero, #zero, w + bw] })
            }
            #[inline]
            fn add_body_wrench(&self, body: usize, q: &[#real; #n], force: [#real; 3], moment: [#real; 3], g: &mut [#real; #n]) -> bool {
                if body >= #nb {
                    return false;
                }
                let mut dir = [#zero; #n_wrench];
                dir[3 * body..3 * body + 3].copy_from_slice(&[force[0], force[1], moment[2]]);
                let mut out = [#zero; #n];
                #wrench
                for (g, out) in g.iter_mut().zip(&out) {
                    *g += *out;
                }
                true
            }
        }
    }
}
