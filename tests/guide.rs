//! The guide (`docs/`, an mdBook: `docs/book.toml`, `docs/SUMMARY.md`) and
//! the README hold together: every chapter of `docs/guide/` is in the
//! summary, every relative link of the Markdown files names a file that
//! exists (and, with `#anchor`, a heading of that file), and every
//! `{{#include FILE:ANCHOR}}` names a file and an anchor in it. Their Rust
//! examples run as doctests (`src/lib.rs`), their Python examples in
//! `python/tests/test_readme.py`.

use std::path::{Path, PathBuf};

/// The repository's root.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The Markdown files the guide and the repository's front pages are made of.
fn markdown_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = ["README.md", "BENCHMARKS.md", "CHANGELOG.md", "FUZZING.md"]
        .iter()
        .map(|name| root().join(name))
        .collect();
    for dir in ["docs", "docs/guide"] {
        let entries = std::fs::read_dir(root().join(dir)).expect("the guide's directory");
        let mut found: Vec<PathBuf> = entries
            .map(|entry| entry.expect("an entry").path())
            .filter(|path| path.extension().is_some_and(|e| e == "md"))
            .collect();
        found.sort();
        files.extend(found);
    }
    files
}

/// The text outside fenced code blocks (links in code are not links).
fn prose(text: &str) -> String {
    let mut inside = false;
    let mut kept = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside;
        } else if !inside {
            kept.push_str(line);
            kept.push('\n');
        }
    }
    kept
}

/// The targets of the Markdown links `[text](target)` of `text`.
fn link_targets(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(end) = after.find(')') else { break };
        targets.push(after[..end].to_string());
        rest = &after[end..];
    }
    targets
}

/// The anchor mdBook and GitHub give a heading: lower case, spaces as
/// hyphens, punctuation other than hyphens and underscores dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors of the headings of the Markdown file `path`.
fn anchors(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("a Markdown file");
    prose(&text)
        .lines()
        .filter(|line| line.starts_with('#'))
        .map(|line| slug(line.trim_start_matches('#')))
        .collect()
}

/// Whether `target`, a link of the file `from`, is broken: a relative path
/// that names no file, or an anchor that names no heading.
fn broken(from: &Path, target: &str) -> Option<String> {
    if target.contains("://") || target.starts_with("mailto:") {
        return None;
    }
    let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
    let file = match path {
        "" => from.to_path_buf(),
        _ => from.parent().expect("a directory").join(path),
    };
    if !file.exists() {
        return Some(format!("{target}: no file {}", file.display()));
    }
    let is_markdown = file.extension().is_some_and(|e| e == "md");
    if !anchor.is_empty() && is_markdown && !anchors(&file).contains(&anchor.to_string()) {
        return Some(format!(
            "{target}: no heading `{anchor}` in {}",
            file.display()
        ));
    }
    None
}

#[test]
fn every_relative_link_names_a_file_and_heading_that_exist() {
    let mut problems = Vec::new();
    for file in markdown_files() {
        let text = std::fs::read_to_string(&file).expect("readable");
        for target in link_targets(&prose(&text)) {
            if let Some(problem) = broken(&file, &target) {
                problems.push(format!("{}: {problem}", file.display()));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "broken links:\n{}",
        problems.join("\n")
    );
}

#[test]
fn every_include_names_a_file_and_an_anchor_in_it() {
    let mut includes = 0;
    for file in markdown_files() {
        let text = std::fs::read_to_string(&file).expect("readable");
        for directive in text.split("{{#include ").skip(1) {
            let directive = &directive[..directive.find("}}").expect("a closed include")];
            let (path, anchor) = directive.split_once(':').unwrap_or((directive, ""));
            let included = file.parent().expect("a directory").join(path.trim());
            let body = std::fs::read_to_string(&included)
                .unwrap_or_else(|_| panic!("{}: no file {}", file.display(), included.display()));
            if !anchor.is_empty() {
                for mark in ["ANCHOR: ", "ANCHOR_END: "] {
                    let line = format!("{mark}{anchor}");
                    assert!(
                        body.contains(&line),
                        "{}: no `{line}` in {path}",
                        file.display()
                    );
                }
            }
            includes += 1;
        }
    }
    assert!(
        includes >= 2,
        "the first chapter includes the README's examples"
    );
}

#[test]
fn every_chapter_is_in_the_summary() {
    let summary = std::fs::read_to_string(root().join("docs/SUMMARY.md")).expect("the summary");
    let listed = link_targets(&summary);
    let chapters = std::fs::read_dir(root().join("docs/guide")).expect("the chapters");
    for chapter in chapters {
        let path = chapter.expect("an entry").path();
        if path.extension().is_some_and(|e| e == "md") {
            let name = format!(
                "guide/{}",
                path.file_name().expect("a name").to_string_lossy()
            );
            assert!(listed.contains(&name), "{name} is not in docs/SUMMARY.md");
        }
    }
    for target in &listed {
        assert!(
            root().join("docs").join(target).exists(),
            "{target} in docs/SUMMARY.md"
        );
    }
}

#[test]
fn slugs_are_those_mdbook_gives() {
    assert_eq!(slug(" Design maps"), "design-maps");
    assert_eq!(
        slug("The constraint analysis and `REPORT`"),
        "the-constraint-analysis-and-report"
    );
    assert_eq!(slug("1. The model language"), "1-the-model-language");
}
