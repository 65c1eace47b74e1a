//! The shell commands of the guide and the README run, so that neither can
//! drift from the command line. Every `sh` and `console` block of
//! `README.md` and `docs/guide/*.md` is read (the contributing chapter
//! states the convention):
//!
//! - in a `sh` block each line is a command (a trailing `\` continues it,
//!   `#` starts a comment), and the `# ` lines after it are what it prints;
//!   in a `console` block a command follows `$ `, and the lines after it
//!   are what it prints;
//! - `cargo run --release -- ARGS` and `chaplygin ARGS` run this test
//!   build's binary with ARGS; a block's commands run one after the other,
//!   as a reader pastes them, in a scratch directory of the block's own
//!   (where `models`, `examples` and `tests` name the repository's, and a
//!   command reads what an earlier one of its block wrote), the blocks all
//!   at once; `cargo run --example NAME` must name an example
//!   (`tests/examples.rs` runs them); any other command must be one of
//!   [`NOT_RUN`], with the reason;
//! - what a command prints is its standard output, then its standard
//!   error: every line the guide shows must be among them, in order, where
//!   `...` in a line stands for any text (and a line `...` for lines left
//!   out), and a number for any number within `1e-9` of the largest
//!   number of the guide's line (the last digits of a result may depend on
//!   the build profile);
//! - a command shown printing `error:` must fail, any other must succeed
//!   and print no `warning:` it is not shown printing.

use crate::support::markdown::{blocks, guide_pages, root, shown};
use crate::support::printed::{Token, numbers, tokens};
use crate::support::scratch;
use std::path::Path;
use std::process::{Command, Output};
use tempfile::TempDir;

/// The commands of the guide no test runs, as written (continuations
/// joined, comments dropped, words single-spaced), and why.
const NOT_RUN: [(&str, &str); 6] = [
    ("cargo test --workspace", "the tests themselves"),
    (
        "bash .ci/run",
        "what CI runs: formatting, lints, every test, the docs and the Python package, minutes",
    ),
    (
        "CHAPLYGIN_SCREENSHOTS=write cargo test -p chaplygin-cli --test integration animation",
        "the tests themselves, writing the guide's screenshots",
    ),
    (
        "pip install ./python",
        "builds the Python package in release, minutes; `python/test.sh` runs its tests, \
         `python/tests/test_readme.py` the guide's Python",
    ),
    (
        "bash python/test.sh",
        "the Python package's tests, the last step of `.ci/run`",
    ),
    (
        "cargo run --release -- map bicycle --at dot(theta_r)=-v/rR --at dot(phi)=0 \
         --at dot(delta)=0 --speed v=0:10:0.05 --param c=0:0.16:0.01 \
         --param w=0.8:1.4:0.05 --out out/map",
        "221 designs at 201 speeds, two minutes in the test build; `cli/tests/design_map.rs` \
         checks maps of fewer",
    ),
];

/// A command of the guide and what the guide shows it printing.
struct Shown {
    /// Where it is: `file:line`.
    place: String,
    /// Its words, as the shell splits them.
    words: Vec<String>,
    /// The lines it prints, as the guide shows them.
    printed: Vec<String>,
}

/// The commands of each `sh` and `console` block of `page`, in order.
fn commands(page: &Path) -> Vec<Vec<Shown>> {
    let text = std::fs::read_to_string(page).expect("readable");
    let mut all = Vec::new();
    for block in blocks(&text) {
        let console = match block.info.as_str() {
            "sh" => false,
            "console" => true,
            _ => continue,
        };
        let mut found = Vec::new();
        let mut lines = block.lines.iter().enumerate();
        while let Some((index, line)) = lines.next() {
            let place = || format!("{}:{}", shown(page), block.line + 1 + index);
            match (console, line.strip_prefix("$ ")) {
                (true, Some(command)) => found.push(command_at(place(), command, &mut lines)),
                (false, _) if line.trim().is_empty() => {}
                (false, _) if !line.trim_start().starts_with('#') => {
                    found.push(command_at(place(), line, &mut lines));
                }
                _ => {
                    let output = if console {
                        line.as_str()
                    } else {
                        comment(line)
                    };
                    let last = found
                        .last_mut()
                        .unwrap_or_else(|| panic!("{}: no command", place()));
                    last.printed.push(output.to_string());
                }
            }
        }
        all.push(found);
    }
    all
}

/// The command `first` at `place`, continued on the next of `lines` while
/// it ends with `\`.
fn command_at<'a>(
    place: String,
    first: &str,
    lines: &mut impl Iterator<Item = (usize, &'a String)>,
) -> Shown {
    let mut joined = first.to_string();
    while joined.trim_end().ends_with('\\') {
        joined = joined.trim_end().trim_end_matches('\\').to_string();
        joined.push_str(lines.next().expect("a continued line").1);
    }
    let words = shlex::split(&joined).unwrap_or_else(|| panic!("{place}: unbalanced quotes"));
    Shown {
        place,
        words,
        printed: Vec::new(),
    }
}

/// The text of a `# ` line of a `sh` block.
fn comment(line: &str) -> &str {
    let line = line.trim_start().trim_start_matches('#');
    line.strip_prefix(' ').unwrap_or(line)
}

/// What a command of the guide is, for this test.
enum Kind<'a> {
    /// The binary, with these arguments.
    Binary(&'a [String]),
    /// An example, by name.
    Example(&'a str),
    /// One of [`NOT_RUN`].
    NotRun,
}

/// What `words` are, or why they are none of the commands the test knows.
fn kind(words: &[String]) -> Result<Kind<'_>, String> {
    let text: Vec<&str> = words.iter().map(String::as_str).collect();
    if NOT_RUN
        .iter()
        .any(|(command, _)| *command == text.join(" "))
    {
        return Ok(Kind::NotRun);
    }
    match text.as_slice() {
        ["cargo", "run", "--release", "--", ..] => Ok(Kind::Binary(&words[4..])),
        ["cargo", "run", "--", ..] => Ok(Kind::Binary(&words[3..])),
        ["chaplygin", ..] => Ok(Kind::Binary(&words[1..])),
        ["cargo", "run", "--example", name] | ["cargo", "run", "--release", "--example", name] => {
            Ok(Kind::Example(name))
        }
        _ => Err(format!(
            "`{}` is neither the binary (`cargo run --release -- ...`, `chaplygin ...`) nor \
             an example (`cargo run --example NAME`): run it in this test, or list it in \
             NOT_RUN with the reason",
            text.join(" ")
        )),
    }
}

/// Whether `name` is an example of the workspace: `examples/NAME.rs`, or
/// `examples/PACKAGE/examples/NAME.rs` of a package there.
fn is_example(name: &str) -> bool {
    let examples = root().join("examples");
    let file = format!("{name}.rs");
    examples.join(&file).is_file()
        || std::fs::read_dir(&examples)
            .expect("examples/")
            .any(|entry| {
                entry
                    .expect("an entry")
                    .path()
                    .join("examples")
                    .join(&file)
                    .is_file()
            })
}

/// The scratch directory of the block `index`, where `models`, `examples`
/// and `tests` are the repository's.
fn block_directory(index: usize) -> TempDir {
    let directory = scratch(&format!("guide-block-{index}"));
    for shared in ["models", "examples", "tests"] {
        std::os::unix::fs::symlink(root().join(shared), directory.path().join(shared))
            .expect("a link in the scratch directory");
    }
    directory
}

/// The binary run with `arguments` in `directory`.
fn run(directory: &Path, arguments: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .current_dir(directory)
        .output()
        .expect("the binary runs")
}

/// Whether the printed line `line` is the guide's `expected` (see the
/// module's documentation).
fn matches(expected: &str, line: &str) -> bool {
    let largest = numbers(expected)
        .into_iter()
        .map(f64::abs)
        .fold(0.0, f64::max);
    let tolerance = 1e-9 * largest;
    let same = |a: &Token, b: &Token| match (a, b) {
        (Token::Number(a), Token::Number(b)) => (a - b).abs() <= tolerance,
        _ => a == b,
    };
    let is_at = |pattern: &[Token], at: usize, printed: &[Token]| {
        printed.len() >= at + pattern.len()
            && pattern.iter().zip(&printed[at..]).all(|(a, b)| same(a, b))
    };
    let printed = tokens(line);
    let pieces: Vec<Vec<Token>> = expected.split("...").map(tokens).collect();
    let (first, last) = (&pieces[0], &pieces[pieces.len() - 1]);
    if !is_at(first, 0, &printed) {
        return false;
    }
    if pieces.len() == 1 {
        return first.len() == printed.len();
    }
    let mut at = first.len();
    for piece in &pieces[1..pieces.len() - 1] {
        match (at..=printed.len()).find(|&start| is_at(piece, start, &printed)) {
            Some(start) => at = start + piece.len(),
            None => return false,
        }
    }
    printed.len() >= at + last.len() && is_at(last, printed.len() - last.len(), &printed)
}

/// What is wrong with what the command `shown` printed, if anything.
fn judged(shown: &Shown, output: &Output) -> Result<(), String> {
    let (stdout, stderr) = (
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr),
    );
    let printed: Vec<&str> = stdout.lines().chain(stderr.lines()).collect();
    let shows = |start: &str| shown.printed.iter().any(|line| line.starts_with(start));
    if output.status.success() == shows("error:") {
        return Err(format!("unexpected {}", output.status));
    }
    if !shows("warning:") && stderr.lines().any(|line| line.starts_with("warning:")) {
        return Err("a warning it is not shown printing".into());
    }
    let mut rest = printed.iter();
    let shown_lines = (shown.printed.iter()).filter(|line| !["", "..."].contains(&line.trim()));
    for expected in shown_lines {
        if !rest.any(|line| matches(expected, line)) {
            return Err(format!("does not print `{expected}` (in order)"));
        }
    }
    Ok(())
}

/// The commands of `block` the binary runs, with their arguments; an
/// example must be the workspace's, and any other command one of
/// [`NOT_RUN`].
fn binary_runs(block: &[Shown]) -> Vec<(&Shown, &[String])> {
    let mut runs = Vec::new();
    for command in block {
        match kind(&command.words) {
            Ok(Kind::Binary(arguments)) => runs.push((command, arguments)),
            Ok(Kind::Example(name)) => {
                assert!(is_example(name), "{}: no example `{name}`", command.place);
            }
            Ok(Kind::NotRun) => {}
            Err(problem) => panic!("{}: {problem}", command.place),
        }
    }
    runs
}

/// What is wrong with the commands of the block `index`, run one after
/// the other in its scratch directory.
fn block_problems(index: usize, runs: &[(&Shown, &[String])]) -> Vec<String> {
    let directory = block_directory(index);
    (runs.iter())
        .filter_map(|&(command, arguments)| {
            let output = run(directory.path(), arguments);
            judged(command, &output).err().map(|problem| {
                format!(
                    "{}: {problem}\nstdout:\n{}\nstderr:\n{}",
                    command.place,
                    String::from_utf8_lossy(&output.stdout),
                    String::from_utf8_lossy(&output.stderr)
                )
            })
        })
        .collect()
}

/// The guide's blocks run all at once, each in a thread of its own (the
/// longest, a gait optimization, takes seconds unoptimized), and each
/// command judged by what it printed.
#[test]
fn the_guides_commands_run_and_print_what_it_shows() {
    let blocks: Vec<Vec<Shown>> = guide_pages()
        .iter()
        .flat_map(|page| commands(page))
        .collect();
    let runs: Vec<Vec<(&Shown, &[String])>> =
        blocks.iter().map(|block| binary_runs(block)).collect();
    assert!(
        runs.iter().map(Vec::len).sum::<usize>() >= 10,
        "the guide's commands are found"
    );
    let problems: Vec<String> = std::thread::scope(|scope| {
        let running: Vec<_> = (runs.iter().enumerate())
            .filter(|(_, block)| !block.is_empty())
            .map(|(index, block)| scope.spawn(move || block_problems(index, block)))
            .collect();
        (running.into_iter())
            .flat_map(|block| block.join().expect("the block's thread"))
            .collect()
    });
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

#[test]
fn printed_lines_match_with_ellipses_and_numbers_near() {
    let line = "net displacement per cycle: x = -0.8070292067978685, y = -1.0e-16, theta = 3e-17";
    assert!(matches(
        "net displacement per cycle: x = -0.8070292067978683, y = -2.7887442107287344e-16, theta = 9.093745721722168e-17",
        line
    ));
    assert!(!matches(
        "net displacement per cycle: x = -0.8070292, y = 0, theta = 0",
        line
    ));
    assert!(matches("net displacement ... x = ...", line));
    assert!(matches("... theta = 3e-17", line));
    assert!(!matches("... theta = 3e-17 and more", line));
    assert!(!matches("net displacement", line));
    assert!(matches(
        "t = 2.35: 118 steps of rk4 in ... s, engine jit; ...",
        "t = 2.35: 118 steps of rk4 in 0.310 s, engine jit; energy drift 8.451e0"
    ));
    assert_eq!(
        tokens("a1=-1.5+2e3*cos(1.0*t)"),
        [
            Token::Text('a'),
            Token::Text('1'),
            Token::Text('='),
            Token::Number(-1.5),
            Token::Text('+'),
            Token::Number(2e3),
            Token::Text('*'),
            Token::Text('c'),
            Token::Text('o'),
            Token::Text('s'),
            Token::Text('('),
            Token::Number(1.0),
            Token::Text('*'),
            Token::Text('t'),
            Token::Text(')'),
        ]
    );
}
