//! A [`Program`] as a Cranelift function, compiled to machine code.
//!
//! The program is already in SSA form on one block, so each of its values is
//! one Cranelift value, kept in a table indexed by [`Value::index`]; no
//! variables are needed. The function is `fn(inputs: *const f64, outputs:
//! *mut f64)`: an input is loaded from `inputs` where it is read, and each
//! output is stored into `outputs` as soon as it is computed. Arithmetic, negation and
//! square roots are the machine's IEEE operations; the other functions are
//! calls of [`Routine`]s. A value read far from its definition is reloaded
//! (see [`plan`](crate::plan)).
//!
//! A [`Translator`] needs only the ISA and the routines' declarations, not
//! the module, so several can compile at once on different threads.

use crate::plan::{self, Plan};
use crate::routines::Routine;
use chaplygin_codegen::ir::{Instruction, Op, Program, Value};
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::ir::{
    self, AbiParam, ExtFuncData, ExternalName, FuncRef, InstBuilder, MemFlagsData, Signature,
    StackSlot, StackSlotData, StackSlotKind, UserExternalName, types,
};
use cranelift_codegen::isa::TargetIsa;
use cranelift_codegen::{CodegenError, Context};
use cranelift_frontend::{FuncInstBuilder, FunctionBuilder, FunctionBuilderContext};
use cranelift_module::{FuncId, ModuleReloc};

/// The size of an `f64` in bytes.
const F64_BYTES: usize = 8;

/// The byte offset of element `index` of an array of `f64`.
///
/// # Panics
///
/// If the offset does not fit an `i32` (an array of more than 2 GiB).
fn offset(index: usize) -> i32 {
    index
        .checked_mul(F64_BYTES)
        .and_then(|bytes| i32::try_from(bytes).ok())
        .expect("arrays of f64 fit 2 GiB")
}

/// The declarations of the routines, indexed by the routine's discriminant.
pub(crate) type Routines = [FuncId; Routine::ALL.len()];

/// The signature of every program, `(inputs: *const f64, outputs: *mut f64)`.
pub(crate) fn program_signature(isa: &dyn TargetIsa) -> Signature {
    let pointer = AbiParam::new(isa.pointer_type());
    let mut signature = Signature::new(isa.default_call_conv());
    signature.params.extend([pointer, pointer]);
    signature
}

/// A program's machine code, ready to be defined in the module.
pub(crate) struct Compiled {
    /// The function the code defines.
    pub(crate) id: FuncId,
    /// The alignment the code needs, in bytes.
    pub(crate) alignment: u64,
    /// The machine code.
    pub(crate) bytes: Vec<u8>,
    /// Where the addresses of the routines go.
    pub(crate) relocs: Vec<ModuleReloc>,
}

/// Compiles programs, reusing its contexts from one to the next.
pub(crate) struct Translator<'a> {
    isa: &'a dyn TargetIsa,
    routines: &'a Routines,
    context: Context,
    builder_context: FunctionBuilderContext,
}

impl<'a> Translator<'a> {
    pub(crate) fn new(isa: &'a dyn TargetIsa, routines: &'a Routines) -> Translator<'a> {
        Translator {
            isa,
            routines,
            context: Context::new(),
            builder_context: FunctionBuilderContext::new(),
        }
    }

    /// Compiles `program` as the function `id`.
    ///
    /// # Panics
    ///
    /// If the program breaks [`Program`]'s invariants: an input slot at or
    /// past [`Program::input_count`], or a value read before it is defined.
    pub(crate) fn compile(
        &mut self,
        program: &Program,
        id: FuncId,
    ) -> Result<Compiled, CodegenError> {
        self.context.clear();
        self.context.func.signature = program_signature(self.isa);
        let builder = FunctionBuilder::new(&mut self.context.func, &mut self.builder_context);
        let mut body = Body::new(builder, self.routines, program, self.isa.pointer_type());
        for instruction in program.instructions() {
            body.instruction(instruction);
        }
        body.builder.ins().return_(&[]);
        body.builder.finalize(self.isa.frontend_config());
        let alignment = self
            .context
            .compile(self.isa, &mut ControlPlane::default())
            .map_err(|error| error.inner)?
            .buffer
            .alignment;
        let code = self
            .context
            .compiled_code()
            .expect("the function was just compiled");
        Ok(Compiled {
            id,
            alignment: u64::from(alignment),
            bytes: code.code_buffer().to_vec(),
            relocs: code
                .buffer
                .relocs()
                .iter()
                .map(|reloc| ModuleReloc::from_mach_reloc(reloc, &self.context.func, id))
                .collect(),
        })
    }
}

/// Where a value is read from when it has no register copy near the read.
#[derive(Clone, Copy)]
enum Home {
    /// Input slot `i`, loaded where it is read.
    Input(usize),
    /// A constant, materialized where it is read.
    Constant(f64),
    /// Spill slot `i`, stored into when the value is defined.
    Slot(usize),
    /// Nowhere: the value is not defined yet, or every use is near.
    None,
}

/// A value in a register: the Cranelift value, the position of the
/// instruction that defined or reloaded it and the number of calls made
/// by then.
#[derive(Clone, Copy)]
struct Held {
    value: ir::Value,
    position: usize,
    calls: usize,
}

/// The function being built from one program.
struct Body<'a> {
    builder: FunctionBuilder<'a>,
    routines: &'a Routines,
    /// Each routine's import into this function, once it is called.
    imported: [Option<FuncRef>; Routine::ALL.len()],
    plan: Plan,
    /// The stack slot holding the plan's spill slots.
    spills: StackSlot,
    /// The type of addresses.
    pointer: ir::Type,
    /// Each program value's home and latest register copy, by index.
    homes: Vec<Home>,
    held: Vec<Option<Held>>,
    /// The output positions of each value, by index.
    outputs_of: Vec<Vec<usize>>,
    /// The pointers to the inputs and to the outputs.
    inputs: ir::Value,
    outputs: ir::Value,
    input_count: usize,
    /// The position of the instruction being emitted, and the calls before it.
    position: usize,
    calls: usize,
}

impl<'a> Body<'a> {
    /// The function's entry block, its spill slots, and the program's tables.
    fn new(
        mut builder: FunctionBuilder<'a>,
        routines: &'a Routines,
        program: &Program,
        pointer: ir::Type,
    ) -> Body<'a> {
        let block = builder.create_block();
        builder.append_block_params_for_function_params(block);
        builder.switch_to_block(block);
        builder.seal_block(block);
        let plan = Plan::new(program);
        let spills = builder.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            offset(plan.slot_count()).unsigned_abs(),
            F64_BYTES.trailing_zeros() as u8,
        ));
        let (inputs, outputs) = (
            builder.block_params(block)[0],
            builder.block_params(block)[1],
        );
        Body {
            builder,
            routines,
            imported: [None; Routine::ALL.len()],
            plan,
            spills,
            pointer,
            homes: vec![Home::None; program.value_count()],
            held: vec![None; program.value_count()],
            outputs_of: outputs_of(program),
            inputs,
            outputs,
            input_count: program.input_count(),
            position: 0,
            calls: 0,
        }
    }

    /// Emits one instruction and defines the values it computes.
    fn instruction(&mut self, instruction: &Instruction) {
        match instruction.op {
            Op::Input(slot) => self.define_lazily(instruction.result, Home::Input(slot)),
            Op::Constant(ref c) => {
                self.define_lazily(instruction.result, Home::Constant(c.value()))
            }
            Op::SinCos { angle, cosine } => {
                // `angle.sin_cos()` is `(angle.sin(), angle.cos())`.
                let angle = self.get(angle);
                let sine = self.call(Routine::Sin, &[angle]);
                let cos = self.call(Routine::Cos, &[angle]);
                self.calls += 1;
                self.define(cosine, cos);
                self.define(instruction.result, sine);
            }
            ref op => {
                let result = self.operation(op);
                self.calls += usize::from(plan::calls(op));
                self.define(instruction.result, result);
            }
        }
        self.position += 1;
    }

    /// Records `value` as computed here into `defined`; stores it into its
    /// spill slot if it has one, and into the outputs it is.
    fn define(&mut self, value: Value, defined: ir::Value) {
        if let Some(slot) = self.plan.slot(value) {
            let offset = offset(slot);
            self.builder
                .ins()
                .stack_store(self.pointer, defined, self.spills, offset);
            self.homes[value.index()] = Home::Slot(slot);
        }
        self.hold(value, defined);
        self.store_outputs(value, defined);
    }

    /// Records `value`, an input or a constant, as loaded or materialized
    /// where it is read; if it is an output, it is stored now.
    fn define_lazily(&mut self, value: Value, home: Home) {
        self.homes[value.index()] = home;
        if !self.outputs_of[value.index()].is_empty() {
            let defined = self.get(value);
            self.store_outputs(value, defined);
        }
    }

    /// Stores `value`, computed into `defined`, into the outputs it is.
    fn store_outputs(&mut self, value: Value, defined: ir::Value) {
        for &output in &self.outputs_of[value.index()] {
            let offset = offset(output);
            self.builder
                .ins()
                .store(MemFlagsData::trusted(), defined, self.outputs, offset);
        }
    }

    /// Makes `held` the register copy of `value` from here on.
    fn hold(&mut self, value: Value, held: ir::Value) {
        self.held[value.index()] = Some(Held {
            value: held,
            position: self.position,
            calls: self.calls,
        });
    }

    /// Emits an operation that computes one value and returns it.
    fn operation(&mut self, op: &Op) -> ir::Value {
        match op {
            Op::Add(a, b) => self.binary(*a, *b, |ins, a, b| ins.fadd(a, b)),
            Op::Sub(a, b) => self.binary(*a, *b, |ins, a, b| ins.fsub(a, b)),
            Op::Mul(a, b) => self.binary(*a, *b, |ins, a, b| ins.fmul(a, b)),
            Op::Div(a, b) => self.binary(*a, *b, |ins, a, b| ins.fdiv(a, b)),
            Op::Neg(a) => self.unary(*a, |ins, a| ins.fneg(a)),
            Op::Sqrt(a) => self.unary(*a, |ins, a| ins.sqrt(a)),
            Op::Powi(a, n) => {
                let a = self.get(*a);
                let n = self.builder.ins().iconst(types::I32, i64::from(*n));
                self.call(Routine::Powi, &[a, n])
            }
            Op::Powf(a, e) => {
                let a = self.get(*a);
                let e = self.builder.ins().f64const(e.value());
                self.call(Routine::Powf, &[a, e])
            }
            Op::Sin(a) => self.call_on(Routine::Sin, *a),
            Op::Cos(a) => self.call_on(Routine::Cos, *a),
            Op::Tan(a) => self.call_on(Routine::Tan, *a),
            Op::Exp(a) => self.call_on(Routine::Exp, *a),
            Op::Ln(a) => self.call_on(Routine::Ln, *a),
            Op::Asin(a) => self.call_on(Routine::Asin, *a),
            Op::Acos(a) => self.call_on(Routine::Acos, *a),
            Op::Atan(a) => self.call_on(Routine::Atan, *a),
            Op::Atan2(y, x) => {
                let (y, x) = (self.get(*y), self.get(*x));
                self.call(Routine::Atan2, &[y, x])
            }
            Op::Input(_) | Op::Constant(_) | Op::SinCos { .. } => {
                unreachable!("`instruction` emits inputs, constants and sin_cos")
            }
        }
    }

    /// The Cranelift value of `value` at this instruction: its register copy
    /// if that is near, else a reload from its home.
    fn get(&mut self, value: Value) -> ir::Value {
        if let Some(held) = self.held[value.index()]
            && self.position - held.position <= plan::NEAR
            && self.calls == held.calls
        {
            return held.value;
        }
        let reloaded = match self.homes[value.index()] {
            Home::Input(slot) => self.input(slot),
            Home::Constant(c) => self.builder.ins().f64const(c),
            Home::Slot(slot) => {
                let offset = offset(slot);
                self.builder
                    .ins()
                    .stack_load(self.pointer, types::F64, self.spills, offset)
            }
            Home::None => {
                panic!("{value} is read before it is defined, or far from it without a home")
            }
        };
        self.hold(value, reloaded);
        reloaded
    }

    /// Loads input slot `slot`.
    fn input(&mut self, slot: usize) -> ir::Value {
        assert!(
            slot < self.input_count,
            "input slot {slot} of a program with {} inputs",
            self.input_count
        );
        let offset = offset(slot);
        let flags = MemFlagsData::trusted().with_readonly();
        self.builder
            .ins()
            .load(types::F64, flags, self.inputs, offset)
    }

    fn unary(
        &mut self,
        a: Value,
        emit: impl FnOnce(FuncInstBuilder<'_, '_>, ir::Value) -> ir::Value,
    ) -> ir::Value {
        let a = self.get(a);
        emit(self.builder.ins(), a)
    }

    fn binary(
        &mut self,
        a: Value,
        b: Value,
        emit: impl FnOnce(FuncInstBuilder<'_, '_>, ir::Value, ir::Value) -> ir::Value,
    ) -> ir::Value {
        let (a, b) = (self.get(a), self.get(b));
        emit(self.builder.ins(), a, b)
    }

    fn call_on(&mut self, routine: Routine, a: Value) -> ir::Value {
        let a = self.get(a);
        self.call(routine, &[a])
    }

    /// Calls `routine` on `arguments` and returns its result.
    fn call(&mut self, routine: Routine, arguments: &[ir::Value]) -> ir::Value {
        let function = self.import(routine);
        let call = self.builder.ins().call(function, arguments);
        self.builder.inst_results(call)[0]
    }

    /// The routine's import into this function, made on first use (what
    /// `Module::declare_func_in_func` makes of an imported function).
    fn import(&mut self, routine: Routine) -> FuncRef {
        let id = self.routines[routine as usize];
        let func = &mut *self.builder.func;
        *self.imported[routine as usize].get_or_insert_with(|| {
            let call_conv = func.signature.call_conv;
            let signature = func.import_signature(routine.signature(call_conv));
            let name = func.declare_imported_user_function(UserExternalName {
                namespace: 0,
                index: id.as_u32(),
            });
            func.import_function(ExtFuncData {
                name: ExternalName::user(name),
                signature,
                colocated: false,
                patchable: false,
            })
        })
    }
}

/// The output positions of each value of `program`, by index.
fn outputs_of(program: &Program) -> Vec<Vec<usize>> {
    let mut outputs_of = vec![Vec::new(); program.value_count()];
    for (position, value) in program.outputs().iter().enumerate() {
        outputs_of[value.index()].push(position);
    }
    outputs_of
}
