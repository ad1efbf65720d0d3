//! The README's Rust snippet is the crate-level doctest of `solvers/src/lib.rs` (which
//! `cargo test --doc` compiles and runs): the snippet's `main` body, line for line, must be that
//! doctest, so that the snippet a new user copies is one that runs.

#[test]
fn readme_rust_snippet_is_the_crate_doctest() {
    let readme = read("README.md");
    let start = readme
        .find("```rust\n")
        .expect("a ```rust block in the README")
        + 8;
    let block = &readme[start..start + readme[start..].find("```").expect("closed block")];
    let body: Vec<&str> = block
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("fn main") && *l != "Ok(())" && *l != "}")
        .collect();
    let lib = read("solvers/src/lib.rs");
    let doc: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(str::trim)
        .collect();
    let open = doc
        .iter()
        .position(|l| *l == "```")
        .expect("a doctest in lib.rs")
        + 1;
    let close = open
        + doc[open..]
            .iter()
            .position(|l| *l == "```")
            .expect("closed doctest");
    // The doctest's hidden lines (`# …`) are the `?` plumbing the README's `main` replaces.
    let doctest: Vec<&str> = doc[open..close]
        .iter()
        .copied()
        .filter(|l| !l.is_empty() && !l.starts_with("# "))
        .collect();
    assert_eq!(
        body, doctest,
        "the README snippet and the crate doctest differ"
    );
    assert!(body.len() >= 8, "snippet too short: {body:?}");
}

fn read(path: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path))
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}
