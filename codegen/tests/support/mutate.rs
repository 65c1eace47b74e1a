//! Structure-aware mutation of model texts, shared by the `expand` fuzz
//! target and its property test: a text is split into tokens, and each
//! mutation step `(operation, position, choice)` replaces a token with a word
//! of the models' vocabulary, inserts one, deletes a token, copies a run of
//! tokens elsewhere (which nests and repeats sub-expressions), or inserts a
//! raw byte.

use super::models;
use std::sync::OnceLock;

/// Words the models are made of, beyond those of the built-in texts.
const EXTRA_VOCABULARY: &[&str] = &[
    "sin",
    "cos",
    "tan",
    "sqrt",
    "exp",
    "ln",
    "asin",
    "acos",
    "atan",
    "atan2",
    "dot",
    "^",
    "*",
    "/",
    "+",
    "-",
    "(",
    ")",
    "[",
    "]",
    ",",
    ":",
    "=",
    "0",
    "1",
    "2",
    "-1",
    "0.5",
    "40",
    "1e300",
    "define",
    "mass_matrix",
    "distribution",
    "momentum_basis",
    "symmetry",
    "se2",
    "translation",
    "rotation",
    "inputs",
    "#[deny_holonomic]",
    "///",
    "//",
];

/// The built-in models' token lists and the vocabulary of the mutations.
struct Corpus {
    /// Each built-in model, tokenized.
    models: Vec<Vec<String>>,
    /// The words mutations insert.
    vocabulary: Vec<String>,
}

/// The corpus, built once.
fn corpus() -> &'static Corpus {
    static CORPUS: OnceLock<Corpus> = OnceLock::new();
    CORPUS.get_or_init(|| {
        let models: Vec<Vec<String>> = models::built_in()
            .into_iter()
            .map(|(_, text)| tokens(&text))
            .collect();
        let mut vocabulary: Vec<String> = models
            .iter()
            .flatten()
            .filter(|token| !token.trim().is_empty())
            .cloned()
            .chain(EXTRA_VOCABULARY.iter().map(|word| word.to_string()))
            .collect();
        vocabulary.sort();
        vocabulary.dedup();
        Corpus { models, vocabulary }
    })
}

/// Splits a text into words (identifiers and numbers), runs of white space
/// and single other characters; concatenating them gives the text back.
fn tokens(text: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let class = |c: char| {
        if c.is_alphanumeric() || c == '_' || c == '.' {
            0
        } else if c.is_whitespace() {
            1
        } else {
            2
        }
    };
    let mut previous = None;
    for c in text.chars() {
        let current = class(c);
        match out.last_mut() {
            Some(last) if previous == Some(current) && current != 2 => last.push(c),
            _ => out.push(c.to_string()),
        }
        previous = Some(current);
    }
    out
}

/// Applies the mutation steps of `data` (triples of bytes) to `tokens`.
fn mutate(tokens: &mut Vec<String>, vocabulary: &[String], data: &[u8]) {
    for step in data.chunks_exact(3) {
        let (operation, position, choice) = (step[0], usize::from(step[1]), usize::from(step[2]));
        let at = position * tokens.len() / 256;
        let word = vocabulary[choice % vocabulary.len()].clone();
        match operation % 6 {
            0 if at < tokens.len() => tokens[at] = word,
            1 => tokens.insert(at, format!(" {word} ")),
            2 if at < tokens.len() => {
                tokens.remove(at);
            }
            3 => {
                let end = (at + 1 + choice % 16).min(tokens.len());
                let run: Vec<String> = tokens[at..end].to_vec();
                let target = usize::from(operation) * tokens.len() / 256;
                tokens.splice(target..target, run);
            }
            4 => tokens.insert(at, char::from(step[2]).to_string()),
            _ => {}
        }
    }
}

/// A built-in model (picked by `pick`) with the mutations of `data` applied.
pub fn mutated_model(pick: u8, data: &[u8]) -> String {
    let corpus = corpus();
    let mut tokens = corpus.models[usize::from(pick) % corpus.models.len()].clone();
    mutate(&mut tokens, &corpus.vocabulary, data);
    tokens.concat()
}
