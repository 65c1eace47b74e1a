//! Which engine runs a model read from its text: native code compiled
//! from the model's programs at run time (`jit`, the default) or the IR
//! interpreter (`interpret`, the reference both are tested against).

use super::catalog::{BuiltIn, Source};
use super::document::Rejected;
use crate::jit::{JitError, Native};
use chaplygin_codegen::interpret::{Backend, InterpretedModel, Interpreter};

/// What runs a model's programs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum EngineChoice {
    /// Native code compiled at run time with Cranelift; the interpreter
    /// where Cranelift does not support the host (with a note).
    Jit,
    /// The IR interpreter.
    Interpret,
}

/// A model read from its text, and where it came from.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The model, its programs run by the engine chosen.
    pub model: InterpretedModel,
    /// The name its errors are reported against: a built-in's name, or
    /// the file's path.
    pub label: String,
    /// The built-in it is, if any (its default configuration and motion).
    pub built_in: Option<&'static BuiltIn>,
    /// Why the JIT was not used where it was chosen (the host is not one
    /// Cranelift supports): the interpreter runs the model instead.
    pub fallback: Option<JitError>,
}

/// The model of `source`, its programs run by `engine`.
///
/// # Errors
/// The model's diagnostics.
pub fn load(source: &Source, engine: EngineChoice) -> Result<Loaded, Rejected> {
    load_with(source, engine, Native::for_host)
}

/// [`load`], the JIT's backend being `native`: where there is none
/// (Cranelift does not support the host), the interpreter, and the error in
/// [`Loaded::fallback`]. The derivation's own numeric searches run on the
/// same backend as the model's programs.
fn load_with(
    source: &Source,
    engine: EngineChoice,
    native: impl FnOnce() -> Result<Native, JitError>,
) -> Result<Loaded, Rejected> {
    let label = source.file_name();
    let (native, fallback) = match engine {
        EngineChoice::Jit => match native() {
            Ok(native) => (Some(native), None),
            Err(error) => (None, Some(error)),
        },
        EngineChoice::Interpret => (None, None),
    };
    let backend: &dyn Backend = match &native {
        Some(native) => native,
        None => &Interpreter,
    };
    let model = InterpretedModel::from_source_on(source.text(), backend)
        .map_err(|diagnostics| Rejected::new(&label, &diagnostics))?;
    let built_in = match source {
        Source::BuiltIn(built_in) => Some(*built_in),
        Source::File { .. } => None,
    };
    Ok(Loaded {
        model,
        label,
        built_in,
        fallback,
    })
}

/// `model` derived again with a generalized force `force(q)` along each
/// coordinate of `forced` as an input after the declared ones
/// (`InterpretedModel::with_coordinate_forces_on`), run by the engine
/// `model` runs on, its parameters' values kept; errors are reported
/// against `label`.
///
/// # Errors
/// The model's diagnostics.
pub fn with_coordinate_forces(
    model: &InterpretedModel,
    forced: &[usize],
    label: &str,
) -> Result<InterpretedModel, Rejected> {
    let native = match model.engine().name() {
        "jit" => Native::for_host().ok(),
        _ => None,
    };
    let backend: &dyn Backend = match &native {
        Some(native) => native,
        None => &Interpreter,
    };
    model
        .with_coordinate_forces_on(forced, backend)
        .map_err(|diagnostics| Rejected::new(label, &diagnostics))
}

#[cfg(test)]
mod tests {
    use super::{EngineChoice, load, load_with};
    use crate::driver::catalog::Source;
    use crate::jit::JitError;

    #[test]
    fn a_host_cranelift_does_not_support_runs_the_interpreter() {
        let sleigh = Source::File {
            path: "sleigh.model".into(),
            text: include_str!("catalog/sleigh.model").into(),
        };
        let unsupported = || Err(JitError::UnsupportedHost("riscv32".into()));
        let loaded = load_with(&sleigh, EngineChoice::Jit, unsupported).expect("the model loads");
        assert_eq!(loaded.model.engine().name(), "interpret");
        assert!(matches!(
            loaded.fallback,
            Some(JitError::UnsupportedHost(_))
        ));
        let native = load(&sleigh, EngineChoice::Jit).expect("the model loads");
        assert_eq!(native.model.engine().name(), "jit");
        assert!(native.fallback.is_none());
        assert_eq!(
            loaded.model.momenta(&[0.0, 0.0, 0.3], &[1.0, 0.3, 0.5]),
            native.model.momenta(&[0.0, 0.0, 0.3], &[1.0, 0.3, 0.5])
        );
    }
}
