//! Parts: a sub-assembly declared once and used several times.
//!
//! ```text
//! part corner(x0) { statements }              a part, with parameters
//! corner front_left(x0: 1.3);                 an instance: the part's statements once more
//! corner front_right(x0: 1.3) mirrored y;     its mirror image (`crate::mirror`)
//! ```
//!
//! An instance is the part's statements with each parameter replaced by its value (an
//! expression, a number or a name) and each name the part declares — its bodies, its labels,
//! the points and vectors it declares on bodies outside it, the instances it holds — made the
//! instance's own: the body `upper_arm` of the instance `front_left` is the body
//! `front_left.upper_arm` (the identifier `front_left_upper_arm` in the generated Rust API; the
//! written form in every text the user reads, see [`crate::names`]). Names the part does not
//! declare (`ground`, a chassis, the mechanism's parameters, `t`) are the mechanism's. Outside
//! the part, `front_left.upper_arm` and `front_left.upper_arm.B` name what the instance made,
//! and an instance may be indexed and made in a loop (`corner c[i](...)`, then `c[2].upper_arm`).
//! Parts may use other parts; a part's statements may loop over its parameters.
//!
//! Expanded on the tokens before anything else but the `let`s ([`crate::bind`]), loops with
//! them ([`crate::repeat`]), so an instance generates exactly what its statements written out
//! by hand generate.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Delimiter, Group, Ident, TokenStream, TokenTree};

use crate::names::Names;
use crate::scene::{label, statements};

/// A part: its name, its parameters and its statements.
struct Part {
    name: Ident,
    params: Vec<Ident>,
    body: TokenStream,
}

/// What an instance declares, by the names its statements use, for each instance in scope
/// (identifier as made → the names after its `.`).
type Namespaces = BTreeMap<String, BTreeSet<String>>;

/// The mechanism with its parts' definitions taken out, every loop unrolled and every instance
/// expanded.
pub fn expand(input: TokenStream, names: &mut Names) -> syn::Result<TokenStream> {
    expand_with(input, names, false)
}

/// [`expand`] for a placeholder: an instance missing a parameter takes 0 for it, and a
/// parameter its part does not have is ignored, so that what the instance makes is still there.
pub fn expand_leniently(input: TokenStream, names: &mut Names) -> syn::Result<TokenStream> {
    expand_with(input, names, true)
}

fn expand_with(input: TokenStream, names: &mut Names, lenient: bool) -> syn::Result<TokenStream> {
    let mut out = TokenStream::new();
    let mut done = false;
    for tt in input {
        match tt {
            // The mechanism's body: the first brace group (attributes are `#[...]`, brackets).
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace && !done => {
                done = true;
                let body = crate::bind::substitute(g.stream(), lenient)?;
                let (definitions, rest): (Vec<_>, Vec<_>) =
                    statements(body).into_iter().partition(|s| matches!(s.first(), Some(TokenTree::Ident(k)) if k == "part"));
                let mut parts: Vec<Part> = Vec::new();
                for d in &definitions {
                    let part = definition(d)?;
                    if parts.iter().any(|p| p.name == part.name) {
                        return Err(syn::Error::new(
                            part.name.span(),
                            format!("part `{0}` is declared twice: expected a new name, found `{0}` again", part.name),
                        ));
                    }
                    parts.push(part);
                }
                // Leniently, the parameters' integral defaults may bound a loop.
                let constants = if lenient { integral_defaults(&rest) } else { Vec::new() };
                let lenient = lenient.then_some(constants.as_slice());
                let spatial = rest.iter().any(|s| matches!(s.first(), Some(TokenTree::Ident(k)) if k == "spatial"));
                let level = level(rest.clone().into_iter().flatten().collect(), &parts, names, &mut Vec::new(), lenient, spatial)
                    .map_err(|e| parameters_as_bounds(e, &rest))?;
                let mut group = Group::new(Delimiter::Brace, level.tokens.into_iter().collect());
                group.set_span(g.span());
                out.extend([TokenTree::Group(group)]);
            }
            other => out.extend([other]),
        }
    }
    Ok(out)
}

/// `part name(p, q, ...) { statements }`
fn definition(s: &[TokenTree]) -> syn::Result<Part> {
    let shape = "expected `part name(parameter, ...) { statements }`";
    let at = |k: usize| s.get(k).map_or(s[0].span(), TokenTree::span);
    let name = match s.get(1) {
        Some(TokenTree::Ident(n)) => n.clone(),
        _ => return Err(syn::Error::new(at(1), shape)),
    };
    let reserved = crate::parse::STATEMENTS.contains(&name.to_string().as_str()) || name == "part" || name == "for";
    if reserved {
        return Err(syn::Error::new(
            name.span(),
            format!("`{name}` is a statement of its own: expected a part's name, found `{name}`; a part needs another name"),
        ));
    }
    let params = match s.get(2) {
        Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis => {
            let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
            let mut params: Vec<Ident> = Vec::new();
            for p in tokens.split(|t| is_punct(t, ',')).filter(|p| !p.is_empty()) {
                match p {
                    [TokenTree::Ident(id)] if params.contains(id) => {
                        return Err(syn::Error::new(
                            id.span(),
                            format!("parameter `{id}` of part `{name}` is declared twice: expected a new name, found `{id}` again"),
                        ))
                    }
                    [TokenTree::Ident(id)] => params.push(id.clone()),
                    _ => return Err(syn::Error::new(p[0].span(), format!("{shape}: a parameter is a name"))),
                }
            }
            params
        }
        _ => return Err(syn::Error::new(at(2), format!("{shape}: the parameters in parentheses, `()` for none"))),
    };
    let body = match (s.get(3), s.get(4), s.len()) {
        (Some(TokenTree::Group(g)), _, 4) | (Some(TokenTree::Group(g)), Some(TokenTree::Punct(_)), 5)
            if g.delimiter() == Delimiter::Brace =>
        {
            g.stream()
        }
        _ => return Err(syn::Error::new(at(3), format!("{shape}: the part's statements in braces"))),
    };
    Ok(Part { name, params, body })
}

/// One level's statements — the mechanism's or an instance's — flat, and the instances they hold.
struct Level {
    tokens: Vec<TokenTree>,
    namespaces: Namespaces,
}

/// A loop bound that names a parameter gets the reason it cannot: a parameter may change at run
/// time, a loop is unrolled when the mechanism is built.
fn parameters_as_bounds(e: syn::Error, statements: &[Vec<TokenTree>]) -> syn::Error {
    let unchanged = e.clone();
    let params: Vec<String> = statements
        .iter()
        .filter(|s| matches!(s.first(), Some(TokenTree::Ident(k)) if k == "params"))
        .filter_map(|s| match s.get(1) {
            Some(TokenTree::Group(g)) => Some(g.stream().into_iter().collect::<Vec<_>>()),
            _ => None,
        })
        .flat_map(|tokens| {
            tokens
                .windows(2)
                .filter_map(|w| match w {
                    [TokenTree::Ident(name), colon] if is_punct(colon, ':') => Some(name.to_string()),
                    _ => None,
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut all: Option<syn::Error> = None;
    for one in e {
        let message = one.to_string();
        let named = params.iter().find(|p| message.contains(&format!("found `{p}`, which is not a loop variable")));
        let one = match named {
            Some(p) => syn::Error::new(
                one.span(),
                format!("{message}; `{p}` is a parameter, which may change at run time, and a loop is unrolled when the mechanism is built: write a number"),
            ),
            None => one,
        };
        match &mut all {
            Some(all) => all.combine(one),
            None => all = Some(one),
        }
    }
    all.unwrap_or(unchanged)
}

/// The parameters `name: number` of a `params { ... }` whose number is an integer.
fn integral_defaults(statements: &[Vec<TokenTree>]) -> Vec<(String, i64)> {
    let mut out = Vec::new();
    for s in statements {
        if let [TokenTree::Ident(k), TokenTree::Group(g), ..] = s.as_slice() {
            if k == "params" {
                let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
                for w in tokens.windows(3) {
                    if let [TokenTree::Ident(name), colon, TokenTree::Literal(value)] = w {
                        let value = value.to_string().parse::<f64>().ok().filter(|v| v.fract() == 0.0 && v.abs() < 1e9);
                        if let (true, Some(value)) = (is_punct(colon, ':'), value) {
                            out.push((name.to_string(), value as i64));
                        }
                    }
                }
            }
        }
    }
    out
}

/// Statements that belong to the mechanism, not to a part.
const MECHANISM_ONLY: &[&str] = &["params", "scene", "spatial", "scalar"];

/// Unrolls a statement list, expands its instances (inside `within`, the chain of parts being
/// expanded) and resolves its references into them.
fn level(
    body: TokenStream,
    parts: &[Part],
    names: &mut Names,
    within: &mut Vec<String>,
    lenient: Option<&[(String, i64)]>,
    spatial: bool,
) -> syn::Result<Level> {
    let unrolled = match lenient {
        Some(constants) => crate::repeat::unroll_statements_leniently(body, names, constants)?,
        None => crate::repeat::unroll_statements(body, names)?,
    };
    let mut namespaces = Namespaces::new();
    // Each statement, or the expansion of an instance.
    let mut pieces: Vec<(bool, Vec<TokenTree>)> = Vec::new();
    for s in statements(unrolled) {
        if let Some(TokenTree::Ident(k)) = s.first() {
            if k == "part" {
                let why = if within.is_empty() { "outside every loop" } else { "not inside another part" };
                return Err(syn::Error::new(
                    k.span(),
                    format!(
                        "a part is declared at the mechanism's level, {why}: expected it there, found `part` {}",
                        if within.is_empty() { "inside a loop" } else { "inside a part" }
                    ),
                ));
            }
            if let Some(part) = within.last().filter(|_| MECHANISM_ONLY.contains(&k.to_string().as_str())) {
                return Err(syn::Error::new(
                    k.span(),
                    format!("`{k}` belongs to the mechanism, not to part `{part}`: expected a part's statement, found `{k}`; a part's values are its parameters"),
                ));
            }
        }
        match instance(&s, parts, lenient.is_some(), spatial)? {
            Some((part, name, args, mirror)) => {
                if namespaces.contains_key(&name.to_string()) {
                    return Err(syn::Error::new(
                        name.span(),
                        format!("instance `{0}` is made twice: expected a new name, found `{0}` again", names.written(&name.to_string())),
                    ));
                }
                if within.contains(&part.name.to_string()) {
                    let chain = within.join(" → ");
                    return Err(syn::Error::new(
                        part.name.span(),
                        format!("part `{0}` uses itself: expected parts that end, found the cycle {chain} → {0}", part.name),
                    ));
                }
                within.push(part.name.to_string());
                let inner = level(substitute(part.body.clone(), &part.params, &args), parts, names, within, lenient, spatial);
                within.pop();
                let mut inner = inner?;
                if let Some(mirror) = mirror {
                    match mirror.apply(inner.tokens.clone(), &names.written(&name.to_string())) {
                        Ok(tokens) => inner.tokens = tokens,
                        // A placeholder keeps the instance, unreflected, so that its names exist.
                        Err(_) if lenient.is_some() => {}
                        Err(e) => return Err(e),
                    }
                }
                let (tokens, made) = own(inner, &name.to_string(), names);
                namespaces.extend(made);
                pieces.push((false, tokens));
            }
            None => pieces.push((true, s)),
        }
    }
    // An instance's name is its own: `front_left.x` cannot be both a body's coordinate and a member.
    for (own_statement, piece) in &pieces {
        let declared = match piece.as_slice() {
            [TokenTree::Ident(k), TokenTree::Ident(b), ..] if *own_statement && (k == "body" || k == "particle") => Some(b),
            _ if *own_statement => label(piece),
            _ => None,
        };
        if let Some(d) = declared.filter(|d| namespaces.contains_key(&d.to_string())) {
            return Err(syn::Error::new(
                d.span(),
                format!(
                    "`{0}` is already the name of a part's instance: expected a new name, found `{0}` again",
                    names.written(&d.to_string())
                ),
            ));
        }
    }
    let mut tokens = Vec::new();
    for (own_statement, piece) in pieces {
        if own_statement {
            tokens.extend(resolve(&piece, &namespaces, names)?);
        } else {
            tokens.extend(piece);
        }
    }
    Ok(Level { tokens, namespaces })
}

/// An instance statement `part name(param: value, ...) [mirrored axis];`: its part, name,
/// arguments and reflection.
#[allow(clippy::type_complexity)]
fn instance<'p>(
    s: &[TokenTree],
    parts: &'p [Part],
    lenient: bool,
    spatial: bool,
) -> syn::Result<Option<(&'p Part, Ident, Vec<(Ident, Vec<TokenTree>)>, Option<crate::mirror::Mirror>)>> {
    let (Some(TokenTree::Ident(kind)), Some(TokenTree::Ident(name))) = (s.first(), s.get(1)) else { return Ok(None) };
    let axis = if spatial { "y" } else { "x" };
    let (args, mirrored) = match &s[2..] {
        [TokenTree::Group(g), semi] if g.delimiter() == Delimiter::Parenthesis && is_punct(semi, ';') => (Some(g), None),
        [semi] if is_punct(semi, ';') => (None, None),
        [TokenTree::Group(g), TokenTree::Ident(m), rest @ ..] if g.delimiter() == Delimiter::Parenthesis && m == "mirrored" => {
            (Some(g), Some((m, rest)))
        }
        [TokenTree::Ident(m), rest @ ..] if m == "mirrored" => (None, Some((m, rest))),
        // An instance of a part with something else after its parameters.
        [TokenTree::Group(g), other, ..] if g.delimiter() == Delimiter::Parenthesis && parts.iter().any(|p| p.name == *kind) => {
            if lenient {
                (Some(g), None)
            } else {
                let hint = match other {
                    TokenTree::Ident(w) => crate::parse::closest(&w.to_string(), &["mirrored"], &[]),
                    _ => String::new(),
                };
                return Err(syn::Error::new(
                    other.span(),
                    format!("expected `;` or `mirrored {axis};` after the parameters of instance `{name}`, found `{other}`{hint}"),
                ));
            }
        }
        _ => return Ok(None),
    };
    let mirror = match mirrored {
        None => None,
        Some((_, [TokenTree::Ident(a), semi])) if is_punct(semi, ';') => match crate::mirror::Mirror::parse(a, spatial) {
            Ok(m) => Some(m),
            Err(_) if lenient => None,
            Err(e) => return Err(e),
        },
        Some(_) if lenient => None,
        Some((m, _)) => {
            return Err(syn::Error::new(
                m.span(),
                format!(
                    "expected `{kind} {name}(...) mirrored {axis};` (the axis the mirror plane is normal to), found something else after `mirrored`"
                ),
            ))
        }
    };
    let Some(part) = parts.iter().find(|p| p.name == *kind) else {
        // `kind name(...);` is an instance's shape, not a statement's.
        if args.is_some() && !parts.is_empty() && !crate::parse::STATEMENTS.contains(&kind.to_string().as_str()) {
            let known: Vec<String> = parts.iter().map(|p| p.name.to_string()).collect();
            let known: Vec<&str> = known.iter().map(String::as_str).collect();
            let hint = crate::parse::closest(&kind.to_string(), &known, &[]);
            return Err(syn::Error::new(
                kind.span(),
                format!("unknown part: expected {}, found `{kind}`{hint}", crate::parse::one_of(&known, "a part")),
            ));
        }
        return Ok(None);
    };
    let mut given: Vec<(Ident, Vec<TokenTree>)> = Vec::new();
    let tokens: Vec<TokenTree> = args.map(|g| g.stream().into_iter().collect()).unwrap_or_default();
    let wanted: Vec<String> = part.params.iter().map(Ident::to_string).collect();
    let wanted: Vec<&str> = wanted.iter().map(String::as_str).collect();
    for arg in tokens.split(|t| is_punct(t, ',')).filter(|a| !a.is_empty()) {
        let (param, value) = match arg {
            [TokenTree::Ident(p), colon, value @ ..] if is_punct(colon, ':') && !value.is_empty() => (p.clone(), value.to_vec()),
            _ => return Err(syn::Error::new(arg[0].span(), format!("expected `parameter: value`; part `{kind}` takes {}", list(&wanted)))),
        };
        if !part.params.contains(&param) && lenient {
            continue;
        }
        if !part.params.contains(&param) {
            let hint = crate::parse::closest(&param.to_string(), &wanted, &[]);
            return Err(syn::Error::new(
                param.span(),
                format!("part `{kind}` has no parameter `{param}`: expected {}, found `{param}`{hint}", list(&wanted)),
            ));
        }
        if given.iter().any(|(p, _)| *p == param) {
            return Err(syn::Error::new(
                param.span(),
                format!("parameter `{param}` is given twice: expected each parameter once, found `{param}` again"),
            ));
        }
        given.push((param, value));
    }
    if lenient {
        for p in &part.params {
            if !given.iter().any(|(g, _)| g == p) {
                given.push((p.clone(), vec![TokenTree::Literal(proc_macro2::Literal::f64_unsuffixed(0.0))]));
            }
        }
    }
    let missing: Vec<String> = part.params.iter().filter(|p| !given.iter().any(|(g, _)| g == *p)).map(|p| format!("`{p}: ...`")).collect();
    if !missing.is_empty() {
        return Err(syn::Error::new(
            name.span(),
            format!(
                "instance `{name}` of part `{kind}` needs a value for each parameter: expected {}, found none; add it",
                missing.join(", ")
            ),
        ));
    }
    Ok(Some((part, name.clone(), given, mirror)))
}

fn list(params: &[&str]) -> String {
    if params.is_empty() {
        "no parameters".to_string()
    } else {
        params.iter().map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", ")
    }
}

/// A part's statements with each parameter replaced by its value: a name or a number as it is, an
/// expression in parentheses. Not a name after `.` (a point or coordinate), an option's name
/// (`k: ...`) or a function's.
fn substitute(body: TokenStream, params: &[Ident], args: &[(Ident, Vec<TokenTree>)]) -> TokenStream {
    let tokens: Vec<TokenTree> = body.into_iter().collect();
    let mut out = Vec::new();
    for (i, tt) in tokens.iter().enumerate() {
        match tt {
            TokenTree::Ident(id) if is_name(&tokens, i) && params.contains(id) => {
                let (_, value) = args.iter().find(|(p, _)| p == id).expect("every parameter has a value");
                match value.as_slice() {
                    [single @ (TokenTree::Ident(_) | TokenTree::Literal(_))] => out.push(single.clone()),
                    _ => {
                        let mut group = Group::new(Delimiter::Parenthesis, value.iter().cloned().collect());
                        group.set_span(id.span());
                        out.push(TokenTree::Group(group));
                    }
                }
            }
            TokenTree::Group(g) => {
                let mut group = Group::new(g.delimiter(), substitute(g.stream(), params, args));
                group.set_span(g.span());
                out.push(TokenTree::Group(group));
            }
            other => out.push(other.clone()),
        }
    }
    out.into_iter().collect()
}

/// Whether the identifier `tokens[i]` is in a name's place: not after `.`, not an option's name
/// before a single `:`, not a function before its arguments.
fn is_name(tokens: &[TokenTree], i: usize) -> bool {
    let after_dot = after_dot(tokens, i);
    let option = matches!(tokens.get(i + 1), Some(TokenTree::Punct(p)) if p.as_char() == ':')
        && !matches!(tokens.get(i + 2), Some(TokenTree::Punct(p)) if p.as_char() == ':');
    let call = matches!(tokens.get(i + 1), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis);
    !after_dot && !option && !call
}

/// An instance's statements with the names its part declares made its own (`name_x`, written
/// `name.x`), and the namespaces it adds: its own and those of the instances it holds.
fn own(inner: Level, instance: &str, names: &mut Names) -> (Vec<TokenTree>, Namespaces) {
    let statements = statements(inner.tokens.into_iter().collect());
    let mut declared: BTreeSet<String> = BTreeSet::new();
    let mut bodies: BTreeSet<String> = BTreeSet::new();
    for s in &statements {
        if let (Some(TokenTree::Ident(k)), Some(TokenTree::Ident(b))) = (s.first(), s.get(1)) {
            if k == "body" || k == "particle" {
                bodies.insert(b.to_string());
            }
        }
        if let Some(l) = label(s) {
            declared.insert(l.to_string());
        }
    }
    declared.extend(bodies.iter().cloned());
    // Points and vectors the part declares on bodies outside it.
    let mut outer_points: BTreeSet<(String, String)> = BTreeSet::new();
    for s in &statements {
        if let [TokenTree::Ident(k), TokenTree::Ident(b), dot, TokenTree::Ident(p), ..] = s.as_slice() {
            if (k == "point" || k == "vector") && is_punct(dot, '.') && !bodies.contains(&b.to_string()) {
                outer_points.insert((b.to_string(), p.to_string()));
            }
        }
    }
    let made = |name: &str, names: &mut Names| -> String {
        let id = format!("{instance}_{name}");
        names.record(&id, format!("{}.{}", names.written(instance), names.written(name)));
        id
    };
    let mut tokens = Vec::new();
    for s in &statements {
        let labelled = label(s).is_some();
        for (k, tt) in s.iter().enumerate() {
            if k == 0 {
                // The statement's keyword (`spring spring: ...` declares the label `spring`).
                tokens.push(tt.clone());
            } else if labelled && k == 1 {
                let TokenTree::Ident(l) = tt else { unreachable!("a label is an identifier") };
                let id = made(&l.to_string(), names);
                names.record_label(&id, &l.to_string());
                tokens.push(TokenTree::Ident(Ident::new(&id, l.span())));
            } else {
                tokens.push(rename(s, k, &declared, &outer_points, &made, names));
            }
        }
    }
    let mut namespaces = Namespaces::new();
    let mut members: BTreeSet<String> = declared.clone();
    members.extend(outer_points.iter().map(|(_, p)| p.clone()));
    for (nested, inner_members) in inner.namespaces {
        members.insert(nested.clone());
        namespaces.insert(made(&nested, names), inner_members);
    }
    namespaces.insert(instance.to_string(), members);
    (tokens, namespaces)
}

/// `tokens[i]` renamed where it names something the instance declares.
fn rename(
    tokens: &[TokenTree],
    i: usize,
    declared: &BTreeSet<String>,
    outer_points: &BTreeSet<(String, String)>,
    made: &dyn Fn(&str, &mut Names) -> String,
    names: &mut Names,
) -> TokenTree {
    match &tokens[i] {
        TokenTree::Ident(id) if is_name(tokens, i) && declared.contains(&id.to_string()) => {
            TokenTree::Ident(Ident::new(&made(&id.to_string(), names), id.span()))
        }
        // `outer.p`: a point or vector the part declares on a body outside it.
        TokenTree::Ident(id) if i >= 2 && after_dot(tokens, i) => match &tokens[i - 2] {
            TokenTree::Ident(b) if outer_points.contains(&(b.to_string(), id.to_string())) => {
                TokenTree::Ident(Ident::new(&made(&id.to_string(), names), id.span()))
            }
            _ => tokens[i].clone(),
        },
        TokenTree::Group(g) => {
            let inner: Vec<TokenTree> = g.stream().into_iter().collect();
            let renamed: TokenStream = (0..inner.len()).map(|k| rename(&inner, k, declared, outer_points, made, names)).collect();
            let mut group = Group::new(g.delimiter(), renamed);
            group.set_span(g.span());
            TokenTree::Group(group)
        }
        other => other.clone(),
    }
}

/// A statement with every reference into an instance, `instance.name` (`front_left.upper_arm`,
/// `vehicle.front_left.upper_arm`), made the identifier the instance made.
fn resolve(tokens: &[TokenTree], namespaces: &Namespaces, names: &Names) -> syn::Result<Vec<TokenTree>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            TokenTree::Ident(id) if namespaces.contains_key(&id.to_string()) => {
                let mut current = id.to_string();
                while let Some(members) = namespaces.get(&current) {
                    let (Some(dot), Some(TokenTree::Ident(member))) = (tokens.get(i + 1), tokens.get(i + 2)) else { break };
                    if !is_punct(dot, '.') {
                        break;
                    }
                    if !members.contains(&member.to_string()) {
                        let known: Vec<&str> = members.iter().map(String::as_str).collect();
                        let hint = crate::parse::closest(&member.to_string(), &known, &[]);
                        return Err(syn::Error::new(
                            member.span(),
                            format!(
                                "`{}` has no `{member}`: expected one of {}, found `{member}`{hint}",
                                names.written(&current),
                                known.iter().map(|m| format!("`{}`", names.written(m))).collect::<Vec<_>>().join(", ")
                            ),
                        ));
                    }
                    current = format!("{current}_{member}");
                    i += 2;
                }
                out.push(TokenTree::Ident(Ident::new(&current, id.span())));
            }
            TokenTree::Group(g) => {
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                let mut group = Group::new(g.delimiter(), resolve(&inner, namespaces, names)?.into_iter().collect());
                group.set_span(g.span());
                out.push(TokenTree::Group(group));
            }
            other => out.push(other.clone()),
        }
        i += 1;
    }
    Ok(out)
}

/// Whether `tokens[i]` follows a single `.` (`body.x`; not a range's `..`).
fn after_dot(tokens: &[TokenTree], i: usize) -> bool {
    i > 0 && is_punct(&tokens[i - 1], '.') && !(i > 1 && is_punct(&tokens[i - 2], '.'))
}

fn is_punct(tt: &TokenTree, c: char) -> bool {
    matches!(tt, TokenTree::Punct(p) if p.as_char() == c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expand::{assert_same_code, canonical, canonical_text, expand};
    use quote::quote;

    fn expanded(input: TokenStream) -> (String, Names) {
        let mut names = Names::default();
        let out = super::expand(input, &mut names).unwrap_or_else(|e| panic!("{e}"));
        (out.to_string(), names)
    }

    /// Two instances of a part, one nested part, a point on an outer body and references from
    /// outside: the statements a user would write out by hand.
    #[test]
    fn an_instance_is_its_parts_statements_with_its_own_names() {
        let (got, names) = expanded(quote!(M {
            part arm(x0, side, frame) {
                body link { mass: 1.0, inertia: 0.1, at: [x0, side * 0.5, 0.0] }
                point frame.mount = [x0, side * 0.2];
                revolute pivot: frame.mount ~ link[0.0, -side * 0.3] { viscous: 0.1 };
                tip t();
            }
            part tip() {
                body mass_ { mass: 0.1, inertia: 0.01 }
            }
            body chassis { mass: 10.0, inertia: 1.0 }
            arm left(x0: 1.0, side: 1.0, frame: chassis);
            arm right(x0: 1.0 + 0.0, side: -1.0, frame: chassis);
            revolute_revolute rod: left.link[0.0, 0.0] ~ right.t.mass_[0.0, 0.0] { length: 1.0 };
            fix right.link.x;
            scene S without left.pivot;
        }));
        let want = quote!(M {
            body left_link { mass: 1.0, inertia: 0.1, at: [1.0, 1.0 * 0.5, 0.0] }
            point chassis.left_mount = [1.0, 1.0 * 0.2];
            revolute left_pivot: chassis.left_mount ~ left_link[0.0, -1.0 * 0.3] { viscous: 0.1 };
            body left_t_mass_ { mass: 0.1, inertia: 0.01 }
            body right_link { mass: 1.0, inertia: 0.1, at: [(1.0 + 0.0), (-1.0) * 0.5, 0.0] }
            point chassis.right_mount = [(1.0 + 0.0), (-1.0) * 0.2];
            revolute right_pivot: chassis.right_mount ~ right_link[0.0, -(-1.0) * 0.3] { viscous: 0.1 };
            body right_t_mass_ { mass: 0.1, inertia: 0.01 }
            body chassis { mass: 10.0, inertia: 1.0 }
            revolute_revolute rod: left_link[0.0, 0.0] ~ right_t_mass_[0.0, 0.0] { length: 1.0 };
            fix right_link.x;
            scene S without left_pivot;
        });
        // The instances come where they are made, the mechanism's own statements after them in order.
        let order = |s: &str| s.replace("body chassis { mass : 10.0 , inertia : 1.0 } ", "");
        assert_eq!(order(&got), order(&want.to_string()));
        assert_eq!(names.rewrite("right_t_mass_.x, chassis.left_mount, left_pivot"), "right.t.mass_.x, chassis.left.mount, left.pivot");
        let mut group = names.made_from("pivot");
        group.sort();
        assert_eq!(group, ["left_pivot", "right_pivot"], "a part's label names its element in every instance");
    }

    /// A particle is a part's own, as a body is (a new user's `particle bob` in a part of two
    /// instances was one `bob` twice).
    #[test]
    fn a_particle_in_a_part_is_each_instances_own() {
        let (got, names) = expanded(quote!(M {
            part weight(x) { particle bob { mass: 0.3, at: [x, 0.0] } }
            weight a(x: 1.0);
            weight b(x: 2.0);
        }));
        let want = quote!(M { particle a_bob { mass: 0.3, at: [1.0, 0.0] } particle b_bob { mass: 0.3, at: [2.0, 0.0] } });
        assert_eq!(got, want.to_string());
        assert_eq!(names.rewrite("b_bob.x"), "b.bob.x");
    }

    #[test]
    fn a_part_loops_over_its_parameters_and_instances_are_made_in_loops() {
        let (got, names) = expanded(quote!(M {
            part chain(n) { for k in 0..n { body l[k] { mass: 1.0, inertia: 0.1 } } }
            for i in 0..2 { chain c[i](n: i + 1); }
        }));
        let want = quote!(M { body c_0_l_0 { mass: 1.0, inertia: 0.1 } body c_1_l_0 { mass: 1.0, inertia: 0.1 } body c_1_l_1 { mass: 1.0, inertia: 0.1 } });
        assert_eq!(got, want.to_string());
        assert_eq!(names.rewrite("c_1_l_1.phi"), "c[1].l[1].phi");
    }

    /// A vehicle's four corners from one part generate what the corners written out generate.
    #[test]
    fn instances_generate_what_their_statements_written_out_generate() {
        let with_parts = quote!(pub Car {
            gravity [0.0, -9.81];
            body chassis { mass: 100.0, inertia: 20.0, at: [0.0, 0.5, 0.0] }
            part corner(x0) {
                body wheel { mass: 10.0, inertia: 0.4, at: [x0, 0.3, 0.0] }
                translational strut: chassis[x0, -0.2] along [0.0, 1.0] ~ wheel[0.0, 0.0] along [0.0, 1.0];
                spring spring: chassis[x0, -0.2] ~ wheel[0.0, 0.0] { k: 2.0e4, length: 0.2, c: 800.0 };
            }
            corner front(x0: 1.2);
            corner rear(x0: -1.3);
            fix chassis.x;
        });
        let written = quote!(pub Car {
            gravity [0.0, -9.81];
            body chassis { mass: 100.0, inertia: 20.0, at: [0.0, 0.5, 0.0] }
            body front_wheel { mass: 10.0, inertia: 0.4, at: [1.2, 0.3, 0.0] }
            translational front_strut: chassis[1.2, -0.2] along [0.0, 1.0] ~ front_wheel[0.0, 0.0] along [0.0, 1.0];
            spring front_spring: chassis[1.2, -0.2] ~ front_wheel[0.0, 0.0] { k: 2.0e4, length: 0.2, c: 800.0 };
            body rear_wheel { mass: 10.0, inertia: 0.4, at: [-1.3, 0.3, 0.0] }
            translational rear_strut: chassis[-1.3, -0.2] along [0.0, 1.0] ~ rear_wheel[0.0, 0.0] along [0.0, 1.0];
            spring rear_spring: chassis[-1.3, -0.2] ~ rear_wheel[0.0, 0.0] { k: 2.0e4, length: 0.2, c: 800.0 };
            fix chassis.x;
        });
        let a = canonical(with_parts);
        // The texts read as written: `front.wheel.y`, not `front_wheel.y`.
        let mut names = Names::default();
        for made in ["front_wheel", "front_strut", "front_spring", "rear_wheel", "rear_strut", "rear_spring"] {
            names.record(made, made.replacen('_', ".", 1));
        }
        let b = canonical_text(names.rewrite_strings(expand(written)).to_string());
        assert!(a.contains("\"front.wheel.y\"") && !a.contains("\"front_wheel.y\""), "coordinate names read as written");
        assert_same_code(&a, &b);
    }

    #[test]
    fn mistakes_in_parts_and_instances_are_errors_that_say_what_is_expected() {
        let body = quote!(body b { mass: 1.0, inertia: 0.1 });
        let cases = [
            (
                quote!(M { part arm(x) { #body } arm a(y: 1.0); }),
                "part `arm` has no parameter `y`: expected `x`, found `y` (did you mean `x`?)",
            ),
            (
                quote!(M { part arm(x, side) { #body } arm a(x: 1.0); }),
                "instance `a` of part `arm` needs a value for each parameter: expected `side: ...`, found none; add it",
            ),
            (quote!(M { part arm(x) { #body } arm a(x: 1.0, x: 2.0); }), "parameter `x` is given twice"),
            (quote!(M { part arm(x) { #body } arm a(x 1.0); }), "expected `parameter: value`; part `arm` takes `x`"),
            (quote!(M { part arm() { #body } arm a(); arm a(); }), "instance `a` is made twice"),
            (
                quote!(M { part arm() { #body } arm a(); body a { mass: 1.0, inertia: 0.1 } }),
                "`a` is already the name of a part's instance",
            ),
            (quote!(M { part arm() { #body } amr a(); }), "unknown part: expected `arm`, found `amr` (did you mean `arm`?)"),
            (
                quote!(M { part arm() { #body } arm a(); fix a.bb.x; }),
                "`a` has no `bb`: expected one of `b`, found `bb` (did you mean `b`?)",
            ),
            (
                quote!(M { part arm() { arm inner(); } arm a(); }),
                "part `arm` uses itself: expected parts that end, found the cycle arm → arm",
            ),
            (quote!(M { part arm() { params { k: 1.0 } } arm a(); }), "`params` belongs to the mechanism, not to part `arm`"),
            (quote!(M { part arm() { part b() {} } arm a(); }), "a part is declared at the mechanism's level, not inside another part"),
            (quote!(M { for i in 0..1 { part b() {} } }), "a part is declared at the mechanism's level, outside every loop"),
            (quote!(M { part body() {} }), "`body` is a statement of its own: expected a part's name, found `body`"),
            (quote!(M { part arm {} }), "the parameters in parentheses, `()` for none"),
            (quote!(M { part arm() {} part arm() {} }), "part `arm` is declared twice"),
        ];
        for (input, want) in cases {
            let e = super::expand(input, &mut Names::default()).expect_err(want).to_string();
            assert!(e.contains(want), "{e}\n  wanted: {want}");
        }
    }

    /// A mistake inside an instance names the body as the user would write it.
    #[test]
    fn errors_read_names_as_written() {
        let out = expand(quote!(M {
            part arm() { body link { mass: 1.0, inertia: 0.0 } revolute ground[0.0, 0.0] ~ link[0.0, 0.0]; }
            arm c[2]();
            fix c[2].lnk.x;
        }))
        .to_string();
        assert!(out.contains("`c[2]` has no `lnk`: expected one of `link`, found `lnk` (did you mean `link`?)"), "{out}");
        let out = expand(quote!(M {
            part arm() { body link { mass: 1.0, inertia: 0.0 } revolute ground[0.0, 0.0] ~ link[0.0, 0.0]; }
            arm c[2]();
        }))
        .to_string();
        assert!(out.contains("body `c[2].link`"), "{out}");
    }
}
