//! A declared momentum basis: k independent rows spanning g(D).

use super::*;

impl Checker {
    // ----- momentum basis ------------------------------------------------

    /// A declared momentum basis: k = n - c independent rows spanning g(D),
    /// i.e. `A g^-1 h^T = 0` exactly.
    pub(super) fn momentum_basis(
        &mut self,
        section: Option<&&Section>,
        g: &Matrix,
        a: &Matrix,
        n: usize,
    ) -> Option<MomentumBasis> {
        let section = section?;
        let list = self.list(section)?;
        let k = n - a.rows();
        if list.items.len() != k {
            self.diagnostics.error(
                section.key.span(),
                format!(
                    "the momentum basis needs k = n - c = {n} - {} = {k} rows, found {}",
                    a.rows(),
                    list.items.len()
                ),
            );
            return None;
        }
        let mut names = Vec::new();
        let mut entries = Vec::new();
        for item in &list.items {
            let (declared, _) = self.named_item(item, "a momentum-basis row")?;
            let row = self.row_of_expressions(item, n, "a momentum-basis row")?;
            for expr in row {
                entries.push(self.velocity_free(
                    expr,
                    "a momentum-basis row depends on the configuration only: no velocities",
                )?);
            }
            names.push(declared);
        }
        let h = Matrix::new(k, n, entries).ok()?;
        if !self.rule_independent_rows(&h, &names, "momentum-basis row") {
            return None;
        }
        self.rule_spans_momenta(&h, g, a, &names)
            .then_some(MomentumBasis { names, rows: h })
    }

    /// Each row of h lies in g(D): the column `A g^-1 h_i^T` is exactly zero.
    pub(super) fn rule_spans_momenta(
        &mut self,
        h: &Matrix,
        g: &Matrix,
        a: &Matrix,
        names: &[Declared],
    ) -> bool {
        let atoms = self.store.atoms().clone();
        let Ok(product) = g
            .inverse(&atoms)
            .and_then(|inverse| a.mul(&inverse, &atoms))
            .and_then(|ag| ag.mul(&h.transpose(), &atoms))
        else {
            return false;
        };
        for (j, name) in names.iter().enumerate() {
            if (0..product.rows()).any(|i| !product.get(i, j).is_zero()) {
                self.diagnostics.error(
                    name.span,
                    format!(
                        "momentum-basis row `{}` is not in g(D): the momenta of allowed motions \
                         satisfy A g^-1 h^T = 0, and this row's column is not zero",
                        name.name
                    ),
                );
                return false;
            }
        }
        true
    }
}
