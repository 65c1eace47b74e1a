//! The checked model: a declaration turned into exact symbolic objects.
//!
//! [`check`] takes the syntax tree and produces a [`Model`]: the metric
//! `g(q)` (from the kinetic energy by exact second derivatives,
//! `g_ij = d^2 T / d qdot_i d qdot_j`, or as declared), the potential `V(q)`,
//! the constraint rows `A(q)` (`A qdot = 0`; from a declared distribution, a
//! basis of its annihilator), the input matrix `B(q)`, and the optional
//! momentum basis `h(q)` and symmetry group. A model declared as a mechanism
//! (frames, points, bodies, gravity, rolling contacts, holonomic
//! constraints) has its `T`, `V` and constraint rows derived by the
//! [`mechanism`] stage, and joined to the declared ones. Every rule of the
//! model language is one function in [`check`]; all violations are reported
//! at once.
//!
//! The model is plain data: ids of expressions and normal forms. The
//! expressions themselves, the atoms the normal forms are written over and
//! the engine's caches live in the [`Context`] that [`check`] returns
//! beside it; every later stage reads the model by `&` and extends the
//! context through one `&mut`.

mod check;
pub mod coordinate_sets;
pub mod domain;
pub mod drawing;
mod invariance;
mod lower;
pub mod mechanism;
#[cfg(test)]
mod tests;

pub use check::{check, check_within};
pub use mechanism::bodies::BodyMotion;
pub use mechanism::{FrameTurn, Mechanism, MechanismExpressions, TurnedBy};

use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::sym::{Context, ExprId, Matrix, Rational, RationalFunction, SymbolId};
use proc_macro2::{Ident, Span, TokenStream};

/// A name the user declared, with where they declared it.
#[derive(Clone, Debug)]
pub struct Declared {
    /// The name as written.
    pub name: String,
    /// Where it was written.
    pub span: Span,
}

/// A coordinate or parameter: a declared name that is also a symbol.
#[derive(Clone, Debug)]
pub struct Variable {
    /// The declaration.
    pub declared: Declared,
    /// Its symbol in the model's context.
    pub symbol: SymbolId,
}

/// A parameter with its default value.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The declaration and symbol.
    pub variable: Variable,
    /// The declared default, exact.
    pub default: Rational,
}

/// Options set by attributes on the model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// `#[deny_holonomic]`: integrable constraints are an error, not a report.
    pub deny_holonomic: bool,
}

/// One factor of a symmetry group acting on coordinates (indices into the
/// coordinate list): the runtime's type, which the generated code names too.
pub use chaplygin_runtime::linearize::GroupFactor;

/// A declared symmetry group: the product of its factors.
#[derive(Clone, Debug)]
pub struct Symmetry {
    /// The factors, as written.
    pub factors: Vec<GroupFactor>,
    /// Where the group was declared (its first token).
    pub span: Span,
}

impl Symmetry {
    /// The group coordinates, factor by factor: `x, y, theta` for `se2`,
    /// the coordinate for an abelian factor. The body velocity `xi` of the
    /// momentum equation has this layout.
    pub fn group_coordinates(&self) -> Vec<usize> {
        self.factors
            .iter()
            .flat_map(|factor| match *factor {
                GroupFactor::Se2 { x, y, theta } => vec![x, y, theta],
                GroupFactor::Translation(q) | GroupFactor::Rotation(q) => vec![q],
            })
            .collect()
    }
}

/// Where a dropped contact row depends on the others.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Redundancy {
    /// At every configuration.
    Everywhere,
    /// On the surface of the holonomic constraints `f(q) = 0`.
    OnHolonomicSurface,
}

impl Redundancy {
    /// Where, in words, as the report prints it.
    pub fn describe(self) -> &'static str {
        match self {
            Redundancy::Everywhere => "everywhere",
            Redundancy::OnHolonomicSurface => "on the surface of the holonomic constraints",
        }
    }
}

/// A `no_slip` row dropped because the rows before it imply it
/// (docs/INTERFACE.md section 4, redundant contacts).
#[derive(Clone, Debug)]
pub struct RedundantRow {
    /// The row's name.
    pub name: String,
    /// Where it depends on the others.
    pub redundancy: Redundancy,
}

impl RedundantRow {
    /// The row and where it depends on the others, in words.
    pub fn describe(&self) -> String {
        let where_ = self.redundancy.describe();
        format!("{} (implied by the rows before it {where_})", self.name)
    }
}

/// A declared momentum basis `h(q)`: k one-forms spanning `g(D)`.
#[derive(Clone, Debug)]
pub struct MomentumBasis {
    /// The names of the rows (the reduced momenta).
    pub names: Vec<Declared>,
    /// `h`, k x n.
    pub rows: Matrix,
}

/// The energies and the metric as expressions
/// ([`Context::compact_expression`]): the normal forms written out,
/// or for a mechanism's large entries the expressions they were derived as
/// from the bodies' velocities (equal to the normal forms).
#[derive(Clone, Debug)]
pub struct EnergyExpressions {
    /// `T(q, qdot)`.
    pub kinetic: ExprId,
    /// `V(q)`.
    pub potential: ExprId,
    /// `g(q) = d^2 T / d qdot^2`, n x n: for a mechanism's large entries
    /// the declared part's second derivatives plus the bodies' Kane form
    /// ([`BodyMotion::mass_matrix`]).
    pub mass_matrix: Matrix<ExprId>,
    /// The part of `T` declared as an energy (`T` less the bodies'), its
    /// normal form written out.
    pub declared_kinetic: ExprId,
    /// The declared bodies' motions, in order, then the motions the
    /// `orient` frames add (each a unit-norm term of `T`, no body).
    pub bodies: Vec<BodyMotion>,
}

/// A checked model.
#[derive(Clone, Debug)]
pub struct Model {
    /// The struct's name.
    pub name: Ident,
    /// Doc comment lines.
    pub docs: Vec<String>,
    /// The struct's visibility, as written.
    pub visibility: TokenStream,
    /// Attribute options.
    pub options: Options,
    /// Whether emission writes each item's Rust statements (the macro and
    /// the build script) or only lowers its program (the interpreter, which
    /// runs the programs: writing the benchmark bicycle's 105 MB of Rust
    /// took a third of its interpreted linearization).
    pub emits_rust: bool,
    /// `q`, in declared order.
    pub coordinates: Vec<Variable>,
    /// `qdot`, in the coordinates' order.
    pub velocities: Vec<SymbolId>,
    /// The parameters, in declared order.
    pub parameters: Vec<Parameter>,
    /// `T(q, qdot) = 1/2 qdot^T g qdot`.
    pub kinetic_energy: RationalFunction,
    /// `V(q)`.
    pub potential_energy: RationalFunction,
    /// `g(q)`, n x n, symmetric.
    pub mass_matrix: Matrix,
    /// `T`, `V` and `g` as the expressions emitted code computes them.
    pub energy_expressions: EnergyExpressions,
    /// The constraint names (`c1, c2, ...` when derived from a distribution).
    pub constraints: Vec<Declared>,
    /// `A(q)`, c x n, full row rank.
    pub constraint_matrix: Matrix,
    /// `A(q)` as the expressions emitted code computes it: the normal
    /// forms written out, or for a large derived entry the expression it
    /// was derived as (equal to the normal form).
    pub constraint_expressions: Matrix<ExprId>,
    /// The contact rows dropped because the others imply them.
    pub redundant_rows: Vec<RedundantRow>,
    /// The input names.
    pub inputs: Vec<Declared>,
    /// `B(q)`, n x p.
    pub input_matrix: Matrix,
    /// The declared momentum basis, if any.
    pub momentum_basis: Option<MomentumBasis>,
    /// The declared symmetry, if any.
    pub symmetry: Option<Symmetry>,
    /// The mechanism sections' frames, points, energies, contacts and
    /// holonomic constraints (empty for a model declared by its energy).
    pub mechanism: Mechanism,
}

impl Model {
    /// Number of coordinates `n`.
    pub fn n(&self) -> usize {
        self.coordinates.len()
    }

    /// Number of constraints `c`.
    pub fn c(&self) -> usize {
        self.constraints.len()
    }

    /// Degrees of freedom in velocity, `k = n - c`.
    pub fn k(&self) -> usize {
        self.n() - self.c()
    }

    /// Number of inputs `p`.
    pub fn p(&self) -> usize {
        self.inputs.len()
    }

    /// The coordinate symbols, in order.
    pub fn coordinate_symbols(&self) -> Vec<SymbolId> {
        self.coordinates.iter().map(|c| c.symbol).collect()
    }

    /// The parameter symbols, in order.
    pub fn parameter_symbols(&self) -> Vec<SymbolId> {
        self.parameters.iter().map(|p| p.variable.symbol).collect()
    }

    /// The normal form of a scalar expression written in the model language
    /// over this model's coordinates, parameters and velocities `dot(q)`,
    /// e.g. a hand-derived energy to compare with the derived one, in the
    /// model's context `cx`.
    pub fn normal_of_text(
        &self,
        cx: &mut Context,
        text: &str,
    ) -> Result<RationalFunction, Diagnostics> {
        let syntax = crate::syntax::parse_str(&format!("struct Expression {{ value: {text} }}"))?;
        let Some(expr) = syntax.sections.first().and_then(|s| s.value.as_expr()) else {
            return Err(Diagnostic::new(syntax.name.span(), "expected one expression").into());
        };
        let mut scope = lower::Scope::default();
        for coordinate in &self.coordinates {
            let binding = lower::Binding::Coordinate(coordinate.symbol);
            scope.bind(&coordinate.declared.name, binding);
        }
        for parameter in &self.parameters {
            let binding = lower::Binding::Parameter(parameter.variable.symbol);
            scope.bind(&parameter.variable.declared.name, binding);
        }
        let mut diagnostics = Diagnostics::default();
        let lowered = lower::Lowerer {
            cx,
            scope: &scope,
            diagnostics: &mut diagnostics,
        }
        .lower(expr);
        let Some(id) = lowered else {
            return Err(diagnostics);
        };
        cx.normal(id)
            .map_err(|error| Diagnostic::new(expr.first_span(), error.to_string()).into())
    }

    /// The parameters' default values as `f64`, in order.
    pub fn parameter_defaults(&self) -> Vec<f64> {
        self.parameters.iter().map(|p| p.default.to_f64()).collect()
    }

    /// The model with a generalized force along each coordinate of
    /// `forced` (indices into [`Model::coordinates`]) as an input after the
    /// declared ones, named `force(q)`: its column of `B(q)` is the unit
    /// vector `e_q`, so that `g qddot = ... + B u` gains `e_q force(q)`.
    pub fn with_coordinate_forces(mut self, forced: &[usize]) -> Model {
        let (n, p) = (self.n(), self.p());
        let entries = (0..n).flat_map(|i| {
            let declared = self.input_matrix.row_entries(i);
            let unit = forced.iter().map(move |&j| match i == j {
                true => RationalFunction::one(),
                false => RationalFunction::zero(),
            });
            declared.into_iter().chain(unit)
        });
        self.input_matrix = Matrix::new(n, p + forced.len(), entries.collect())
            .expect("n rows of p + forced entries");
        self.inputs.extend(forced.iter().map(|&j| {
            let coordinate = &self.coordinates[j].declared;
            Declared {
                name: format!("force({})", coordinate.name),
                span: coordinate.span,
            }
        }));
        self
    }
}
