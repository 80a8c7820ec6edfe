//! Every class of user mistake in `mechanism!` is a compile error with a span on the offending
//! token (trybuild compares the compiler's messages with the committed `.stderr` files).
#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}
