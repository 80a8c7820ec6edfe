//! Names as the user wrote them.
//!
//! Repetition and parts make identifiers out of structured names: the indexed name `l[3]` is the
//! identifier `l_3`, and the body `upper_arm` of the part instance `corner[2]` is
//! `corner_2_upper_arm`. Those identifiers are what the generated Rust API uses (`Name::L_3`,
//! `m.corner_2_upper_arm_b()`), but every text the user reads — compile errors, the body,
//! coordinate and row names, the model description, the docs — shows the name as written:
//! `l[3]`, `corner[2].upper_arm`. [`Names`] records each made identifier with its written form,
//! and [`Names::rewrite_strings`] applies the record to every string literal of an expansion.

use std::collections::HashMap;

use proc_macro2::{Group, Literal, TokenStream, TokenTree};

/// Made identifiers and how the user wrote them.
#[derive(Default)]
pub struct Names {
    written: HashMap<String, String>,
    /// Each label a part's instance made, with the label as the part declares it.
    labels: HashMap<String, String>,
}

impl Names {
    /// Records that the identifier `made` stands for `written`.
    pub fn record(&mut self, made: &str, written: String) {
        self.written.insert(made.to_string(), written);
    }

    /// Records that an instance made the label `made` from its part's label `from` (itself made
    /// when the part is inside another part).
    pub fn record_label(&mut self, made: &str, from: &str) {
        let root = self.labels.get(from).cloned().unwrap_or_else(|| from.to_string());
        self.labels.insert(made.to_string(), root);
    }

    /// Every label made from a part's label `label`, in every instance: the group a scene leaves
    /// out by that label.
    pub fn made_from(&self, label: &str) -> Vec<String> {
        self.labels.iter().filter(|(_, root)| *root == label).map(|(made, _)| made.clone()).collect()
    }

    /// How the user wrote the identifier `name` (the identifier itself when it was not made).
    pub fn written(&self, name: &str) -> String {
        self.written.get(name).cloned().unwrap_or_else(|| name.to_string())
    }

    /// `text` with every whole identifier that was made replaced by its written form.
    pub fn rewrite(&self, text: &str) -> String {
        let mut out = String::with_capacity(text.len());
        let mut word = String::new();
        let flush = |word: &mut String, out: &mut String| {
            match self.written.get(word.as_str()) {
                Some(w) => out.push_str(w),
                None => out.push_str(word),
            }
            word.clear();
        };
        for c in text.chars() {
            if c.is_alphanumeric() || c == '_' {
                word.push(c);
            } else {
                flush(&mut word, &mut out);
                out.push(c);
            }
        }
        flush(&mut word, &mut out);
        out
    }

    /// `tokens` with every string literal rewritten (see [`Names::rewrite`]): the error messages
    /// of `compile_error!`, the name constants, the docs and the model description.
    pub fn rewrite_strings(&self, tokens: TokenStream) -> TokenStream {
        if self.written.is_empty() {
            return tokens;
        }
        tokens
            .into_iter()
            .map(|tt| match tt {
                TokenTree::Group(g) => {
                    let mut group = Group::new(g.delimiter(), self.rewrite_strings(g.stream()));
                    group.set_span(g.span());
                    TokenTree::Group(group)
                }
                TokenTree::Literal(l) => TokenTree::Literal(self.rewrite_literal(l)),
                other => other,
            })
            .collect()
    }

    fn rewrite_literal(&self, l: Literal) -> Literal {
        let text = l.to_string();
        if !text.starts_with('"') {
            return l;
        }
        let Ok(s) = syn::parse_str::<syn::LitStr>(&text) else { return l };
        let value = s.value();
        let rewritten = self.rewrite(&value);
        if rewritten == value {
            return l;
        }
        let mut new = Literal::string(&rewritten);
        new.set_span(l.span());
        new
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    #[test]
    fn made_identifiers_read_as_written_in_every_string() {
        let mut names = Names::default();
        names.record("l_3", "l[3]".into());
        names.record("corner_2_upper_arm", "corner[2].upper_arm".into());
        assert_eq!(names.rewrite("unknown body `l_3` (did you mean `l_30`?)"), "unknown body `l[3]` (did you mean `l_30`?)");
        assert_eq!(names.rewrite("corner_2_upper_arm.phi"), "corner[2].upper_arm.phi");
        let tokens = quote!(
            const N: &[&str] = &["l_3.x", "b.y"];
            const K: usize = 3;
            fn l_3() {}
        );
        let want = quote!(
            const N: &[&str] = &["l[3].x", "b.y"];
            const K: usize = 3;
            fn l_3() {}
        );
        assert_eq!(names.rewrite_strings(tokens).to_string(), want.to_string());
    }
}
