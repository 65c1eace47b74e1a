//! Normal forms evaluated modulo a prime: each atom once, then the
//! polynomials. Symbols, sines and cosines and kernels are evaluated as the
//! expressions they stand for; a square-root atom `r` as the principal root
//! of its radicand's value, so `r^2 = u` holds at the point (the only
//! relation the normal form uses of `r`).

use super::Values;
use crate::sym::modular::{
    ModularError, PRIME, add, inverse, multiply, points, power, rank, square_root,
};
use crate::sym::poly::{AtomId, Poly};
use crate::sym::{Context, Matrix, RationalFunction};
use rustc_hash::FxHashMap as HashMap;

impl Context {
    /// The values of `forms` modulo [`PRIME`] at the point of `values`
    /// (whose expression values are reused and extended).
    pub fn evaluate_normal_modular(
        &mut self,
        forms: &[RationalFunction],
        values: &mut Values,
    ) -> Result<Vec<u64>, ModularError> {
        let mut atoms = AtomValues::default();
        forms
            .iter()
            .map(|form| {
                let numerator = atoms.of_poly(self, form.numerator(), values)?;
                let mut denominator = 1;
                for (factor, multiplicity) in form.denominator() {
                    let value = atoms.of_poly(self, factor, values)?;
                    let value = power(value, i64::from(*multiplicity)).unwrap_or(0);
                    denominator = multiply(denominator, value, PRIME);
                }
                let reciprocal =
                    inverse(denominator, PRIME).ok_or_else(|| ModularError::Undefined {
                        expr: "a denominator of a normal form".to_string(),
                    })?;
                Ok(multiply(numerator, reciprocal, PRIME))
            })
            .collect()
    }
}

/// The values of the atoms met so far.
#[derive(Default)]
struct AtomValues(HashMap<AtomId, u64>);

impl AtomValues {
    fn of_poly(
        &mut self,
        cx: &mut Context,
        poly: &Poly,
        values: &mut Values,
    ) -> Result<u64, ModularError> {
        let mut sum = 0;
        for (monomial, coefficient) in poly.terms() {
            let mut term = coefficient
                .residue(PRIME)
                .ok_or_else(|| ModularError::Undefined {
                    expr: format!("the coefficient {coefficient}"),
                })?;
            for &(atom, exponent) in monomial.factors() {
                let value = self.of_atom(cx, atom, values)?;
                term = multiply(term, power(value, i64::from(exponent)).unwrap_or(0), PRIME);
            }
            sum = add(sum, term);
        }
        Ok(sum)
    }

    fn of_atom(
        &mut self,
        cx: &mut Context,
        atom: AtomId,
        values: &mut Values,
    ) -> Result<u64, ModularError> {
        if let Some(&value) = self.0.get(&atom) {
            return Ok(value);
        }
        let value = match cx.atoms().radicand_of(atom).cloned() {
            Some(radicand) => {
                let value = self.of_poly(cx, &radicand, values)?;
                let root = cx.expression_of_atom(atom);
                square_root(value).ok_or_else(|| ModularError::Undefined {
                    expr: cx.display(root).to_string(),
                })?
            }
            None => {
                let expression = cx.expression_of_atom(atom);
                values.of(cx, &[expression])?[0]
            }
        };
        self.0.insert(atom, value);
        Ok(value)
    }
}

impl Context {
    /// For each `i`, whether the first `i + 1` rows of `matrix` have full
    /// rank at one of two random points ([`points`], skipping points
    /// where an entry is undefined). A rank at a point is a lower bound of
    /// the generic rank: `true` is proved, `false` only probable.
    pub fn prefixes_of_full_rank_at_points(
        &mut self,
        matrix: &Matrix,
    ) -> Result<Vec<bool>, ModularError> {
        let columns = matrix.columns();
        let mut full = vec![false; matrix.rows()];
        let mut defined_points = 0;
        let mut last_undefined = None;
        for point in points() {
            let values =
                match self.evaluate_normal_modular(matrix.entries(), &mut Values::at(point)) {
                    Ok(values) => values,
                    Err(undefined @ ModularError::Undefined { .. }) => {
                        last_undefined = Some(undefined);
                        continue;
                    }
                    Err(outside) => return Err(outside),
                };
            for (i, prefix_full) in full.iter_mut().enumerate() {
                *prefix_full |= rank(values[..(i + 1) * columns].to_vec(), i + 1, columns) == i + 1;
            }
            defined_points += 1;
            if defined_points == 2 || full.iter().all(|&f| f) {
                return Ok(full);
            }
        }
        match (defined_points, last_undefined) {
            (0, Some(undefined)) => Err(undefined),
            _ => Ok(full),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::modular::at_defined_points;
    use crate::sym::residues::Values;
    use crate::sym::{Context, Function, Matrix, Rational, RationalFunction, SymbolKind};

    /// `(store, r, cos y)` with `r = sqrt(1 + sin(x)^2)`.
    fn store_with_root() -> (Context, crate::sym::ExprId, crate::sym::ExprId) {
        let mut cx = Context::new();
        let x = cx.declare("x", SymbolKind::Coordinate);
        let y = cx.declare("y", SymbolKind::Coordinate);
        let (x, y) = (cx.symbol(x), cx.symbol(y));
        let sine = cx.apply(Function::Sin, x).expect("applies");
        let square = cx.pow(sine, Rational::integer(2)).expect("applies");
        let one = cx.integer(1);
        let radicand = cx.add2(one, square);
        let root = cx.sqrt(radicand).expect("applies");
        let cosine = cx.apply(Function::Cos, y).expect("applies");
        (cx, root, cosine)
    }

    /// The normal form (a root atom reduced by `r^2 = u`, a cleared
    /// denominator) and the expression it came from take the same value:
    /// the atoms' evaluation against the DAG's.
    #[test]
    fn a_normal_form_with_a_root_evaluates_as_its_expression() {
        let (mut cx, root, cosine) = store_with_root();
        let product = cx.mul2(root, cosine);
        let reciprocal = cx.pow(root, Rational::integer(-3)).expect("applies");
        let expression = cx.add2(product, reciprocal);
        let form = cx.normal(expression).expect("in the class");
        let pairs = at_defined_points(4, |point| {
            let from_form = cx
                .clone()
                .evaluate_normal_modular(std::slice::from_ref(&form), &mut Values::at(point))?;
            let from_expression = cx.evaluate_modular(&[expression], &point)?;
            Ok((from_form[0], from_expression[0]))
        })
        .expect("four points where 1 + sin(x)^2 is a square");
        for (from_form, from_expression) in pairs {
            assert_eq!(from_form, from_expression);
        }
    }

    /// Rows `(r, 1)`, `cos(y) (r, 1)`, `(1, 0)`: the first alone has full
    /// rank, the second depends on it, and the three have rank 2.
    #[test]
    fn prefixes_of_full_rank_are_found_and_dependent_rows_are_not() {
        let (mut cx, root, cosine) = store_with_root();
        let scaled = cx.mul2(cosine, root);
        let entries: Vec<RationalFunction> = [root, cx.integer(1), scaled, cosine]
            .into_iter()
            .map(|e| cx.normal(e).expect("in the class"))
            .chain([RationalFunction::one(), RationalFunction::zero()])
            .collect();
        let rows = Matrix::new(3, 2, entries).expect("3 x 2");
        let full = cx
            .prefixes_of_full_rank_at_points(&rows)
            .expect("in the class");
        assert_eq!(full, [true, false, false]);
    }
}
