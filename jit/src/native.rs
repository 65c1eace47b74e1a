//! Every `unsafe` use of the crate: calling the finalized code, freeing it,
//! and sharing it between threads.
//!
//! # Why the calls are sound
//!
//! [`Code::finalize`] turns each finalized function's address into an
//! `unsafe extern "C" fn(*const f64, *mut f64)`. That is the function's
//! type: [`translate`](crate::translate) declares every program with the
//! parameters `(pointer, pointer)` and no results, in the ISA's default
//! calling convention, which is the host's C convention (`extern "C"`).
//!
//! The code touches no memory of the caller's but the two arrays: it loads
//! `inputs[i]` only for input slots `i` below the program's input count
//! (checked as each load is emitted) and stores `outputs[j]` once for each
//! output `j` of the program; the byte offsets are checked to fit. Its other
//! accesses are to its own stack frame, in the spill slot sized for the
//! program's spills. Its calls go to the wrappers of
//! [`routines`](crate::routines), each declared with its exact Rust
//! signature. [`Code::run`] checks both slices' lengths against the counts
//! recorded beside the address before each call, so every access is in
//! bounds; and `inputs` and `outputs` cannot overlap (one is borrowed shared,
//! the other exclusively). The frames are probed (`enable_probestack`,
//! inline), so a stack overflow inside the code reaches the guard page as
//! Rust's own code does.
//!
//! # Why freeing is sound
//!
//! [`JITModule::free_memory`] unmaps the code; afterwards no address taken
//! from the module may be called. The addresses live only in [`Code`],
//! beside the module, and are never handed out; `Drop` frees the module when
//! [`Code`] itself goes away, when no call can be running (it would borrow
//! the [`Code`]) and none can follow. A [`Code`] owns its module from before
//! the first definition, so a compilation that fails frees what it made.
//!
//! # Why `Code` is `Sync`
//!
//! `JITModule` is `Send` but not `Sync`, because of its symbol cache (a
//! `RefCell`) and its symbol look-up closures; only `&mut self` methods and
//! `Drop` touch the module here, never a shared reference. What
//! `&Code` reaches is the address table and the finalized code, which is
//! immutable (mapped read and execute) and keeps no state: each call works
//! on its own stack and on the slices it is given, and the wrappers it calls
//! are pure functions of their arguments. So any number of threads may run
//! the code at once.

use crate::JitError;
use chaplygin_codegen::ir::IrError;
use cranelift_jit::JITModule;
use cranelift_module::FuncId;

/// The type of every compiled program.
type Entry = unsafe extern "C" fn(inputs: *const f64, outputs: *mut f64);

/// A program defined in a module, not yet finalized.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Defined {
    /// The function.
    pub(crate) id: FuncId,
    /// The number of inputs it reads.
    pub(crate) inputs: usize,
    /// The number of outputs it writes.
    pub(crate) outputs: usize,
}

/// A finalized program: its entry and the slice lengths it needs.
#[derive(Clone, Copy)]
struct Function {
    entry: Entry,
    inputs: usize,
    outputs: usize,
}

/// A JIT module and the entries of its finalized programs.
pub(crate) struct Code {
    functions: Vec<Function>,
    /// Always present; taken only by `Drop`.
    module: Option<JITModule>,
}

impl Code {
    /// Takes a module that has no code yet: from here on its memory is
    /// freed with the [`Code`], whatever happens.
    pub(crate) fn new(module: JITModule) -> Code {
        Code {
            functions: Vec::new(),
            module: Some(module),
        }
    }

    /// The module, to declare and define functions in.
    pub(crate) fn module(&mut self) -> &mut JITModule {
        self.module
            .as_mut()
            .expect("the module is there until `Code` drops")
    }

    /// Finalizes the module's definitions and takes the entry of each program.
    pub(crate) fn finalize(&mut self, defined: &[Defined]) -> Result<(), JitError> {
        let module = self.module();
        module.finalize_definitions()?;
        let functions: Vec<Function> = defined
            .iter()
            .map(|program| Function {
                // SAFETY: the address is a finalized function of type
                // `Entry` (module documentation).
                entry: unsafe {
                    std::mem::transmute::<*const u8, Entry>(
                        module.get_finalized_function(program.id),
                    )
                },
                inputs: program.inputs,
                outputs: program.outputs,
            })
            .collect();
        self.functions.extend(functions);
        Ok(())
    }

    /// The number of programs.
    pub(crate) fn len(&self) -> usize {
        self.functions.len()
    }

    /// Runs program `index` (panics if there is none), after checking the
    /// slices' lengths as [`Program::evaluate`](chaplygin_codegen::ir::Program::evaluate) does.
    pub(crate) fn run(
        &self,
        index: usize,
        inputs: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), IrError> {
        let function = self.functions[index];
        if inputs.len() != function.inputs {
            return Err(IrError::InputCount {
                expected: function.inputs,
                found: inputs.len(),
            });
        }
        if outputs.len() != function.outputs {
            return Err(IrError::OutputCount {
                expected: function.outputs,
                found: outputs.len(),
            });
        }
        // SAFETY: the lengths match what the code reads and writes (module
        // documentation).
        unsafe { (function.entry)(inputs.as_ptr(), outputs.as_mut_ptr()) };
        Ok(())
    }
}

impl Drop for Code {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: no entry outlives `self` (module documentation).
            unsafe { module.free_memory() };
        }
    }
}

// SAFETY: shared references reach only the immutable code (module documentation).
unsafe impl Sync for Code {}
