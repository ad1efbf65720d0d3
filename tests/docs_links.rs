//! The README and the pages in docs/ link to each other, to files of the repository and to
//! figures. This test keeps those links from rotting: every relative link and image path in
//! README.md and docs/*.md must name a file or directory that exists, and every `#anchor` into a
//! markdown file must name one of its headings (GitHub's heading ids). It also checks the
//! generated-table markers of the docs pages (`<!-- BEGIN generated: COMMAND -->` …
//! `<!-- END generated -->`, rewritten by the measuring commands with `--write-docs`) and that
//! the README keeps its two set-up commands.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every docs/*.md.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/ exists")
        .map(|e| e.expect("readable docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// The text outside fenced code blocks, line by line (line numbers kept), with inline code
/// spans blanked: links inside code are not links.
fn prose_lines(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence: Option<&str> = None;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some(f) = fence {
            if t.starts_with(f) {
                fence = None;
            }
            continue;
        }
        if t.starts_with("```") {
            fence = Some("```");
            continue;
        }
        if t.starts_with("~~~") {
            fence = Some("~~~");
            continue;
        }
        // Blank inline code spans (a run of n backticks closes at the next run of n).
        let mut s = String::with_capacity(line.len());
        let chars: Vec<char> = line.chars().collect();
        let mut k = 0;
        while k < chars.len() {
            if chars[k] == '`' {
                let mut n = 0;
                while k + n < chars.len() && chars[k + n] == '`' {
                    n += 1;
                }
                let open = k;
                k += n;
                let mut closed = None;
                let mut j = k;
                while j < chars.len() {
                    if chars[j] == '`' {
                        let mut m = 0;
                        while j + m < chars.len() && chars[j + m] == '`' {
                            m += 1;
                        }
                        if m == n {
                            closed = Some(j + m);
                            break;
                        }
                        j += m;
                    } else {
                        j += 1;
                    }
                }
                match closed {
                    Some(end) => {
                        s.push_str(&" ".repeat(end - open));
                        k = end;
                    }
                    None => {
                        s.extend(&chars[open..k]);
                    }
                }
            } else {
                s.push(chars[k]);
                k += 1;
            }
        }
        out.push((i + 1, s));
    }
    out
}

/// Targets of inline links and images, `[text](target)` / `![alt](target "title")`.
fn link_targets(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        // The target ends at the matching ')' (targets may hold balanced parentheses).
        let mut depth = 0usize;
        let mut end = None;
        for (j, c) in after.char_indices() {
            match c {
                '(' => depth += 1,
                ')' if depth == 0 => {
                    end = Some(j);
                    break;
                }
                ')' => depth -= 1,
                _ => {}
            }
        }
        let Some(end) = end else { break };
        let target = after[..end].trim();
        let target = target.split_whitespace().next().unwrap_or("");
        let target = target.trim_start_matches('<').trim_end_matches('>');
        out.push(target.to_string());
        rest = &after[end..];
    }
    out
}

/// GitHub's id of a heading: lower case, punctuation dropped (letters, digits, '-', '_' and
/// spaces kept), spaces to '-'; a repeated id gets "-1", "-2", ….
fn heading_ids(text: &str) -> HashSet<String> {
    let mut ids = HashSet::new();
    let mut fence = false;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = !fence;
            continue;
        }
        if fence || !t.starts_with('#') {
            continue;
        }
        let title = t.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_' || *c == ' ')
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let mut id = slug.clone();
        let mut n = 0;
        while ids.contains(&id) {
            n += 1;
            id = format!("{slug}-{n}");
        }
        ids.insert(id);
    }
    ids
}

/// Every broken relative link of one page, as "page:line: target: why".
fn broken_links(page: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(page).expect("page readable");
    let dir = page.parent().expect("page has a directory");
    let rel = page
        .strip_prefix(root())
        .unwrap_or(page)
        .display()
        .to_string();
    let mut broken = Vec::new();
    for (n, line) in prose_lines(&text) {
        for target in link_targets(&line) {
            if target.is_empty() {
                broken.push(format!("{rel}:{n}: empty link target"));
                continue;
            }
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, anchor) = match target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (target.as_str(), None),
            };
            let file = if path.is_empty() {
                page.to_path_buf()
            } else {
                dir.join(path)
            };
            if !file.exists() {
                broken.push(format!(
                    "{rel}:{n}: {target}: {} does not exist",
                    file.display()
                ));
                continue;
            }
            if let Some(anchor) = anchor
                && file.extension().is_some_and(|e| e == "md")
            {
                let ids = heading_ids(&std::fs::read_to_string(&file).expect("target readable"));
                if !ids.contains(anchor) {
                    broken.push(format!(
                        "{rel}:{n}: {target}: no heading with id {anchor:?} in {}",
                        file.display()
                    ));
                }
            }
        }
    }
    broken
}

#[test]
fn every_relative_link_and_image_of_readme_and_docs_resolves() {
    let pages = pages();
    // README plus the pages the README's documentation table promises.
    for must in [
        "guide.md",
        "design-studies.md",
        "results.md",
        "validation.md",
        "performance.md",
        "slider-crank.md",
        "methods.md",
        "conventions.md",
        "REFERENCES.md",
    ] {
        assert!(
            pages
                .iter()
                .any(|p| p.ends_with(Path::new("docs").join(must))),
            "docs/{must} is missing"
        );
    }
    let broken: Vec<String> = pages.iter().flat_map(|p| broken_links(p)).collect();
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_link_checker_finds_what_it_must() {
    // The checker itself: a link in a code span or fence is no link; a target with a title or
    // balanced parentheses is read whole; GitHub's heading ids.
    let lines = prose_lines(
        "a [x](one.md) `[y](two.md)` b\n```\n[z](three.md)\n```\n![i](p(1).png \"t\") [w](#a-b)",
    );
    let targets: Vec<String> = lines.iter().flat_map(|(_, l)| link_targets(l)).collect();
    assert_eq!(targets, ["one.md", "p(1).png", "#a-b"]);
    let ids = heading_ids("# The cases ([Key2002], Table II)\n## `run` it: §5\n## Same\n## Same\n");
    for id in ["the-cases-key2002-table-ii", "run-it-5", "same", "same-1"] {
        assert!(ids.contains(id), "{id} not in {ids:?}");
    }
    // A page with a missing file and a missing anchor reports both.
    let dir = std::env::temp_dir().join(format!("jbearing-docs-links-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("page.md");
    std::fs::write(
        &page,
        "# Top\n[a](page.md#top) [b](missing.png) [c](#nowhere)\n",
    )
    .unwrap();
    let broken = broken_links(&page);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(broken.len(), 2, "{broken:?}");
    assert!(broken[0].contains("missing.png"), "{broken:?}");
    assert!(broken[1].contains("nowhere"), "{broken:?}");
}

#[test]
fn generated_blocks_are_well_formed() {
    // Each `<!-- BEGIN generated: COMMAND -->` is closed by `<!-- END generated -->` before the
    // next BEGIN, names a command, and no command owns two blocks of one page.
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let mut open: Option<(usize, String)> = None;
        let mut seen = HashSet::new();
        for (i, line) in text.lines().enumerate() {
            let t = line.trim();
            if let Some(rest) = t.strip_prefix("<!-- BEGIN generated:") {
                let command = rest.trim_end_matches("-->").trim().to_string();
                assert!(
                    open.is_none(),
                    "{}:{}: BEGIN inside the block opened at line {}",
                    page.display(),
                    i + 1,
                    open.as_ref().unwrap().0
                );
                assert!(
                    !command.is_empty(),
                    "{}:{}: no command",
                    page.display(),
                    i + 1
                );
                assert!(
                    seen.insert(command.clone()),
                    "{}:{}: second block of {command:?}",
                    page.display(),
                    i + 1
                );
                open = Some((i + 1, command));
            } else if t == "<!-- END generated -->" {
                assert!(
                    open.take().is_some(),
                    "{}:{}: END without BEGIN",
                    page.display(),
                    i + 1
                );
            }
        }
        assert!(
            open.is_none(),
            "{}: block opened at line {} is never closed",
            page.display(),
            open.unwrap().0
        );
    }
}

#[test]
fn readme_keeps_its_two_set_up_commands() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    for (command, script) in [
        (
            "bash scripts/run_compressor.sh",
            "scripts/run_compressor.sh",
        ),
        ("bash scripts/test.sh", "scripts/test.sh"),
    ] {
        assert!(
            readme.lines().any(|l| l.trim_start().starts_with(command)),
            "README.md lost the set-up command {command:?}"
        );
        assert!(root().join(script).is_file(), "{script} is missing");
    }
}
