//! Inputs: a force on a coordinate or a column of B(q).

use super::*;

impl Checker {
    // ----- inputs --------------------------------------------------------

    /// `(names, B)`: each input a force on a coordinate or a column of B.
    pub(super) fn inputs(
        &mut self,
        section: Option<&&Section>,
        coordinates: &[Variable],
    ) -> Option<(Vec<Declared>, Matrix)> {
        let n = coordinates.len();
        let Some(list) = section.and_then(|s| self.list(s)) else {
            return (section.is_none()).then(|| (Vec::new(), Matrix::zeros(n, 0)));
        };
        let mut names: Vec<Declared> = Vec::new();
        let mut columns = Vec::new();
        let mut ok = true;
        for item in &list.items {
            let Some((declared, value)) = self.named_item(item, "an input") else {
                ok = false;
                continue;
            };
            ok &= self.rule_unique_in_section(&names, &declared.name, declared.span);
            match self.input_column(item, value, coordinates) {
                Some(column) => columns.push(column),
                None => ok = false,
            }
            names.push(declared);
        }
        if !ok {
            return None;
        }
        let p = names.len();
        let mut b = Matrix::zeros(n, p);
        for (j, column) in columns.into_iter().enumerate() {
            for (i, entry) in column.into_iter().enumerate() {
                b.set(i, j, entry);
            }
        }
        Some((names, b))
    }

    /// An input names a coordinate, or gives a column of n velocity-free entries.
    pub(super) fn input_column(
        &mut self,
        item: &Item,
        value: &Value,
        coordinates: &[Variable],
    ) -> Option<Vec<RationalFunction>> {
        let n = coordinates.len();
        if let Value::Expr(Expr::Name(ident)) = value {
            let name = ident.to_string();
            let Some(index) = coordinates.iter().position(|c| c.declared.name == name) else {
                self.diagnostics.error(
                    ident.span(),
                    format!("an input acts on a coordinate, and `{name}` is not a coordinate (or give a column `[b_1, ..., b_n]`)"),
                );
                return None;
            };
            return Some(
                (0..n)
                    .map(|i| {
                        if i == index {
                            RationalFunction::one()
                        } else {
                            RationalFunction::zero()
                        }
                    })
                    .collect(),
            );
        }
        if value.as_list().is_none() {
            self.diagnostics.error(
                value.span(),
                "an input is a coordinate's name or a column `[b_1, ..., b_n]`",
            );
            return None;
        }
        let row = self.row_of_expressions(item, n, "an input column")?;
        row.into_iter()
            .map(|expr| {
                self.velocity_free(
                    expr,
                    "an input column depends on the configuration only: no velocities",
                )
            })
            .collect()
    }
}
