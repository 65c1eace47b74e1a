//! Implementations of the runtime's formulation traits
//! (`::chaplygin::runtime::system::ReducedPortHamiltonian` and
//! `LagrangeDalembert`) for the generated struct, so that every integrator of
//! the runtime runs on it. Each method forwards to the inherent item of the
//! same name (inherent items take precedence in `Type::item` paths).

use super::f64_type;
use crate::model::Model;
use proc_macro2::TokenStream;
use quote::quote;

/// The two trait impls of `model`'s struct.
pub(crate) fn implementations(model: &Model) -> TokenStream {
    let name = &model.name;
    let f64 = f64_type();
    let (n, c, p) = (model.n(), model.c(), model.p());
    let s = n + model.k();
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
            fn output(&self, x: &[#f64; #s]) -> [#f64; #p] {
                #name::output(self, x)
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
        }
    }
}
