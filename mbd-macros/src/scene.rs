//! Scenes: variants of one mechanism with effects left out, each its own generated type.
//!
//! ```text
//! scene Name [without item, item, ...] [actuating driver [= force], ...];
//!     item := a statement's label | gravity | friction;   driver := a driver's label
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
//!
//! `actuating` frees a driven coordinate: the driver's row is gone and an actuator exerts a
//! generalized force F along the coordinate it drove, in the sense that increases it — the force
//! the driver exerted (its multiplier λ, N or N·m), so inverse dynamics of the driven scene gives
//! the forces that make the free scene follow the same motion. F is the new parameter
//! `label_force` (default 0), or the expression after `=`. Each kind of driver has its actuator:
//!
//! | driver | actuator |
//! |---|---|
//! | `distance(Pi, Pj)` | `actuator Pi ~ Pj { force: -(F) }` (a push F along the line) |
//! | `angle(i, j)` | `torque_actuator i ~ j { torque: -(F) }` |
//! | planar `body.phi`, `body.x`, `body.y` | `torque body = F`, `force body[0, 0] = [F, 0]`, `[0, F]` |
//! | spatial `body.x`, `.y`, `.z` | `force body[0, 0, 0] = [F, 0, 0]`, … |
//! | spatial `joint.angle`, `joint.stroke` | `torque_actuator joint { torque: -(F) }`, `force_actuator joint { force: -(F) }` |

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
    let spatial = kept.iter().any(|s| keyword(s).is_some_and(|k| k == "spatial"));
    for scene in &scenes {
        let Scene { name: scene_name, without: left_out, actuating } = parse_scene(scene)?;
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
        // Each actuated driver's labels (a part's label: every instance's), with the force.
        let mut actuated: Vec<(String, &Ident, &Option<Vec<TokenTree>>)> = Vec::new();
        for (item, force) in &actuating {
            let word = item.to_string();
            let group: Vec<String> = names.made_from(&word).into_iter().filter(|l| labels.contains(l)).collect();
            let mut own: Vec<String> = if labels.contains(&word) { vec![word.clone()] } else { group };
            let drivers: Vec<String> =
                kept.iter().filter(|s| keyword(s).is_some_and(|k| k == "drive")).filter_map(|s| label(s).map(|l| l.to_string())).collect();
            if own.is_empty() || !own.iter().all(|l| drivers.contains(l)) {
                if lenient {
                    // A placeholder actuates the driver the user most likely meant, so that its
                    // force's parameter is there.
                    let candidates: Vec<&str> = drivers.iter().map(String::as_str).collect();
                    match crate::parse::nearest(&word, &candidates, &[]) {
                        Some(d) if !actuated.iter().any(|(a, ..)| a == d) => own = vec![d.to_string()],
                        _ => continue,
                    }
                    actuated.extend(own.into_iter().map(|l| (l, item, force)));
                    continue;
                }
                let written: Vec<String> = drivers.iter().map(|l| names.written(l)).collect();
                let candidates: Vec<&str> = written.iter().map(String::as_str).collect();
                let what = match kept.iter().find(|s| label(s).is_some_and(|l| own.contains(&l.to_string()))).and_then(|s| keyword(s)) {
                    Some(k) => format!("`{word}`, a `{k}` statement"),
                    None => format!("`{word}`{}", crate::parse::closest(&word, &candidates, &[])),
                };
                return Err(syn::Error::new(
                    item.span(),
                    format!(
                        "scene `{scene_name}` actuates what is not a labelled driver of `{name}`: expected a driver's label \
                         (`drive lift: ...`; here: {}), found {what}",
                        if candidates.is_empty() { "none".to_string() } else { candidates.join(", ") }
                    ),
                ));
            }
            if left_out_labels.iter().any(|l| own.contains(l)) {
                return Err(syn::Error::new(
                    item.span(),
                    format!("scene `{scene_name}` both leaves out and actuates `{word}`: expected it in one list, found it in both"),
                ));
            }
            if actuated.iter().any(|(a, ..)| own.contains(a)) {
                return Err(syn::Error::new(
                    item.span(),
                    format!("scene `{scene_name}` actuates `{word}` twice: expected each driver once, found `{word}` again"),
                ));
            }
            actuated.extend(own.into_iter().map(|l| (l, item, force)));
        }
        let no_gravity = left_out.iter().any(|i| i == "gravity");
        let without = |s: &Vec<TokenTree>| {
            !(label(s).is_some_and(|l| left_out_labels.contains(&l.to_string()))
                || (no_gravity && keyword(s).is_some_and(|k| k == "gravity")))
        };
        let friction = left_out.iter().any(|i| i == "friction");
        let mut body_tokens: Vec<TokenTree> = Vec::new();
        for s in kept.iter().filter(|s| without(s)) {
            match label(s).and_then(|l| actuated.iter().find(|(a, ..)| l == a)) {
                Some((_, item, force)) => body_tokens.extend(actuator(s, item, force.as_deref(), spatial)?),
                None if friction => body_tokens.extend(strip_friction(s)),
                None => body_tokens.extend(s.iter().cloned()),
            }
        }
        let mut what: Vec<String> = Vec::new();
        if !left_out.is_empty() {
            let list: Vec<String> = left_out.iter().map(|i| format!("`{i}`")).collect();
            what.push(format!("without {}", list.join(", ")));
        }
        if !actuated.is_empty() {
            let list: Vec<String> = actuated
                .iter()
                .map(|(l, _, force)| match force {
                    Some(f) => format!("`{}` (force `{}`)", names.written(l), f.iter().cloned().collect::<TokenStream>()),
                    None => format!("`{}` (force: the parameter `{l}_force`)", names.written(l)),
                })
                .collect();
            what.push(format!(
                "with {} as actuators: each exerts a force (N, or N·m on an angle) along the coordinate it drove, in the sense that increases it",
                list.join(", ")
            ));
        }
        let doc = format!("Scene of [`{name}`]: the same mechanism {}.", what.join("; "));
        out.push(rebuild(&scene_name, body_tokens.into_iter().collect(), Some(doc)));
    }
    Ok((base, out))
}

/// A driver statement `drive label: target = f;` made an actuator of the same label along the
/// coordinate it drove (see the module's table), with the force `force`, or the new parameter
/// `label_force` declared before it. The new tokens carry `item`'s span: a mistake in them is
/// reported on the scene's item.
fn actuator(s: &[TokenTree], item: &Ident, force: Option<&[TokenTree]>, spatial: bool) -> syn::Result<Vec<TokenTree>> {
    let span = item.span();
    let Some(label) = label(s) else { unreachable!("an actuated driver is found by its label") };
    let target_end = s.iter().position(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == '=')).unwrap_or(s.len());
    let target = &s[3..target_end];
    let mut out: TokenStream = TokenStream::new();
    let f: TokenStream = match force {
        Some(f) => f.iter().cloned().collect(),
        None => {
            let param = Ident::new(&format!("{label}_force"), span);
            out.extend(quote::quote_spanned!(span=> params { #param: 0.0 }));
            quote::quote_spanned!(span=> #param)
        }
    };
    let f = TokenTree::Group(Group::new(Delimiter::Parenthesis, f));
    let zero = quote::quote_spanned!(span=> 0.0);
    let statement = match target {
        [TokenTree::Ident(kind), TokenTree::Group(args)]
            if (kind == "distance" || kind == "angle") && args.delimiter() == Delimiter::Parenthesis =>
        {
            let args: Vec<TokenTree> = args.stream().into_iter().collect();
            let mut sides = args.split(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ','));
            let (Some(a), Some(b)) = (sides.next(), sides.next()) else { return Ok(s.to_vec()) };
            let (a, b): (TokenStream, TokenStream) = (a.iter().cloned().collect(), b.iter().cloned().collect());
            if kind == "distance" {
                quote::quote_spanned!(span=> actuator #label: #a ~ #b { force: -#f };)
            } else {
                quote::quote_spanned!(span=> torque_actuator #label: #a ~ #b { torque: -#f };)
            }
        }
        [TokenTree::Ident(x), TokenTree::Punct(dot), TokenTree::Ident(coordinate)] if dot.as_char() == '.' => {
            let c = coordinate.to_string();
            let axes: &[&str] = if spatial { &["x", "y", "z"] } else { &["x", "y"] };
            if let Some(k) = axes.iter().position(|a| *a == c) {
                let components: Vec<TokenStream> = (0..axes.len()).map(|i| if i == k { f.clone().into() } else { zero.clone() }).collect();
                let origin = vec![zero.clone(); axes.len()];
                quote::quote_spanned!(span=> force #label: #x[#(#origin),*] = [#(#components),*];)
            } else {
                match (spatial, c.as_str()) {
                    (false, "phi") => quote::quote_spanned!(span=> torque #label: #x = #f;),
                    (true, "angle") => quote::quote_spanned!(span=> torque_actuator #label: #x { torque: -#f };),
                    (true, "stroke") => quote::quote_spanned!(span=> force_actuator #label: #x { force: -#f };),
                    // Not a driver's shape: left as it is, for the parser to report.
                    _ => return Ok(s.to_vec()),
                }
            }
        }
        _ => return Ok(s.to_vec()),
    };
    out.extend(statement);
    Ok(out.into_iter().collect())
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

/// A `scene` statement: its name, what it leaves out and which drivers it makes actuators (with
/// their force's tokens, where given).
struct Scene {
    name: Ident,
    without: Vec<Ident>,
    actuating: Vec<(Ident, Option<Vec<TokenTree>>)>,
}

/// `scene Name without a, b, c actuating d, e = force;` (either list may be absent, not both).
fn parse_scene(s: &[TokenTree]) -> syn::Result<Scene> {
    let shape = "expected `scene Name without item, item, ...;` (an item is a statement's label, `gravity` or `friction`) \
                 and/or `actuating driver, driver = force, ...` (a driver's label)";
    let at = |k: usize| s.get(k).map_or(s[0].span(), TokenTree::span);
    let name = match s.get(1) {
        Some(TokenTree::Ident(n)) => n.clone(),
        _ => return Err(syn::Error::new(at(1), shape)),
    };
    let mut scene = Scene { name, without: Vec::new(), actuating: Vec::new() };
    let is = |k: usize, c: char| matches!(s.get(k), Some(TokenTree::Punct(p)) if p.as_char() == c);
    let mut k = 2;
    if matches!(s.get(k), Some(TokenTree::Ident(w)) if w == "without") {
        k += 1;
        loop {
            match s.get(k) {
                Some(TokenTree::Ident(item)) => scene.without.push(item.clone()),
                _ => return Err(syn::Error::new(at(k), shape)),
            }
            k += 1;
            if !is(k, ',') {
                break;
            }
            k += 1;
        }
    }
    if matches!(s.get(k), Some(TokenTree::Ident(w)) if w == "actuating") {
        k += 1;
        loop {
            let item = match s.get(k) {
                Some(TokenTree::Ident(item)) => item.clone(),
                _ => return Err(syn::Error::new(at(k), shape)),
            };
            k += 1;
            let mut force = None;
            if is(k, '=') {
                let start = k + 1;
                while k + 1 < s.len() && !is(k + 1, ',') && !is(k + 1, ';') {
                    k += 1;
                }
                if k < start {
                    return Err(syn::Error::new(at(start), "expected the actuator's force after `=`, found none"));
                }
                force = Some(s[start..=k].to_vec());
                k += 1;
            }
            scene.actuating.push((item, force));
            if !is(k, ',') {
                break;
            }
            k += 1;
        }
    }
    if (scene.without.is_empty() && scene.actuating.is_empty()) || !is(k, ';') || k + 1 != s.len() {
        return Err(syn::Error::new(at(k), shape));
    }
    Ok(scene)
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

    /// A scene actuating a driver is its mechanism written with the actuator in the driver's
    /// place: each kind of driver, token for token.
    #[test]
    fn a_scene_actuating_a_driver_generates_what_its_mechanism_written_with_the_actuator_generates() {
        let bodies = quote! {
            gravity [0.0, -9.81];
            body a { mass: 1.0, inertia: 0.01, at: [0.1, 0.0, 0.0] }
            body b { mass: 0.5, inertia: 0.02, at: [0.3, 0.0, 0.0] }
            body c { mass: 0.8, inertia: 0.03, at: [1.0, -1.0, 0.0] }
            revolute ground[0.0, 0.0] ~ a[-0.1, 0.0];
            revolute a[0.1, 0.0] ~ b[-0.1, 0.0];
            translational ground[0.0, -1.0] along [1.0, 0.0] ~ c[0.0, 0.0] along [1.0, 0.0];
        };
        let with_scene = quote!(Arm {
            #bodies
            drive turn: a.phi = 0.5 * t;
            drive bend: angle(a, b) = 0.1;
            drive push: c.x = 1.0;
            drive reach: distance(ground[0.5, 0.5], b[0.1, 0.0]) = 0.6;
            scene Free actuating turn, bend = 2.0 * t, push, reach;
        });
        let written = quote!(Free {
            #bodies
            params { turn_force: 0.0 }
            torque turn: a = (turn_force);
            torque_actuator bend: a ~ b { torque: -(2.0 * t) };
            params { push_force: 0.0 }
            force push: c[0.0, 0.0] = [(push_force), 0.0];
            params { reach_force: 0.0 }
            actuator reach: ground[0.5, 0.5] ~ b[0.1, 0.0] { force: -(reach_force) };
        });
        let both = expand(with_scene.clone()).to_string();
        let base = expand(quote!(Arm {
            #bodies
            drive turn: a.phi = 0.5 * t;
            drive bend: angle(a, b) = 0.1;
            drive push: c.x = 1.0;
            drive reach: distance(ground[0.5, 0.5], b[0.1, 0.0]) = 0.6;
        }))
        .to_string();
        let scene = both.strip_prefix(base.as_str()).expect("the base comes first, as it expands alone");
        let doc_at = scene.find("# [doc = \"Scene of").expect("the scene's doc line");
        let doc_end = doc_at + scene[doc_at..].find("\"] ").expect("its end") + 3;
        let scene = format!("{}{}", &scene[..doc_at].trim_end().trim_end_matches("# [doc = \"\"]"), &scene[doc_end..]);
        assert_same_code(&canonical_text(scene.trim().to_string()), &canonical(written));
        assert!(both.contains("with `turn` (force: the parameter `turn_force`), `bend` (force `2.0 * t`)"), "{both}");
    }

    /// In space: a joint's angle and stroke and a body's coordinate.
    #[test]
    fn a_spatial_scene_actuating_a_driver_writes_the_joints_actuator() {
        let with_scene = quote!(Lift {
            spatial;
            body e { mass: 1.0, inertia: [0.1, 0.1, 0.1] }
            cylindrical sleeve: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ e[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
            drive turn: sleeve.angle = t;
            drive lift: sleeve.stroke = 0.1 * t;
            body f { mass: 1.0, inertia: [0.1, 0.1, 0.1], at: [1.0, 0.0, 0.0] }
            translational rail: ground[1.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ f[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
            drive rise: f.z = 0.2;
            scene Free actuating turn, lift, rise;
        });
        let out = expand(with_scene).to_string();
        let (_, free) = out.split_once("struct Free").expect("the scene");
        for element in [
            "\"turn\"",
            "\"lift\"",
            "\"rise\"",
            "\"rotational spring-damper-actuator\"",
            "\"translational spring-damper-actuator\"",
            "\"applied force\"",
        ] {
            assert!(free.contains(element), "{element} is not in the scene's expansion");
        }
        assert!(out.contains("\"turn: angle\"") && out.contains("\"rise: z\""), "the base's driver rows");
        assert!(
            !free.contains("\"turn: angle\"") && !free.contains("\"lift: stroke\"") && !free.contains("\"rise: z\""),
            "gone in the scene"
        );
        for parameter in ["turn_force", "lift_force", "rise_force"] {
            assert!(free.contains(parameter), "{parameter}");
        }
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
            (quote!(M { body b { mass: 1.0, inertia: 0.1 } scene S; }), "and/or `actuating driver, driver = force, ...`"),
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute pin: ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S actuating pin; }),
                "scene `S` actuates what is not a labelled driver of `M`: expected a driver's label (`drive lift: ...`; here: turn), found `pin`, a `revolute` statement",
            ),
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S actuating trun; }),
                "found `trun` (did you mean `turn`?)",
            ),
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S actuating turn, turn = 2.0; }),
                "scene `S` actuates `turn` twice: expected each driver once, found `turn` again",
            ),
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S without turn actuating turn; }),
                "scene `S` both leaves out and actuates `turn`: expected it in one list, found it in both",
            ),
            (
                quote!(M { params { turn_force: 1.0 } body b { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S actuating turn; }),
                "duplicate parameter `turn_force`",
            ),
            (
                quote!(M { body b { mass: 1.0, inertia: 0.1 } revolute ground[0.0, 0.0] ~ b[0.0, 0.0]; drive turn: b.phi = t; scene S actuating turn = ; }),
                "expected the actuator's force after `=`, found none",
            ),
        ];
        for (input, want) in cases {
            let e = expand(input).to_string();
            assert!(e.contains(want), "{e}\n  wanted: {want}");
        }
    }
}
