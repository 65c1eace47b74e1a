//! The guide built as a book: `mdbook build docs` into a scratch directory
//! reports no error or warning (mdBook reports a missing include on
//! standard error and still exits 0), and every link of a page's text (its
//! `<main>`; the rest is mdBook's own) names a file of the built book and,
//! with `#anchor`, an element of that page with that id. mdBook runs where
//! it is on `PATH`; without it the test says it skipped, and fails where
//! `CHAPLYGIN_BOOK_TESTS=require` (as `.ci/run` sets it, after installing
//! mdBook when missing with `.ci/install-mdbook`).

use crate::support::markdown::{broken, root};
use crate::support::{scratch, tool};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The `.html` files under `dir`.
fn pages(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).expect("a directory of the book") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            found.extend(pages(&path));
        } else if path.extension().is_some_and(|e| e == "html") {
            found.push(path);
        }
    }
    found
}

/// The `href` and `src` values of the `<main>` of the page `html` (none
/// for mdBook's own pages without one, such as its table of contents).
fn main_links(html: &str) -> Vec<String> {
    let Some(start) = html.find("<main>") else {
        return Vec::new();
    };
    let end = html[start..]
        .find("</main>")
        .map_or(html.len(), |end| start + end);
    let mut links = Vec::new();
    for attribute in ["href=\"", "src=\""] {
        for piece in html[start..end].split(attribute).skip(1) {
            links.push(piece[..piece.find('"').expect("a closed attribute")].to_string());
        }
    }
    links
}

/// The ids of the elements of `path`, if it is a page.
fn ids(path: &Path) -> Option<Vec<String>> {
    if path.extension().is_none_or(|e| e != "html") {
        return None;
    }
    let html = std::fs::read_to_string(path).expect("a page");
    let values = html.split(" id=\"").skip(1);
    Some(
        values
            .map(|v| v[..v.find('"').expect("a closed id")].to_string())
            .collect(),
    )
}

/// Whether the line `line` of mdBook's log is an error or a warning: its
/// level, among its first words, is `ERROR` or `WARN` (`[ERROR]` after
/// the time in mdBook 0.4, first in 0.5).
fn is_error_or_warning(line: &str) -> bool {
    (line.split_whitespace().take(3))
        .any(|word| ["ERROR", "WARN"].contains(&word.trim_matches(['[', ']'])))
}

#[test]
fn the_book_builds_without_a_problem_and_its_links_resolve() {
    let Some(mdbook) = tool(
        "mdbook",
        "CHAPLYGIN_BOOK_TESTS",
        "`cargo install mdbook`, or `bash .ci/install-mdbook` on Debian",
    ) else {
        return;
    };
    let scratch_directory = scratch("book");
    let book = scratch_directory.path();
    let output = Command::new(mdbook)
        .args(["build", "docs", "--dest-dir"])
        .arg(book)
        .current_dir(root())
        .output()
        .expect("mdbook runs");
    let log = String::from_utf8_lossy(&output.stderr).into_owned()
        + &String::from_utf8_lossy(&output.stdout);
    let reported = log.lines().any(is_error_or_warning);
    assert!(output.status.success() && !reported, "{log}");
    let mut problems = Vec::new();
    let built = pages(book);
    assert!(built.len() > 12, "a page per chapter in {}", book.display());
    for page in &built {
        let html = std::fs::read_to_string(page).expect("a page");
        for target in main_links(&html) {
            if let Some(problem) = broken(page, &target, ids) {
                let shown = page
                    .strip_prefix(book)
                    .unwrap_or(page)
                    .display()
                    .to_string();
                problems.push(format!("{shown}: {problem}"));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "broken links in the book:\n{}",
        problems.join("\n")
    );
}
