//! The chain parse → model → formulation → emit: a `mechanism!`'s parts, loops and scenes
//! expanded, each mechanism generated (`generate`: its type and trait implementations; `named`:
//! named access), and on mistakes the errors beside a placeholder of the type.

mod generate;
mod named;

use proc_macro2::TokenStream;
use quote::quote;

pub use generate::generate;

use crate::emit::real;
use crate::model::Partial;
use crate::parse::{BodyDef, Expr, Item, MechanismDef};

/// Expands a `mechanism!` invocation: its parts and loops expanded ([`crate::part`],
/// [`crate::repeat`]), then the base mechanism and each of its scenes ([`crate::scene`]); every
/// name in its texts as the user wrote it ([`crate::names`]). Never fails: mistakes become
/// `compile_error!`s next to a placeholder of the mechanism's type, generated from its statements
/// without mistakes, so code that uses the type does not add follow-up errors. A mistake in the
/// base is reported once: its scenes, which share it, are then only placeholders.
pub fn expand(input: TokenStream) -> TokenStream {
    let mut names = crate::names::Names::default();
    let written = input.clone();
    let out = refuse_raw_identifiers(&input)
        .and_then(|()| crate::part::expand(input, &mut names))
        .and_then(|input| crate::scene::split(input.clone(), &names).map_err(|e| statements_that_do_not_parse(input).unwrap_or(e)))
        .map(|(base, scenes)| {
            let (mut out, ok) = expand_one(base);
            for scene in scenes {
                if ok {
                    out.extend(expand_one(scene).0);
                } else if let Ok((def, _)) = syn::parse::Parser::parse2(MechanismDef::parse_recovering, scene) {
                    out.extend(placeholder(def));
                }
            }
            out
        });
    // A mistake in a part, a loop, an instance or a scene: the placeholders of the mechanism
    // expanded leniently, or without the statement that has it.
    let out = out.unwrap_or_else(|e| {
        let errors = crate::wording::compile_errors(e);
        let placeholders = placeholders_without_the_mistake(written);
        quote!(#errors #placeholders)
    });
    names.rewrite_strings(out)
}

/// The errors of the mechanism's statements that do not parse, its scenes set aside: where a
/// scene names what the mechanism does not have, a statement that does not parse (a missing `;`
/// that joins `drive motor: ...` to the statement before it) is the mistake to report.
fn statements_that_do_not_parse(input: TokenStream) -> Option<syn::Error> {
    use proc_macro2::{Delimiter, Group, TokenTree};
    let without_scenes: TokenStream = input
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                let kept = crate::scene::statements(g.stream())
                    .into_iter()
                    .filter(|s| !matches!(s.first(), Some(TokenTree::Ident(k)) if k == "scene"))
                    .flatten()
                    .collect();
                TokenTree::Group(Group::new(Delimiter::Brace, kept))
            }
            other => other,
        })
        .collect();
    syn::parse::Parser::parse2(MechanismDef::parse_recovering, without_scenes).ok().and_then(|(_, errors)| errors)
}

/// The placeholders of a mechanism (and its scenes) whose parts, loops, instances or scenes do
/// not expand: made of the mechanism with its instances' parameters taken leniently, or without
/// the first top-level statement whose removal lets it expand, or, when no one statement does,
/// of what parses as written.
fn placeholders_without_the_mistake(written: TokenStream) -> TokenStream {
    use proc_macro2::{Delimiter, Group, TokenTree};
    let tokens: Vec<TokenTree> = written.clone().into_iter().collect();
    let body = tokens.iter().position(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace));
    let expands = |input: TokenStream| {
        let names = &mut crate::names::Names::default();
        refuse_raw_identifiers(&input)
            .and_then(|()| crate::part::expand_leniently(input, names))
            .and_then(|input| crate::scene::split_leniently(input, names))
    };
    let placeholder_of =
        |input: TokenStream| syn::parse::Parser::parse2(MechanismDef::parse_recovering, input).map(|(def, _)| placeholder(def)).ok();
    // Instances' parameters and scenes' items are taken leniently: one missing or misspelt loses
    // nothing else.
    if let Ok((base, scenes)) = expands(written.clone()) {
        return std::iter::once(base).chain(scenes).filter_map(placeholder_of).collect();
    }
    if let Some(at) = body {
        let TokenTree::Group(g) = &tokens[at] else { unreachable!("found as a brace group") };
        let statements = crate::scene::statements(g.stream());
        for k in 0..statements.len() {
            let kept: TokenStream = statements.iter().enumerate().filter(|&(i, _)| i != k).flat_map(|(_, s)| s.clone()).collect();
            let mut candidate = tokens.clone();
            candidate[at] = TokenTree::Group(Group::new(Delimiter::Brace, kept));
            if let Ok((base, scenes)) = expands(candidate.into_iter().collect()) {
                return std::iter::once(base).chain(scenes).filter_map(placeholder_of).collect();
            }
        }
    }
    placeholder_of(written).unwrap_or_default()
}

/// A raw identifier (`r#type`) names nothing in a mechanism: the names it makes from names
/// (`l_3`, `front_left_hub`, `CRANK`) would not be identifiers.
fn refuse_raw_identifiers(input: &TokenStream) -> syn::Result<()> {
    for tt in input.clone() {
        match tt {
            proc_macro2::TokenTree::Ident(id) if id.to_string().starts_with("r#") => {
                let plain = id.to_string()[2..].to_string();
                return Err(syn::Error::new(
                    id.span(),
                    format!("a raw identifier cannot name a body, point or element: expected a plain name, found `{id}`; write `{plain}_`"),
                ));
            }
            proc_macro2::TokenTree::Group(g) => refuse_raw_identifiers(&g.stream())?,
            _ => {}
        }
    }
    Ok(())
}

/// Expands one mechanism; whether it had no mistakes. With mistakes: their errors, and a
/// placeholder of the mechanism ([`placeholder`]).
fn expand_one(input: TokenStream) -> (TokenStream, bool) {
    let (def, parse_errors) = match syn::parse::Parser::parse2(MechanismDef::parse_recovering, input) {
        Ok(parsed) => parsed,
        Err(e) => return (crate::wording::compile_errors(e), false),
    };
    let errors = match parse_errors {
        // The statements that did not parse are reported; the rest are not checked, since what
        // they name may be in a statement that did not parse.
        Some(e) => e,
        None => match def.validate().and_then(|m| generate(&m)) {
            Ok(ts) => return (ts, true),
            Err(e) => e,
        },
    };
    let errors = crate::wording::compile_errors(errors);
    let placeholder = placeholder(def);
    (quote!(#errors #placeholder), false)
}

/// The type of a mechanism that has mistakes, generated in full from its statements without
/// mistakes, so that the user's code using it — its constants, traits, accessors and solvers —
/// adds no errors of its own: one mistake, one error. Statements are taken in order, each kept
/// if it adds no error (a joint naming a body whose statement is wrong goes with it), or else
/// replaced by the first of its [`stand_ins`] that has fewer errors, so that what names it still
/// resolves. If what is left still does not generate, the bare struct with its parameters.
fn placeholder(mut def: MechanismDef) -> TokenStream {
    let count = |def: &MechanismDef| def.validate().err().map_or(0, |e| e.into_iter().count());
    let partial = def.partial();
    let spatial = def.items.iter().any(|i| matches!(i, Item::Spatial(_)));
    let body_names: Vec<String> =
        def.items.iter().filter_map(|i| if let Item::Body(b) = i { Some(b.name.to_string()) } else { None }).collect();
    let bodies: Vec<&str> = body_names.iter().map(String::as_str).collect();
    let mut left = std::mem::take(&mut def.items);
    let mut errors = count(&def);
    // Passes until one keeps nothing more: a statement may name what a later one declares.
    loop {
        let kept = def.items.len();
        let mut dropped = Vec::new();
        for statement in left {
            let candidates = stand_ins(&statement, spatial, &bodies);
            def.items.push(statement);
            let mut now = count(&def);
            // The first stand-in with fewer errors, instead.
            for stand_in in candidates {
                if now == 0 {
                    break;
                }
                let original = std::mem::replace(def.items.last_mut().expect("just pushed"), stand_in);
                let instead = count(&def);
                if instead < now {
                    now = instead;
                    break;
                }
                *def.items.last_mut().expect("just pushed") = original;
            }
            if now > errors {
                dropped.extend(def.items.pop());
            } else {
                errors = now;
            }
        }
        if dropped.is_empty() || def.items.len() == kept {
            break;
        }
        left = dropped;
    }
    // A type needs a body: where none is left, one of unit mass and inertia stands in.
    if !def.items.iter().any(|i| matches!(i, Item::Body(_))) {
        let name = proc_macro2::Ident::new("placeholder", def.name.span());
        def.items.push(Item::Body(BodyDef::unit(name, spatial, false)));
    }
    let generated = def.validate().and_then(|mut m| {
        m.warnings.clear();
        generate(&m)
    });
    generated.unwrap_or_else(|_| stub(&partial))
}

/// What may stand in for a statement with a mistake, in order ([`placeholder`]), so that the
/// names it makes (`Name::MOTOR`, `Name::CRANK`) are still there: a body of unit mass and
/// inertia, parameters with defaults 0, a driver of a constant (on the body whose name is
/// nearest, where its own is misspelt; of each of its body's coordinates, where its coordinate
/// is wrong), a joint without its options (and on the bodies whose names are nearest, where
/// its own are misspelt), a point on a misspelt body on the body whose name is nearest.
fn stand_ins(statement: &Item, spatial: bool, bodies: &[&str]) -> Vec<Item> {
    match statement {
        // A point on a misspelt body: on the body it is nearest to.
        Item::Point(p) => crate::parse::nearest(&p.body.to_string(), bodies, &["ground"])
            .map(|body| Item::Point(crate::parse::NamedVector { body: syn::Ident::new(body, p.body.span()), ..p.clone() }))
            .into_iter()
            .collect(),
        // A driver of a constant; where its coordinate is what is wrong, of each of its body's.
        Item::Drive(d) => {
            let constant = crate::parse::DriveDef { f: Expr::number(1.0, d.f.span, d.f.end), ..d.clone() };
            let mut candidates = vec![Item::Drive(constant.clone())];
            if let crate::parse::DriveTarget::Coordinate { body, coordinate } = &d.target {
                // On a misspelt body: on the body it is nearest to.
                if let Some(nearest) = crate::parse::nearest(&body.to_string(), bodies, &[]) {
                    let target = crate::parse::DriveTarget::Coordinate {
                        body: syn::Ident::new(nearest, body.span()),
                        coordinate: coordinate.clone(),
                    };
                    candidates.push(Item::Drive(crate::parse::DriveDef { target, ..constant.clone() }));
                }
                candidates.extend(["phi", "x", "y", "z"].iter().map(|c| {
                    let target =
                        crate::parse::DriveTarget::Coordinate { body: body.clone(), coordinate: syn::Ident::new(c, coordinate.span()) };
                    Item::Drive(crate::parse::DriveDef { target, ..constant.clone() })
                }));
            }
            candidates
        }
        Item::Joint(j) => {
            let bare = crate::parse::JointDef { options: Vec::new(), ..j.clone() };
            // On a misspelt body: on the body it is nearest to (and without its options).
            let declared = |body: &syn::Ident| body == "ground" || bodies.iter().any(|b| body == b);
            let near = |a: &crate::parse::Attach| match crate::parse::nearest(&a.body.to_string(), bodies, &["ground"]) {
                Some(body) if !declared(&a.body) => crate::parse::Attach { body: syn::Ident::new(body, a.body.span()), ..a.clone() },
                _ => a.clone(),
            };
            let moved = crate::parse::JointDef { i: near(&j.i), j: near(&j.j), ..bare.clone() };
            [(!j.options.is_empty()).then_some(bare), (!declared(&j.i.body) || !declared(&j.j.body)).then_some(moved)]
                .into_iter()
                .flatten()
                .map(Item::Joint)
                .collect()
        }
        Item::Body(b) => vec![Item::Body(BodyDef::unit(b.name.clone(), spatial, b.particle))],
        Item::Params(ps) => {
            vec![Item::Params(ps.iter().map(|(name, value)| (name.clone(), Expr::number(0.0, value.span, value.end))).collect())]
        }
        _ => Vec::new(),
    }
}

/// The type of a mechanism whose description has mistakes: its name and parameters, `Default`,
/// and nothing that could raise errors of its own.
fn stub(p: &Partial) -> TokenStream {
    let Partial { attrs, vis, name, scalar, params } = p;
    let real = real(*scalar);
    quote! {
        #(#attrs)*
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #vis struct #name { #(pub #params: #real,)* }
    }
}

/// The expansion of `input` as text, with the temporaries `v<n>` renumbered v0, v1, … in order
/// of first appearance and `MODEL_JSON` set aside (it describes each expression as written): two
/// declarations that generate the same functions give the same text.
#[cfg(test)]
pub fn canonical(input: TokenStream) -> String {
    canonical_text(expand(input).to_string())
}

/// [`canonical`] of an expansion's text.
#[cfg(test)]
pub fn canonical_text(mut code: String) -> String {
    assert!(!code.contains("compile_error"), "{code}");
    let json = code.find("const MODEL_JSON").expect("the model JSON");
    let end = json + code[json..].find("\" ;").expect("its end");
    code.replace_range(json..end, "");
    let mut seen = std::collections::HashMap::new();
    let (mut out, mut word) = (String::new(), String::new());
    for c in code.chars().chain([' ']) {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        if word.len() > 1 && word.starts_with('v') && word[1..].bytes().all(|b| b.is_ascii_digit()) {
            let next = seen.len();
            word = format!("v{}", seen.entry(word.clone()).or_insert(next));
        }
        out.push_str(&word);
        out.push(c);
        word.clear();
    }
    out
}

/// Panics with the first difference of two canonical expansions and its surroundings.
#[cfg(test)]
pub fn assert_same_code(a: &str, b: &str) {
    if let Some(at) = a.chars().zip(b.chars()).position(|(x, y)| x != y).or((a.len() != b.len()).then_some(a.len().min(b.len()))) {
        let around = |s: &str| s.chars().skip(at.saturating_sub(150)).take(300).collect::<String>();
        panic!("the expansions differ at character {at}:\nfirst:  …{}…\nsecond: …{}…", around(a), around(b));
    }
}

#[cfg(test)]
mod snapshot {
    use std::path::PathBuf;

    /// The expansion of `examples/expand/slider_crank.rs`, formatted, equals the committed
    /// `slider_crank.expanded.rs` (regenerate with `MBD_BLESS=1`).
    #[test]
    fn snapshot() {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/expand");
        let source = std::fs::read_to_string(dir.join("slider_crank.rs")).expect("read the snapshot's input");
        let file = syn::parse_file(&source).expect("the snapshot's input parses");
        let tokens = file
            .items
            .iter()
            .find_map(|item| match item {
                syn::Item::Macro(m) if m.mac.path.is_ident("mechanism") => Some(m.mac.tokens.clone()),
                _ => None,
            })
            .expect("the snapshot's input holds a mechanism! invocation");
        let expanded = super::expand(tokens);
        let formatted = prettyplease::unparse(&syn::parse2(expanded).expect("the expansion is valid Rust"));
        let text =
            format!("// Generated from slider_crank.rs by `MBD_BLESS=1 cargo test -p mbd-macros snapshot`. Do not edit.\n{formatted}");
        let path = dir.join("slider_crank.expanded.rs");
        if std::env::var_os("MBD_BLESS").is_some() {
            std::fs::write(&path, &text).expect("write the snapshot");
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(committed == text, "{} is out of date: rerun with MBD_BLESS=1 and review the diff", path.display());
    }
}
