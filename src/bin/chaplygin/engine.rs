//! Which engine runs a model read from its text (a `.model` file, or a
//! built-in the command line does not compile with rustc): native code
//! compiled from the model's programs at run time (`jit`, the default) or
//! the IR interpreter (`interpret`, the reference both are tested against).

use crate::derive::Rejected;
use chaplygin_codegen::interpret::InterpretedModel;

/// `--engine`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EngineChoice {
    /// Native code compiled at run time with Cranelift; the interpreter
    /// where Cranelift does not support the host (with a note).
    Jit,
    /// The IR interpreter.
    Interpret,
}

/// The model of `text` (errors reported against `path`), its programs run
/// by `engine`.
///
/// # Errors
/// The model's diagnostics.
pub fn load(path: &str, text: &str, engine: EngineChoice) -> Result<InterpretedModel, Rejected> {
    let mut model = InterpretedModel::from_source(text)
        .map_err(|diagnostics| Rejected(diagnostics.render(path).trim_end().to_string()))?;
    if engine == EngineChoice::Jit
        && let Err(error) = chaplygin::jit::compile(&mut model)
    {
        eprintln!("note: {error}; running the interpreter");
    }
    Ok(model)
}
