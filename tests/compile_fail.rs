//! Bad component declarations and bad `connect()` lines are compile errors that point
//! at the offending tokens.

#[test]
fn bad_declarations_and_connections_do_not_compile() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
