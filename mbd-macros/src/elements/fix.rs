//! `fix body.c [= value];` — a simple constraint (Nikravesh 7.2): the coordinate c keeps a value,
//! by default its initial value `at:`. Planar bodies: c is `x`, `y` or `phi`; spatial bodies: `x`,
//! `y` or `z` (an orientation is held by a `rigid` joint, since no single Euler parameter is an
//! angle a user would fix).
//!
//! Row `c`: q_c − value.

use serde_json::{json, Value};

use super::{Driven, Joint, Resolved};
use crate::frames::{Builder, Row, RowUnit};
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
    let coord = Coord::from_ident(r.space, &f.coordinate).filter(|c| !c.is_euler_parameter());
    if coord.is_none() {
        let msg = match r.space {
            crate::model::Space::Planar => format!("unknown coordinate: expected `x`, `y` or `phi`, found `{}`", f.coordinate),
            crate::model::Space::Spatial => format!(
                "`{}` cannot be fixed: expected a spatial body's `x`, `y` or `z`, found its orientation's `{}`; hold its orientation with a `rigid` joint (to `ground` or to another body)",
                f.coordinate, f.coordinate
            ),
        };
        r.errors.push(f.coordinate.span(), msg);
    }
    match (body, coord) {
        (Some(BodyRef::Ground), _) => {
            r.errors.push(f.body.span(), "expected a moving body, found `ground`, which is fixed already");
            None
        }
        (Some(BodyRef::Body(k)), Some(coord)) => {
            if driven.coords.insert((k, coord), f.coordinate.span()).is_some() {
                r.errors.push(
                    f.coordinate.span(),
                    format!(
                        "`{}.{}` is fixed or driven twice: expected one `fix` or `drive` per coordinate, found a second one; remove one",
                        f.body,
                        coord.name()
                    ),
                );
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
        vec![Row { name: self.coord.name(), value: b.g.sub(q, f), unit: RowUnit::of(self.coord) }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"body": cx.body(BodyRef::Body(self.body)), "coordinate": self.coord.name(), "value": cx.expr(&self.value)})
    }
}
