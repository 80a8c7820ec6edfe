//! `gravity [gx, gy];` — m g on every body's centre of mass (m/s², any direction):
//! Q = (∂ṙ_k/∂v)ᵀ m_k g, V = −Σ m_k gᵀ r_k.

use super::Generalized;
use crate::frames::Builder;
use crate::model::{BodyRef, Coord, MExpr};

pub fn apply(b: &mut Builder, g: &[MExpr; 2], out: &mut Generalized) {
    let g = b.exprs(g);
    for k in 0..b.model.bodies.len() {
        let m = b.expr(&b.model.bodies[k].mass);
        for (a, coord) in [Coord::X, Coord::Y].into_iter().enumerate() {
            let w = b.g.mul(m, g[a]);
            b.add_to_origin_velocity(&mut out.h, k, a, w);
            // V = −m gᵀ r
            let r = b.coord(BodyRef::Body(k), coord);
            let e = b.g.mul(w, r);
            out.potential = b.g.sub(out.potential, e);
        }
    }
}
