//! No folder of the workspace's crates ([`CRATE_SOURCES`]), at any depth, has an import
//! circle between its direct children: a child (a file, or a subfolder with
//! everything in it) names a sibling by `super::b`, `crate::path::to::b` or
//! an item its parent imports from `b`, and `b` names it back, directly or
//! round a longer loop. Test code is left out: `#[cfg(test)]` items and the
//! files `tests.rs`, `proptests.rs` and `fixtures.rs`. Comments and string
//! literals are not read, so a documentation link is not an import.
//!
//! A circle that remains is listed in [`KNOWN_CIRCLES`]: a circle not in
//! the list fails the test, and so does a listed circle that is gone, so
//! the list can only shrink.

use crate::support::scratch;
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use tempfile::TempDir;

/// The circles that remain, each a folder and the exact set of its
/// children in the loop (`name.rs`, or `name/` for a folder with a
/// `mod.rs`): none.
const KNOWN_CIRCLES: &[(&str, &[&str])] = &[];

/// The source folders of the workspace's crates: the library `chaplygin`,
/// its command line, the compiler and its macros, the runtime, the JIT,
/// the models and the Python module.
const CRATE_SOURCES: [&str; 8] = [
    "src",
    "cli/src",
    "codegen/src",
    "codegen/macros/src",
    "runtime/src",
    "jit/src",
    "models/src",
    "python/src",
];

/// Files that are test code whatever module declares them.
const TEST_FILES: [&str; 3] = ["tests.rs", "proptests.rs", "fixtures.rs"];

/// The circles of the crates are exactly the known ones.
#[test]
fn no_folder_has_an_import_circle_between_its_children() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = BTreeSet::new();
    for crate_source in CRATE_SOURCES {
        for circle in circles(&root.join(crate_source)) {
            found.insert(circle.named_in(root, crate_source));
        }
    }
    let known: BTreeSet<(String, Vec<String>)> = KNOWN_CIRCLES
        .iter()
        .map(|(folder, children)| {
            let children = children.iter().map(ToString::to_string).collect();
            (folder.to_string(), children)
        })
        .collect();
    let new: Vec<String> = found.difference(&known).map(describe).collect();
    let gone: Vec<String> = known.difference(&found).map(describe).collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "import circles not in KNOWN_CIRCLES:\n{}\nlisted circles that no longer exist \
         (remove them from KNOWN_CIRCLES):\n{}",
        new.join("\n"),
        gone.join("\n")
    );
}

/// A loop of three files through `crate::` and grouped `super::` paths is
/// found; a folder whose only loop runs through a comment, a string or test
/// code has none.
#[test]
fn a_circle_between_siblings_is_found_and_named() {
    let tree = SyntheticTree::new("circle");
    tree.write("lib.rs", "mod a;\nmod b;\nmod c;\nmod outer;\n");
    tree.write("a.rs", "use crate::b::Bee;\npub struct Ay;\n");
    tree.write("b.rs", "use super::{c::{self, Sea}};\npub struct Bee;\n");
    tree.write("c.rs", "pub struct Sea(crate::a::Ay);\n");
    tree.write(
        "outer/mod.rs",
        "mod inner;\nmod other;\npub use other::Thing;\n",
    );
    tree.write(
        "outer/inner.rs",
        "use super::Thing;\n// use super::other::x (a comment, not an import)\n",
    );
    tree.write(
        "outer/other.rs",
        "pub struct Thing;\nconst S: &str = \"super::inner::Y\";\n#[cfg(test)]\nmod tests {\n    use super::super::inner;\n}\n",
    );
    let found: Vec<(String, Vec<String>)> = circles(tree.root())
        .into_iter()
        .map(|circle| circle.named_in(tree.root(), "."))
        .collect();
    assert_eq!(
        found,
        [(
            ".".to_string(),
            vec!["a.rs".into(), "b.rs".into(), "c.rs".into()]
        )]
    );
}

/// A child that names a sibling's item through its parent's renamed import
/// depends on that sibling.
#[test]
fn a_circle_through_a_parents_import_is_found() {
    let tree = SyntheticTree::new("reexport");
    tree.write("lib.rs", "pub mod outer;\n");
    tree.write(
        "outer/mod.rs",
        "mod left;\nmod right;\nuse right::Right as Renamed;\n",
    );
    tree.write("outer/left.rs", "pub fn left(_: super::Renamed) {}\n");
    tree.write(
        "outer/right.rs",
        "pub struct Right;\nfn back() { super::left::left(Right) }\n",
    );
    let found: Vec<(String, Vec<String>)> = circles(tree.root())
        .into_iter()
        .map(|circle| circle.named_in(tree.root(), "."))
        .collect();
    assert_eq!(
        found,
        [(
            "./outer".to_string(),
            vec!["left.rs".into(), "right.rs".into()]
        )]
    );
}

/// A circle: a folder (its module path) and its children in the loop.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Circle {
    folder: Vec<String>,
    children: Vec<String>,
}

impl Circle {
    /// The folder as a path under `crate_source` (itself under `root`), and
    /// the children as the files they are (`name.rs`, or `name/` for a
    /// folder with a `mod.rs`).
    fn named_in(&self, root: &Path, crate_source: &str) -> (String, Vec<String>) {
        let folder = std::iter::once(crate_source.to_string())
            .chain(self.folder.iter().cloned())
            .collect::<Vec<_>>()
            .join("/");
        let children = self
            .children
            .iter()
            .map(|child| {
                if root.join(&folder).join(format!("{child}.rs")).exists() {
                    format!("{child}.rs")
                } else {
                    format!("{child}/")
                }
            })
            .collect();
        (folder, children)
    }
}

/// A circle as the test reports it.
fn describe((folder, children): &(String, Vec<String>)) -> String {
    format!("  {folder}: {}", children.join(" <-> "))
}

/// Every import circle between the children of a folder of the crate whose
/// sources are under `source`.
fn circles(source: &Path) -> Vec<Circle> {
    let modules = modules(source);
    let children = children_by_folder(&modules);
    let imports: BTreeMap<&[String], BTreeMap<String, String>> = modules
        .iter()
        .filter(|module| children.contains_key(module.path.as_slice()))
        .map(|module| {
            (
                module.path.as_slice(),
                imports_of_children(module, &children),
            )
        })
        .collect();
    let mut edges: BTreeMap<Vec<String>, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for module in &modules {
        for target in &module.references {
            if let Some((folder, from, to)) =
                sibling_edge(&module.path, target, &children, &imports)
            {
                eprintln!(
                    "EDGE {folder:?} {from} -> {to} via {target:?} in {:?}",
                    module.path
                );
                edges
                    .entry(folder)
                    .or_default()
                    .entry(from)
                    .or_default()
                    .insert(to);
            }
        }
    }
    edges
        .into_iter()
        .flat_map(|(folder, graph)| {
            strongly_connected(&graph)
                .into_iter()
                .map(move |children| Circle {
                    folder: folder.clone(),
                    children,
                })
        })
        .collect()
}

/// A module of the crate read from its file.
struct Module {
    /// Its path from the crate root (empty for the root).
    path: Vec<String>,
    /// The tokens of its code, test items, comments and literals removed.
    tokens: Vec<String>,
    /// Every module path or item path its code names, resolved from the
    /// crate root.
    references: Vec<Vec<String>>,
    /// Its child modules declared `#[cfg(test)] mod name;`.
    test_children: Vec<String>,
}

/// The crate's modules, test code left out.
fn modules(source: &Path) -> Vec<Module> {
    let mut files = Vec::new();
    rust_files(source, &mut files);
    let mut modules: Vec<Module> = files
        .iter()
        .filter(|file| !TEST_FILES.iter().any(|name| file.ends_with(name)))
        .map(|file| read_module(source, file))
        .collect();
    let test_modules: Vec<Vec<String>> = modules
        .iter()
        .flat_map(|module| {
            module
                .test_children
                .iter()
                .map(|name| child_path(&module.path, name))
        })
        .collect();
    modules.retain(|module| {
        !test_modules
            .iter()
            .any(|test| module.path.starts_with(test))
    });
    modules
}

/// `path` extended by one segment.
fn child_path(path: &[String], name: &str) -> Vec<String> {
    let mut child = path.to_vec();
    child.push(name.to_string());
    child
}

/// Every `.rs` file under `folder`.
fn rust_files(folder: &Path, files: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = fs::read_dir(folder)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", folder.display()))
        .map(|entry| entry.expect("a readable folder entry").path())
        .collect();
    entries.sort();
    for entry in entries {
        if entry.is_dir() {
            rust_files(&entry, files);
        } else if entry.extension().is_some_and(|e| e == "rs") {
            files.push(entry);
        }
    }
}

/// The module a file holds, with what its code names.
fn read_module(source: &Path, file: &Path) -> Module {
    let relative = file.strip_prefix(source).expect("a file under the source");
    let mut path: Vec<String> = relative
        .iter()
        .map(|segment| {
            segment
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_string()
        })
        .collect();
    if matches!(path.last().map(String::as_str), Some("mod" | "lib")) {
        path.pop();
    }
    let text = fs::read_to_string(file).expect("a readable source file");
    let all_tokens = tokens(&text);
    let test_children = test_module_names(&all_tokens);
    let tokens = without_test_items(&all_tokens);
    let references = references(&path, &tokens);
    Module {
        path,
        tokens,
        references,
        test_children,
    }
}

/// The names of the modules declared `#[cfg(test)] mod name;`.
fn test_module_names(tokens: &[String]) -> Vec<String> {
    (0..tokens.len())
        .filter(|&i| is_cfg_test(&tokens[i..]))
        .filter_map(|i| {
            let item = &tokens[i + CFG_TEST.len()..];
            let end = item.iter().position(|t| t == ";" || t == "{")?;
            let at = item[..end].iter().position(|t| t == "mod")?;
            (at + 2 == end && item[end] == ";").then(|| item[at + 1].clone())
        })
        .collect()
}

/// The tokens of the attribute `#[cfg(test)]`.
const CFG_TEST: [&str; 7] = ["#", "[", "cfg", "(", "test", ")", "]"];

/// Whether the tokens start with `#[cfg(test)]`.
fn is_cfg_test(tokens: &[String]) -> bool {
    tokens.len() >= CFG_TEST.len() && tokens.iter().zip(CFG_TEST).all(|(t, c)| t == c)
}

/// The tokens without the items marked `#[cfg(test)]`: each ends at its
/// first `;` outside braces or at the brace closing its first `{`.
fn without_test_items(tokens: &[String]) -> Vec<String> {
    let mut kept = Vec::with_capacity(tokens.len());
    let mut i = 0;
    while i < tokens.len() {
        if !is_cfg_test(&tokens[i..]) {
            kept.push(tokens[i].clone());
            i += 1;
            continue;
        }
        i += CFG_TEST.len();
        let mut depth = 0usize;
        while i < tokens.len() {
            let token = tokens[i].as_str();
            i += 1;
            match token {
                "{" => depth += 1,
                "}" if depth == 1 => break,
                "}" => depth = depth.saturating_sub(1),
                ";" if depth == 0 => break,
                _ => {}
            }
        }
    }
    kept
}

/// The tokens of Rust code: identifiers and numbers, `::`, and single
/// punctuation; comments, string and character literals and lifetimes
/// dropped.
fn tokens(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let rest = &chars[i..];
        if rest.starts_with(&['/', '/']) {
            i += rest.iter().position(|&c| c == '\n').unwrap_or(rest.len());
        } else if rest.starts_with(&['/', '*']) {
            i += block_comment_length(rest);
        } else if let Some(length) = string_length(rest) {
            i += length;
        } else if c == '\'' {
            i += quote_length(rest);
        } else if c.is_alphanumeric() || c == '_' {
            let length = rest
                .iter()
                .position(|&c| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            tokens.push(rest[..length].iter().collect());
            i += length;
        } else if rest.starts_with(&[':', ':']) {
            tokens.push("::".to_string());
            i += 2;
        } else {
            if !c.is_whitespace() {
                tokens.push(c.to_string());
            }
            i += 1;
        }
    }
    tokens
}

/// The length of a (nested) block comment at the start of `text`.
fn block_comment_length(text: &[char]) -> usize {
    let mut depth = 0;
    let mut i = 0;
    while i < text.len() {
        if text[i..].starts_with(&['/', '*']) {
            depth += 1;
            i += 2;
        } else if text[i..].starts_with(&['*', '/']) {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    text.len()
}

/// The length of a string literal (`"..."`, `b"..."`, `r#"..."#`, ...) at
/// the start of `text`, if one starts there.
fn string_length(text: &[char]) -> Option<usize> {
    let prefix = text
        .iter()
        .position(|&c| !matches!(c, 'b' | 'c' | 'r'))
        .unwrap_or(text.len());
    let raw = text[..prefix].contains(&'r');
    let hashes = text[prefix..].iter().take_while(|&&c| c == '#').count();
    let open = prefix + hashes;
    if prefix > 2 || text.get(open) != Some(&'"') || (hashes > 0 && !raw) {
        return None;
    }
    let mut i = open + 1;
    while i < text.len() {
        match text[i] {
            '\\' if !raw => i += 2,
            '"' if text[i + 1..]
                .iter()
                .take(hashes)
                .filter(|&&c| c == '#')
                .count()
                == hashes =>
            {
                return Some(i + 1 + hashes);
            }
            _ => i += 1,
        }
    }
    Some(text.len())
}

/// The length of a character literal, or of a lifetime's quote, at the
/// start of `text`.
fn quote_length(text: &[char]) -> usize {
    match text.get(1) {
        Some('\\') => 2 + text[2..].iter().position(|&c| c == '\'').unwrap_or(0) + 1,
        Some(_) if text.get(2) == Some(&'\'') => 3,
        _ => 1,
    }
}

/// The paths a module's tokens name that start at `crate` or `super`,
/// resolved from the crate root; `super` inside an inline `mod name { .. }`
/// is relative to it.
fn references(module: &[String], tokens: &[String]) -> Vec<Vec<String>> {
    let mut references = Vec::new();
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    for (i, token) in tokens.iter().enumerate() {
        match token.as_str() {
            "{" => {
                depth += 1;
                if i >= 2 && tokens[i - 2] == "mod" {
                    inline.push((tokens[i - 1].clone(), depth));
                }
            }
            "}" => {
                if inline.last().is_some_and(|&(_, at)| at == depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
            }
            "crate" | "super" if starts_path(tokens, i) => {
                let here: Vec<String> = module
                    .iter()
                    .cloned()
                    .chain(inline.iter().map(|(name, _)| name.clone()))
                    .collect();
                for (path, _) in use_tree(&tokens[i..]).0 {
                    references.extend(resolve(&here, &path));
                }
            }
            _ => {}
        }
    }
    references
}

/// Whether the path starting at token `i` is a path (followed by `::`),
/// and not the continuation of another path or a visibility `pub(in ..)`.
fn starts_path(tokens: &[String], i: usize) -> bool {
    let previous = i.checked_sub(1).map(|p| tokens[p].as_str());
    tokens.get(i + 1).is_some_and(|t| t == "::") && !matches!(previous, Some("::" | "in"))
}

/// A leaf of a use tree: its path, and the name it is brought in as when
/// renamed (`path as name`).
type Leaf = (Vec<String>, Option<String>);

/// The leaves of a use tree or path at the start of `tokens`
/// (`a::b::{c as d, e::{self, f}}`), and how many tokens it took.
fn use_tree(tokens: &[String]) -> (Vec<Leaf>, usize) {
    let mut prefix = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let token = tokens[i].as_str();
        if token == "{" {
            let (leaves, used) = use_group(&tokens[i..]);
            let leaves = leaves
                .into_iter()
                .map(|(path, alias)| ([prefix.clone(), path].concat(), alias))
                .collect();
            return (leaves, i + used);
        }
        if !is_identifier(token) {
            break;
        }
        if token != "self" {
            prefix.push(token.to_string());
        }
        i += 1;
        if tokens.get(i).is_some_and(|t| t == "::") {
            i += 1;
        } else {
            break;
        }
    }
    let alias = tokens
        .get(i)
        .filter(|t| *t == "as")
        .and_then(|_| tokens.get(i + 1).cloned());
    let used = if alias.is_some() { i + 2 } else { i };
    (vec![(prefix, alias)], used)
}

/// The leaves of a group `{a, b::c, ..}` at the start of `tokens`, and how
/// many tokens it took.
fn use_group(tokens: &[String]) -> (Vec<Leaf>, usize) {
    let mut leaves = Vec::new();
    let mut i = 1;
    while i < tokens.len() && tokens[i] != "}" {
        let (branch, length) = use_tree(&tokens[i..]);
        leaves.extend(branch);
        i += length.max(1);
        if tokens.get(i).is_some_and(|t| t == ",") {
            i += 1;
        }
    }
    (leaves, i + 1)
}

/// Whether a token is an identifier or keyword.
fn is_identifier(token: &str) -> bool {
    token
        .chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// A path starting at `crate` or `super`, seen from module `here`, as a
/// path from the crate root.
fn resolve(here: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut resolved = match path.first()?.as_str() {
        "crate" => Vec::new(),
        _ => here.to_vec(),
    };
    let mut segments = path.iter().peekable();
    if path[0] == "crate" {
        segments.next();
    }
    while segments.next_if(|s| *s == "super").is_some() {
        resolved.pop()?;
    }
    resolved.extend(segments.cloned());
    Some(resolved)
}

/// For each folder module, its child modules' names.
fn children_by_folder(modules: &[Module]) -> BTreeMap<&[String], BTreeSet<String>> {
    let mut children: BTreeMap<&[String], BTreeSet<String>> = BTreeMap::new();
    for module in modules {
        if let Some((name, parent)) = module.path.split_last() {
            children.entry(parent).or_default().insert(name.clone());
        }
    }
    children
}

/// The names a folder module's `use` items bring in from its children, with
/// the child each comes from (children see their parent's imports as
/// `super::name`).
fn imports_of_children(
    module: &Module,
    children: &BTreeMap<&[String], BTreeSet<String>>,
) -> BTreeMap<String, String> {
    let own = &children[module.path.as_slice()];
    let tokens = &module.tokens;
    let mut imports = BTreeMap::new();
    for (i, token) in tokens.iter().enumerate() {
        if token != "use" {
            continue;
        }
        for (path, alias) in use_tree(&tokens[i + 1..]).0 {
            let (Some(first), Some(last)) = (path.first(), path.last()) else {
                continue;
            };
            if own.contains(first) {
                imports.insert(alias.unwrap_or_else(|| last.clone()), first.clone());
            }
        }
    }
    imports
}

/// The edge a reference from module `from` to `target` makes between two
/// children of one folder: the folder, the child holding `from`, and the
/// child `target` enters (directly, or through an import of the folder's
/// module).
fn sibling_edge(
    from: &[String],
    target: &[String],
    children: &BTreeMap<&[String], BTreeSet<String>>,
    imports: &BTreeMap<&[String], BTreeMap<String, String>>,
) -> Option<(Vec<String>, String, String)> {
    let common = from.iter().zip(target).take_while(|(a, b)| a == b).count();
    let folder = &from[..common];
    let (source, entered) = (from.get(common)?, target.get(common)?);
    let sibling = if children.get(folder)?.contains(entered) {
        entered.clone()
    } else {
        imports.get(folder)?.get(entered)?.clone()
    };
    (sibling != *source).then(|| (folder.to_vec(), source.clone(), sibling))
}

/// The strongly connected components of more than one node, each sorted.
fn strongly_connected(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |start: &String| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![start.clone()];
        while let Some(node) = stack.pop() {
            for next in graph.get(&node).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|node| (node, reach(node))).collect();
    let mut components: BTreeSet<Vec<String>> = BTreeSet::new();
    for (node, from_node) in &reachable {
        let component: Vec<String> = from_node
            .iter()
            .filter(|other| {
                reachable
                    .get(other)
                    .is_some_and(|back| back.contains(*node))
            })
            .cloned()
            .collect();
        if component.len() > 1 {
            components.insert(component);
        }
    }
    components.into_iter().collect()
}

/// A crate's source tree written in a scratch directory, removed when
/// dropped.
struct SyntheticTree {
    directory: TempDir,
}

impl SyntheticTree {
    /// An empty tree in a scratch directory named after `name`.
    fn new(name: &str) -> SyntheticTree {
        SyntheticTree {
            directory: scratch(&format!("import-circles-{name}")),
        }
    }

    /// The folder the tree's files are written in.
    fn root(&self) -> &Path {
        self.directory.path()
    }

    /// Writes `text` into the tree's `file`, a path relative to its root.
    fn write(&self, file: &str, text: &str) {
        let path = self.root().join(file);
        fs::create_dir_all(path.parent().expect("a file in a folder"))
            .expect("a writable temp dir");
        fs::write(path, text).expect("a writable temp file");
    }
}
