//! The build-script door: `.model` files turned into Rust source in `OUT_DIR`.
//!
//! ```no_run
//! // build.rs
//! chaplygin_codegen::Builder::new()
//!     .model_file("models/sleigh.model")
//!     .write_to_out_dir()?;
//! # Ok::<(), chaplygin_codegen::BuildError>(())
//! ```
//!
//! and in the crate, `include!(concat!(env!("OUT_DIR"), "/sleigh.rs"));`.
//! Errors carry the file, line and column of the offending token.

use crate::diagnostic::Diagnostics;
use crate::sym::Budget;
use std::path::{Path, PathBuf};

/// Reads `.model` files and writes the generated Rust next to the build's output.
#[derive(Clone, Debug, Default)]
pub struct Builder {
    files: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
}

/// Why the build-script door failed.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The failure.
        source: std::io::Error,
    },
    /// `OUT_DIR` is not set (the builder runs outside a build script) and no
    /// output directory was given.
    #[error("OUT_DIR is not set: call Builder::out_dir or run from a build script")]
    NoOutDir,
    /// The model is rejected; one `file:line:col: error: message` line per problem.
    #[error("{rendered}")]
    Model {
        /// The file.
        path: PathBuf,
        /// The rendered diagnostics.
        rendered: String,
    },
}

impl Builder {
    /// A builder with no files.
    pub fn new() -> Builder {
        Builder::default()
    }

    /// Adds a `.model` file (relative paths are relative to the crate root,
    /// where build scripts run).
    pub fn model_file(mut self, path: impl AsRef<Path>) -> Builder {
        self.files.push(path.as_ref().to_path_buf());
        self
    }

    /// Writes into `directory` instead of `OUT_DIR`.
    pub fn out_dir(mut self, directory: impl AsRef<Path>) -> Builder {
        self.out_dir = Some(directory.as_ref().to_path_buf());
        self
    }

    /// Generates `<stem>.rs` for every file, and tells cargo to rerun the
    /// build script when a model file changes. Returns the written paths.
    pub fn write_to_out_dir(self) -> Result<Vec<PathBuf>, BuildError> {
        let out_dir = match self.out_dir {
            Some(directory) => directory,
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        let mut written = Vec::with_capacity(self.files.len());
        for file in &self.files {
            println!("cargo:rerun-if-changed={}", file.display());
            let source = std::fs::read_to_string(file).map_err(|source| BuildError::Io {
                path: file.clone(),
                source,
            })?;
            let code = generate(&source).map_err(|diagnostics| BuildError::Model {
                path: file.clone(),
                rendered: diagnostics.render(&file.display().to_string()),
            })?;
            let stem = file.file_stem().unwrap_or(file.as_os_str());
            let target = out_dir.join(stem).with_extension("rs");
            std::fs::write(&target, code).map_err(|source| BuildError::Io {
                path: target.clone(),
                source,
            })?;
            written.push(target);
        }
        Ok(written)
    }
}

/// The Rust source generated for the text of a `.model` file, within the
/// default derivation budget ([`crate::sym::budget`]): the items
/// `chaplygin::model!` expands the same text to, formatted.
pub fn generate(source: &str) -> Result<String, Diagnostics> {
    generate_within(source, Budget::default())
}

/// [`generate`] charging the derivation to `budget`, which afterwards tells
/// how much of it the model used.
pub fn generate_within(source: &str, budget: Budget) -> Result<String, Diagnostics> {
    let items = crate::compile_within(&crate::syntax::parse_str(source)?, budget)?;
    Ok(formatted(items))
}

/// Items as Rust source text, formatted by `prettyplease` (as
/// `cargo expand` shows a macro's expansion).
pub fn formatted(items: proc_macro2::TokenStream) -> String {
    match syn::parse2::<syn::File>(items.clone()) {
        Ok(file) => prettyplease::unparse(&file),
        Err(_) => items.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::{formatted, generate};
    use proc_macro2::TokenStream;

    /// The macro door (`model!`'s tokens) and the build-script door (a
    /// file's text) compile one model to the same Rust.
    #[test]
    fn both_doors_emit_the_same_items() {
        let source = crate::fixtures::SNAKEBOARD;
        let tokens: TokenStream = source.parse().expect("the model text lexes");
        let expanded = formatted(crate::expand(tokens));
        assert_eq!(expanded, generate(source).expect("generates"));
        assert!(expanded.contains("pub fn reduced_rhs("), "{expanded}");
    }
}
