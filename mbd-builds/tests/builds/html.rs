//! Reading the pages `cargo doc` wrote.

/// The page's text: tags dropped, entities `&lt;`, `&gt;`, `&amp;`, `&quot;`, `&#39;` decoded.
pub(crate) fn text(html: &str) -> String {
    let mut out = String::with_capacity(html.len());
    let mut in_tag = false;
    for c in html.chars() {
        match c {
            '<' => in_tag = true,
            '>' if in_tag => {
                in_tag = false;
                out.push(' ');
            }
            _ if !in_tag => out.push(c),
            _ => {}
        }
    }
    let out = out.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&#39;", "'").replace("&amp;", "&");
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Asserts that `page` holds the table row `row` ("| 2 | crank.phi | rad |").
pub(crate) fn has_row(page: &str, row: &str) {
    let cells = row.trim_matches('|').split('|').map(str::trim).collect::<Vec<_>>().join(" ");
    assert!(page.contains(&cells), "the page lacks the row {row:?}");
}
