//! Compiling programs for the host into one JIT module.
//!
//! The programs are compiled on as many threads as the machine runs at once,
//! each thread with its own [`Translator`], the largest programs first; the
//! machine code is then defined in the module and finalized on the calling
//! thread.

use crate::JitError;
use crate::native::{Code, Defined};
use crate::routines::{self, Routine};
use crate::translate::{self, Compiled, Routines, Translator};
use chaplygin_codegen::ir::Program;
use cranelift_codegen::isa::{OwnedTargetIsa, TargetIsa};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module};
use std::num::NonZero;
use std::thread;

/// Cranelift's settings: no optimization (see [`crate`]'s documentation),
/// the register allocator that can afford the largest programs, the JIT's
/// requirements (absolute addresses, calls that reach any address), and
/// probed stack frames. The IR verifier is set apart ([`Verify`]).
const SETTINGS: [(&str, &str); 6] = [
    ("opt_level", "none"),
    ("regalloc_algorithm", "backtracking"),
    ("is_pic", "false"),
    ("use_colocated_libcalls", "false"),
    ("enable_probestack", "true"),
    ("probestack_strategy", "inline"),
];

/// Whether Cranelift's IR verifier checks each translated function before
/// its code is generated: a check of the translation, which the JIT's own
/// tests make on every program they compile; a load does not (it took 14 %
/// of the benchmark bicycle's load in a debug build).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Verify {
    /// The verifier runs.
    Yes,
    /// It does not.
    No,
}

/// Compiles every program into one module and finalizes it.
pub(crate) fn compile(programs: &[&Program], verify: Verify) -> Result<Code, JitError> {
    let isa = host_isa(verify)?;
    let mut builder = JITBuilder::with_isa(isa.clone(), cranelift_module::default_libcall_names());
    routines::register(&mut builder);
    let mut code = Code::new(JITModule::new(builder));
    let module = code.module();
    let routines = declare_routines(module)?;
    let signature = translate::program_signature(&*isa);
    let ids = programs
        .iter()
        .map(|_| Ok(module.declare_anonymous_function(&signature)?))
        .collect::<Result<Vec<FuncId>, JitError>>()?;
    for function in compile_in_parallel(&*isa, &routines, programs, &ids)? {
        module.define_function_bytes(
            function.id,
            function.alignment,
            &function.bytes,
            &function.relocs,
        )?;
    }
    let defined: Vec<Defined> = programs
        .iter()
        .zip(ids)
        .map(|(program, id)| Defined {
            id,
            inputs: program.input_count(),
            outputs: program.outputs().len(),
        })
        .collect();
    code.finalize(&defined)?;
    Ok(code)
}

/// Fails with [`JitError::UnsupportedHost`] where Cranelift has no backend
/// for the host, as [`compile`] would.
pub(crate) fn supported() -> Result<(), JitError> {
    host_isa(Verify::No).map(|_| ())
}

/// The host's ISA with [`SETTINGS`], the verifier as `verify` says.
fn host_isa(verify: Verify) -> Result<OwnedTargetIsa, JitError> {
    let mut flags = settings::builder();
    let verifier = (
        "enable_verifier",
        if verify == Verify::Yes {
            "true"
        } else {
            "false"
        },
    );
    for (name, value) in SETTINGS.into_iter().chain([verifier]) {
        flags
            .set(name, value)
            .map_err(|error| JitError::Compile(format!("setting {name}={value}: {error}")))?;
    }
    cranelift_native::builder()
        .map_err(|message| JitError::UnsupportedHost(message.to_string()))?
        .finish(settings::Flags::new(flags))
        .map_err(|error| JitError::Compile(error.to_string()))
}

/// Declares every routine as an import of the module.
fn declare_routines(module: &mut JITModule) -> Result<Routines, JitError> {
    let call_conv = module.isa().default_call_conv();
    let mut routines = [FuncId::from_u32(0); Routine::ALL.len()];
    for routine in Routine::ALL {
        routines[routine as usize] = module.declare_function(
            routine.name(),
            Linkage::Import,
            &routine.signature(call_conv),
        )?;
    }
    Ok(routines)
}

/// Compiles program `i` as function `ids[i]`, for every `i`, on several threads.
fn compile_in_parallel(
    isa: &dyn TargetIsa,
    routines: &Routines,
    programs: &[&Program],
    ids: &[FuncId],
) -> Result<Vec<Compiled>, JitError> {
    let threads = thread::available_parallelism().map_or(1, NonZero::get);
    let shares = shares(programs, threads);
    let compile_share = |share: &Vec<usize>| {
        let mut translator = Translator::new(isa, routines);
        share
            .iter()
            .map(|&i| translator.compile(programs[i], ids[i]))
            .collect::<Result<Vec<Compiled>, _>>()
    };
    let compiled = thread::scope(|scope| {
        let workers: Vec<_> = shares
            .iter()
            .map(|share| scope.spawn(move || compile_share(share)))
            .collect();
        workers
            .into_iter()
            .map(|worker| {
                worker
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .collect::<Result<Vec<_>, _>>()
    });
    compiled
        .map(|shares| shares.into_iter().flatten().collect())
        .map_err(|error| JitError::Compile(error.to_string()))
}

/// The indices of the programs split into at most `threads` shares of about
/// equal numbers of instructions (each next largest program goes to the
/// smallest share); no share is empty.
fn shares(programs: &[&Program], threads: usize) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..programs.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(programs[i].instructions().len()));
    let mut shares = vec![(0, Vec::new()); threads.min(programs.len())];
    for i in order {
        let smallest = shares
            .iter_mut()
            .min_by_key(|(size, _)| *size)
            .expect("there is a share for every program");
        smallest.0 += programs[i].instructions().len() + 1;
        smallest.1.push(i);
    }
    shares.into_iter().map(|(_, share)| share).collect()
}
