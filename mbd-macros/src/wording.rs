//! The last step of every error: a message that says what was expected also says what was found.
//!
//! The macro's own messages are written that way. The parser's leaf errors come from syn
//! ("expected `,`", "expected identifier", "unexpected end of input, expected `;`") and name only
//! what was expected; here they are completed with the source text under their span, which the
//! compiler gives a procedural macro (`Span::source_text`, stable since Rust 1.66). Outside the
//! compiler (unit tests) there is no source text, and the message is kept as it is.

use proc_macro2::TokenStream;

/// `e` as `compile_error!`s, each message completed with what was found, and each mistake once:
/// a mistake inside a `for` loop is found in every iteration (`cc[0]`, `cc[1]`, …), at the same
/// token; only the first is kept.
pub fn compile_errors(e: syn::Error) -> TokenStream {
    let mut all: Option<syn::Error> = None;
    let mut seen = Vec::new();
    for one in e {
        let key = (one.span().start(), one.span().end(), without_digits(&one.to_string()));
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        let message = with_found(&one.to_string(), || one.span().source_text());
        let one = syn::Error::new(one.span(), message);
        match &mut all {
            Some(all) => all.combine(one),
            None => all = Some(one),
        }
    }
    all.map(|e| e.to_compile_error()).unwrap_or_default()
}

/// `message` without its numbers: the same mistake in two iterations of a loop names two indices.
fn without_digits(message: &str) -> String {
    message.chars().filter(|c| !c.is_ascii_digit()).collect()
}

/// `message` with ", found …" where it names only what was expected. `source` is the text under
/// the error's span, when there is one.
fn with_found(message: &str, source: impl FnOnce() -> Option<String>) -> String {
    if message.contains("found") {
        return message.to_string();
    }
    // syn's message at the end of a group: nothing more is written before its closing delimiter.
    if let Some(expected) = message.strip_prefix("unexpected end of input, ") {
        return format!("{expected}, found nothing more before the closing bracket");
    }
    if message.starts_with("unexpected end of input") {
        return format!("{message}: nothing more is written before the closing bracket");
    }
    if !message.starts_with("expected") {
        return message.to_string();
    }
    let found = match source() {
        Some(text) if !text.trim().is_empty() => describe(text.trim()),
        _ => return message.to_string(),
    };
    // "expected X: how to write it" → "expected X, found Y: how to write it".
    match help_at(message) {
        Some(at) => format!("{}, found {found}{}", &message[..at], &message[at..]),
        None => format!("{message}, found {found}"),
    }
}

/// Where the help after "expected X" begins: the first `: ` or `; ` outside backticks.
fn help_at(message: &str) -> Option<usize> {
    let mut quoted = false;
    let bytes = message.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        match b {
            b'`' => quoted = !quoted,
            b':' | b';' if !quoted && bytes.get(i + 1) == Some(&b' ') => return Some(i),
            _ => {}
        }
    }
    None
}

/// A token's source text as a message quotes it: short, and on one line.
fn describe(text: &str) -> String {
    let line = text.lines().next().unwrap_or_default();
    let mut short: String = line.chars().take(30).collect();
    if short.len() < text.len() {
        short.push('…');
    }
    format!("`{short}`")
}

#[cfg(test)]
mod tests {
    use super::with_found;

    #[test]
    fn syn_messages_say_what_was_found() {
        assert_eq!(with_found("expected `,`", || Some("inertia".into())), "expected `,`, found `inertia`");
        assert_eq!(
            with_found("expected a point on the body: `.name`", || Some("(1.0)".into())),
            "expected a point on the body, found `(1.0)`: `.name`"
        );
        assert_eq!(
            with_found("unexpected end of input, expected `;`", || None),
            "expected `;`, found nothing more before the closing bracket"
        );
        assert_eq!(
            with_found("expected `parameter: value`; part `c` takes `x`", || Some("x".into())),
            "expected `parameter: value`, found `x`; part `c` takes `x`"
        );
        let long = "{ mass: 1.0, inertia: 2.0, velocity: [0.0, 0.0, 0.0] }";
        assert_eq!(with_found("expected `;`", || Some(long.into())), "expected `;`, found `{ mass: 1.0, inertia: 2.0, vel…`");
    }

    #[test]
    fn complete_messages_and_missing_source_are_kept() {
        assert_eq!(with_found("`atan2` takes 2 arguments, found 1", || Some("x".into())), "`atan2` takes 2 arguments, found 1");
        assert_eq!(with_found("expected `,`", || None), "expected `,`");
        assert_eq!(with_found("duplicate body `a`", || Some("a".into())), "duplicate body `a`");
    }
}
