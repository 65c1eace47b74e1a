//! A goal's given velocities checked against the velocity constraints
//! `A(q) qdot = 0` before the solve. Where the goal gives every
//! coordinate that `A` reads, the velocities it leaves free meet the
//! constraints at best with the residual
//!
//! ```text
//! min_v |A_free v + A_given qdot_given|,
//! ```
//!
//! by least squares. A goal with a residual beyond round-off is reached by
//! no motion: without the check the solver may meet the discrete problem
//! by a jump in the last interval, which the replay then refuses with a
//! less direct reason.

use crate::runtime::nalgebra::{DMatrix, DVector};
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};

/// The least residual of `A(q) qdot` over the velocities `goal` leaves
/// free, relative to the largest given velocity (at least 1); `None`
/// where it gives no velocity or leaves free a coordinate `A` reads.
pub(super) fn residual(model: &InterpretedModel, goal: &[Option<f64>]) -> Option<f64> {
    let (n, c) = (model.sizes().n, model.sizes().c);
    let (q, qdot) = goal[..2 * n].split_at(n);
    if c == 0 || qdot.iter().all(Option::is_none) {
        return None;
    }
    let (_, program) = model
        .programs()
        .find(|(name, _)| *name == "constraint_matrix")?;
    if (0..n).any(|i| program.reads(i) && q[i].is_none()) {
        return None;
    }
    let pose: Vec<f64> = q.iter().map(|v| v.unwrap_or(0.0)).collect();
    let a = DMatrix::from_row_slice(c, n, &evaluated(model.constraint_matrix(&pose)));
    let free: Vec<usize> = (0..n).filter(|&j| qdot[j].is_none()).collect();
    let given = DVector::from_fn(n, |j, _| qdot[j].unwrap_or(0.0));
    let fixed = &a * &given;
    let left = if free.is_empty() {
        fixed
    } else {
        let columns = DMatrix::from_fn(c, free.len(), |r, k| a[(r, free[k])]);
        let best = columns
            .clone()
            .svd(true, true)
            .solve(&(-&fixed), 1e-12)
            .ok()?;
        columns * best + fixed
    };
    Some(left.amax() / given.amax().max(1.0))
}

#[cfg(test)]
mod tests {
    use super::residual;
    use chaplygin_codegen::interpret::InterpretedModel;

    /// The differential drive heading along x: its wheels' rates fix the
    /// body's velocity, `dot(x) = r (dot(phi_r) + dot(phi_l)) / 2`.
    #[test]
    fn the_drives_wheels_at_rest_forbid_a_forward_speed() {
        let model =
            InterpretedModel::from_source(include_str!("../../catalog/differential_drive.model"))
                .expect("the model derives");
        let goal = |speed: f64, wheels: f64, heading: Option<f64>| {
            let mut goal = vec![None; 12];
            goal[2] = heading;
            goal[5] = Some(speed);
            goal[8] = Some(wheels);
            goal[9] = Some(wheels);
            residual(&model, &goal)
        };
        let forbidden = goal(1.0, 0.0, Some(0.0)).expect("decided");
        assert!((forbidden - 1.0).abs() < 1e-12, "{forbidden}");
        let allowed = goal(0.05 * 4.0, 4.0, Some(0.0)).expect("decided");
        assert!(allowed < 1e-14, "{allowed}");
        assert_eq!(goal(1.0, 0.0, None), None);
    }
}
