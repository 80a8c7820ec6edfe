//! Scenes: variants of one mechanism with effects left out, each its own generated type.
//!
//! ```text
//! scene Name without item, item, ...;      item := a statement's label | gravity | friction
//! ```
//!
//! Split on the (unrolled) tokens before parsing: the mechanism without its `scene` statements is
//! the base; each scene is the same token stream under the scene's name with the statements it
//! leaves out removed — a labelled joint, driver, constraint or force element (`actuator lift:
//! ...`; `front_left.shock` in a part's instance; a part's label `shock`, that element in
//! every instance of the part), every `gravity` statement, or with `friction` every joint's friction options
//! (`viscous`, `coulomb`, `radius`, `slip_velocity`, `bearing`). Each is then expanded on its
//! own, so what a scene leaves out is absent from its generated code, and what it keeps is
//! generated exactly as the base generates it.

use proc_macro2::{Delimiter, Group, Ident, Punct, Spacing, TokenStream, TokenTree};
use quote::quote;

use crate::names::Names;

/// The effects a scene can leave out besides labelled statements.
const EFFECTS: &[&str] = &["gravity", "friction"];

/// A joint's friction options, which `without friction` removes.
const FRICTION_OPTIONS: &[&str] = &["viscous", "coulomb", "radius", "slip_velocity", "bearing"];

/// The base mechanism's tokens and each scene's.
pub fn split(input: TokenStream, names: &Names) -> syn::Result<(TokenStream, Vec<TokenStream>)> {
    split_with(input, names, false)
}

/// [`split`] for a placeholder: a scene leaving out what the mechanism does not have leaves out
/// the rest, so that the scene's type is still there.
pub fn split_leniently(input: TokenStream, names: &Names) -> syn::Result<(TokenStream, Vec<TokenStream>)> {
    split_with(input, names, true)
}

fn split_with(input: TokenStream, names: &Names, lenient: bool) -> syn::Result<(TokenStream, Vec<TokenStream>)> {
    let tokens: Vec<TokenTree> = input.into_iter().collect();
    let Some(body_at) = tokens.iter().position(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace)) else {
        // Not a mechanism's shape: the parser will say what is missing.
        return Ok((tokens.into_iter().collect(), Vec::new()));
    };
    let TokenTree::Group(body) = &tokens[body_at] else { unreachable!("found as a brace group") };
    let name = match body_at.checked_sub(1).map(|k| &tokens[k]) {
        Some(TokenTree::Ident(name)) => name.clone(),
        _ => return Ok((tokens.into_iter().collect(), Vec::new())),
    };
    let statements = statements(body.stream());
    let (scenes, kept): (Vec<_>, Vec<_>) = statements.into_iter().partition(|s| keyword(s).is_some_and(|k| k == "scene"));
    let labels: Vec<String> = kept.iter().filter_map(|s| label(s)).map(|l| l.to_string()).collect();
    let has_gravity = kept.iter().any(|s| keyword(s).is_some_and(|k| k == "gravity"));
    let has_friction = kept.iter().any(|s| has_friction_options(s));
    // The scene's doc line goes after the mechanism's own doc comments, before its visibility.
    let vis_at = (0..body_at - 1).find(|&k| !is_attribute(&tokens, k)).unwrap_or(body_at - 1);
    let rebuild = |name: &Ident, body_tokens: TokenStream, doc: Option<String>| -> TokenStream {
        let mut out: TokenStream = tokens[..vis_at].iter().cloned().collect();
        if let Some(doc) = doc {
            out.extend(quote!(#[doc = ""] #[doc = #doc]));
        }
        out.extend(tokens[vis_at..body_at - 1].iter().cloned());
        out.extend([TokenTree::Ident(name.clone())]);
        let mut group = Group::new(Delimiter::Brace, body_tokens);
        group.set_span(body.span());
        out.extend([TokenTree::Group(group)]);
        out.extend(tokens[body_at + 1..].iter().cloned());
        out
    };
    let base = rebuild(&name, kept.iter().flatten().cloned().collect(), None);
    let mut seen: Vec<String> = vec![name.to_string()];
    let mut out = Vec::new();
    for scene in &scenes {
        let (scene_name, left_out) = parse_scene(scene)?;
        if seen.contains(&scene_name.to_string()) {
            return Err(syn::Error::new(
                scene_name.span(),
                format!("`{scene_name}` is already the name of the mechanism or of another scene: expected a new name, found `{scene_name}` again; each scene is its own type"),
            ));
        }
        seen.push(scene_name.to_string());
        // Each item's labels: its own, or those its instances made of a part's label.
        let mut left_out_labels: Vec<String> = Vec::new();
        for item in &left_out {
            let word = item.to_string();
            let group: Vec<String> = names.made_from(&word).into_iter().filter(|l| labels.contains(l)).collect();
            let known =
                labels.contains(&word) || !group.is_empty() || (word == "friction" && has_friction) || (word == "gravity" && has_gravity);
            if !known && lenient {
                continue;
            }
            if !known {
                let written: Vec<String> = labels.iter().map(|l| names.written(l)).collect();
                let names: Vec<&str> = written.iter().map(String::as_str).collect();
                let hint = crate::parse::closest(&word, &names, EFFECTS);
                return Err(syn::Error::new(
                    item.span(),
                    format!(
                        "scene `{scene_name}` leaves out what `{name}` does not have: expected a labelled statement \
                         (`actuator lift: ...`; here: {}), a part's label (left out in every instance), `gravity` or `friction`, \
                         found `{word}`{hint}",
                        if names.is_empty() { "none is labelled".to_string() } else { names.join(", ") }
                    ),
                ));
            }
            left_out_labels.push(word);
            left_out_labels.extend(group);
        }
        let no_gravity = left_out.iter().any(|i| i == "gravity");
        let without = |s: &Vec<TokenTree>| {
            !(label(s).is_some_and(|l| left_out_labels.contains(&l.to_string()))
                || (no_gravity && keyword(s).is_some_and(|k| k == "gravity")))
        };
        let friction = left_out.iter().any(|i| i == "friction");
        let body_tokens: TokenStream =
            kept.iter().filter(|s| without(s)).flat_map(|s| if friction { strip_friction(s) } else { s.clone() }).collect();
        let list: Vec<String> = left_out.iter().map(|i| format!("`{i}`")).collect();
        let doc = format!("Scene of [`{name}`]: the same mechanism without {}.", list.join(", "));
        out.push(rebuild(&scene_name, body_tokens, Some(doc)));
    }
    Ok((base, out))
}

/// Whether `tokens[k]` is part of an outer attribute `#[...]`.
fn is_attribute(tokens: &[TokenTree], k: usize) -> bool {
    match &tokens[k] {
        TokenTree::Punct(p) => p.as_char() == '#',
        TokenTree::Group(g) => {
            g.delimiter() == Delimiter::Bracket && k > 0 && matches!(&tokens[k - 1], TokenTree::Punct(p) if p.as_char() == '#')
        }
        _ => false,
    }
}

/// Statements at the mechanism's level: each ends at `;` or at a brace group.
pub(crate) fn statements(input: TokenStream) -> Vec<Vec<TokenTree>> {
    let mut out = Vec::new();
    let mut current = Vec::new();
    for tt in input {
        let ends = matches!(&tt, TokenTree::Punct(p) if p.as_char() == ';')
            || matches!(&tt, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
        current.push(tt);
        if ends {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    // A joint or force with options ends at its brace group and then at `;`: join the `;`.
    let mut joined: Vec<Vec<TokenTree>> = Vec::new();
    for s in out {
        match (joined.last_mut(), s.as_slice()) {
            (Some(last), [TokenTree::Punct(p)]) if p.as_char() == ';' => last.extend(s),
            _ => joined.push(s),
        }
    }
    joined
}

fn keyword(s: &[TokenTree]) -> Option<&Ident> {
    match s.first() {
        Some(TokenTree::Ident(k)) => Some(k),
        _ => None,
    }
}

/// A statement's label: `kind label: ...` (not `::`).
pub(crate) fn label(s: &[TokenTree]) -> Option<&Ident> {
    match (s.get(1), s.get(2), s.get(3)) {
        (Some(TokenTree::Ident(l)), Some(TokenTree::Punct(colon)), next)
            if colon.as_char() == ':' && !matches!(next, Some(TokenTree::Punct(p)) if p.as_char() == ':') =>
        {
            Some(l)
        }
        _ => None,
    }
}

/// `scene Name without a, b, c;`
fn parse_scene(s: &[TokenTree]) -> syn::Result<(Ident, Vec<Ident>)> {
    let shape = "expected `scene Name without item, item, ...;` (an item is a statement's label, `gravity` or `friction`)";
    let at = |k: usize| s.get(k).map_or(s[0].span(), TokenTree::span);
    let name = match s.get(1) {
        Some(TokenTree::Ident(n)) => n.clone(),
        _ => return Err(syn::Error::new(at(1), shape)),
    };
    match s.get(2) {
        Some(TokenTree::Ident(w)) if w == "without" => {}
        _ => return Err(syn::Error::new(at(2), shape)),
    }
    let mut items = Vec::new();
    let mut k = 3;
    loop {
        match s.get(k) {
            Some(TokenTree::Ident(item)) => items.push(item.clone()),
            _ => return Err(syn::Error::new(at(k), shape)),
        }
        match s.get(k + 1) {
            Some(TokenTree::Punct(p)) if p.as_char() == ',' => k += 2,
            Some(TokenTree::Punct(p)) if p.as_char() == ';' && k + 2 == s.len() => return Ok((name, items)),
            _ => return Err(syn::Error::new(at(k + 1), shape)),
        }
    }
}

/// Whether a statement's options braces hold fields (joints and force elements; not a body's
/// fields or the parameters).
fn has_options(s: &[TokenTree]) -> bool {
    keyword(s).is_some_and(|k| k != "params" && k != "body")
}

/// Whether an option field (`name: value`) is one of a joint's friction options.
fn is_friction_field(field: &[TokenTree]) -> bool {
    matches!(field.first(), Some(TokenTree::Ident(n)) if FRICTION_OPTIONS.contains(&n.to_string().as_str()))
}

/// The option fields of a brace group, split at commas.
fn fields(g: &Group) -> Vec<Vec<TokenTree>> {
    let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
    tokens.split(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ',')).map(<[TokenTree]>::to_vec).collect()
}

fn has_friction_options(s: &[TokenTree]) -> bool {
    has_options(s)
        && s.iter().any(
            |tt| matches!(tt, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace && fields(g).iter().any(|f| is_friction_field(f))),
        )
}

/// The statement with its friction option fields removed.
fn strip_friction(s: &[TokenTree]) -> Vec<TokenTree> {
    if !has_options(s) {
        return s.to_vec();
    }
    s.iter()
        .map(|tt| match tt {
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                let mut kept: Vec<TokenTree> = Vec::new();
                for field in fields(g).iter().filter(|f| !f.is_empty() && !is_friction_field(f)) {
                    if !kept.is_empty() {
                        kept.push(TokenTree::Punct(Punct::new(',', Spacing::Alone)));
                    }
                    kept.extend(field.iter().cloned());
                }
                let mut group = Group::new(Delimiter::Brace, kept.into_iter().collect());
                group.set_span(g.span());
                TokenTree::Group(group)
            }
            other => other.clone(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::expand::{assert_same_code, canonical, canonical_text, expand};
    use quote::quote;

    /// A scene is its mechanism written without what it leaves out: a labelled force element,
    /// gravity and the joints' friction — the same generated code, token for token.
    #[test]
    fn a_scene_generates_what_its_mechanism_written_without_the_effects_generates() {
        let items = quote! {
            params { k: 50.0 }
            gravity [0.0, -9.81];
            body crank { mass: 1.0, inertia: 0.01, at: [0.05, 0.0, 0.0] }
            body slider { mass: 0.5, inertia: 1.0e-4, at: [0.2, 0.0, 0.0] }
            revolute pin: ground[0.0, 0.0] ~ crank[-0.05, 0.0] { viscous: 0.02, coulomb: 0.1, radius: 0.01 };
            revolute_revolute rod: crank[0.05, 0.0] ~ slider[0.0, 0.0] { length: 0.15 };
            translational slide: ground[0.0, 0.0] along [1.0, 0.0] ~ slider[0.0, 0.0] along [1.0, 0.0] { coulomb: 0.2 };
            spring return_spring: ground[0.3, 0.0] ~ slider[0.0, 0.0] { k: k, length: 0.1 };
            torque motor: crank = 0.5;
        };
        let with_scene = quote!(Crank { #items scene Bare without return_spring, gravity, friction; });
        let written = quote!(Bare {
            params { k: 50.0 }
            body crank { mass: 1.0, inertia: 0.01, at: [0.05, 0.0, 0.0] }
            body slider { mass: 0.5, inertia: 1.0e-4, at: [0.2, 0.0, 0.0] }
            revolute pin: ground[0.0, 0.0] ~ crank[-0.05, 0.0] {};
            revolute_revolute rod: crank[0.05, 0.0] ~ slider[0.0, 0.0] { length: 0.15 };
            translational slide: ground[0.0, 0.0] along [1.0, 0.0] ~ slider[0.0, 0.0] along [1.0, 0.0] {};
            torque motor: crank = 0.5;
        });
        let both = expand(with_scene).to_string();
        assert!(both.contains("struct Crank") && both.contains("struct Bare"), "the base and the scene are two types");
        // The scene's part of the expansion: expand the base alone and take what follows it.
        let base = expand(quote!(Crank { #items })).to_string();
        let scene = both.strip_prefix(base.as_str()).expect("the base comes first, as it expands alone");
        let scene = scene.replace(
            "# [doc = \"\"] # [doc = \"Scene of [`Crank`]: the same mechanism without `return_spring`, `gravity`, `friction`.\"] ",
            "",
        );
        assert_same_code(&canonical_text(scene.trim().to_string()), &canonical(written));
    }

    /// A part's label leaves out that element in every instance; an instance's label only there.
    #[test]
    fn a_scene_leaves_out_a_parts_element_in_every_instance_or_in_one() {
        let out = expand(quote!(Car {
            part corner(x0) {
                body wheel { mass: 10.0, inertia: 0.4, at: [x0, 0.3, 0.0] }
                spring coil: ground[x0, 1.0] ~ wheel[0.0, 0.0] { k: 1.0e4, length: 0.7 };
            }
            corner front(x0: 1.2);
            corner rear(x0: -1.3);
            scene Bare without coil;
            scene FrontOnly without rear.coil;
        }))
        .to_string();
        let (base, scenes) = out.split_once("struct Bare").expect("the scene Bare");
        let (bare, front_only) = scenes.split_once("struct FrontOnly").expect("the scene FrontOnly");
        assert!(base.contains("\"front.coil\"") && base.contains("\"rear.coil\""), "{base}");
        assert!(!bare.contains("\"front.coil\"") && !bare.contains("\"rear.coil\""), "{bare}");
        assert!(front_only.contains("\"front.coil\"") && !front_only.contains("\"rear.coil\""), "{front_only}");
    }

    #[test]
    fn a_scene_that_leaves_out_what_is_not_there_is_an_error_naming_what_is() {
        let cases = [
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute pin: ground[0.0, 0.0] ~ b[0.0, 0.0]; scene S without pn; }),
                "scene `S` leaves out what `M` does not have: expected a labelled statement (`actuator lift: ...`; here: pin), a part's label (left out in every instance), `gravity` or `friction`, found `pn` (did you mean `pin`?)",
            ),
            (quote!(M { body b { mass: 1.0, inertia: 0.1 } scene S without gravity; }), "leaves out what `M` does not have: expected a labelled statement (`actuator lift: ...`; here: none is labelled), a part's label (left out in every instance), `gravity` or `friction`, found `gravity`"),
            (quote!(M { body b { mass: 1.0, inertia: 0.1 } scene S without friction; }), "found `friction`"),
            (quote!(M { gravity [0.0, -9.81]; body b { mass: 1.0, inertia: 0.1 } scene M without gravity; }), "`M` is already the name of the mechanism or of another scene"),
            (quote!(M { body b { mass: 1.0, inertia: 0.1 } scene S with friction; }), "expected `scene Name without item, item, ...;`"),
        ];
        for (input, want) in cases {
            let e = expand(input).to_string();
            assert!(e.contains(want), "{e}\n  wanted: {want}");
        }
    }
}
