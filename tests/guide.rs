//! The guide (`docs/`, an mdBook: `docs/book.toml`, `docs/SUMMARY.md`) and
//! the README hold together: every chapter of `docs/guide/` is in the
//! summary, every relative link of the Markdown files names a file that
//! exists (and, with `#anchor`, a heading of that file), a link on a page
//! of the book names a file of the book's source (`docs/`), as the built
//! book holds nothing else, and every `{{#include FILE:ANCHOR}}` names a
//! file and an anchor in it, the links of the text it brings in checked
//! from the page that shows them. Their Rust examples run as doctests
//! (`src/lib.rs`), their Python examples in `python/tests/test_readme.py`,
//! their shell commands in `cli/tests/guide_commands.rs`; the book itself is
//! built in `tests/guide_book.rs`.

use crate::support::markdown::{
    broken, is_external, link_targets, markdown_files, prose, root, shown,
};
use std::path::{Path, PathBuf};

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

/// The anchors of the headings of `path`, if it is a Markdown file.
fn anchors(path: &Path) -> Option<Vec<String>> {
    if path.extension().is_none_or(|e| e != "md") {
        return None;
    }
    let text = std::fs::read_to_string(path).expect("a Markdown file");
    let headings = prose(&text)
        .lines()
        .filter(|line| line.starts_with('#'))
        .map(|line| slug(line.trim_start_matches('#')))
        .collect();
    Some(headings)
}

/// The book's source (`src` in `docs/book.toml`): the files mdBook renders
/// and copies into the book.
fn book_source() -> PathBuf {
    root().join("docs")
}

/// Whether `target`, a link that exists from the page `page`, leaves the
/// book where `page` is one of its pages: the built book holds the
/// book's source alone, so there the link would name nothing.
fn outside_the_book(page: &Path, target: &str) -> Option<String> {
    let path = target.split('#').next().unwrap_or_default();
    if is_external(target) || path.is_empty() || !page.starts_with(book_source()) {
        return None;
    }
    let file = std::fs::canonicalize(page.parent().expect("a directory").join(path)).ok()?;
    let source = std::fs::canonicalize(book_source()).expect("docs/");
    (!file.starts_with(&source)).then(|| {
        format!(
            "{target}: {} is outside the book's source, docs/, so the built book has no such \
             page (name the file as code, or link a page of docs/)",
            shown(&file)
        )
    })
}

/// An `{{#include FILE}}` or `{{#include FILE:ANCHOR}}` of a page.
struct Include {
    /// The file, resolved from the page's directory.
    file: PathBuf,
    /// The anchor, empty for the whole file.
    anchor: String,
}

/// The includes of the page `page`, whose text is `text`.
fn includes(page: &Path, text: &str) -> Vec<Include> {
    (text.split("{{#include ").skip(1))
        .map(|directive| {
            let directive = &directive[..directive.find("}}").expect("a closed include")];
            let (path, anchor) = directive.split_once(':').unwrap_or((directive, ""));
            Include {
                file: page.parent().expect("a directory").join(path.trim()),
                anchor: anchor.trim().to_string(),
            }
        })
        .collect()
}

/// The text `include` brings into the page `page`: the lines between its
/// anchor's `ANCHOR:` and `ANCHOR_END:` marks, or the whole file.
fn included_text(page: &Path, include: &Include) -> String {
    let body = std::fs::read_to_string(&include.file)
        .unwrap_or_else(|_| panic!("{}: no file {}", shown(page), include.file.display()));
    if include.anchor.is_empty() {
        return body;
    }
    let mark = |kind: &str| {
        let line = format!("{kind}: {}", include.anchor);
        body.lines()
            .position(|l| l.contains(&line))
            .unwrap_or_else(|| panic!("{}: no `{line}` in {}", shown(page), shown(&include.file)))
    };
    let (start, end) = (mark("ANCHOR"), mark("ANCHOR_END"));
    assert!(
        start < end,
        "{}: the anchor `{}` ends before it starts",
        shown(page),
        include.anchor
    );
    body.lines().collect::<Vec<_>>()[start + 1..end].join("\n")
}

/// The links each page shows, with the page: those of its own text and
/// those of the text its includes bring in, which resolve from the page.
fn shown_links() -> Vec<(PathBuf, String)> {
    let mut links = Vec::new();
    for page in markdown_files() {
        let text = std::fs::read_to_string(&page).expect("readable");
        let mut shown_text = prose(&text);
        for include in includes(&page, &text) {
            shown_text.push_str(&prose(&included_text(&page, &include)));
        }
        links.extend(
            link_targets(&shown_text)
                .into_iter()
                .map(|t| (page.clone(), t)),
        );
    }
    links
}

#[test]
fn every_relative_link_names_a_file_and_heading_that_exist() {
    let problems: Vec<String> = (shown_links().iter())
        .filter_map(|(page, target)| {
            let problem = broken(page, target, anchors).or_else(|| outside_the_book(page, target));
            problem.map(|problem| format!("{}: {problem}", shown(page)))
        })
        .collect();
    assert!(
        problems.is_empty(),
        "broken links:\n{}",
        problems.join("\n")
    );
}

#[test]
fn every_include_names_a_file_and_an_anchor_in_it() {
    let mut count = 0;
    for page in markdown_files() {
        let text = std::fs::read_to_string(&page).expect("readable");
        for include in includes(&page, &text) {
            assert!(!included_text(&page, &include).trim().is_empty());
            count += 1;
        }
    }
    assert!(
        count >= 2,
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
