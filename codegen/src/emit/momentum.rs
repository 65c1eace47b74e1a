//! The momentum-equation items of a model with a symmetry (MATH.md section 4,
//! [`crate::derive::momentum`]): with the shape `r` (the coordinates the group
//! does not act on, nr of them) and the momenta `p` (mp of them),
//!
//! ```text
//! momentum(q, qdot)              p = h(q) M(q) qdot,  h_i = (R(theta) e_i(r), 0)
//! momentum_rhs(r, rdot, p)       pdot = rdot^T H rdot + rdot^T K p + p^T D p  (unforced)
//! momentum_input_matrix(q)       h(q) B(q): with inputs, pdot += momentum_input_matrix(q) u
//! nonholonomic_connection(r)     A_nh(r), dg x nr
//! locked_inertia(r)              I(r) = e II e^T, mp x mp
//! body_velocity(r, rdot, p)      xi = -A_nh(r) rdot + e(r)^T I(r)^-1 p
//! shape_acceleration(r, rdot, p, u)
//!                                the shape rows of `acceleration` at the group
//!                                identity with qdot = (xi, rdot)    (1.3)
//! momentum_rhs_jacobian(r, rdot, p), body_velocity_jacobian(r, rdot, p)
//!                                their Jacobians in (r, rdot, p)
//! connection_divisor(r)          d = det S and dd/dr: A_nh = N / d is singular where d = 0 (4.2)
//! connection_curvature(r)        principally kinematic only (mp = 0): F = -dA + [A, A]
//!                                on each shape plane (4.3)
//! ```
//!
//! `shape_acceleration` calls `body_velocity` and `acceleration` (by
//! invariance, section 2's shape rows do not depend on the group element);
//! its operation count is the sum of theirs.
//!
//! and a report section with the basis `e(r)` and the coefficient tensors.
//! `xi` has one entry per group coordinate, factor by factor (`(v1, v2,
//! omega)` for `se2`, the velocity for `translation` and `rotation`).

use super::port_hamiltonian::{
    Signature, item, matrix_type, rows_literal, vector_literal, vector_type,
};
use super::report::Section;
use super::{Argument, Function, coordinates, f64_type, velocities};
use crate::derive::momentum::{Curvature, Momentum};
use crate::diagnostic::Diagnostics;
use crate::ir::OperationCount;
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{ExprId, Matrix, RationalFunction};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

const TITLE: &str =
    "Momentum equation (Bloch-Krishnaprasad-Marsden-Murray; Koon & Marsden 1.1-1.2)";

/// The seven functions and the report's section; `emitted` are the items
/// emitted before (`acceleration` among them).
pub(super) fn functions(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
    emitted: &[Function],
) -> Result<(Vec<Function>, Section), Diagnostics> {
    let section = report_section(model, cx, momentum);
    let reconstruction = body_velocity(model, cx, momentum)?;
    let acceleration = emitted
        .iter()
        .find(|f| f.name == "acceleration")
        .ok_or_else(|| {
            Diagnostics::internal(model.name.span(), "`acceleration` was not emitted")
        })?;
    let shape = shape_acceleration(model, momentum, &reconstruction, acceleration);
    let mut functions = vec![
        momentum_of_state(model, cx, momentum)?,
        momentum_rhs(model, cx, momentum)?,
        momentum_input_matrix(model, cx, momentum)?,
        connection(model, cx, momentum)?,
        shape_matrix(
            model,
            cx,
            momentum,
            "locked_inertia",
            "The locked inertia `I(r) = e II e^T` on S: `p = I(r) Omega`.",
            &momentum.locked_inertia,
        )?,
        reconstruction,
        shape,
        momentum_rhs_jacobian(model, cx, momentum)?,
        body_velocity_jacobian(model, cx, momentum)?,
        basis_divisors(model, cx, momentum)?,
        connection_divisor(model, cx, momentum)?,
    ];
    if let Some(curvature) = &momentum.curvature {
        functions.push(connection_curvature(model, cx, momentum, curvature)?);
    }
    Ok((functions, section))
}

/// The divisors of the momentum basis `e(r)` that depend on the parameters
/// alone (the factors of its entries' denominators free of the shape), each
/// described: where one is zero the basis degenerates at every
/// configuration (the roller racer's, normalized by its value `d1 - d2` at
/// the defaults, at `d1 = d2`).
pub(super) fn divisors(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Vec<(String, ExprId)> {
    let parameters = model.parameter_symbols();
    let mut divisors: Vec<(String, ExprId)> = Vec::new();
    for entry in momentum.basis.entries() {
        for (factor, _) in entry.denominator() {
            let divisor = RationalFunction::from_poly(factor.clone());
            let expression = cx.expression_of(&divisor);
            let constant = cx
                .free_symbols(expression)
                .iter()
                .all(|symbol| parameters.contains(symbol));
            if constant && !divisors.iter().any(|(_, e)| *e == expression) {
                let text = cx.display(expression).to_string();
                let description =
                    format!("a division in the momentum basis e(r): {text} must not vanish");
                divisors.push((description, expression));
            }
        }
    }
    divisors
}

/// `basis_divisors()`: the values of [`divisors`].
fn basis_divisors(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let outputs: Vec<ExprId> = divisors(model, cx, momentum)
        .into_iter()
        .map(|(_, expression)| expression)
        .collect();
    let signature = Signature {
        name: "basis_divisors",
        doc: "The divisors of the momentum basis `e(r)` that depend on the parameters \
              alone, in the order of `BASIS_DIVISORS`: where one is zero the basis \
              degenerates at every configuration."
            .to_string(),
        arguments: Vec::new(),
        returns: vector_type(outputs.len()),
    };
    item(model, cx, signature, &outputs, vector_literal)
}

/// `BASIS_DIVISORS`: the description of each of [`divisors`].
pub(super) fn divisors_constant(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> TokenStream {
    let descriptions: Vec<String> = divisors(model, cx, momentum)
        .into_iter()
        .map(|(description, _)| description)
        .collect();
    let count = descriptions.len();
    quote! {
        /// The divisors of the momentum basis `e(r)` that depend on the
        /// parameters alone, described (`basis_divisors` gives their values).
        pub const BASIS_DIVISORS: [&'static ::core::primitive::str; #count] = [#(#descriptions),*];
    }
}

/// The report's momentum section for a model with a symmetry whose
/// momentum equation is not derived ([`crate::derive::MOMENTUM_WITH_HOLONOMIC`]).
pub(super) fn omitted() -> Section {
    let mut section = Section::new(TITLE);
    section.line(crate::derive::MOMENTUM_WITH_HOLONOMIC);
    section
}

fn report_section(model: &Model, cx: &mut Context, momentum: &Momentum) -> Section {
    let mut section = Section::new(TITLE);
    let shape: Vec<&str> = momentum
        .shape
        .iter()
        .map(|&i| model.coordinates[i].declared.name.as_str())
        .collect();
    let momenta = match momentum.momenta.len() {
        0 => "none (S = 0: the constraints fix every group velocity)".to_string(),
        count => format!("p1..p{count}"),
    };
    section.line(format!(
        "shape r = ({}); momenta {momenta}",
        shape.join(", ")
    ));
    matrix_lines(cx, &mut section, "e", &momentum.basis);
    for (i, tensors) in momentum.coefficients.iter().enumerate() {
        let i = i + 1;
        matrix_lines(cx, &mut section, &format!("H{i}"), &tensors.shape);
        matrix_lines(cx, &mut section, &format!("K{i}"), &tensors.mixed);
        matrix_lines(cx, &mut section, &format!("D{i}"), &tensors.momentum);
    }
    connection_lines(model, cx, &mut section, momentum);
    if momentum.input_coupling.is_zero() {
        section.line("inputs enter the momentum equation: no (h B = 0)");
    } else {
        section.line("inputs enter the momentum equation: yes, pdot += (h B) u");
        matrix_lines(cx, &mut section, "h B", &momentum.input_coupling);
    }
    section
}

/// The connection's divisor, where it vanishes, and the curvature's
/// planes.
fn connection_lines(model: &Model, cx: &mut Context, section: &mut Section, momentum: &Momentum) {
    let denominator = cx.expression_of(&momentum.connection_quotient.denominator);
    let shown = cx.display(denominator).to_string();
    section.line(format!(
        "connection A_nh = N / d by Cramer's rule, singular where d = 0: d = {shown}"
    ));
    let Some(curvature) = &momentum.curvature else {
        return;
    };
    let names: Vec<&str> = momentum
        .shape
        .iter()
        .map(|&i| model.coordinates[i].declared.name.as_str())
        .collect();
    let points: Vec<String> = (momentum.singular_shapes.iter().take(3))
        .map(|q| {
            let values: Vec<String> = (momentum.shape.iter().zip(&names))
                .map(|(&i, name)| format!("{name} = {:.4}", q[i]))
                .collect();
            values.join(", ")
        })
        .collect();
    section.line(match points.is_empty() {
        true => format!(
            "  singular shapes found ({} random lines, parameters at their defaults): none",
            crate::derive::constraints::charts::LINES
        ),
        false => format!(
            "  singular shapes found ({} random lines, parameters at their defaults): {}, e.g. {}",
            crate::derive::constraints::charts::LINES,
            momentum.singular_shapes.len(),
            points.join("; ")
        ),
    });
    let planes: Vec<String> = (curvature.planes.iter())
        .map(|&(i, j)| format!("({}, {})", names[i], names[j]))
        .collect();
    section.line(format!(
        "principally kinematic: curvature F = -dA + [A, A] on the planes {} (connection_curvature)",
        planes.join(", ")
    ));
}

/// One line per row of `matrix`: `  name row i: [..]`.
fn matrix_lines(cx: &mut Context, section: &mut Section, name: &str, matrix: &Matrix) {
    let entries = matrix.to_expressions(cx);
    for (i, row) in entries.chunks(matrix.columns().max(1)).enumerate() {
        let shown: Vec<String> = row.iter().map(|&e| cx.display(e).to_string()).collect();
        section.line(format!("  {name} row {}: [{}]", i + 1, shown.join(", ")));
    }
}

fn shape_argument(model: &Model, momentum: &Momentum) -> Argument {
    Argument {
        name: "r",
        symbols: momentum
            .shape
            .iter()
            .map(|&i| model.coordinates[i].symbol)
            .collect(),
    }
}

fn reduced_arguments(model: &Model, momentum: &Momentum) -> Vec<Argument> {
    vec![
        shape_argument(model, momentum),
        Argument {
            name: "rdot",
            symbols: momentum.shape_velocities.clone(),
        },
        Argument {
            name: "p",
            symbols: momentum.momenta.clone(),
        },
    ]
}

/// An item returning the vector `entries`.
fn vector_item(
    model: &Model,
    cx: &mut Context,
    signature: Signature,
    entries: &[RationalFunction],
) -> Result<Function, Diagnostics> {
    let outputs: Vec<_> = entries
        .iter()
        .map(|entry| cx.expression_of(entry))
        .collect();
    item(model, cx, signature, &outputs, vector_literal)
}

fn momentum_of_state(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let signature = Signature {
        name: "momentum",
        doc: "The nonholonomic momentum `p_i = <dL/dqdot, h_i(q)>`, `h_i = (R(theta) e_i(r), 0)` \
              (MATH.md section 4; the basis `e` is printed in `REPORT`)."
            .to_string(),
        arguments: vec![coordinates(model), velocities(model)],
        returns: vector_type(momentum.momenta.len()),
    };
    vector_item(model, cx, signature, &momentum.momentum)
}

fn momentum_rhs(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let signature = Signature {
        name: "momentum_rhs",
        doc: "The momentum equation `pdot = rdot^T H rdot + rdot^T K p + p^T D p` \
              (Koon & Marsden 1.2; `H`, `K`, `D` are printed in `REPORT`), without inputs: \
              add `momentum_input_matrix(q) u`."
            .to_string(),
        arguments: reduced_arguments(model, momentum),
        returns: vector_type(momentum.momenta.len()),
    };
    vector_item(model, cx, signature, &momentum.rhs)
}

fn body_velocity(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let signature = Signature {
        name: "body_velocity",
        doc: "The reconstruction `xi = g^-1 gdot = -A_nh(r) rdot + e(r)^T I(r)^-1 p` \
              (Koon & Marsden 1.1), in the body frame: `(v1, v2, omega)` for `se2`, \
              the velocity for an abelian factor, factor by factor; `A_nh` as `N / d` \
              by Cramer's rule."
            .to_string(),
        arguments: reduced_arguments(model, momentum),
        returns: vector_type(momentum.basis.columns()),
    };
    let quotient = &momentum.connection_quotient;
    let nr = momentum.shape.len();
    let denominator = cx.expression_of(&quotient.denominator);
    let mut outputs = Vec::with_capacity(quotient.numerators.rows());
    for (i, vertical) in momentum.vertical_velocity.iter().enumerate() {
        let terms: Vec<ExprId> = (0..nr)
            .map(|j| {
                let entry = cx.expression_of(quotient.numerators.get(i, j));
                let rate = cx.symbol(momentum.shape_velocities[j]);
                cx.mul2(entry, rate)
            })
            .collect();
        let horizontal = cx.add(&terms);
        let horizontal = quotient_of(model, cx, horizontal, denominator)?;
        let vertical = cx.expression_of(vertical);
        outputs.push(cx.sub(vertical, horizontal));
    }
    item(model, cx, signature, &outputs, vector_literal)
}

/// `numerator / denominator` as an expression, not brought to normal form.
fn quotient_of(
    model: &Model,
    cx: &mut Context,
    numerator: ExprId,
    denominator: ExprId,
) -> Result<ExprId, Diagnostics> {
    cx.div(numerator, denominator)
        .map_err(|error| Diagnostics::internal(model.name.span(), error.to_string()))
}

/// `nonholonomic_connection(r)`: `A_nh = N / d`, entry by entry.
fn connection(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let quotient = &momentum.connection_quotient;
    let denominator = cx.expression_of(&quotient.denominator);
    let outputs = quotient_entries(model, cx, &quotient.numerators, denominator)?;
    let doc = "The nonholonomic connection `A_nh(r)`: the horizontal body velocity is \
               `-A_nh(r) rdot` (Koon & Marsden 1.1); the geometric phase of a shape loop is \
               built from it. Computed as `N(r) / d(r)` by Cramer's rule, finite wherever \
               the connection is defined.";
    let size = (quotient.numerators.rows(), quotient.numerators.columns());
    let name = "nonholonomic_connection";
    shape_rows_item(model, cx, momentum, (name, doc.to_string()), &outputs, size)
}

/// `connection_curvature(r)`: `F = P / d^2`, one column per plane of shape
/// coordinates.
fn connection_curvature(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
    curvature: &Curvature,
) -> Result<Function, Diagnostics> {
    let denominator = cx.expression_of(&momentum.connection_quotient.denominator);
    let square = cx.mul2(denominator, denominator);
    let outputs = quotient_entries(model, cx, &curvature.numerators, square)?;
    let names: Vec<String> = momentum
        .shape
        .iter()
        .map(|&i| model.coordinates[i].declared.name.clone())
        .collect();
    let planes: Vec<String> = curvature
        .planes
        .iter()
        .map(|&(i, j)| format!("({}, {})", names[i], names[j]))
        .collect();
    let doc = format!(
        "The curvature of the local connection of a principally kinematic model, \
         `F_ij = -(dA_j/dr_i - dA_i/dr_j) + [A_i, A_j]` (`A_i` the i-th column of \
         `A_nh`; Hatton & Choset 2011): a loop of signed area `a` around `r` in the \
         plane `(r_i, r_j)` moves the body by about `F_ij(r) a`, and turns it by \
         exactly the integral of the rotation entry over the enclosed area. Rows as \
         `body_velocity`, columns the planes {}.",
        planes.join(", ")
    );
    let size = (curvature.numerators.rows(), curvature.numerators.columns());
    shape_rows_item(
        model,
        cx,
        momentum,
        ("connection_curvature", doc),
        &outputs,
        size,
    )
}

/// `connection_divisor(r)`: `d` and its gradient `dd/dr`.
fn connection_divisor(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let quotient = &momentum.connection_quotient;
    let divisor = std::iter::once(&quotient.denominator);
    let outputs: Vec<ExprId> = (divisor.chain(&quotient.divisor_gradient))
        .map(|entry| cx.expression_of(entry))
        .collect();
    let signature = Signature {
        name: "connection_divisor",
        doc: "The divisor `d(r)` of the connection `A_nh = N / d` (Cramer's rule: \
              `d = det S`), then its gradient `dd/dr`: the connection is singular where \
              `d = 0`."
            .to_string(),
        arguments: vec![shape_argument(model, momentum)],
        returns: vector_type(outputs.len()),
    };
    item(model, cx, signature, &outputs, vector_literal)
}

/// Each entry of `numerators` over `denominator`, row-major.
fn quotient_entries(
    model: &Model,
    cx: &mut Context,
    numerators: &Matrix,
    denominator: ExprId,
) -> Result<Vec<ExprId>, Diagnostics> {
    numerators
        .entries()
        .iter()
        .map(|entry| {
            let numerator = cx.expression_of(entry);
            quotient_of(model, cx, numerator, denominator)
        })
        .collect()
}

/// `momentum_rhs_jacobian(r, rdot, p)`: `d pdot / d(r, rdot, p)`.
fn momentum_rhs_jacobian(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let jacobian = &momentum.sensitivity.momentum;
    let (rows, columns) = (jacobian.rows(), jacobian.columns());
    let outputs: Vec<ExprId> = (jacobian.entries().iter())
        .map(|entry| cx.expression_of(entry))
        .collect();
    let signature = Signature {
        name: "momentum_rhs_jacobian",
        doc: "The Jacobian of `momentum_rhs` in its arguments: columns `r`, then \
              `rdot`, then `p` (exact derivatives; a gait's forward sensitivities)."
            .to_string(),
        arguments: reduced_arguments(model, momentum),
        returns: matrix_type(rows, columns),
    };
    item(model, cx, signature, &outputs, |values| {
        rows_literal(values, rows, columns)
    })
}

/// `body_velocity_jacobian(r, rdot, p)`: `d xi / d(r, rdot, p) = P / d^2 + V`.
fn body_velocity_jacobian(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let sensitivity = &momentum.sensitivity;
    let (rows, columns) = (sensitivity.quotient.rows(), sensitivity.quotient.columns());
    let denominator = cx.expression_of(&momentum.connection_quotient.denominator);
    let square = cx.mul2(denominator, denominator);
    let quotients = quotient_entries(model, cx, &sensitivity.quotient, square)?;
    let outputs: Vec<ExprId> = (quotients.into_iter().zip(sensitivity.vertical.entries()))
        .map(|(quotient, vertical)| {
            let vertical = cx.expression_of(vertical);
            cx.add(&[quotient, vertical])
        })
        .collect();
    let signature = Signature {
        name: "body_velocity_jacobian",
        doc: "The Jacobian of `body_velocity` in its arguments: columns `r`, then \
              `rdot`, then `p` (exact derivatives of `-(N rdot) / d + e^T I^-1 p`; a \
              gait's forward sensitivities)."
            .to_string(),
        arguments: reduced_arguments(model, momentum),
        returns: matrix_type(rows, columns),
    };
    item(model, cx, signature, &outputs, |values| {
        rows_literal(values, rows, columns)
    })
}

/// `shape_acceleration(r, rdot, p, u)`: `acceleration` at
/// `q = (0, r)`, `qdot = (xi(r, rdot, p), rdot)`, its shape rows.
fn shape_acceleration(
    model: &Model,
    momentum: &Momentum,
    reconstruction: &Function,
    acceleration: &Function,
) -> Function {
    let f64 = f64_type();
    let (n, nr, mp, p) = (
        model.n(),
        momentum.shape.len(),
        momentum.momenta.len(),
        model.p(),
    );
    let mut q: Vec<TokenStream> = vec![quote!(0.0); n];
    let mut qdot = q.clone();
    let mut group = 0;
    for i in 0..n {
        match momentum.shape.iter().position(|&s| s == i) {
            Some(a) => {
                let a = Literal::usize_unsuffixed(a);
                q[i] = quote!(r[#a]);
                qdot[i] = quote!(rdot[#a]);
            }
            None => {
                let j = Literal::usize_unsuffixed(group);
                qdot[i] = quote!(xi[#j]);
                group += 1;
            }
        }
    }
    let rows = momentum.shape.iter().map(|&i| Literal::usize_unsuffixed(i));
    let body = if nr == 0 {
        quote!([])
    } else {
        quote! {
            let xi = self.body_velocity(r, rdot, p);
            let (qddot, _) = self.acceleration(&[#(#q),*], &[#(#qdot),*], u);
            [#(qddot[#rows]),*]
        }
    };
    let names = if nr == 0 {
        [quote!(_r), quote!(_rdot), quote!(_p), quote!(_u)]
    } else {
        [quote!(r), quote!(rdot), quote!(p), quote!(u)]
    };
    let [r, rdot, p_name, u] = names;
    let item = quote! {
        /// The shape equations (Koon & Marsden 1.3): the shape rows of
        /// `acceleration` at the group identity with the reconstructed
        /// velocity `qdot = (body_velocity(r, rdot, p), rdot)` and inputs `u`.
        pub fn shape_acceleration(
            &self,
            #r: &[#f64; #nr],
            #rdot: &[#f64; #nr],
            #p_name: &[#f64; #mp],
            #u: &[#f64; #p],
        ) -> [#f64; #nr] {
            #body
        }
    };
    let operations = OperationCount {
        before_cse: reconstruction.operations.before_cse + acceleration.operations.before_cse,
        after_cse: reconstruction.operations.after_cse + acceleration.operations.after_cse,
    };
    Function {
        name: "shape_acceleration",
        item,
        operations,
        lowered: None,
    }
}

fn momentum_input_matrix(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
) -> Result<Function, Diagnostics> {
    let signature = Signature {
        name: "momentum_input_matrix",
        doc: "`h(q) B(q)`, mp x p: the inputs' term of the momentum equation, \
              `pdot = momentum_rhs(r, rdot, p) + momentum_input_matrix(q) u`."
            .to_string(),
        arguments: vec![coordinates(model)],
        returns: matrix_type(
            momentum.input_coupling.rows(),
            momentum.input_coupling.columns(),
        ),
    };
    matrix_item(model, cx, signature, &momentum.input_coupling)
}

/// An item of the shape `r` returning `matrix`.
fn shape_matrix(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
    name: &'static str,
    doc: &str,
    matrix: &Matrix,
) -> Result<Function, Diagnostics> {
    let outputs: Vec<ExprId> = (matrix.entries().iter())
        .map(|entry| cx.expression_of(entry))
        .collect();
    let size = (matrix.rows(), matrix.columns());
    shape_rows_item(model, cx, momentum, (name, doc.to_string()), &outputs, size)
}

/// An item of the shape `r` returning the `rows x columns` matrix of
/// `outputs`, row-major.
fn shape_rows_item(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
    (name, doc): (&'static str, String),
    outputs: &[ExprId],
    (rows, columns): (usize, usize),
) -> Result<Function, Diagnostics> {
    let signature = Signature {
        name,
        doc,
        arguments: vec![shape_argument(model, momentum)],
        returns: matrix_type(rows, columns),
    };
    item(model, cx, signature, outputs, |values| {
        rows_literal(values, rows, columns)
    })
}

/// An item returning `matrix`.
fn matrix_item(
    model: &Model,
    cx: &mut Context,
    signature: Signature,
    matrix: &Matrix,
) -> Result<Function, Diagnostics> {
    let (rows, columns) = (matrix.rows(), matrix.columns());
    let outputs: Vec<_> = matrix
        .entries()
        .iter()
        .map(|entry| cx.expression_of(entry))
        .collect();
    item(model, cx, signature, &outputs, |values| {
        rows_literal(values, rows, columns)
    })
}
