//! Implementations of the runtime's formulation traits
//! (`::chaplygin::runtime::system::ReducedPortHamiltonian`,
//! `LagrangeDalembert` and `ModelNames`) for the generated struct, so that
//! every integrator of the runtime runs on it. Each method forwards to the
//! inherent item of the same name (inherent items take precedence in
//! `Type::item` paths); the regularity measures call
//! `::chaplygin::runtime::monitor` with the model's sizes.

use super::f64_type;
use crate::model::Model;
use proc_macro2::TokenStream;
use quote::quote;

/// The runtime trait impls of `model`'s struct.
pub(crate) fn implementations(model: &Model) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    let s = n + k;
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
    quote! {
        impl #system::ReducedPortHamiltonian<#s, #p> for #name {
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
            fn momenta(&self, q: &[#f64; #n], qdot: &[#f64; #n]) -> [#f64; #k] {
                #name::momenta(self, q, qdot)
            }
            fn velocities(&self, q: &[#f64; #n], alpha: &[#f64; #k]) -> [#f64; #n] {
                #name::velocities(self, q, alpha)
            }
        }

        impl #system::Parameters for #name {
            const PARAMETERS: &'static [&'static ::core::primitive::str] = &#name::PARAMETERS;
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
            const COORDINATES: &'static [&'static ::core::primitive::str] = &#name::COORDINATES;
            const MOMENTA: &'static [&'static ::core::primitive::str] = &#name::MOMENTA;
            const INPUTS: &'static [&'static ::core::primitive::str] = &#name::INPUTS;
            const CONSTRAINTS: &'static [&'static ::core::primitive::str] = &#name::CONSTRAINTS;
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
