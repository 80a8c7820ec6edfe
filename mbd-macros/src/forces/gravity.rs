//! `gravity [gx, gy];` (`[gx, gy, gz]` in space) — m g on every body's centre of mass (m/s², any
//! direction):
//! Q = (∂ṙ_k/∂v)ᵀ m_k g, V = −Σ m_k gᵀ r_k.

use super::Generalized;
use crate::frames::Builder;
use crate::model::{BodyRef, Coord, MExpr};

pub fn apply(b: &mut Builder, g: &[MExpr], out: &mut Generalized) {
    let g: Vec<_> = g.iter().map(|e| b.expr(e)).collect();
    let axes = &[Coord::X, Coord::Y, Coord::Z][..g.len()];
    for k in 0..b.model.bodies.len() {
        let m = b.expr(&b.model.bodies[k].mass);
        for (a, &coord) in axes.iter().enumerate() {
            let w = b.g.mul(m, g[a]);
            b.add_to_origin_velocity(&mut out.h, k, a, w);
            // V = −m gᵀ r
            let r = b.coord(BodyRef::Body(k), coord);
            let e = b.g.mul(w, r);
            out.potential = b.g.sub(out.potential, e);
        }
    }
}
