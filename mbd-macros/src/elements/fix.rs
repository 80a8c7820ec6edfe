//! `fix body.c [= value];` — a simple constraint (Nikravesh 7.2): the coordinate c keeps a value,
//! by default its initial value `at:`.
//!
//! Row `c`: q_c − value.

use serde_json::{json, Value};

use super::{Driven, Joint, Resolved};
use crate::frames::{Builder, Row};
use crate::json::Ctx;
use crate::model::{Body, BodyRef, Coord, MExpr, Resolver, Scope};
use crate::parse::FixDef;

#[derive(Debug)]
pub struct Fix {
    pub body: usize,
    pub coord: Coord,
    pub value: MExpr,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a FixDef, driven: &mut Driven, bodies: &[Body]) -> Option<Resolved<'a>> {
    let body = r.body(&f.body);
    if r.space == crate::model::Space::Spatial {
        r.errors.push(
            f.keyword.span(),
            "`fix` is planar: in space, drive the coordinate (`drive body.x = 0.1;`) or hold the body with a `rigid` joint",
        );
        return None;
    }
    let coord = Coord::from_ident(r.space, &f.coordinate);
    if coord.is_none() {
        r.errors.push(f.coordinate.span(), format!("unknown coordinate `{}`: a body has `x`, `y` and `phi`", f.coordinate));
    }
    match (body, coord) {
        (Some(BodyRef::Ground), _) => {
            r.errors.push(f.body.span(), "the ground is fixed already");
            None
        }
        (Some(BodyRef::Body(k)), Some(coord)) => {
            if driven.coords.insert((k, coord), f.coordinate.span()).is_some() {
                r.errors.push(f.coordinate.span(), format!("`{}.{}` is already fixed or driven", f.body, coord.name()));
                return None;
            }
            let value = match &f.value {
                Some(e) => r.expr(e, Scope::Params),
                None => bodies.iter().find(|b| b.name == f.body).map(|b| b.q0[coord.index()].clone()),
            };
            value.map(|value| {
                let name = format!("fix {}.{}", f.body, coord.name());
                (f.label.as_ref(), name, f.keyword.span(), Box::new(Fix { body: k, coord, value }) as Box<dyn Joint>, Vec::new())
            })
        }
        _ => None,
    }
}

impl Joint for Fix {
    fn kind(&self) -> &'static str {
        "fix"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(BodyRef::Body(self.body)), None)
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let q = b.coord(BodyRef::Body(self.body), self.coord);
        let f = b.expr(&self.value);
        vec![Row { name: self.coord.name(), value: b.g.sub(q, f) }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"body": cx.body(BodyRef::Body(self.body)), "coordinate": self.coord.name(), "value": cx.expr(&self.value)})
    }
}
