//! A model from its text whose programs run as native code: the engines of
//! [`InterpretedModel`] ([`chaplygin_codegen::interpret::Engine`]) made of
//! [`NativePrograms`], all compiled at once or each on its first run
//! ([`OnDemand`], which the [`Native`] backend makes), and [`JitModel`], a
//! model loaded that way.

use crate::{JitError, NativePrograms, host};
use chaplygin_codegen::diagnostic::Diagnostics;
use chaplygin_codegen::interpret::{Backend, Engine, InterpretedModel, Interpreter};
use chaplygin_codegen::ir::{IrError, Program};
use std::ops::{Deref, DerefMut};
use std::path::Path;
use std::sync::OnceLock;

impl Engine for NativePrograms {
    fn name(&self) -> &'static str {
        "jit"
    }

    fn evaluate(
        &self,
        index: usize,
        _program: &Program,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        NativePrograms::evaluate(self, index, inputs, outputs)
    }
}

/// Runs the programs of `model` as native code from then on, each compiled
/// the first time it runs ([`OnDemand`]); where Cranelift has no backend
/// for the host, `model` keeps its engine and the error says why.
///
/// # Errors
/// [`JitError::UnsupportedHost`].
pub fn compile(model: &mut InterpretedModel) -> Result<(), JitError> {
    let native = Native::for_host()?;
    model.set_engine(|programs| Ok(native.engine(programs)))
}

/// The backend of native code on this host: its engines are [`OnDemand`].
/// A model loaded on it ([`InterpretedModel::from_source_on`]) runs its
/// derivation's numeric searches as native code too, not only its
/// functions.
#[derive(Clone, Copy, Debug)]
pub struct Native(());

impl Native {
    /// The backend, where Cranelift supports the host.
    ///
    /// # Errors
    /// [`JitError::UnsupportedHost`].
    pub fn for_host() -> Result<Native, JitError> {
        host::supported()?;
        Ok(Native(()))
    }
}

impl Backend for Native {
    fn engine(&self, programs: &[&Program]) -> Box<dyn Engine> {
        Box::new(OnDemand::new(programs.len()))
    }
}

/// The engine of [`compile`]: each program compiled to native code
/// ([`NativePrograms`]) on its first run, by the thread that runs it, and
/// kept. A model loads without compiling what it never runs (a
/// linearization of the benchmark bicycle runs six of its 29 programs);
/// once a program is compiled its runs allocate nothing. Should Cranelift
/// refuse a program, that program is interpreted instead (the same bits).
pub struct OnDemand {
    compiled: Vec<OnceLock<Option<NativePrograms>>>,
}

impl OnDemand {
    /// Nothing compiled yet, for `programs` programs.
    pub fn new(programs: usize) -> OnDemand {
        OnDemand {
            compiled: (0..programs).map(|_| OnceLock::new()).collect(),
        }
    }

    /// How many programs have been compiled so far.
    pub fn compiled(&self) -> usize {
        self.compiled
            .iter()
            .filter(|cell| matches!(cell.get(), Some(Some(_))))
            .count()
    }
}

impl Engine for OnDemand {
    fn name(&self) -> &'static str {
        "jit"
    }

    fn evaluate(
        &self,
        index: usize,
        program: &Program,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        let native = self.compiled[index].get_or_init(|| NativePrograms::compile(&[program]).ok());
        match native {
            Some(native) => native.evaluate(0, inputs, outputs),
            None => Interpreter.evaluate(index, program, inputs, outputs),
        }
    }
}

impl std::fmt::Debug for OnDemand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OnDemand")
            .field("programs", &self.compiled.len())
            .field("compiled", &self.compiled())
            .finish()
    }
}

/// Why a model could not be loaded on the JIT.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read `{path}`: {source}")]
    Read {
        /// The path given.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The model text was rejected.
    #[error("{rendered}")]
    Model {
        /// Each error with its line and column.
        diagnostics: Diagnostics,
        /// The diagnostics as `file:line:col: error: ...` lines.
        rendered: String,
    },
    /// Cranelift could not compile the programs.
    #[error(transparent)]
    Jit(#[from] JitError),
}

/// A model read from its text, every derived function compiled to native
/// code at run time: an [`InterpretedModel`] (whose methods it derefs to)
/// on the [`NativePrograms`] engine.
#[derive(Debug)]
pub struct JitModel(InterpretedModel);

impl JitModel {
    /// Parses, checks, derives and compiles the model text.
    ///
    /// # Errors
    /// [`LoadError::Model`] with the diagnostics, or [`LoadError::Jit`].
    pub fn from_source(text: &str) -> Result<JitModel, LoadError> {
        JitModel::named("model", text)
    }

    /// The model of `text`, its diagnostics rendered against `file`.
    fn named(file: &str, text: &str) -> Result<JitModel, LoadError> {
        let native = Native::for_host()?;
        let model = InterpretedModel::from_source_on(text, &native).map_err(|diagnostics| {
            LoadError::Model {
                rendered: diagnostics.render(file),
                diagnostics,
            }
        })?;
        Ok(JitModel(model))
    }

    /// [`JitModel::from_source`] of the file at `path`.
    ///
    /// # Errors
    /// [`LoadError::Read`], or those of [`JitModel::from_source`].
    pub fn from_file(path: impl AsRef<Path>) -> Result<JitModel, LoadError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| LoadError::Read {
            path: path.display().to_string(),
            source,
        })?;
        JitModel::named(&path.display().to_string(), &text)
    }

    /// The model itself, its programs on the native engine.
    pub fn into_inner(self) -> InterpretedModel {
        self.0
    }
}

impl Deref for JitModel {
    type Target = InterpretedModel;

    fn deref(&self) -> &InterpretedModel {
        &self.0
    }
}

impl DerefMut for JitModel {
    fn deref_mut(&mut self) -> &mut InterpretedModel {
        &mut self.0
    }
}
