//! Stage 0: repeated structure, unrolled on the tokens before [`crate::parse`] sees them.
//!
//! ```text
//! for i in a..b { statements }     (also a..=b; nested loops; a, b integer expressions)
//! name[index]                      (an indexed name: the body, point or joint `name_index`)
//! ```
//!
//! Inside a loop's statements the loop variable stands for its value: in expressions it is the
//! number (`at: [0.1 * i, 0.0, 0.0]`), and in an indexed name `crank[i + 1]` the index. Integer
//! expressions (bounds and indices) take integer literals, enclosing loop variables, `+ − * / %`
//! and parentheses. An indexed name is an identifier followed by brackets holding one such
//! expression; it becomes the identifier `name_index` (`crank[3]` is `crank_3`, `cell[1][2]` is
//! `cell_1_2`), which names the same thing anywhere, inside a loop or not. Brackets holding
//! anything else (a point's coordinates `crank[0.05, 0.0]`) are left alone. A name after `.`
//! (a point or coordinate, `crank.x`) and a name before a single `:` (an option, `k: 1.0`, or
//! a label) are never replaced by a loop variable: a spring's `{ k: 2.0 }` inside
//! `for k in 0..n` keeps its stiffness option.
//!
//! Every produced token keeps the span of the token it came from, so a mistake inside a loop is
//! reported on the statement that made it (once per repetition that makes it).

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};

use crate::names::Names;

/// The most statements one mechanism may unroll to: a typo such as `0..100000000` is an error
/// here, not an expansion that exhausts the compiler's memory.
const MAX_REPETITIONS: usize = 100_000;

/// Unrolls every `for` loop and indexed name of a statement list (a mechanism's or a part's,
/// see [`crate::part::expand`]); each indexed name's identifier is recorded in `names` with its
/// written form.
pub fn unroll_statements(input: TokenStream, names: &mut Names) -> syn::Result<TokenStream> {
    statements(input, &mut Unroll { scope: Vec::new(), count: 0, names, lenient: false })
}

/// [`unroll_statements`] for a placeholder: a bound may also be a parameter of an integer
/// default (given in `constants`) or an integral number such as `2.0`, so that what a loop
/// with such a mistake makes is still there.
pub fn unroll_statements_leniently(input: TokenStream, names: &mut Names, constants: &[(String, i64)]) -> syn::Result<TokenStream> {
    statements(input, &mut Unroll { scope: constants.to_vec(), count: 0, names, lenient: true })
}

/// Loop variables in scope, innermost last.
type Scope = Vec<(String, i64)>;

/// The state of one unrolling: the loop variables in scope, the repetitions so far and the
/// indexed names made.
struct Unroll<'a> {
    scope: Scope,
    count: usize,
    names: &'a mut Names,
    /// Integral numbers taken as bounds ([`unroll_statements_leniently`]).
    lenient: bool,
}

/// A statement list: each `for` at a statement's start unrolled, every other token transformed.
fn statements(input: TokenStream, u: &mut Unroll) -> syn::Result<TokenStream> {
    let tokens: Vec<TokenTree> = input.into_iter().collect();
    let mut out = Vec::new();
    let mut at_start = true;
    let mut i = 0;
    while i < tokens.len() {
        if at_start && matches!(&tokens[i], TokenTree::Ident(id) if id == "for") {
            let (end, expanded) = unroll_for(&tokens, i, u)?;
            out.extend(expanded);
            i = end;
            at_start = true;
            continue;
        }
        let tt = &tokens[i];
        // A statement ends at `;` or at a brace group at its own level (`body b { ... }`).
        at_start = matches!(tt, TokenTree::Punct(p) if p.as_char() == ';')
            || matches!(tt, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
        i = transform_one(&tokens, i, u, &mut out)?;
    }
    Ok(out.into_iter().collect())
}

/// Unrolls the loop `for var in a..b { body }` starting at `tokens[start]`; returns the index
/// after it and its statements.
fn unroll_for(tokens: &[TokenTree], start: usize, u: &mut Unroll) -> syn::Result<(usize, TokenStream)> {
    let keyword = tokens[start].span();
    let shape = "expected `for i in a..b { statements }`";
    let var = match tokens.get(start + 1) {
        Some(TokenTree::Ident(v)) => v.clone(),
        other => return Err(syn::Error::new(other.map_or(keyword, TokenTree::span), format!("{shape}: a loop variable after `for`"))),
    };
    match tokens.get(start + 2) {
        Some(TokenTree::Ident(k)) if k == "in" => {}
        other => return Err(syn::Error::new(other.map_or(var.span(), TokenTree::span), format!("{shape}: `in` after `{var}`"))),
    }
    let body_at = (start + 3..tokens.len())
        .find(|&k| matches!(&tokens[k], TokenTree::Group(g) if g.delimiter() == Delimiter::Brace))
        .ok_or_else(|| syn::Error::new(var.span(), format!("{shape}: the loop's statements in braces")))?;
    let range = &tokens[start + 3..body_at];
    let range_span = range.first().map_or(var.span(), TokenTree::span);
    // Split the range at `..` or `..=`.
    let dots = (0..range.len().saturating_sub(1))
        .find(|&k| is_punct(&range[k], '.') && is_punct(&range[k + 1], '.'))
        .ok_or_else(|| syn::Error::new(range_span, format!("{shape}: a range `a..b` or `a..=b` after `in`")))?;
    let inclusive = range.get(dots + 2).is_some_and(|t| is_punct(t, '='));
    let upper = &range[dots + if inclusive { 3 } else { 2 }..];
    let bound = |part: &[TokenTree], which: &str| -> syn::Result<i64> {
        let span = part.first().map_or(range_span, TokenTree::span);
        let integral = |part: &[TokenTree]| match part {
            [TokenTree::Literal(l)] => l.to_string().parse::<f64>().ok().filter(|v| v.fract() == 0.0 && v.abs() < 1e9).map(|v| v as i64),
            _ => None,
        };
        if let Some(value) = integral(part).filter(|_| u.lenient) {
            return Ok(value);
        }
        integer(part, &u.scope).map_err(|why| {
            syn::Error::new(
                span,
                format!(
                    "the {which} bound of a `for`: expected an integer expression of numbers and enclosing loop variables, found {why}"
                ),
            )
        })
    };
    let (a, b) = (bound(&range[..dots], "lower")?, bound(upper, "upper")?);
    let b = if inclusive { b + 1 } else { b };
    let TokenTree::Group(body) = &tokens[body_at] else { unreachable!("found as a brace group") };
    let mut out = TokenStream::new();
    for k in a..b {
        u.count += 1;
        if u.count > MAX_REPETITIONS {
            return Err(syn::Error::new(
                range_span,
                format!("expected at most {MAX_REPETITIONS} repetitions, found more: is the range what you meant?"),
            ));
        }
        u.scope.push((var.to_string(), k));
        let unrolled = statements(body.stream(), u);
        u.scope.pop();
        out.extend(unrolled?);
    }
    Ok((body_at + 1, out))
}

/// Transforms `tokens[i]` (and, for an indexed name, the brackets after it) into `out`; returns
/// the index of the next token.
fn transform_one(tokens: &[TokenTree], i: usize, u: &mut Unroll, out: &mut Vec<TokenTree>) -> syn::Result<usize> {
    let after_dot = i > 0 && is_punct(&tokens[i - 1], '.');
    // `name:` but not `name::`: an option's or a label's name.
    let before_colon = matches!(tokens.get(i + 1), Some(TokenTree::Punct(p)) if p.as_char() == ':' && p.spacing() == Spacing::Alone);
    match &tokens[i] {
        TokenTree::Ident(id) => {
            // `name[index]...`: one identifier, `name_index...`.
            let mut name = id.to_string();
            let mut written = u.names.written(&name);
            let mut k = i + 1;
            while let Some(TokenTree::Group(g)) = tokens.get(k) {
                if g.delimiter() != Delimiter::Bracket {
                    break;
                }
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                match integer(&inner, &u.scope) {
                    Ok(index) if index >= 0 => {
                        name = format!("{name}_{index}");
                        written = format!("{written}[{index}]");
                    }
                    Ok(index) => {
                        return Err(syn::Error::new(
                            g.span(),
                            format!("an index must not be negative: expected 0 or more, found {index} for `{id}[…]`"),
                        ))
                    }
                    Err(_) => break,
                }
                k += 1;
            }
            if k > i + 1 {
                u.names.record(&name, written);
                out.push(TokenTree::Ident(Ident::new(&name, id.span())));
                return Ok(k);
            }
            match u.scope.iter().rev().find(|(v, _)| id == v) {
                Some(&(_, value)) if !after_dot && !before_colon => out.extend(number(value, id.span())),
                _ => out.push(tokens[i].clone()),
            }
            Ok(i + 1)
        }
        TokenTree::Group(g) => {
            let inner: Vec<TokenTree> = g.stream().into_iter().collect();
            let mut transformed = Vec::new();
            let mut k = 0;
            while k < inner.len() {
                k = transform_one(&inner, k, u, &mut transformed)?;
            }
            let mut group = Group::new(g.delimiter(), transformed.into_iter().collect());
            group.set_span(g.span());
            out.push(TokenTree::Group(group));
            Ok(i + 1)
        }
        other => {
            out.push(other.clone());
            Ok(i + 1)
        }
    }
}

/// The loop variable's value as tokens: a literal, or `(-n)` for a negative one.
fn number(value: i64, span: Span) -> Vec<TokenTree> {
    let mut literal = Literal::i64_unsuffixed(value.abs());
    literal.set_span(span);
    if value >= 0 {
        return vec![TokenTree::Literal(literal)];
    }
    let mut minus = Punct::new('-', Spacing::Alone);
    minus.set_span(span);
    let mut group = Group::new(Delimiter::Parenthesis, [TokenTree::Punct(minus), TokenTree::Literal(literal)].into_iter().collect());
    group.set_span(span);
    vec![TokenTree::Group(group)]
}

fn is_punct(tt: &TokenTree, c: char) -> bool {
    matches!(tt, TokenTree::Punct(p) if p.as_char() == c)
}

/// Evaluates an integer expression (`+ − * / %`, unary minus, parentheses, integer literals and
/// loop variables in scope); the error says what is not one.
fn integer(tokens: &[TokenTree], scope: &Scope) -> Result<i64, String> {
    let mut at = 0;
    let value = sum(tokens, &mut at, scope)?;
    if at != tokens.len() {
        return Err(format!("`{}`", tokens[at]));
    }
    Ok(value)
}

fn sum(t: &[TokenTree], at: &mut usize, scope: &Scope) -> Result<i64, String> {
    let mut value = product(t, at, scope)?;
    while let Some(op) = t.get(*at).filter(|x| is_punct(x, '+') || is_punct(x, '-')) {
        let minus = is_punct(op, '-');
        *at += 1;
        let rhs = product(t, at, scope)?;
        value = if minus { value.checked_sub(rhs) } else { value.checked_add(rhs) }.ok_or("overflow")?;
    }
    Ok(value)
}

fn product(t: &[TokenTree], at: &mut usize, scope: &Scope) -> Result<i64, String> {
    let mut value = unary(t, at, scope)?;
    while let Some(op) = t.get(*at).filter(|x| is_punct(x, '*') || is_punct(x, '/') || is_punct(x, '%')) {
        let op = if let TokenTree::Punct(p) = op { p.as_char() } else { unreachable!("filtered") };
        *at += 1;
        let rhs = unary(t, at, scope)?;
        value = match op {
            '*' => value.checked_mul(rhs),
            _ if rhs == 0 => return Err("division by zero".into()),
            '/' => value.checked_div(rhs),
            _ => value.checked_rem(rhs),
        }
        .ok_or("overflow")?;
    }
    Ok(value)
}

fn unary(t: &[TokenTree], at: &mut usize, scope: &Scope) -> Result<i64, String> {
    let token = t.get(*at).ok_or("an expression is missing")?;
    *at += 1;
    match token {
        TokenTree::Punct(p) if p.as_char() == '-' => unary(t, at, scope)?.checked_neg().ok_or_else(|| "overflow".into()),
        TokenTree::Literal(l) => l.to_string().parse::<i64>().map_err(|_| format!("`{l}`, which is not an integer")),
        TokenTree::Ident(id) => scope
            .iter()
            .rev()
            .find(|(v, _)| id == v)
            .map(|&(_, value)| value)
            .ok_or_else(|| format!("`{id}`, which is not a loop variable")),
        // Parentheses, and the invisible group around a `macro_rules!` fragment (`0..$n`).
        TokenTree::Group(g) if matches!(g.delimiter(), Delimiter::Parenthesis | Delimiter::None) => {
            integer(&g.stream().into_iter().collect::<Vec<_>>(), scope)
        }
        other => Err(format!("`{other}`")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn unrolled(input: TokenStream) -> String {
        crate::part::expand(input, &mut Names::default()).unwrap_or_else(|e| panic!("{e}")).to_string()
    }

    #[test]
    fn a_loop_repeats_its_statements_with_the_variable_replaced() {
        let got = unrolled(quote!(M {
            body l[0] { at: [0.05, 0.0, 0.0] }
            for i in 1..3 {
                body l[i] { at: [0.05 + 0.1 * i, 0.0, 0.0] }
                revolute l[i - 1][0.05, 0.0] ~ l[i][-0.05, 0.0];
            }
        }));
        let want = quote!(M {
            body l_0 { at: [0.05, 0.0, 0.0] }
            body l_1 { at: [0.05 + 0.1 * 1, 0.0, 0.0] }
            revolute l_0[0.05, 0.0] ~ l_1[-0.05, 0.0];
            body l_2 { at: [0.05 + 0.1 * 2, 0.0, 0.0] }
            revolute l_1[0.05, 0.0] ~ l_2[-0.05, 0.0];
        });
        assert_eq!(got, want.to_string());
    }

    #[test]
    fn nested_loops_inclusive_ranges_and_two_indices() {
        let got = unrolled(quote!(M {
            for i in 0..=1 { for j in i..2 { point cell[i][j].p = [i, -j]; } }
        }));
        let want = quote!(M {
            point cell_0_0.p = [0, -0]; point cell_0_1.p = [0, -1]; point cell_1_1.p = [1, -1];
        });
        assert_eq!(got, want.to_string());
    }

    /// A `macro_rules!` fragment reaches the macro wrapped in an invisible group: a bound or an
    /// index passed as `$n` still counts.
    #[test]
    fn bounds_and_indices_from_a_macro_rules_fragment() {
        let n = Group::new(Delimiter::None, quote!(2));
        let got = unrolled(quote!(M { for i in 0..#n { body l[i + #n] {} } }));
        assert_eq!(got, quote!(M { body l_2 {} body l_3 {} }).to_string());
    }

    #[test]
    fn names_after_a_dot_and_point_brackets_are_left_alone() {
        let got = unrolled(quote!(M { for x in 0..1 { fix b.x = x; revolute ground[0.0, 0.0] ~ b[x, 0.0]; gravity [0.0, -9.81]; } }));
        let want = quote!(M { fix b.x = 0; revolute ground[0.0, 0.0] ~ b[0, 0.0]; gravity [0.0, -9.81]; });
        assert_eq!(got, want.to_string());
    }

    /// An option named like the loop variable (a spring's `k`) stays an option; its value is
    /// replaced.
    #[test]
    fn option_names_are_left_alone() {
        let got = unrolled(quote!(M { for k in 1..2 { rotational_spring l[k - 1] ~ l[k] { k: 0.5 * k, c: k }; } }));
        let want = quote!(M { rotational_spring l_0 ~ l_1 { k: 0.5 * 1, c: 1 }; });
        assert_eq!(got, want.to_string());
    }

    #[test]
    fn malformed_loops_are_errors_that_say_what_is_expected() {
        let cases = [
            (quote!(M { for 3 in 0..2 {} }), "a loop variable after `for`"),
            (quote!(M { for i of 0..2 {} }), "`in` after `i`"),
            (quote!(M { for i in 0..2; }), "the loop's statements in braces"),
            (quote!(M { for i in 0 to 2 {} }), "a range `a..b`"),
            (
                quote!(M { for i in 0..n {} }),
                "the upper bound of a `for`: expected an integer expression of numbers and enclosing loop variables, found `n`, which is not a loop variable",
            ),
            (quote!(M { for i in 0.5..2 {} }), "found `0.5`, which is not an integer"),
            (
                quote!(M { params { n: 2.0 } for i in 0..n {} }),
                "found `n`, which is not a loop variable; `n` is a parameter, which may change at run time, and a loop is unrolled when the mechanism is built: write a number",
            ),
            (quote!(M { for i in 0..2 { body l[i - 1] {} } }), "an index must not be negative: expected 0 or more, found -1 for `l[…]`"),
            (quote!(M { for i in 0..1000000 {} }), "expected at most 100000 repetitions, found more"),
        ];
        for (input, want) in cases {
            let e = crate::part::expand(input, &mut Names::default()).expect_err(want).to_string();
            assert!(e.contains(want), "{e}\n  wanted: {want}");
        }
    }

    /// The repeated and the written-out declarations (indexed names without loops) of a chain of 4
    /// parallelogram loops (those of `mbd-long/tests/singular.rs`) expand to the same code, token for token — every generated
    /// function, constant and name — once the temporaries `v<n>` are numbered in order of
    /// appearance (the loop's `0.5 * k` folds to the written-out `1.0`, but its constants took
    /// node numbers in the expression graph first), with `MODEL_JSON` set aside: it describes each
    /// expression as written.
    #[test]
    fn a_repeated_chain_generates_what_the_written_out_chain_generates() {
        let repeated = quote!(pub Parallelograms4 {
            gravity [0.0, -9.81];
            for k in 0..=4 {
                body crank[k] { mass: 1.0, inertia: 0.0075, at: [0.5 * k + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
                revolute ground[0.5 * k, 0.0] ~ crank[k][-0.15, 0.0];
            }
            for k in 0..4 {
                body coupler[k] { mass: 1.0, inertia: 0.020_833_333_333_333_33, at: [0.5 * k + 0.25 + 0.3 * cos(PI / 2.0), 0.3, 0.0] }
                revolute crank[k][0.15, 0.0] ~ coupler[k][-0.25, 0.0];
                revolute crank[k + 1][0.15, 0.0] ~ coupler[k][0.25, 0.0];
            }
        });
        let written = quote!(pub Parallelograms4 {
            gravity [0.0, -9.81];
            body crank[0] { mass: 1.0, inertia: 0.0075, at: [0.0 + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
            revolute ground[0.0, 0.0] ~ crank[0][-0.15, 0.0];
            body crank[1] { mass: 1.0, inertia: 0.0075, at: [0.5 + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
            revolute ground[0.5, 0.0] ~ crank[1][-0.15, 0.0];
            body crank[2] { mass: 1.0, inertia: 0.0075, at: [1.0 + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
            revolute ground[1.0, 0.0] ~ crank[2][-0.15, 0.0];
            body crank[3] { mass: 1.0, inertia: 0.0075, at: [1.5 + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
            revolute ground[1.5, 0.0] ~ crank[3][-0.15, 0.0];
            body crank[4] { mass: 1.0, inertia: 0.0075, at: [2.0 + 0.15 * cos(PI / 2.0), 0.15, PI / 2.0] }
            revolute ground[2.0, 0.0] ~ crank[4][-0.15, 0.0];
            body coupler[0] { mass: 1.0, inertia: 0.020_833_333_333_333_33, at: [0.25 + 0.3 * cos(PI / 2.0), 0.3, 0.0] }
            revolute crank[0][0.15, 0.0] ~ coupler[0][-0.25, 0.0];
            revolute crank[1][0.15, 0.0] ~ coupler[0][0.25, 0.0];
            body coupler[1] { mass: 1.0, inertia: 0.020_833_333_333_333_33, at: [0.75 + 0.3 * cos(PI / 2.0), 0.3, 0.0] }
            revolute crank[1][0.15, 0.0] ~ coupler[1][-0.25, 0.0];
            revolute crank[2][0.15, 0.0] ~ coupler[1][0.25, 0.0];
            body coupler[2] { mass: 1.0, inertia: 0.020_833_333_333_333_33, at: [1.25 + 0.3 * cos(PI / 2.0), 0.3, 0.0] }
            revolute crank[2][0.15, 0.0] ~ coupler[2][-0.25, 0.0];
            revolute crank[3][0.15, 0.0] ~ coupler[2][0.25, 0.0];
            body coupler[3] { mass: 1.0, inertia: 0.020_833_333_333_333_33, at: [1.75 + 0.3 * cos(PI / 2.0), 0.3, 0.0] }
            revolute crank[3][0.15, 0.0] ~ coupler[3][-0.25, 0.0];
            revolute crank[4][0.15, 0.0] ~ coupler[3][0.25, 0.0];
        });
        let (a, b) = (crate::expand::canonical(repeated), crate::expand::canonical(written));
        assert!(a.contains("\"crank[4].phi\""), "coordinate names carry the index as written");
        crate::expand::assert_same_code(&a, &b);
    }
}
