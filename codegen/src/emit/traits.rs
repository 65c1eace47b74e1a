//! Implementations of the runtime's formulation traits
//! (`::chaplygin::runtime::system::ReducedPortHamiltonian`,
//! `LagrangeDalembert`, `Holonomic`, `ModelNames`, and with a symmetry
//! `MomentumEquations`) for the generated struct, so that
//! every integrator of the runtime runs on it. Each method forwards to the
//! inherent item of the same name (inherent items take precedence in
//! `Type::item` paths); the regularity measures call
//! `::chaplygin::runtime::monitor` with the model's sizes.

use super::f64_type;
use crate::derive::constraints::{ChartFit, Elimination};
use crate::model::{GroupFactor, Model, Symmetry};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// `CHARTS`, the dependent speeds of each chart of D derived at build time,
/// when there are several and none is a declared momentum basis (nothing
/// otherwise).
pub(crate) fn charts_constant(model: &Model, charts: &[ChartFit]) -> TokenStream {
    let dependent: Vec<&Vec<usize>> = charts
        .iter()
        .filter_map(|fit| match fit {
            ChartFit::Coordinates(dependent, _) | ChartFit::Body(dependent, _) => Some(dependent),
            ChartFit::Declared => None,
        })
        .collect();
    if charts.len() < 2 || dependent.len() < charts.len() {
        return TokenStream::new();
    }
    let (c, count) = (model.c(), charts.len());
    let rows = dependent.iter().map(|dependent| {
        let columns = dependent.iter().map(|&j| Literal::usize_unsuffixed(j));
        quote!([#(#columns),*])
    });
    quote! {
        /// The charts of D derived at build time: each chart's dependent
        /// speeds (coordinate indices, or body-velocity indices for a
        /// basis chosen in the body frame), chart 0 the basis the other
        /// items use. The items named `..._chart{i}` are the reduced form
        /// in chart `i`.
        pub const CHARTS: [[::core::primitive::usize; #c]; #count] = [#(#rows),*];
    }
}

/// What a chart method computes in a run-time chart: an expression of
/// `chart` (a `chaplygin_runtime::partition::RuntimeChart`), and its value
/// for an index past the last run-time chart.
struct Runtime {
    value: TokenStream,
    missing: TokenStream,
}

/// The `match` calling `item` (`item_chart{i}` in generated chart `i`)
/// with `arguments`, and `runtime` in the run-time charts.
fn in_chart(
    model: &Model,
    count: usize,
    chart: TokenStream,
    (item, arguments): (&str, TokenStream),
    runtime: Runtime,
) -> TokenStream {
    let name = &model.name;
    let base = proc_macro2::Ident::new(item, proc_macro2::Span::call_site());
    let arms = (1..count).map(|i| {
        let charted =
            proc_macro2::Ident::new(&format!("{item}_chart{i}"), proc_macro2::Span::call_site());
        let i = Literal::usize_unsuffixed(i);
        quote!(#i => #name::#charted(self, #arguments),)
    });
    let generated = Literal::usize_unsuffixed(count);
    let with_chart = with_chart(model);
    let Runtime { value, missing } = runtime;
    quote! {
        match #chart {
            0 => #name::#base(self, #arguments),
            #(#arms)*
            index => #with_chart(self, index - #generated, |chart| #value).unwrap_or(#missing),
        }
    }
}

/// `chaplygin_runtime::partition::with_chart` at the model's sizes.
fn with_chart(model: &Model) -> TokenStream {
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    quote!(::chaplygin::runtime::partition::with_chart::<Self, #n, #c, #k, #p, _>)
}

/// The expression of a chart's fit at the configuration `q` (and state `x`).
fn fit_of(model: &Model, fit: &ChartFit) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, c, p) = (model.n(), model.c(), model.p());
    let monitor = quote!(::chaplygin::runtime::monitor);
    let columns = |dependent: &[usize]| {
        let columns = dependent.iter().map(|&j| Literal::usize_unsuffixed(j));
        quote!([#(#columns),*])
    };
    match fit {
        ChartFit::Coordinates(dependent, Elimination::Exact) => {
            let dependent = columns(dependent);
            quote!(#monitor::pivot_ratio(&#name::constraint_matrix(self, &q), &#dependent))
        }
        ChartFit::Coordinates(dependent, Elimination::InOrder) => {
            let dependent = columns(dependent);
            quote!(#monitor::elimination_ratio(
                &::chaplygin::runtime::arrays::matrix_from_rows(&#name::constraint_matrix(self, &q)),
                &#dependent,
            ))
        }
        ChartFit::Body(dependent, elimination) => {
            let dependent = columns(dependent);
            let ratio = match elimination {
                Elimination::Exact => {
                    quote!(#monitor::signed_pivot_ratio(&rows, &#dependent).abs())
                }
                Elimination::InOrder => quote!(#monitor::elimination_ratio(&rows, &#dependent)),
            };
            quote! {{
                let identity = #monitor::at_group_identity(
                    <#name as ::chaplygin::runtime::linearize::Linearization<#n, #c, #p>>::symmetry(self),
                    q,
                );
                let rows = ::chaplygin::runtime::arrays::matrix_from_rows(
                    &#name::constraint_matrix(self, &identity),
                );
                #ratio
            }}
        }
        ChartFit::Declared => {
            let (s, k) = (n + model.k(), model.k());
            quote! {{
                let energies = |q: &[#f64; #n]| -> [#f64; #k] {
                    let rest = #name::energy(self, q, &[0.0; #n]);
                    ::core::array::from_fn(|j| {
                        let unit: [#f64; #k] = ::core::array::from_fn(|i| #f64::from(i == j));
                        #name::energy(self, q, &#name::velocities(self, q, &unit)) - rest
                    })
                };
                #monitor::declared_basis_fit(
                    <#name as ::chaplygin::runtime::system::ReducedPortHamiltonian<#s, #p>>::regularity(self, x),
                    &energies(&q),
                    &energies(&[0.0; #n]),
                )
            }}
        }
    }
}

/// The `ReducedPortHamiltonian` chart methods of a model with constraint
/// rows: its generated charts `charts` and the run-time charts after them
/// (nothing without constraints: the trait's defaults, one chart).
fn chart_methods(model: &Model, charts: &[ChartFit]) -> TokenStream {
    if model.c() == 0 {
        return TokenStream::new();
    }
    let count = charts.len();
    let f64 = f64_type();
    let (n, k, p) = (model.n(), model.k(), model.p());
    let s = n + k;
    let nan = quote!(#f64::NAN);
    let call = |item: &str, arguments: TokenStream, runtime: Runtime| {
        in_chart(model, count, quote!(chart), (item, arguments), runtime)
    };
    let vector = |size: usize, fill: TokenStream| Runtime {
        value: quote!(::chaplygin::runtime::partition::vector::<#size>(|out| #fill)),
        missing: quote!([#nan; #size]),
    };
    let matrix = |rows: usize, columns: usize, fill: TokenStream| Runtime {
        value: quote!(::chaplygin::runtime::partition::matrix::<#rows, #columns>(|out| #fill)),
        missing: quote!([[#nan; #columns]; #rows]),
    };
    let scalar = |value: TokenStream, missing: TokenStream| Runtime { value, missing };
    let velocities_from = in_chart(
        model,
        count,
        quote!(from),
        ("velocities", quote!(&q, &alpha)),
        vector(n, quote!(chart.velocities(&q, &alpha, out))),
    );
    let momenta_to = in_chart(
        model,
        count,
        quote!(to),
        ("momenta", quote!(&q, &qdot)),
        vector(k, quote!(chart.momenta(&qdot, out))),
    );
    let rhs = call(
        "reduced_rhs",
        quote!(x, u),
        vector(s, quote!(chart.rhs(x, u, out))),
    );
    let rhs_jacobian = call(
        "reduced_rhs_jacobian",
        quote!(x, u),
        matrix(s, s, quote!(chart.rhs_jacobian(x, u, out))),
    );
    let hamiltonian = call(
        "hamiltonian",
        quote!(x),
        scalar(quote!(chart.hamiltonian(x)), nan.clone()),
    );
    let gradient = call(
        "hamiltonian_gradient",
        quote!(x),
        vector(s, quote!(chart.hamiltonian_gradient(x, out))),
    );
    let structure = call(
        "structure_matrix",
        quote!(x),
        matrix(s, s, quote!(chart.structure_matrix(x, out))),
    );
    let input_matrix = call(
        "input_matrix",
        quote!(x),
        matrix(s, p, quote!(chart.input_matrix(x, out))),
    );
    let velocities = call(
        "velocities",
        quote!(&q, &alpha),
        vector(n, quote!(chart.velocities(&q, &alpha, out))),
    );
    let unit_velocities = call(
        "velocities",
        quote!(&q, &unit),
        vector(n, quote!(chart.velocities(&q, &unit, out))),
    );
    let fits = charts.iter().enumerate().map(|(i, fit)| {
        let i = Literal::usize_unsuffixed(i);
        let fit = fit_of(model, fit);
        quote!(#i => #fit,)
    });
    let generated = Literal::usize_unsuffixed(count);
    let with_chart = with_chart(model);
    let (c, name) = (model.c(), &model.name);
    let configuration = quote!(let q: [#f64; #n] = ::core::array::from_fn(|i| x[i]););
    quote! {
        fn charts(&self) -> ::core::primitive::usize {
            #count
        }
        fn switches_charts(&self) -> ::core::primitive::bool {
            true
        }
        fn chart_fit(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> #f64 {
            #configuration
            match chart {
                #(#fits)*
                index => #with_chart(self, index - #generated, |chart| chart.fit(&q)).unwrap_or(0.0),
            }
        }
        fn pivoted_chart(&self, x: &[#f64; #s]) -> ::core::option::Option<::core::primitive::usize> {
            #configuration
            let model = ::chaplygin::runtime::partition::Compiled::<Self, #n, #c, #k, #p>(self);
            ::chaplygin::runtime::partition::pivoted(&model, &q).map(|index| #generated + index)
        }
        fn change_chart(
            &self,
            from: ::core::primitive::usize,
            to: ::core::primitive::usize,
            x: &[#f64; #s],
        ) -> [#f64; #s] {
            #configuration
            let alpha: [#f64; #k] = ::core::array::from_fn(|i| x[#n + i]);
            let qdot = #velocities_from;
            let alpha = #momenta_to;
            ::core::array::from_fn(|i| if i < #n { q[i] } else { alpha[i - #n] })
        }
        fn chart_rhs(&self, chart: ::core::primitive::usize, x: &[#f64; #s], u: &[#f64; #p]) -> [#f64; #s] {
            #rhs
        }
        fn chart_rhs_jacobian(
            &self,
            chart: ::core::primitive::usize,
            x: &[#f64; #s],
            u: &[#f64; #p],
        ) -> [[#f64; #s]; #s] {
            #rhs_jacobian
        }
        fn chart_hamiltonian(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> #f64 {
            #hamiltonian
        }
        fn chart_hamiltonian_gradient(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> [#f64; #s] {
            #gradient
        }
        fn chart_structure_matrix(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> [[#f64; #s]; #s] {
            #structure
        }
        fn chart_input_matrix(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> [[#f64; #p]; #s] {
            #input_matrix
        }
        fn chart_constraint_violation(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> #f64 {
            #configuration
            let alpha: [#f64; #k] = ::core::array::from_fn(|i| x[#n + i]);
            let qdot = #velocities;
            #name::constraint_residual(self, &q, &qdot)
                .iter()
                .fold(0.0, |worst: #f64, r| worst.max(r.abs()))
        }
        fn chart_regularity(&self, chart: ::core::primitive::usize, x: &[#f64; #s]) -> #f64 {
            #configuration
            let basis: [[#f64; #n]; #k] = ::core::array::from_fn(|j| {
                let unit: [#f64; #k] = ::core::array::from_fn(|i| #f64::from(i == j));
                #unit_velocities
            });
            ::chaplygin::runtime::monitor::reduced_regularity(&#name::constraint_matrix(self, &q), &basis)
        }
    }
}

/// The runtime trait impls of `model`'s struct, with the chart methods
/// when `charts` (each chart's dependent speeds) has several, and
/// `MomentumEquations` when `momentum` was derived.
pub(crate) fn implementations(model: &Model, charts: &[ChartFit], momentum: bool) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    let s = n + k;
    let h = model.mechanism.holonomic.len();
    let parameter_names = model
        .parameters
        .iter()
        .map(|p| p.variable.declared.name.as_str());
    let parameter_fields = model.parameters.iter().map(|p| {
        proc_macro2::Ident::new(&p.variable.declared.name, proc_macro2::Span::call_site())
    });
    let velocities_of_state = quote! {{
        let q: [#f64; #n] = ::core::array::from_fn(|i| x[i]);
        let alpha: [#f64; #k] = ::core::array::from_fn(|i| x[#n + i]);
        let qdot = #name::velocities(self, &q, &alpha);
        (q, qdot)
    }};
    let system = quote!(::chaplygin::runtime::system);
    let momentum_equations = model
        .symmetry
        .as_ref()
        .filter(|_| momentum)
        .map(|symmetry| momentum_equations(model, symmetry));
    let chart_methods = chart_methods(model, charts);
    let chart_momenta = (model.c() > 0).then(|| {
        let (count, vector) = (charts.len(), |size: usize, fill: TokenStream| Runtime {
            value: quote!(::chaplygin::runtime::partition::vector::<#size>(|out| #fill)),
            missing: quote!([#f64::NAN; #size]),
        });
        let momenta = in_chart(
            model,
            count,
            quote!(chart),
            ("momenta", quote!(q, qdot)),
            vector(k, quote!(chart.momenta(qdot, out))),
        );
        let velocities = in_chart(
            model,
            count,
            quote!(chart),
            ("velocities", quote!(q, alpha)),
            vector(n, quote!(chart.velocities(q, alpha, out))),
        );
        quote! {
            fn chart_momenta(
                &self,
                chart: ::core::primitive::usize,
                q: &[#f64; #n],
                qdot: &[#f64; #n],
            ) -> [#f64; #k] {
                #momenta
            }
            fn chart_velocities(
                &self,
                chart: ::core::primitive::usize,
                q: &[#f64; #n],
                alpha: &[#f64; #k],
            ) -> [#f64; #n] {
                #velocities
            }
        }
    });
    quote! {
        #momentum_equations

        impl #system::ReducedPortHamiltonian<#s, #p> for #name {
            #chart_methods
            fn reduced_rhs(&self, x: &[#f64; #s], u: &[#f64; #p]) -> [#f64; #s] {
                #name::reduced_rhs(self, x, u)
            }
            fn reduced_rhs_jacobian(&self, x: &[#f64; #s], u: &[#f64; #p]) -> [[#f64; #s]; #s] {
                #name::reduced_rhs_jacobian(self, x, u)
            }
            fn hamiltonian(&self, x: &[#f64; #s]) -> #f64 {
                #name::hamiltonian(self, x)
            }
            fn hamiltonian_gradient(&self, x: &[#f64; #s]) -> [#f64; #s] {
                #name::hamiltonian_gradient(self, x)
            }
            fn structure_matrix(&self, x: &[#f64; #s]) -> [[#f64; #s]; #s] {
                #name::structure_matrix(self, x)
            }
            fn input_matrix(&self, x: &[#f64; #s]) -> [[#f64; #p]; #s] {
                #name::input_matrix(self, x)
            }
            fn output(&self, x: &[#f64; #s]) -> [#f64; #p] {
                #name::output(self, x)
            }
            fn output_jacobian(&self, x: &[#f64; #s]) -> [[#f64; #s]; #p] {
                #name::output_jacobian(self, x)
            }
            fn constraint_violation(&self, x: &[#f64; #s]) -> #f64 {
                let (q, qdot) = #velocities_of_state;
                #name::constraint_residual(self, &q, &qdot)
                    .iter()
                    .fold(0.0, |worst: #f64, r| worst.max(r.abs()))
            }
            fn regularity(&self, x: &[#f64; #s]) -> #f64 {
                let q: [#f64; #n] = ::core::array::from_fn(|i| x[i]);
                let basis: [[#f64; #n]; #k] = ::core::array::from_fn(|j| {
                    let unit: [#f64; #k] = ::core::array::from_fn(|i| #f64::from(i == j));
                    #name::velocities(self, &q, &unit)
                });
                ::chaplygin::runtime::monitor::reduced_regularity(
                    &#name::constraint_matrix(self, &q),
                    &basis,
                )
            }
        }

        impl #system::Momenta<#n, #k> for #name {
            #chart_momenta
            fn momenta(&self, q: &[#f64; #n], qdot: &[#f64; #n]) -> [#f64; #k] {
                #name::momenta(self, q, qdot)
            }
            fn velocities(&self, q: &[#f64; #n], alpha: &[#f64; #k]) -> [#f64; #n] {
                #name::velocities(self, q, alpha)
            }
        }

        impl #system::Parameters for #name {
            fn parameter_names(&self) -> &[&::core::primitive::str] {
                &#name::PARAMETERS
            }
            fn parameter_mut(
                &mut self,
                name: &::core::primitive::str,
            ) -> ::core::option::Option<&mut #f64> {
                match name {
                    #(#parameter_names => ::core::option::Option::Some(&mut self.#parameter_fields),)*
                    _ => ::core::option::Option::None,
                }
            }
        }

        impl #system::ModelNames for #name {
            fn coordinate_names(&self) -> &[&::core::primitive::str] {
                &#name::COORDINATES
            }
            fn momentum_names(&self) -> &[&::core::primitive::str] {
                &#name::MOMENTA
            }
            fn input_names(&self) -> &[&::core::primitive::str] {
                &#name::INPUTS
            }
            fn constraint_names(&self) -> &[&::core::primitive::str] {
                &#name::CONSTRAINTS
            }
        }

        impl #system::Domain for #name {
            fn guards(&self) -> &[(&::core::primitive::str, #system::Guard)] {
                &#name::DOMAIN
            }
            fn domain(&self, q: &[#f64], values: &mut [#f64]) {
                let q: [#f64; #n] = ::core::array::from_fn(|i| q[i]);
                values.copy_from_slice(&#name::domain(self, &q));
            }
            fn constraint_rows(&self, q: &[#f64], rows: &mut [#f64]) -> ::core::primitive::bool {
                let q: [#f64; #n] = ::core::array::from_fn(|i| q[i]);
                rows.copy_from_slice(#name::constraint_matrix(self, &q).as_flattened());
                true
            }
        }

        impl #system::Holonomic<#n, #h> for #name {
            fn holonomic_names(&self) -> [&::core::primitive::str; #h] {
                #name::HOLONOMIC
            }
            fn holonomic_residual(&self, q: &[#f64; #n]) -> [#f64; #h] {
                #name::holonomic_residual(self, q)
            }
            fn holonomic_jacobian(&self, q: &[#f64; #n]) -> [[#f64; #n]; #h] {
                #name::holonomic_jacobian(self, q)
            }
        }

        impl #system::LagrangeDalembert<#n, #c, #p> for #name {
            fn acceleration(
                &self,
                q: &[#f64; #n],
                qdot: &[#f64; #n],
                u: &[#f64; #p],
            ) -> ([#f64; #n], [#f64; #c]) {
                #name::acceleration(self, q, qdot, u)
            }
            fn energy(&self, q: &[#f64; #n], qdot: &[#f64; #n]) -> #f64 {
                #name::energy(self, q, qdot)
            }
            fn constraint_residual(&self, q: &[#f64; #n], qdot: &[#f64; #n]) -> [#f64; #c] {
                #name::constraint_residual(self, q, qdot)
            }
            fn constraint_regularity(&self, q: &[#f64; #n]) -> #f64 {
                ::chaplygin::runtime::monitor::constraint_regularity(
                    &#name::mass_matrix(self, q),
                    &#name::constraint_matrix(self, q),
                )
            }
        }
    }
}

/// `MomentumEquations<n, nr, mp, p>`: the momentum items, and the
/// reconstruction `qdot` from `body_velocity` (`R(theta) (v1, v2)` and
/// `omega` for an `se2` factor, the velocity for an abelian one, `rdot` on
/// the shape).
fn momentum_equations(model: &Model, symmetry: &Symmetry) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, p) = (model.n(), model.p());
    let group = symmetry.group_coordinates();
    let shape: Vec<usize> = (0..n).filter(|i| !group.contains(i)).collect();
    // The momenta span the group directions the constraints allow: the
    // derivation refuses constraints that restrict the shape velocities, so
    // the c constraint rows are independent on the group's dg directions.
    let (nr, mp) = (shape.len(), group.len() - model.c());
    let shape_indices = shape.iter().map(|&i| Literal::usize_unsuffixed(i));
    let group_velocities = group_velocities(&symmetry.factors);
    let shape_velocities = shape.iter().enumerate().map(|(a, &i)| {
        let (a, i) = (Literal::usize_unsuffixed(a), Literal::usize_unsuffixed(i));
        quote!(qdot[#i] = rdot[#a];)
    });
    let system = quote!(::chaplygin::runtime::system);
    quote! {
        impl #system::MomentumEquations<#n, #nr, #mp, #p> for #name {
            fn shape_indices(&self) -> [::core::primitive::usize; #nr] {
                [#(#shape_indices),*]
            }
            fn basis_divisor_names(&self) -> &[&::core::primitive::str] {
                &#name::BASIS_DIVISORS
            }
            fn basis_divisors(&self, values: &mut [#f64]) {
                values.copy_from_slice(&#name::basis_divisors(self));
            }
            fn momentum(&self, q: &[#f64; #n], qdot: &[#f64; #n]) -> [#f64; #mp] {
                #name::momentum(self, q, qdot)
            }
            fn momentum_rhs(&self, r: &[#f64; #nr], rdot: &[#f64; #nr], p: &[#f64; #mp]) -> [#f64; #mp] {
                #name::momentum_rhs(self, r, rdot, p)
            }
            fn momentum_input_matrix(&self, q: &[#f64; #n]) -> [[#f64; #p]; #mp] {
                #name::momentum_input_matrix(self, q)
            }
            fn shape_acceleration(
                &self,
                r: &[#f64; #nr],
                rdot: &[#f64; #nr],
                p: &[#f64; #mp],
                u: &[#f64; #p],
            ) -> [#f64; #nr] {
                #name::shape_acceleration(self, r, rdot, p, u)
            }
            fn reconstructed_velocity(
                &self,
                q: &[#f64; #n],
                rdot: &[#f64; #nr],
                p: &[#f64; #mp],
            ) -> [#f64; #n] {
                let r = <Self as #system::MomentumEquations<#n, #nr, #mp, #p>>::shape(self, q);
                let xi = #name::body_velocity(self, &r, rdot, p);
                let mut qdot = [0.0; #n];
                #(#group_velocities)*
                #(#shape_velocities)*
                qdot
            }
        }
    }
}

/// The statements setting the group coordinates' `qdot` from the body
/// velocity `xi`, factor by factor.
fn group_velocities(factors: &[GroupFactor]) -> Vec<TokenStream> {
    let mut offset = 0;
    factors
        .iter()
        .map(|factor| {
            let at = |i: usize| Literal::usize_unsuffixed(i);
            let first = at(offset);
            match *factor {
                GroupFactor::Se2 { x, y, theta } => {
                    let (second, third) = (at(offset + 1), at(offset + 2));
                    let (x, y, theta) = (at(x), at(y), at(theta));
                    offset += 3;
                    quote! {
                        let (sin, cos) = q[#theta].sin_cos();
                        qdot[#x] = cos * xi[#first] - sin * xi[#second];
                        qdot[#y] = sin * xi[#first] + cos * xi[#second];
                        qdot[#theta] = xi[#third];
                    }
                }
                GroupFactor::Translation(i) | GroupFactor::Rotation(i) => {
                    let i = at(i);
                    offset += 1;
                    quote!(qdot[#i] = xi[#first];)
                }
            }
        })
        .collect()
}
