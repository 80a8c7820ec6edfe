//! Every class of user mistake in `mechanism!` is a compile error with a span on the offending
//! token (trybuild compares the compiler's messages with the committed `.stderr` files).
#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}

/// The catalogue's messages, as committed: each says what was expected and what was found; the
/// catalogue covers at least 40 classes of mistake, grouped by topic; and each case's `main` uses
/// the mechanism's type (its constants, traits and solvers), so that its committed stderr shows
/// the mistake adds no follow-up error there.
#[test]
fn every_message_says_what_was_expected_and_what_was_found() {
    let mut cases = 0;
    let mut messages = Vec::new();
    for group in std::fs::read_dir("tests/ui").unwrap() {
        let group = group.unwrap().path();
        for file in std::fs::read_dir(&group).unwrap() {
            let file = file.unwrap().path();
            if file.extension().is_some_and(|e| e == "rs") {
                let program = std::fs::read_to_string(&file).unwrap();
                assert!(!program.contains("fn main() {}"), "{}: `main` does not use the mechanism", file.display());
            }
            if file.extension().is_some_and(|e| e == "stderr") {
                cases += 1;
                let text = std::fs::read_to_string(&file).unwrap();
                let errors: Vec<&str> = text.lines().filter(|l| l.starts_with("error:")).collect();
                assert!(!errors.is_empty(), "{}: no error", file.display());
                messages.extend(errors.into_iter().map(|e| (file.clone(), e.to_string())));
            }
        }
    }
    assert!(cases >= 40, "{cases} cases in the catalogue");
    for (file, message) in &messages {
        let (expected, found) = (message.find("expected "), message.find(", found "));
        assert!(
            matches!((expected, found), (Some(e), Some(f)) if e < f),
            "{}: the message does not read \"expected … , found …\":\n{message}",
            file.display()
        );
    }
}
