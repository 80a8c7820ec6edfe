//! Mirrored instances: `corner front_right(x0: 1.3) mirrored y;` is the instance's statements
//! reflected in the plane through the origin normal to y (in the plane: the line normal to x or
//! y), so that one part declares both the left and the right corner of a vehicle.
//!
//! The reflection S negates one world coordinate. A mirrored body's frame is S A S (still
//! right-handed; its principal inertias unchanged), so what is written in a body's frame is
//! reflected by S too, and the mirrored instance moves as the mirror image of the plain one in a
//! world symmetric about that plane. On the tokens, after the part's parameters are replaced and
//! its loops and instances expanded, each statement is rewritten:
//!
//! - positions and directions (`at`, `velocity`, points, vectors, inline points, axes, forces,
//!   gravity): the mirrored component negated;
//! - turns (a planar angle, angular velocity or torque; a joint's angle, its driver, a rotational
//!   spring's rest angle and torque): negated; in space the axial quantities (`omega`, a torque,
//!   the quaternion's vector part, an `axis_angle` axis) keep the mirrored component and negate
//!   the other two, the z-y-x `angles` negate the turns about the other two axes, and the
//!   products of inertia that pair the mirrored axis with another are negated;
//! - a spatial marker's frame becomes (S x, −S y, S z) of the plain one's: its axis and
//!   reference are reflected, and a marker without a reference gets the reflection of the one
//!   it had by default (the coordinate axis least along its axis) — so a joint's angle is −θ,
//!   its stroke s, and a bushing's offsets along and turns about the marker axes (y; x and z)
//!   change sign;
//! - expressions read the mirror image of the state: `b.y` is `(-b.y)` when y is mirrored, `b.phi`
//!   is `(-b.phi)`, and so on.
//!
//! What a mirrored instance cannot reflect is an error on it: a named point or vector declared
//! outside its part (its values are the mechanism's), a marker whose axis is an expression and
//! has no `reference` (its default reference is not known here), a tyre whose vertical is the
//! mirrored axis.

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};

use crate::scene::{label, statements};

/// The reflection: which coordinate it negates, in which space, and where it was asked for.
#[derive(Clone)]
pub struct Mirror {
    pub axis: usize,
    pub spatial: bool,
    pub span: Span,
    /// The instance being reflected, as written (for errors).
    instance: String,
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl Mirror {
    /// The coordinate names of the mirrored axis, `mirrored y` → 1.
    pub fn parse(word: &Ident, spatial: bool) -> syn::Result<Mirror> {
        let axes = if spatial { &AXES[..] } else { &AXES[..2] };
        match axes.iter().position(|a| word == a) {
            Some(axis) => Ok(Mirror { axis, spatial, span: word.span(), instance: String::new() }),
            None => Err(syn::Error::new(
                word.span(),
                format!(
                    "expected the axis the mirror plane is normal to, {}, found `{word}`",
                    if spatial { "`x`, `y` or `z`" } else { "`x` or `y` (in the plane)" }
                ),
            )),
        }
    }

    /// The statements of instance `instance`, reflected.
    pub fn apply(&self, tokens: Vec<TokenTree>, instance: &str) -> syn::Result<Vec<TokenTree>> {
        let this = Mirror { instance: instance.to_string(), ..self.clone() };
        this.reflect(tokens)
    }

    fn reflect(&self, tokens: Vec<TokenTree>) -> syn::Result<Vec<TokenTree>> {
        let statements = statements(tokens.into_iter().collect());
        let declared: Vec<(String, String, Vec<TokenTree>)> = statements
            .iter()
            .filter_map(|s| match s.as_slice() {
                [TokenTree::Ident(k), TokenTree::Ident(b), dot, TokenTree::Ident(p), eq, TokenTree::Group(v), ..]
                    if (k == "point" || k == "vector") && is_punct(dot, '.') && is_punct(eq, '=') =>
                {
                    Some((b.to_string(), p.to_string(), v.stream().into_iter().collect()))
                }
                _ => None,
            })
            .collect();
        let mut out = Vec::new();
        for s in &statements {
            out.extend(self.statement(s, &declared)?);
        }
        Ok(out)
    }

    fn statement(&self, s: &[TokenTree], declared: &[(String, String, Vec<TokenTree>)]) -> syn::Result<Vec<TokenTree>> {
        let Some(TokenTree::Ident(keyword)) = s.first() else { return Ok(s.to_vec()) };
        let kind = keyword.to_string();
        // The statement after its keyword and label.
        let head = if label(s).is_some() { 3 } else { 1 };
        let (lead, rest) = s.split_at(head);
        let mut out: Vec<TokenTree> = lead.to_vec();
        match kind.as_str() {
            "body" | "particle" => out.extend(rest.iter().map(|t| match t {
                TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => self.fields(g, |name, value| self.body_field(name, value)),
                other => other.clone(),
            })),
            "point" | "vector" => out.extend(rest.iter().map(|t| match t {
                TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket => self.list(g, |k, c| self.polar(k, c)),
                other => other.clone(),
            })),
            "gravity" => out.extend(rest.iter().map(|t| match t {
                TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket => self.list(g, |k, c| self.polar(k, c)),
                other => other.clone(),
            })),
            "drive" | "fix" => {
                let eq = rest.iter().position(|t| is_punct(t, '=')).unwrap_or(rest.len());
                let (target, value) = rest.split_at(eq);
                let negated = match target {
                    [TokenTree::Ident(f), TokenTree::Group(args)] if f == "distance" || f == "angle" => {
                        out.push(target[0].clone());
                        out.push(TokenTree::Group(
                            self.regroup(args, self.attachments(&args.stream().into_iter().collect::<Vec<_>>(), declared)?),
                        ));
                        f == "angle"
                    }
                    [_, dot, TokenTree::Ident(c)] if is_punct(dot, '.') => {
                        out.extend(target.iter().cloned());
                        let c = c.to_string();
                        c == AXES[self.axis] || c == "phi" || c == "angle"
                    }
                    _ => {
                        out.extend(target.iter().cloned());
                        false
                    }
                };
                if let [eq, expr @ .., semi] = value {
                    out.push(eq.clone());
                    let expr = self.substitute(expr);
                    out.extend(if negated { self.negated(expr) } else { expr });
                    out.push(semi.clone());
                } else {
                    out.extend(value.iter().cloned());
                }
            }
            "constraint" => out.extend(self.substitute(rest)),
            "force" | "local_force" | "torque" | "local_torque" => {
                let eq = rest.iter().position(|t| is_punct(t, '=')).unwrap_or(rest.len());
                let (at, value) = rest.split_at(eq);
                if kind.ends_with("force") {
                    out.extend(self.attachments(at, declared)?);
                } else {
                    out.extend(at.iter().cloned());
                }
                if let [eq, expr @ .., semi] = value {
                    out.push(eq.clone());
                    let expr = self.substitute(expr);
                    match expr.as_slice() {
                        [TokenTree::Group(g)] if g.delimiter() == Delimiter::Bracket && kind.ends_with("force") => {
                            out.push(self.list(g, |k, c| self.polar(k, c)))
                        }
                        [TokenTree::Group(g)] if g.delimiter() == Delimiter::Bracket => out.push(self.list(g, |k, c| self.axial(k, c))),
                        _ => out.extend(self.negated(expr)),
                    }
                    out.push(semi.clone());
                } else {
                    out.extend(value.iter().cloned());
                }
            }
            "rotational_spring"
            | "rotational_damper"
            | "torque_actuator"
            | "translational_spring"
            | "translational_damper"
            | "force_actuator" => {
                let turn = kind.starts_with("rotational") || kind == "torque_actuator";
                out.extend(rest.iter().map(|t| match t {
                    TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => self.fields(g, |name, value| {
                        let value = self.substitute(&value);
                        if turn && (name == "angle" || name == "torque") {
                            self.negated(value)
                        } else {
                            value
                        }
                    }),
                    other => other.clone(),
                }));
            }
            k if crate::elements::is_joint_keyword(k) || crate::parse::POINT_FORCE_KINDS.contains(&k) => {
                if k == "tyre" && self.axis == if self.spatial { 2 } else { 1 } {
                    return Err(syn::Error::new(
                        keyword.span(),
                        format!(
                            "a tyre acts along the vertical ({}): expected a mirror plane that keeps it, found `mirrored {}` on instance `{}`",
                            AXES[self.axis], AXES[self.axis], self.instance
                        ),
                    ));
                }
                let frames = self.spatial && (k == "bushing" || crate::elements::spatial::spec(k).is_some());
                let options = rest.iter().position(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace));
                let (sides, tail) = rest.split_at(options.unwrap_or(rest.len().saturating_sub(1)));
                let mut done: Vec<TokenTree> = Vec::new();
                let mut side: Vec<TokenTree> = Vec::new();
                let mut which = 0;
                for t in sides {
                    if is_punct(t, '~') {
                        done.extend(self.attachments_with_frame(&side, declared, frames, k, which)?);
                        done.push(t.clone());
                        side.clear();
                        which += 1;
                    } else {
                        side.push(t.clone());
                    }
                }
                done.extend(self.attachments_with_frame(&side, declared, frames, k, which)?);
                out.extend(done);
                out.extend(tail.iter().map(|t| match t {
                    TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => self.fields(g, |name, value| {
                        let value = self.substitute(&value);
                        match (name, value.as_slice()) {
                            // A planar rigid joint's angle and a pin-in-slot's signed distance.
                            ("angle", _) | ("distance", _) if !self.spatial => self.negated(value),
                            ("preload", [TokenTree::Group(g)]) if g.delimiter() == Delimiter::Bracket => {
                                vec![self.list(g, |k, c| if k == 1 || k == 3 || k == 5 { self.negated(c) } else { c })]
                            }
                            _ => value,
                        }
                    }),
                    other => other.clone(),
                }));
            }
            _ => out.extend(rest.iter().cloned()),
        }
        Ok(out)
    }

    /// A body's field: `at` and `velocity` (planar: with φ and ω), `omega`, the orientation, the
    /// products of inertia.
    fn body_field(&self, name: &str, value: Vec<TokenTree>) -> Vec<TokenTree> {
        let [TokenTree::Group(g)] = value.as_slice() else { return value };
        if g.delimiter() != Delimiter::Bracket {
            return value;
        }
        let m = self.axis;
        let field = match name {
            // [x, y, φ] in the plane; [x, y, z] in space.
            "at" | "velocity" => self.list(g, |k, c| if k == m || (!self.spatial && k == 2) { self.negated(c) } else { c }),
            "omega" => self.list(g, |k, c| self.axial(k, c)),
            "quaternion" => self.list(g, |k, c| if k >= 1 && k - 1 != m { self.negated(c) } else { c }),
            "axis_angle" => self.list(g, |k, c| if k < 3 { self.axial(k, c) } else { c }),
            // yaw, pitch, roll: turns about z, y, x.
            "angles" => self.list(g, |k, c| if k < 3 && 2 - k != m { self.negated(c) } else { c }),
            // [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]
            "inertia" => {
                let pairs = [(0, 1), (0, 2), (1, 2)];
                self.list(g, |k, c| match k.checked_sub(3).and_then(|p| pairs.get(p)) {
                    Some(&(a, b)) if (a == m) != (b == m) => self.negated(c),
                    _ => c,
                })
            }
            _ => return value,
        };
        vec![field]
    }

    /// A polar vector's component: negated on the mirrored axis.
    fn polar(&self, k: usize, c: Vec<TokenTree>) -> Vec<TokenTree> {
        if k == self.axis {
            self.negated(c)
        } else {
            c
        }
    }

    /// An axial vector's component (a turn, a torque): negated off the mirrored axis.
    fn axial(&self, k: usize, c: Vec<TokenTree>) -> Vec<TokenTree> {
        if k != self.axis {
            self.negated(c)
        } else {
            c
        }
    }

    /// One side of a joint or force element: its inline point reflected, its axis and reference
    /// too; a spatial marker (`frames`) gets its reference written out.
    fn attachments_with_frame(
        &self,
        side: &[TokenTree],
        declared: &[(String, String, Vec<TokenTree>)],
        frames: bool,
        kind: &str,
        which: usize,
    ) -> syn::Result<Vec<TokenTree>> {
        let mut out = self.attachments(side, declared)?;
        if !frames || side.is_empty() {
            return Ok(out);
        }
        let has_axis = side.iter().any(|t| matches!(t, TokenTree::Ident(a) if a == "along"));
        let has_reference = side.iter().any(|t| matches!(t, TokenTree::Ident(a) if a == "reference"));
        let axis_kind = if kind == "bushing" {
            crate::elements::spatial::Axis::Default
        } else {
            let spec = crate::elements::spatial::spec(kind).expect("a spatial joint");
            if which == 0 {
                spec.axis_i
            } else {
                spec.axis_j
            }
        };
        // No frame, a reference written (and reflected), or an axis missing where the kind needs
        // one (the parser's error).
        if axis_kind == crate::elements::spatial::Axis::None
            || has_reference
            || (!has_axis && axis_kind == crate::elements::spatial::Axis::Required)
        {
            return Ok(out);
        }
        let span = self.span;
        // The plain marker's axis (z by default) and its default reference.
        let axis: Vec<f64> = if has_axis {
            let at = side.iter().position(|t| matches!(t, TokenTree::Ident(a) if a == "along")).expect("found above");
            match self.literal_vector(&side[at + 1..], declared) {
                Some(a) => a,
                None => {
                    return Err(syn::Error::new(
                        side[at].span(),
                        format!(
                            "instance `{}` is mirrored in {}: a marker whose axis is not written in numbers needs its reference there: \
                             expected `along [..] reference [..]`, found no `reference`",
                            self.instance, AXES[self.axis]
                        ),
                    ))
                }
            }
        } else {
            vec![0.0, 0.0, 1.0]
        };
        let magnitudes: Vec<f64> = axis.iter().map(|a| a.abs()).collect();
        let least = (0..3).fold(0, |best, k| if magnitudes[k] < magnitudes[best] { k } else { best });
        let reference: Vec<f64> = (0..3)
            .map(|k| {
                if k != least {
                    0.0
                } else if k == self.axis {
                    -1.0
                } else {
                    1.0
                }
            })
            .collect();
        let vector = |v: &[f64]| {
            let items: Vec<TokenTree> = v
                .iter()
                .enumerate()
                .flat_map(|(k, x)| {
                    let mut t = Vec::new();
                    if k > 0 {
                        t.push(TokenTree::Punct(Punct::new(',', Spacing::Alone)));
                    }
                    if *x < 0.0 {
                        t.push(TokenTree::Punct(Punct::new('-', Spacing::Alone)));
                    }
                    let mut l = Literal::f64_unsuffixed(x.abs());
                    l.set_span(span);
                    t.push(TokenTree::Literal(l));
                    t
                })
                .collect();
            let mut g = Group::new(Delimiter::Bracket, items.into_iter().collect());
            g.set_span(span);
            TokenTree::Group(g)
        };
        if !has_axis {
            let z: Vec<f64> = (0..3)
                .map(|k| {
                    if k != 2 {
                        0.0
                    } else if self.axis == 2 {
                        -1.0
                    } else {
                        1.0
                    }
                })
                .collect();
            out.push(TokenTree::Ident(Ident::new("along", span)));
            out.push(vector(&z));
        }
        out.push(TokenTree::Ident(Ident::new("reference", span)));
        out.push(vector(&reference));
        Ok(out)
    }

    /// The numbers of a vector written `[a, b, c]` (signs allowed) or named by a `vector`
    /// declared in the instance.
    fn literal_vector(&self, tokens: &[TokenTree], declared: &[(String, String, Vec<TokenTree>)]) -> Option<Vec<f64>> {
        let items: Vec<TokenTree> = match tokens {
            [TokenTree::Group(g), ..] if g.delimiter() == Delimiter::Bracket => g.stream().into_iter().collect(),
            [TokenTree::Ident(b), dot, TokenTree::Ident(v), ..] if is_punct(dot, '.') => {
                declared.iter().find(|(db, dv, _)| b == db && v == dv)?.2.clone()
            }
            _ => return None,
        };
        items
            .split(|t| is_punct(t, ','))
            .filter(|c| !c.is_empty())
            .map(|c| match c {
                [TokenTree::Literal(l)] => l.to_string().parse::<f64>().ok(),
                [minus, TokenTree::Literal(l)] if is_punct(minus, '-') => l.to_string().parse::<f64>().ok().map(|x| -x),
                _ => None,
            })
            .collect::<Option<Vec<f64>>>()
            .filter(|v| v.len() == 3)
    }

    /// Attachments (`b[..]`, `b.P`, `along [..]`, `reference [..]`) reflected: inline points and
    /// written vectors; a named point or vector must be declared in the instance.
    fn attachments(&self, tokens: &[TokenTree], declared: &[(String, String, Vec<TokenTree>)]) -> syn::Result<Vec<TokenTree>> {
        let mut out = Vec::new();
        for (i, t) in tokens.iter().enumerate() {
            match t {
                TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket && i > 0 && matches!(tokens[i - 1], TokenTree::Ident(_)) => {
                    out.push(self.list(g, |k, c| self.polar(k, c)))
                }
                TokenTree::Ident(p) if i >= 2 && is_punct(&tokens[i - 1], '.') => {
                    let TokenTree::Ident(b) = &tokens[i - 2] else {
                        out.push(t.clone());
                        continue;
                    };
                    if !declared.iter().any(|(db, dp, _)| b == db && p == dp) {
                        return Err(syn::Error::new(
                            p.span(),
                            format!(
                                "instance `{}` is mirrored in {}, which reflects what its part declares: expected a point or vector declared \
                                 in the part, or written in place (`{b}[x, y, ..]`), found `{b}.{p}`, declared outside it",
                                self.instance, AXES[self.axis]
                            ),
                        ));
                    }
                    out.push(t.clone());
                }
                TokenTree::Group(g) => {
                    out.push(TokenTree::Group(self.regroup(g, self.attachments(&g.stream().into_iter().collect::<Vec<_>>(), declared)?)))
                }
                other => out.push(other.clone()),
            }
        }
        Ok(out)
    }

    /// An expression reading the mirror image of the state: each coordinate or velocity the
    /// reflection negates, negated.
    fn substitute(&self, tokens: &[TokenTree]) -> Vec<TokenTree> {
        let negated: Vec<String> = if self.spatial {
            let mut n = vec![AXES[self.axis].to_string(), format!("v{}", AXES[self.axis])];
            for k in (0..3).filter(|k| *k != self.axis) {
                n.push(format!("w{}", AXES[k]));
                n.push(format!("e{}", k + 1));
            }
            n
        } else {
            vec![AXES[self.axis].to_string(), format!("v{}", AXES[self.axis]), "phi".to_string(), "omega".to_string()]
        };
        let mut out: Vec<TokenTree> = Vec::new();
        let mut i = 0;
        while i < tokens.len() {
            match (&tokens[i], tokens.get(i + 1), tokens.get(i + 2), tokens.get(i + 3)) {
                (TokenTree::Ident(b), Some(dot), Some(TokenTree::Ident(c)), next)
                    if is_punct(dot, '.')
                        && negated.contains(&c.to_string())
                        && !matches!(next, Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis)
                        && !(i > 0 && is_punct(&tokens[i - 1], '.')) =>
                {
                    let read: Vec<TokenTree> = vec![TokenTree::Ident(b.clone()), dot.clone(), TokenTree::Ident(c.clone())];
                    out.extend(self.negated(read));
                    i += 3;
                }
                (TokenTree::Group(g), ..) => {
                    out.push(TokenTree::Group(self.regroup(g, self.substitute(&g.stream().into_iter().collect::<Vec<_>>()))));
                    i += 1;
                }
                (other, ..) => {
                    out.push(other.clone());
                    i += 1;
                }
            }
        }
        out
    }

    /// `(-(tokens))`.
    fn negated(&self, tokens: Vec<TokenTree>) -> Vec<TokenTree> {
        let mut inner = Group::new(Delimiter::Parenthesis, tokens.into_iter().collect());
        inner.set_span(self.span);
        let mut minus = Punct::new('-', Spacing::Alone);
        minus.set_span(self.span);
        let mut outer = Group::new(Delimiter::Parenthesis, [TokenTree::Punct(minus), TokenTree::Group(inner)].into_iter().collect());
        outer.set_span(self.span);
        vec![TokenTree::Group(outer)]
    }

    /// A bracket list with each component (split at top-level commas) mapped with its index.
    fn list(&self, g: &Group, mut f: impl FnMut(usize, Vec<TokenTree>) -> Vec<TokenTree>) -> TokenTree {
        let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
        let mut out: Vec<TokenTree> = Vec::new();
        for (k, c) in tokens.split(|t| is_punct(t, ',')).enumerate() {
            if k > 0 {
                out.push(TokenTree::Punct(Punct::new(',', Spacing::Alone)));
            }
            if !c.is_empty() {
                out.extend(f(k, c.to_vec()));
            }
        }
        TokenTree::Group(self.regroup(g, out))
    }

    /// A brace group of `name: value` fields with each value mapped.
    fn fields(&self, g: &Group, mut f: impl FnMut(&str, Vec<TokenTree>) -> Vec<TokenTree>) -> TokenTree {
        let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
        let mut out: Vec<TokenTree> = Vec::new();
        for (k, field) in tokens.split(|t| is_punct(t, ',')).enumerate() {
            if k > 0 {
                out.push(TokenTree::Punct(Punct::new(',', Spacing::Alone)));
            }
            match field {
                [TokenTree::Ident(name), colon, value @ ..] if is_punct(colon, ':') && !value.is_empty() => {
                    out.push(field[0].clone());
                    out.push(colon.clone());
                    out.extend(f(&name.to_string(), value.to_vec()));
                }
                other => out.extend(other.iter().cloned()),
            }
        }
        TokenTree::Group(self.regroup(g, out))
    }

    /// `tokens` in a group of `g`'s delimiter and span.
    fn regroup(&self, g: &Group, tokens: Vec<TokenTree>) -> Group {
        let mut group = Group::new(g.delimiter(), tokens.into_iter().collect::<TokenStream>());
        group.set_span(g.span());
        group
    }
}

fn is_punct(tt: &TokenTree, c: char) -> bool {
    matches!(tt, TokenTree::Punct(p) if p.as_char() == c)
}

#[cfg(test)]
mod tests {
    use crate::expand::expand;
    use quote::quote;

    /// What a reflection cannot rewrite is an error on it, saying what was expected.
    #[test]
    fn what_a_mirrored_instance_cannot_reflect_is_an_error() {
        let cases = [
            (
                quote!(M { point ground.mount = [1.0, 0.5]; part p() { body b { mass: 1.0, inertia: 0.1 } revolute ground.mount ~ b[0.0, 0.0]; } p l(); p r() mirrored x; }),
                "instance `r` is mirrored in x, which reflects what its part declares: expected a point or vector declared in the part, or written in place (`ground[x, y, ..]`), found `ground.mount`, declared outside it",
            ),
            (
                quote!(M { spatial; params { a: 1.0 } part p() { body b { mass: 1.0, inertia: [0.1, 0.1, 0.1] } revolute ground[0.0, 0.0, 0.0] along [a, 0.0, 0.0] ~ b[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0]; } p r() mirrored y; }),
                "instance `r` is mirrored in y: a marker whose axis is not written in numbers needs its reference there: expected `along [..] reference [..]`, found no `reference`",
            ),
            (
                quote!(M { part p() { body b { mass: 1.0, inertia: 0.1 } tyre b[0.0, 0.0] ~ ground[0.0, 0.0] { radius: 0.3, k: 1.0e5 }; } p r() mirrored y; }),
                "a tyre acts along the vertical (y): expected a mirror plane that keeps it, found `mirrored y` on instance `r`",
            ),
            (quote!(M { part p() { body b { mass: 1.0, inertia: 0.1 } } p r() mirrored z; }), "expected the axis the mirror plane is normal to, `x` or `y` (in the plane), found `z`"),
            (quote!(M { part p() { body b { mass: 1.0, inertia: 0.1 } } p r() mirrored; }), "expected `p r(...) mirrored x;` (the axis the mirror plane is normal to), found something else after `mirrored`"),
            (quote!(M { part p() { body b { mass: 1.0, inertia: 0.1 } } p r() mirror x; }), "expected `;` or `mirrored x;` after the parameters of instance `r`, found `mirror` (did you mean `mirrored`?)"),
        ];
        for (input, want) in cases {
            let e = expand(input).to_string();
            assert!(e.contains(want), "{e}\n  wanted: {want}");
        }
    }
}
