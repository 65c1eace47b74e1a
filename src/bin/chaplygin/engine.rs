//! Which engine runs a model read from its text (a `.model` file, or a
//! built-in the command line does not compile with rustc): native code
//! compiled from the model's programs at run time (`jit`, the default) or
//! the IR interpreter (`interpret`, the reference both are tested against).

use crate::derive::Rejected;
use chaplygin::jit::JitError;
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
    load_with(path, text, engine, chaplygin::jit::compile)
}

/// [`load`], the JIT being `compile`: where it fails (Cranelift does not
/// support the host), a note on standard error and the interpreter.
fn load_with(
    path: &str,
    text: &str,
    engine: EngineChoice,
    compile: impl FnOnce(&mut InterpretedModel) -> Result<(), JitError>,
) -> Result<InterpretedModel, Rejected> {
    let mut model = InterpretedModel::from_source(text)
        .map_err(|diagnostics| Rejected(diagnostics.render(path).trim_end().to_string()))?;
    if engine == EngineChoice::Jit
        && let Err(error) = compile(&mut model)
    {
        eprintln!("note: {error}; running the interpreter");
    }
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::{EngineChoice, load, load_with};
    use chaplygin::jit::JitError;

    const SLEIGH: &str = include_str!("../../../models/sleigh.model");

    #[test]
    fn a_host_cranelift_does_not_support_runs_the_interpreter() {
        let unsupported = |_: &mut _| Err(JitError::UnsupportedHost("riscv32".into()));
        let model = load_with("sleigh.model", SLEIGH, EngineChoice::Jit, unsupported)
            .expect("the model loads");
        assert_eq!(model.engine().name(), "interpret");
        let native = load("sleigh.model", SLEIGH, EngineChoice::Jit).expect("the model loads");
        assert_eq!(native.engine().name(), "jit");
        assert_eq!(
            model.momenta(&[0.0, 0.0, 0.3], &[1.0, 0.3, 0.5]),
            native.momenta(&[0.0, 0.0, 0.3], &[1.0, 0.3, 0.5])
        );
    }
}
