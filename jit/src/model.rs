//! A model from its text whose programs run as native code: the engine of
//! [`InterpretedModel`] ([`chaplygin_codegen::interpret::Engine`]) made of
//! [`NativePrograms`], and [`JitModel`], a model loaded that way.

use crate::{JitError, NativePrograms};
use chaplygin_codegen::diagnostic::Diagnostics;
use chaplygin_codegen::interpret::{Engine, InterpretedModel};
use chaplygin_codegen::ir::{IrError, Program};
use std::ops::{Deref, DerefMut};
use std::path::Path;

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

/// Compiles every program of `model` to native code, which runs them from
/// then on; where Cranelift fails (an unsupported host), `model` keeps its
/// engine and the error says why.
///
/// # Errors
/// [`JitError`] from [`NativePrograms::compile`].
pub fn compile(model: &mut InterpretedModel) -> Result<(), JitError> {
    model.set_engine(|programs| {
        NativePrograms::compile(programs).map(|native| Box::new(native) as Box<dyn Engine>)
    })
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
        let mut model =
            InterpretedModel::from_source(text).map_err(|diagnostics| LoadError::Model {
                rendered: diagnostics.render(file),
                diagnostics,
            })?;
        compile(&mut model)?;
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
