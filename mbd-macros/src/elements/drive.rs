//! `drive body.c = f(t);` — an absolute driver (Nikravesh 7.4): a body's x, y or φ follows f.
//!
//! Row `c`: q_c − f(t).

use proc_macro2::Span;
use serde_json::{json, Value};
use syn::Ident;

use super::{Driven, Joint, Resolved};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Coord, MExpr, Resolver};
use crate::parse::DriveDef;

#[derive(Debug)]
pub struct Drive {
    pub body: usize,
    pub coord: Coord,
    pub f: MExpr,
}

pub fn resolve<'a>(
    r: &mut Resolver,
    d: &'a DriveDef,
    body: &Ident,
    coordinate: &Ident,
    f: Option<MExpr>,
    driven: &mut Driven,
) -> Option<Resolved<'a>> {
    let b = r.body(body);
    let coord = Coord::from_ident(r.space, coordinate).filter(|c| !c.is_euler_parameter());
    if coord.is_none() {
        let msg = match r.space {
            crate::model::Space::Planar => format!("unknown coordinate: expected `x`, `y` or `phi`, found `{coordinate}`"),
            crate::model::Space::Spatial => format!(
                "`{coordinate}` cannot be driven: expected a spatial body's `x`, `y` or `z`, found its orientation's `{coordinate}`; drive its orientation through a joint (`drive hinge.angle = f;`)"
            ),
        };
        r.errors.push(coordinate.span(), msg);
    }
    match (b, coord, f) {
        (Some(BodyRef::Ground), _, _) => {
            r.errors.push(body.span(), "expected a moving body, found `ground`, which cannot be driven");
            None
        }
        (Some(BodyRef::Body(k)), Some(coord), f) => {
            let span: Span = coordinate.span();
            if driven.coords.insert((k, coord), span).is_some() {
                r.errors.push(span, format!("`{body}.{}` is fixed or driven twice: expected one `fix` or `drive` per coordinate, found a second one; remove one", coord.name()));
                return None;
            }
            let f = f?;
            let name = format!("drive {body}.{}", coord.name());
            Some((d.label.as_ref(), name, d.keyword.span(), Box::new(Drive { body: k, coord, f }) as Box<dyn Joint>, Vec::new()))
        }
        _ => None,
    }
}

impl Joint for Drive {
    fn kind(&self) -> &'static str {
        "drive"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(BodyRef::Body(self.body)), None)
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let q = b.coord(BodyRef::Body(self.body), self.coord);
        let f = b.expr(&self.f);
        vec![Row { name: self.coord.name(), value: b.g.sub(q, f), unit: RowUnit::of(self.coord) }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"body": cx.body(BodyRef::Body(self.body)), "coordinate": self.coord.name(), "f": cx.expr(&self.f)})
    }
}
