//! The Rust functions the native code calls for the operations that are not
//! one machine instruction.
//!
//! Each wrapper is the `f64` method the interpreter runs for the operation,
//! behind the C calling convention, so native code and interpreter call the
//! same function on the same arguments. Cranelift finds them by name: the
//! JIT builder is given each name with the wrapper's address, and each
//! function that calls a routine imports it once.

use cranelift_codegen::ir::{AbiParam, Signature, types};
use cranelift_codegen::isa::CallConv;
use cranelift_jit::JITBuilder;

/// A routine the native code calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Routine {
    /// `x.sin()`.
    Sin,
    /// `x.cos()`.
    Cos,
    /// `x.tan()`.
    Tan,
    /// `x.exp()`.
    Exp,
    /// `x.ln()`.
    Ln,
    /// `x.asin()`.
    Asin,
    /// `x.acos()`.
    Acos,
    /// `x.atan()`.
    Atan,
    /// `y.atan2(x)`, with `y` the first argument.
    Atan2,
    /// `x.powi(n)`, with `n` an `i32`.
    Powi,
    /// `x.powf(e)`.
    Powf,
}

impl Routine {
    /// Every routine, in the order of their discriminants.
    pub(crate) const ALL: [Routine; 11] = [
        Routine::Sin,
        Routine::Cos,
        Routine::Tan,
        Routine::Exp,
        Routine::Ln,
        Routine::Asin,
        Routine::Acos,
        Routine::Atan,
        Routine::Atan2,
        Routine::Powi,
        Routine::Powf,
    ];

    /// The symbol the native code imports.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Routine::Sin => "chaplygin_sin",
            Routine::Cos => "chaplygin_cos",
            Routine::Tan => "chaplygin_tan",
            Routine::Exp => "chaplygin_exp",
            Routine::Ln => "chaplygin_ln",
            Routine::Asin => "chaplygin_asin",
            Routine::Acos => "chaplygin_acos",
            Routine::Atan => "chaplygin_atan",
            Routine::Atan2 => "chaplygin_atan2",
            Routine::Powi => "chaplygin_powi",
            Routine::Powf => "chaplygin_powf",
        }
    }

    /// The wrapper's address.
    fn address(self) -> *const u8 {
        match self {
            Routine::Sin => sin as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Cos => cos as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Tan => tan as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Exp => exp as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Ln => ln as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Asin => asin as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Acos => acos as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Atan => atan as extern "C" fn(f64) -> f64 as *const u8,
            Routine::Atan2 => atan2 as extern "C" fn(f64, f64) -> f64 as *const u8,
            Routine::Powi => powi as extern "C" fn(f64, i32) -> f64 as *const u8,
            Routine::Powf => powf as extern "C" fn(f64, f64) -> f64 as *const u8,
        }
    }

    /// The wrapper's signature in the calling convention `call_conv`, the
    /// host's C convention: an `f64` and, for the powers, the exponent (an
    /// `i32` for `powi`, an `f64` for `powf`), for `atan2` the abscissa (an
    /// `f64`), returning an `f64`.
    pub(crate) fn signature(self, call_conv: CallConv) -> Signature {
        let mut signature = Signature::new(call_conv);
        signature.params.push(AbiParam::new(types::F64));
        match self {
            Routine::Powi => signature.params.push(AbiParam::new(types::I32)),
            Routine::Powf | Routine::Atan2 => signature.params.push(AbiParam::new(types::F64)),
            _ => {}
        }
        signature.returns.push(AbiParam::new(types::F64));
        signature
    }
}

/// Gives the JIT builder every routine's name and address.
pub(crate) fn register(builder: &mut JITBuilder) {
    for routine in Routine::ALL {
        builder.symbol(routine.name(), routine.address());
    }
}

extern "C" fn sin(x: f64) -> f64 {
    x.sin()
}

extern "C" fn cos(x: f64) -> f64 {
    x.cos()
}

extern "C" fn tan(x: f64) -> f64 {
    x.tan()
}

extern "C" fn exp(x: f64) -> f64 {
    x.exp()
}

extern "C" fn ln(x: f64) -> f64 {
    x.ln()
}

extern "C" fn asin(x: f64) -> f64 {
    x.asin()
}

extern "C" fn acos(x: f64) -> f64 {
    x.acos()
}

extern "C" fn atan(x: f64) -> f64 {
    x.atan()
}

extern "C" fn atan2(y: f64, x: f64) -> f64 {
    y.atan2(x)
}

extern "C" fn powi(x: f64, n: i32) -> f64 {
    x.powi(n)
}

extern "C" fn powf(x: f64, e: f64) -> f64 {
    x.powf(e)
}
