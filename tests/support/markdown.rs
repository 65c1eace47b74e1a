//! The Markdown files of the guide (`docs/`, an mdBook) and the
//! repository's front pages, read as the checks of `tests/guide*.rs` need
//! them: the files, their fenced code blocks, the text outside those
//! blocks, and its links (and those of the pages the book makes of them).

use std::path::{Path, PathBuf};

/// The repository's root: the folder of the workspace's `Cargo.lock`, the
/// package's own or the one above it (the command line's, `cli/`).
pub fn root() -> PathBuf {
    (Path::new(env!("CARGO_MANIFEST_DIR")).ancestors())
        .find(|folder| folder.join("Cargo.lock").is_file())
        .expect("the workspace's Cargo.lock")
        .to_path_buf()
}

/// The `.md` files of `dir` (relative to the root), sorted.
fn markdown_in(dir: &str) -> Vec<PathBuf> {
    let entries = std::fs::read_dir(root().join(dir)).expect("the guide's directory");
    let mut found: Vec<PathBuf> = entries
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    found.sort();
    found
}

/// The README and the chapters of `docs/guide/`: the pages a user follows
/// step by step.
pub fn guide_pages() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md")];
    files.extend(markdown_in("docs/guide"));
    files
}

/// Every Markdown file of the guide and the repository's front pages.
pub fn markdown_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = ["README.md", "BENCHMARKS.md", "CHANGELOG.md", "FUZZING.md"]
        .iter()
        .map(|name| root().join(name))
        .collect();
    files.extend(markdown_in("docs"));
    files.extend(markdown_in("docs/guide"));
    files
}

/// `path` relative to the root, for messages.
pub fn shown(path: &Path) -> String {
    let relative = path.strip_prefix(root()).unwrap_or(path);
    relative.display().to_string()
}

/// A fenced code block.
pub struct Block {
    /// The line of its opening fence, from 1.
    pub line: usize,
    /// Its info string (`sh`, `rust,ignore`, ...).
    pub info: String,
    /// Its lines.
    pub lines: Vec<String>,
}

/// Whether `line` opens or closes a fenced code block.
fn is_fence(line: &str) -> bool {
    line.trim_start().starts_with("```")
}

/// The fenced code blocks of `text`.
pub fn blocks(text: &str) -> Vec<Block> {
    let mut found = Vec::new();
    let mut open: Option<Block> = None;
    for (index, line) in text.lines().enumerate() {
        match (&mut open, is_fence(line)) {
            (None, true) => {
                open = Some(Block {
                    line: index + 1,
                    info: line.trim_start().trim_start_matches('`').trim().to_string(),
                    lines: Vec::new(),
                });
            }
            (Some(_), true) => found.extend(open.take()),
            (Some(block), false) => block.lines.push(line.to_string()),
            (None, false) => {}
        }
    }
    found
}

/// The text outside fenced code blocks (links in code are not links).
pub fn prose(text: &str) -> String {
    let mut inside = false;
    let mut kept = String::new();
    for line in text.lines() {
        if is_fence(line) {
            inside = !inside;
        } else if !inside {
            kept.push_str(line);
            kept.push('\n');
        }
    }
    kept
}

/// The targets of the Markdown links `[text](target)` of `text`.
pub fn link_targets(text: &str) -> Vec<String> {
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

/// Whether `target` leaves the document set: a URL or a mail address.
pub fn is_external(target: &str) -> bool {
    target.contains("://") || target.starts_with("mailto:")
}

/// What is wrong with the link `target` shown on the page `page`, if
/// anything: a relative path that names no file, or an anchor that is not
/// among the anchors of the file it names (`anchors` of a file: `None`
/// for a file without anchors, which any anchor then names).
pub fn broken(
    page: &Path,
    target: &str,
    anchors: impl Fn(&Path) -> Option<Vec<String>>,
) -> Option<String> {
    if is_external(target) {
        return None;
    }
    let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
    let file = match path {
        "" => page.to_path_buf(),
        _ => page.parent().expect("a directory").join(path),
    };
    if !file.exists() {
        return Some(format!("{target}: no file {}", file.display()));
    }
    let known = (!anchor.is_empty()).then(|| anchors(&file)).flatten();
    (known.is_some_and(|known| !known.iter().any(|a| a == anchor)))
        .then(|| format!("{target}: no anchor `{anchor}` in {}", file.display()))
}
