//! The model argument the commands share, and the engine that runs it.

use chaplygin::driver::Failure;
use chaplygin::driver::catalog::lookup;
use chaplygin::driver::engine::{self, EngineChoice, Loaded};

/// The model a command runs, and the engine that runs it.
#[derive(Debug, clap::Args)]
pub struct ModelArgs {
    /// A built-in model's name, or the path of a `.model` file.
    model: String,
    /// What runs a model from its text: native code compiled at run time,
    /// or the IR interpreter.
    #[arg(long, value_enum, default_value_t = EngineChoice::Jit)]
    engine: EngineChoice,
}

/// The model `args` names, loaded on its engine; where the JIT cannot run
/// on this host, a note on standard error and the interpreter.
///
/// # Errors
/// An unknown model, or the model's diagnostics.
pub fn loaded(args: &ModelArgs) -> Result<Loaded, Failure> {
    let loaded = engine::load(&lookup(&args.model)?, args.engine)?;
    if let Some(error) = &loaded.fallback {
        eprintln!("note: {error}; running the interpreter");
    }
    Ok(loaded)
}
