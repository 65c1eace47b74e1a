//! The Lie algebra of the symmetry group: a product of `se(2)` factors and
//! abelian ones (Koon & Marsden, section 2; MATH.md section 4). A body
//! velocity `xi` has one entry per group coordinate, factor by factor:
//! `(v1, v2, omega)` for `se2`, the velocity for an abelian factor.
//!
//! ```text
//! [(a1, b1, w1), (a2, b2, w2)] = (w2 b1 - w1 b2, w1 a2 - w2 a1, 0)   on each se(2) factor, 0 on abelian ones
//! ```
//!
//! the commutator of the matrices `[[0, -w, a], [w, 0, b], [0, 0, 0]]`.

use crate::model::GroupFactor;
use crate::sym::{Atoms, RationalFunction};

/// For each `se2` factor: where its `(v1, v2, omega)` start in `xi`, and the
/// coordinate index of its `theta`.
pub(super) fn se2_blocks(factors: &[GroupFactor]) -> Vec<(usize, usize)> {
    let mut offset = 0;
    let mut blocks = Vec::new();
    for factor in factors {
        match *factor {
            GroupFactor::Se2 { theta, .. } => {
                blocks.push((offset, theta));
                offset += 3;
            }
            GroupFactor::Translation(_) | GroupFactor::Rotation(_) => offset += 1,
        }
    }
    blocks
}

/// The bracket of the product algebra: zero on abelian factors, and on each
/// se(2) factor `[(a1,b1,w1),(a2,b2,w2)] = (w2 b1 - w1 b2, w1 a2 - w2 a1, 0)`.
pub(super) fn bracket(
    first: &[RationalFunction],
    second: &[RationalFunction],
    factors: &[GroupFactor],
    atoms: &Atoms,
) -> Vec<RationalFunction> {
    let mut result = vec![RationalFunction::zero(); first.len()];
    for (o, _) in se2_blocks(factors) {
        let (a1, b1, w1) = (&first[o], &first[o + 1], &first[o + 2]);
        let (a2, b2, w2) = (&second[o], &second[o + 1], &second[o + 2]);
        result[o] = w2.mul(b1, atoms).sub(&w1.mul(b2, atoms), atoms);
        result[o + 1] = w1.mul(a2, atoms).sub(&w2.mul(a1, atoms), atoms);
    }
    result
}
