//! Stage 0, first of all: named expressions.
//!
//! ```text
//! let name = expression;
//! ```
//!
//! A `let` at the mechanism's level names an expression — of parameters, coordinates,
//! velocities, `t`, other `let`s —, and every use of the name in the mechanism's expressions
//! stands for it, in parentheses: `let psi = 2.0 * atan2(sin(crank.phi / 2.0), cos(crank.phi /
//! 2.0));` then `force gas: piston[0.0, 0.0] = [0.0, if abs(psi) < PI { … } else { 0.0 }];`.
//! Like every name of the mechanism, a `let` may be used before it is written. It is replaced on
//! the tokens before parts, loops and parsing see them, so a mechanism generates exactly what it
//! generates with each use written out by hand; the generated code shares the repeated
//! expression once, as it shares every common subexpression.
//!
//! A name after `.` (a coordinate, `crank.x`) or before a single `:` (an option, a label, a
//! parameter) is never replaced. A `let` may not take the name of a parameter, a body (a name
//! used with `.` or `[`), a label, a loop variable, a part's parameter, a part or an instance, a
//! mirror's axis, a function or a word of the DSL; nor refer to itself, directly or through
//! others; and it must be used: an unused one would never be read, nor a mistake in it
//! reported. A statement's keyword inside its value is a `;` left out.
//! The replacement keeps the spans of the `let`'s expression, so a mistake in it is reported
//! there.

use std::collections::BTreeMap;

use proc_macro2::{Delimiter, Group, Ident, Spacing, TokenStream, TokenTree};

/// Names a `let` may not take: the expressions' own words.
const RESERVED: &[&str] = &[
    "t",
    "PI",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sqrt",
    "exp",
    "ln",
    "pow",
    "abs",
    "sign",
    "min",
    "max",
    "clamp",
    "deg",
    "if",
    "else",
    "ground",
    "angle",
    "along",
    "friction",
    "without",
    "actuating",
    "mirrored",
    "for",
    "in",
    "part",
];

/// A `let` as written: its name and its expression's tokens.
struct Binding {
    name: Ident,
    value: Vec<TokenTree>,
}

/// The mechanism's statements (the tokens inside its braces) with every `let` taken out and
/// every use of its name replaced by its expression in parentheses. Leniently (for a
/// placeholder after an error), the `let`s are taken out where one is in error, and their uses
/// left as they are.
pub fn substitute(body: TokenStream, lenient: bool) -> syn::Result<TokenStream> {
    let tokens: Vec<TokenTree> = body.into_iter().collect();
    let (bindings, rest) = match take_bindings(&tokens) {
        Ok(found) => found,
        Err(_) if lenient => return Ok(without_lets(&tokens).into_iter().collect()),
        Err(e) => return Err(e),
    };
    if bindings.is_empty() {
        return Ok(rest.into_iter().collect());
    }
    let resolved = match resolve(&bindings, &rest) {
        Ok(resolved) => resolved,
        Err(_) if lenient => BTreeMap::new(),
        Err(e) => return Err(e),
    };
    Ok(replace(&rest, &resolved).into_iter().collect())
}

/// The `let` statements (`let` at a statement's start) and the other tokens.
fn take_bindings(tokens: &[TokenTree]) -> syn::Result<(Vec<Binding>, Vec<TokenTree>)> {
    let (mut bindings, mut rest) = (Vec::new(), Vec::new());
    let mut at_start = true;
    let mut i = 0;
    while i < tokens.len() {
        let tt = &tokens[i];
        if at_start && matches!(tt, TokenTree::Ident(k) if k == "let") {
            let name = match tokens.get(i + 1) {
                Some(TokenTree::Ident(n)) => n.clone(),
                other => {
                    return Err(syn::Error::new(
                        other.map_or(tt.span(), TokenTree::span),
                        format!("expected a name after `let` (`let name = expression;`), found {}", written(other)),
                    ))
                }
            };
            match tokens.get(i + 2) {
                Some(TokenTree::Punct(p)) if p.as_char() == '=' && p.spacing() == Spacing::Alone => {}
                other => {
                    return Err(syn::Error::new(
                        other.map_or(name.span(), TokenTree::span),
                        format!("expected `=` after `let {name}`, found {}", written(other)),
                    ))
                }
            }
            let end = (i + 3..tokens.len()).find(|&k| is_punct(&tokens[k], ';')).ok_or_else(|| {
                syn::Error::new(name.span(), format!("expected `;` after the expression of `let {name}`, found the mechanism's end"))
            })?;
            // A statement's keyword in the value: the `;` was left out, and the next statement
            // would be swallowed.
            let keyword = (i + 3..end).find(|&k| {
                matches!(&tokens[k], TokenTree::Ident(w) if crate::parse::STATEMENTS.contains(&w.to_string().as_str()))
                    && !after_dot(tokens, k)
            });
            if let Some(k) = keyword {
                return Err(syn::Error::new(
                    tokens[k].span(),
                    format!("expected `;` after the expression of `let {name}`, found `{}`, a statement's keyword", tokens[k]),
                ));
            }
            if end == i + 3 {
                return Err(syn::Error::new(tokens[end].span(), format!("expected an expression after `let {name} =`, found `;`")));
            }
            let reserved = RESERVED.contains(&name.to_string().as_str()) || crate::parse::STATEMENTS.contains(&name.to_string().as_str());
            if reserved {
                return Err(syn::Error::new(
                    name.span(),
                    format!("expected a name of your own after `let`, found `{name}`, a word of the DSL"),
                ));
            }
            if bindings.iter().any(|b: &Binding| b.name == name) {
                return Err(syn::Error::new(
                    name.span(),
                    format!("expected a new name after `let`, found `{name}` again: `let {name}` is written twice"),
                ));
            }
            bindings.push(Binding { name, value: tokens[i + 3..end].to_vec() });
            i = end + 1;
            at_start = true;
            continue;
        }
        if let Some(nested) = nested_let(tt) {
            return Err(syn::Error::new(
                nested.span(),
                "expected a `let` at the mechanism's level, outside every loop and part, found `let` inside one",
            ));
        }
        at_start = is_punct(tt, ';') || matches!(tt, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
        rest.push(tt.clone());
        i += 1;
    }
    Ok((bindings, rest))
}

/// A `let` at a statement's start inside the brace group `tt` (a loop's or a part's
/// statements), at any depth.
fn nested_let(tt: &TokenTree) -> Option<Ident> {
    let TokenTree::Group(g) = tt else { return None };
    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
    let mut at_start = g.delimiter() == Delimiter::Brace;
    for tt in &inner {
        match tt {
            TokenTree::Ident(k) if at_start && k == "let" => return Some(k.clone()),
            _ => {}
        }
        if let Some(nested) = nested_let(tt) {
            return Some(nested);
        }
        at_start = is_punct(tt, ';') || matches!(tt, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
    }
    None
}

/// A token as a message names it: `x`, or "nothing" at the end.
fn written(tt: Option<&TokenTree>) -> String {
    tt.map_or_else(|| "nothing".to_string(), |tt| format!("`{tt}`"))
}

/// `tokens` without their `let` statements (each to its `;`, or to the end).
fn without_lets(tokens: &[TokenTree]) -> Vec<TokenTree> {
    let mut out = Vec::new();
    let mut at_start = true;
    let mut i = 0;
    while i < tokens.len() {
        if at_start && matches!(&tokens[i], TokenTree::Ident(k) if k == "let") {
            i = (i..tokens.len()).find(|&k| is_punct(&tokens[k], ';')).map_or(tokens.len(), |k| k + 1);
            continue;
        }
        at_start = is_punct(&tokens[i], ';') || matches!(&tokens[i], TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
        out.push(tokens[i].clone());
        i += 1;
    }
    out
}

/// Each `let`'s expression with the `let`s it uses replaced, after checking that none takes a
/// parameter's or a body's name, that each is used, and that none refers to itself.
fn resolve(bindings: &[Binding], rest: &[TokenTree]) -> syn::Result<BTreeMap<String, Vec<TokenTree>>> {
    for b in bindings {
        if let Some(kind) = other_use(rest, &b.name.to_string()) {
            return Err(syn::Error::new(
                b.name.span(),
                format!("expected a name of its own after `let`, found `{}`, which is also {kind}", b.name),
            ));
        }
    }
    // An unused `let` would never be read, nor its mistakes reported.
    let mut used = uses(rest);
    used.extend(bindings.iter().flat_map(|b| uses(&b.value)));
    if let Some(unused) = bindings.iter().find(|b| !used.contains(&b.name.to_string())) {
        return Err(syn::Error::new(
            unused.name.span(),
            format!("expected a use of `let {0}`, found none: use `{0}` or remove it", unused.name),
        ));
    }
    let by_name: BTreeMap<String, &Binding> = bindings.iter().map(|b| (b.name.to_string(), b)).collect();
    let mut resolved = BTreeMap::new();
    for b in bindings {
        resolve_one(&b.name.to_string(), &by_name, &mut resolved, &mut Vec::new())?;
    }
    Ok(resolved)
}

/// Resolves `name` (and the `let`s it uses, first); `path` is the chain being resolved.
fn resolve_one(
    name: &str,
    by_name: &BTreeMap<String, &Binding>,
    resolved: &mut BTreeMap<String, Vec<TokenTree>>,
    path: &mut Vec<String>,
) -> syn::Result<()> {
    if resolved.contains_key(name) {
        return Ok(());
    }
    let binding = by_name[name];
    if path.iter().any(|p| p == name) {
        let cycle = path.iter().skip_while(|p| *p != name).cloned().chain([name.to_string()]).collect::<Vec<_>>().join(" → ");
        return Err(syn::Error::new(
            binding.name.span(),
            format!("expected an expression that does not use its own name, found `let {name}` referring to itself ({cycle})"),
        ));
    }
    path.push(name.to_string());
    for used in uses(&binding.value) {
        if by_name.contains_key(&used) {
            resolve_one(&used, by_name, resolved, path)?;
        }
    }
    path.pop();
    let value = replace(&binding.value, resolved);
    resolved.insert(name.to_string(), value);
    Ok(())
}

/// The names used as values in `tokens` (not after `.`, not before a single `:`), in groups too.
fn uses(tokens: &[TokenTree]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, tt) in tokens.iter().enumerate() {
        match tt {
            TokenTree::Ident(id) if is_value(tokens, i) => out.push(id.to_string()),
            TokenTree::Group(g) => out.extend(uses(&g.stream().into_iter().collect::<Vec<_>>())),
            _ => {}
        }
    }
    out
}

/// What else `name` is in `tokens`, if anything: a parameter (`name:` inside `params { }`), a
/// body (`name.` or `name[`), a label (`keyword name:`), a loop variable (`for name in`), a
/// part's parameter (`part p(name, …)`), a part or an instance (`name(`) or a mirror's axis
/// (`mirrored name`).
fn other_use(tokens: &[TokenTree], name: &str) -> Option<&'static str> {
    for (i, tt) in tokens.iter().enumerate() {
        let previous = |word: &str| i > 0 && matches!(&tokens[i - 1], TokenTree::Ident(w) if w == word);
        match tt {
            TokenTree::Ident(id) if id == name && previous("for") => return Some("a loop variable"),
            TokenTree::Ident(id) if id == name && previous("mirrored") => return Some("a mirror's axis"),
            TokenTree::Ident(id) if id == name && i > 0 && matches!(&tokens[i - 1], TokenTree::Ident(_)) && before_colon(tokens, i) => {
                return Some("a label")
            }
            TokenTree::Ident(id)
                if id == name && matches!(tokens.get(i + 1), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis) =>
            {
                return Some("a part or an instance")
            }
            TokenTree::Ident(id) if id == "part" => {
                if let Some(TokenTree::Group(g)) = tokens.get(i + 2) {
                    let declared = g.stream().into_iter().any(|p| matches!(&p, TokenTree::Ident(p) if p == name));
                    if declared && g.delimiter() == Delimiter::Parenthesis {
                        return Some("a part's parameter");
                    }
                }
            }
            TokenTree::Ident(id) if id == "params" => {
                if let Some(TokenTree::Group(g)) = tokens.get(i + 1) {
                    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                    let declared =
                        (0..inner.len()).any(|k| matches!(&inner[k], TokenTree::Ident(p) if p == name) && before_colon(&inner, k));
                    if declared {
                        return Some("a parameter");
                    }
                }
            }
            TokenTree::Ident(id) if id == name && !after_dot(tokens, i) => {
                let next = tokens.get(i + 1);
                let range = tokens.get(i + 2).is_some_and(|n| is_punct(n, '.'));
                if next.is_some_and(|n| is_punct(n, '.')) && !range
                    || matches!(next, Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Bracket)
                {
                    return Some("a body");
                }
            }
            TokenTree::Group(g) => {
                if let Some(kind) = other_use(&g.stream().into_iter().collect::<Vec<_>>(), name) {
                    return Some(kind);
                }
            }
            _ => {}
        }
    }
    None
}

/// `tokens` with each use of a resolved `let` replaced by its expression in parentheses, spanned
/// at the use.
fn replace(tokens: &[TokenTree], resolved: &BTreeMap<String, Vec<TokenTree>>) -> Vec<TokenTree> {
    let mut out = Vec::with_capacity(tokens.len());
    for (i, tt) in tokens.iter().enumerate() {
        match tt {
            TokenTree::Ident(id) if is_value(tokens, i) => match resolved.get(&id.to_string()) {
                Some(value) => {
                    let mut group = Group::new(Delimiter::Parenthesis, value.iter().cloned().collect());
                    group.set_span(id.span());
                    out.push(TokenTree::Group(group));
                }
                None => out.push(tt.clone()),
            },
            TokenTree::Group(g) => {
                let mut group =
                    Group::new(g.delimiter(), replace(&g.stream().into_iter().collect::<Vec<_>>(), resolved).into_iter().collect());
                group.set_span(g.span());
                out.push(TokenTree::Group(group));
            }
            _ => out.push(tt.clone()),
        }
    }
    out
}

/// Whether the identifier `tokens[i]` stands as a value: not after `.`, not before a single `:`.
fn is_value(tokens: &[TokenTree], i: usize) -> bool {
    !after_dot(tokens, i) && !before_colon(tokens, i)
}

/// After a single `.` (a coordinate or a point, `crank.x`), not after a range's `..`.
fn after_dot(tokens: &[TokenTree], i: usize) -> bool {
    i > 0 && is_punct(&tokens[i - 1], '.') && !(i > 1 && is_punct(&tokens[i - 2], '.'))
}

/// `name:` but not `name::`.
fn before_colon(tokens: &[TokenTree], i: usize) -> bool {
    matches!(tokens.get(i + 1), Some(TokenTree::Punct(p)) if p.as_char() == ':' && p.spacing() == Spacing::Alone)
}

fn is_punct(tt: &TokenTree, c: char) -> bool {
    matches!(tt, TokenTree::Punct(p) if p.as_char() == c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::str::FromStr;

    fn substituted(body: &str) -> String {
        substitute(TokenStream::from_str(body).expect("lexes"), false).unwrap_or_else(|e| panic!("{e}")).to_string()
    }

    fn refused(body: &str) -> String {
        substitute(TokenStream::from_str(body).expect("lexes"), false).err().map(|e| e.to_string()).expect("an error")
    }

    #[test]
    fn a_let_stands_for_its_expression_in_parentheses() {
        let out = substituted("let s = crank.phi / 2.0; torque motor: crank = -k * s * s;");
        assert_eq!(out, TokenStream::from_str("torque motor: crank = -k * (crank.phi / 2.0) * (crank.phi / 2.0);").unwrap().to_string());
    }

    #[test]
    fn lets_use_lets_in_any_order_and_inside_groups() {
        let out = substituted("force f: b[0.0, 0.0] = [0.0, if a > 0.0 { a } else { 0.0 }]; let a = 2.0 * h; let h = b.y - 1.0;");
        let want = "force f: b[0.0, 0.0] = [0.0, if (2.0 * (b.y - 1.0)) > 0.0 { (2.0 * (b.y - 1.0)) } else { 0.0 }];";
        assert_eq!(out, TokenStream::from_str(want).unwrap().to_string());
    }

    #[test]
    fn a_let_in_a_loop_bound_is_replaced() {
        let out = substituted("let n = 3; for i in 0..n { torque m: c = 1.0; } for i in n..=n { torque k: c = 1.0; }");
        let want = "for i in 0..(3) { torque m: c = 1.0; } for i in (3)..=(3) { torque k: c = 1.0; }";
        assert_eq!(out, TokenStream::from_str(want).unwrap().to_string());
    }

    #[test]
    fn an_if_in_a_let_ends_at_its_semicolon() {
        let out = substituted("let p = if b.y > 0.0 { 1.0 } else { 2.0 }; torque m: b = p;");
        assert_eq!(out, TokenStream::from_str("torque m: b = (if b.y > 0.0 { 1.0 } else { 2.0 });").unwrap().to_string());
    }

    #[test]
    fn options_and_coordinates_of_the_same_name_are_left_alone() {
        let out = substituted("let k = 2.0; spring coil: a.P ~ b.Q { k: k, length: 1.0 }; torque m: b = c.k;");
        assert_eq!(out, TokenStream::from_str("spring coil: a.P ~ b.Q { k: (2.0), length: 1.0 }; torque m: b = c.k;").unwrap().to_string());
    }

    #[test]
    fn a_let_without_its_parts_or_with_a_taken_name_is_refused() {
        assert!(refused("let = 1.0;").contains("expected a name after `let` (`let name = expression;`), found `=`"));
        assert!(refused("let a 1.0;").contains("expected `=` after `let a`, found `1.0`"));
        assert!(refused("let a = 1.0").contains("expected `;` after the expression of `let a`"));
        assert!(refused("let a = ;").contains("expected an expression after `let a =`"));
        assert!(refused("let t = 1.0;").contains("found `t`, a word of the DSL"));
        assert!(refused("let body = 1.0;").contains("found `body`, a word of the DSL"));
        assert!(refused("let a = 1.0; let a = 2.0;").contains("`let a` is written twice"));
        assert!(refused("params { k: 1.0 } let k = 2.0;").contains("found `k`, which is also a parameter"));
        assert!(refused("let crank = 2.0; torque m: crank = crank.phi;").contains("found `crank`, which is also a body"));
        assert!(refused("let a = b + 1.0; let b = 2.0 * a; torque m: c = a;").contains("referring to itself (a → b → a)"));
        assert!(refused("let a = 1.0; let b = a < 2.0; torque m: c = a;").contains("expected a use of `let b`, found none"));
        assert!(refused("for i in 0..2 { let a = 1.0; }").contains("expected a `let` at the mechanism's level"));
        assert!(refused("let a = 1.0 gravity [0.0, -9.81]; torque m: c = a;").contains("found `gravity`, a statement's keyword"));
        assert!(refused("let gas = 1.0; force gas: b[0.0, 0.0] = [0.0, gas];").contains("found `gas`, which is also a label"));
        assert!(refused("let i = 1.0; for i in 0..2 { torque m: c = i; }").contains("found `i`, which is also a loop variable"));
        assert!(refused("let x0 = 1.0; part p(x0) { torque m: c = x0; }").contains("found `x0`, which is also a part's parameter"));
        assert!(refused("let front = 1.0; corner front(x0: front);").contains("found `front`, which is also a part or an instance"));
        assert!(refused("let y = 1.0; corner c(x0: y) mirrored y;").contains("found `y`, which is also a mirror's axis"));
        assert!(refused("let angle = 1.0; torque m: c = angle;").contains("found `angle`, a word of the DSL"));
        assert!(refused("part p(x) { body b { mass: 1.0 } let a = x; }").contains("expected a `let` at the mechanism's level"));
    }

    #[test]
    fn leniently_a_let_in_error_leaves_the_statements_as_they_are() {
        let lenient = |body: &str| substitute(TokenStream::from_str(body).unwrap(), true).expect("lenient").to_string();
        let want = TokenStream::from_str("torque m: c = a;").unwrap().to_string();
        assert_eq!(lenient("let a = b; let b = a; torque m: c = a;"), want);
        assert_eq!(lenient("let a 1.0; torque m: c = a;"), want);
    }
}
