//! Linearization: the generated `acceleration_jacobian` against central
//! differences of `acceleration`, and the runtime's linear system about
//! steady motions against hand linearizations (MATH.md section 6).

use crate::common::check_jacobians;
use crate::common::towed::Towed;
use crate::snake2;
use chaplygin::runtime::linearize::{
    AccelerationJacobian, Compiled, GroupFactor, LinearSystem, Linearization, OperatingPoint,
    PointError, SteadyError, linearize,
};
use chaplygin::runtime::system::{Domain, Holonomic, LagrangeDalembert, ModelNames};
use chaplygin_models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};

#[test]
fn acceleration_jacobians_are_the_derivatives_of_acceleration() {
    for t in [0.0, 0.7, -1.3] {
        check_jacobians(
            &Snakeboard::default(),
            [t, -t, 0.3 + t, 0.1, 0.2 - t / 2.0],
            [1.0, 0.5, -0.2, t, 0.3],
            [t, 0.5],
        );
        check_jacobians(&Sleigh::default(), [t, 0.5, 0.2 + t], [1.0, -0.5, t], []);
        check_jacobians(
            &Towed::default(),
            [t, 0.5, 0.2 + t, 0.3 - t],
            [1.0, -0.5, t, 0.7],
            [t],
        );
        check_jacobians(
            &RollingDisk::default(),
            [t, 0.5, 0.2 + t, 0.3 - t],
            [1.0, -0.5, t, 0.7],
            [t, 0.2],
        );
        check_jacobians(
            &DifferentialDrive::default(),
            [t, -t, 0.3 + t, 0.1, 0.2 - t],
            [1.0, 0.5, -0.2, t, 0.3],
            [0.1, t],
        );
        let n = snake2::Snake2::N;
        let q: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 + t / 3.0).collect();
        let qdot: Vec<f64> = (0..n).map(|i| 0.4 - 0.1 * i as f64 + t).collect();
        check_jacobians(
            &snake2::Snake2::default(),
            q.try_into().expect("n entries"),
            qdot.try_into().expect("n entries"),
            [0.3 - t],
        );
    }
}

/// The sleigh moving straight ahead at speed `v` with heading `theta`:
/// the blade's velocity along the heading.
fn sleigh_straight(sleigh: &Sleigh, theta: f64, v: f64) -> Result<LinearSystem, SteadyError> {
    let model = Compiled::new(sleigh);
    let point = OperatingPoint::solve(
        &model,
        &[Some(1.0), Some(-2.0), Some(theta)],
        &[Some(v * theta.cos()), None, Some(0.0)],
    )
    .expect("the blade constraint fixes dot(y)");
    linearize(&model, &point, &[], &[])
}

/// The sleigh's straight motion, linearized by hand. In the body frame of
/// the blade (forward speed `s`, no sideways slip, yaw rate `w`) the centre
/// of mass, a distance `a` ahead, moves with `(s, a w)`; the momentum
/// balances along the heading and about the blade are
///
/// ```text
/// m (s' - a w^2) = 0,     (I + m a^2) w' + m a s w = 0.
/// ```
///
/// About `s = v`, `w = 0`: `ds' = 0` (the energy's zero) and
/// `dw' = -(m a v / (I + m a^2)) dw`: the yaw rate decays for `a v > 0`
/// and grows for `a v < 0`.
#[test]
fn the_sleighs_straight_motion_has_the_hand_eigenvalues() {
    let sleigh = Sleigh {
        m: 1.3,
        inertia: 0.2,
        a: 0.4,
    };
    for (theta, v) in [(0.0, 1.0), (0.7, 2.5), (-2.0, -1.5)] {
        let linear = sleigh_straight(&sleigh, theta, v).expect("a relative equilibrium");
        let expected = -sleigh.m * sleigh.a * v / (sleigh.inertia + sleigh.m * sleigh.a.powi(2));
        assert_eq!(linear.eigenvalues.len(), 2, "{:?}", linear.state);
        let (zero, yaw) = if expected < 0.0 {
            (linear.eigenvalues[0], linear.eigenvalues[1])
        } else {
            (linear.eigenvalues[1], linear.eigenvalues[0])
        };
        assert!(zero.norm() < 1e-12, "{zero}");
        assert!(
            (yaw.re - expected).abs() < 1e-10 && yaw.im == 0.0,
            "{yaw} vs {expected}"
        );
        assert!(linear.is_zero(zero));
        assert_eq!(linear.is_stable(), v > 0.0, "theta {theta}, v {v}");
        assert_eq!(linear.state, ["body(dot(x))", "dot(theta)"]);
    }
}

#[test]
fn a_turning_sleigh_is_not_a_steady_motion() {
    let sleigh = Sleigh::default();
    let model = Compiled::new(&sleigh);
    let point = OperatingPoint::solve(&model, &[None; 3], &[Some(1.0), None, Some(0.5)])
        .expect("the blade constraint fixes dot(y)");
    match linearize(&model, &point, &[], &[]) {
        Err(SteadyError::NotSteady {
            quantity, residual, ..
        }) => {
            // With s = 1, w = 0.5 the hand equations (see the straight
            // motion's test) give s' = a w^2 = 0.125 and the larger
            // w' = -m a s w / (I + m a^2) = -5/7.
            let expected =
                -sleigh.m * sleigh.a * 0.5 / (sleigh.inertia + sleigh.m * sleigh.a.powi(2));
            assert_eq!(quantity, "dot(theta)");
            assert!((residual - expected).abs() < 1e-12, "{residual}");
        }
        other => panic!("expected NotSteady, got {other:?}"),
    }
}

/// The snakeboard at rest, with no input: every eigenvalue is zero (no
/// potential, and the equations are quadratic in the velocities, so the
/// linear system is `psi' = dot(psi)`, `phi' = dot(phi)` and constant
/// speeds), on the five-dimensional reduced state (shape `psi`, `phi` and
/// the three speeds the two constraints leave).
#[test]
fn the_snakeboard_at_rest_has_only_zero_eigenvalues() {
    let board = Snakeboard::default();
    let model = Compiled::new(&board);
    let point = OperatingPoint::solve(
        &model,
        &[Some(0.0), Some(0.0), Some(0.4), Some(0.1), Some(0.3)],
        &[Some(0.0), None, Some(0.0), Some(0.0), Some(0.0)],
    )
    .expect("at rest");
    let linear = linearize(&model, &point, &[0.0, 0.0], &[]).expect("an equilibrium");
    assert_eq!(linear.eigenvalues.len(), 5, "{:?}", linear.state);
    for eigenvalue in &linear.eigenvalues {
        assert!(eigenvalue.norm() == 0.0, "{eigenvalue}");
    }
    // Only three of the zeros have eigenvectors (the shape at rest anywhere,
    // and the speed the constraints leave): a shape velocity moves the shape
    // linearly in time, a Jordan chain, so rest is not asymptotically stable
    // even counting conserved quantities out.
    assert_eq!((linear.zeros(), linear.kernel_dimension()), (5, 3));
    assert!(!linear.is_stable());
    // A torque on the torso is no steady motion.
    let forced = linearize(&model, &point, &[1.0, 0.0], &[]);
    assert!(
        matches!(&forced, Err(SteadyError::NotSteady { quantity, .. }) if quantity == "dot(psi)"),
        "{forced:?}"
    );
}

#[test]
fn velocities_left_free_or_contradicting_the_constraints_are_named() {
    let sleigh = Sleigh::default();
    let model = Compiled::new(&sleigh);
    let at_origin = [Some(0.0); 3];
    let free = OperatingPoint::solve(&model, &at_origin, &[None, None, Some(0.0)]);
    assert_eq!(
        free,
        Err(PointError::FreeVelocities {
            velocities: vec!["dot(x)".into()],
            directions: 1,
        })
    );
    let violated = OperatingPoint::solve(&model, &at_origin, &[Some(0.0), Some(1.0), None]);
    assert_eq!(
        violated,
        Err(PointError::ConstraintViolated {
            constraint: "blade".into(),
            residual: 1.0
        })
    );
    let all_free = OperatingPoint::solve(&model, &at_origin, &[None; 3]);
    assert_eq!(
        all_free,
        Err(PointError::FreeVelocities {
            velocities: vec!["dot(x)".into(), "dot(theta)".into()],
            directions: 2,
        })
    );
}

#[test]
fn a_singular_mass_matrix_is_an_error_not_a_nan() {
    let sleigh = Sleigh {
        m: 0.0,
        inertia: 0.0,
        a: 0.5,
    };
    let linear = sleigh_straight(&sleigh, 0.0, 1.0);
    assert!(
        matches!(linear, Err(SteadyError::MassMatrix(_))),
        "{linear:?}"
    );
}

/// A pendulum in redundant coordinates `(theta, x, y)`, written by hand:
/// a point mass `m` at `(x, y) = (l sin theta, -l cos theta)` (the two
/// configuration constraints), a rotor of inertia `j` turning with
/// `theta`, gravity `gravity` along `-y`, a torque `u` on `theta`. Its
/// acceleration solves the saddle-point system of MATH.md section 2
/// numerically; its Jacobians are Richardson-extrapolated central
/// differences of that (good to about 1e-12 here).
struct Pendulum {
    m: f64,
    l: f64,
    j: f64,
    gravity: f64,
}

impl Pendulum {
    fn constraint_rows(&self, q: &[f64; 3]) -> [[f64; 3]; 2] {
        let (sin, cos) = q[0].sin_cos();
        [[-self.l * cos, 1.0, 0.0], [-self.l * sin, 0.0, 1.0]]
    }
}

/// `d f(x + s e_j)/ds` at `s = 0` for every `j`, by central differences
/// extrapolated once.
fn richardson_jacobian<const D: usize, const R: usize>(
    f: impl Fn(&[f64; D]) -> [f64; R],
    x: &[f64; D],
) -> [[f64; D]; R] {
    let central = |j: usize, h: f64| -> [f64; R] {
        let (mut plus, mut minus) = (*x, *x);
        plus[j] += h;
        minus[j] -= h;
        let (up, down) = (f(&plus), f(&minus));
        std::array::from_fn(|i| (up[i] - down[i]) / (2.0 * h))
    };
    let h = f64::EPSILON.powf(0.2);
    let columns: [[f64; R]; D] = std::array::from_fn(|j| {
        let (coarse, fine) = (central(j, h), central(j, h / 2.0));
        std::array::from_fn(|i| (4.0 * fine[i] - coarse[i]) / 3.0)
    });
    std::array::from_fn(|i| std::array::from_fn(|j| columns[j][i]))
}

impl LagrangeDalembert<3, 2, 1> for Pendulum {
    fn acceleration(&self, q: &[f64; 3], qdot: &[f64; 3], u: &[f64; 1]) -> ([f64; 3], [f64; 2]) {
        use chaplygin::runtime::nalgebra::{SMatrix, SVector};
        let a = self.constraint_rows(q);
        let (sin, cos) = q[0].sin_cos();
        let w2 = qdot[0] * qdot[0];
        let drift = [-self.l * sin * w2, self.l * cos * w2];
        let mass = [self.j, self.m, self.m];
        let force = [u[0], 0.0, -self.m * self.gravity];
        let saddle = SMatrix::<f64, 5, 5>::from_fn(|i, k| match (i < 3, k < 3) {
            (true, true) => {
                if i == k {
                    mass[i]
                } else {
                    0.0
                }
            }
            (true, false) => -a[k - 3][i],
            (false, true) => a[i - 3][k],
            (false, false) => 0.0,
        });
        let rhs = SVector::<f64, 5>::from_fn(|i, _| if i < 3 { force[i] } else { drift[i - 3] });
        let solution = saddle
            .lu()
            .solve(&rhs)
            .unwrap_or(SVector::from_element(f64::NAN));
        (
            [solution[0], solution[1], solution[2]],
            [solution[3], solution[4]],
        )
    }
    fn energy(&self, q: &[f64; 3], qdot: &[f64; 3]) -> f64 {
        self.j / 2.0 * qdot[0].powi(2)
            + self.m / 2.0 * (qdot[1].powi(2) + qdot[2].powi(2))
            + self.m * self.gravity * q[2]
    }
    fn constraint_residual(&self, q: &[f64; 3], qdot: &[f64; 3]) -> [f64; 2] {
        self.constraint_rows(q)
            .map(|row| row.iter().zip(qdot).map(|(a, v)| a * v).sum())
    }
    fn constraint_regularity(&self, _q: &[f64; 3]) -> f64 {
        1.0
    }
}

impl Linearization<3, 2, 1> for Pendulum {
    fn symmetry(&self) -> &[GroupFactor] {
        &[]
    }
    fn mass_matrix(&self, _q: &[f64; 3]) -> [[f64; 3]; 3] {
        [[self.j, 0.0, 0.0], [0.0, self.m, 0.0], [0.0, 0.0, self.m]]
    }
    fn constraint_matrix(&self, q: &[f64; 3]) -> [[f64; 3]; 2] {
        self.constraint_rows(q)
    }
    fn acceleration_jacobian(
        &self,
        q: &[f64; 3],
        qdot: &[f64; 3],
        u: &[f64; 1],
    ) -> AccelerationJacobian<3, 1> {
        (
            richardson_jacobian(|q| self.acceleration(q, qdot, u).0, q),
            richardson_jacobian(|qdot| self.acceleration(q, qdot, u).0, qdot),
            richardson_jacobian(|u| self.acceleration(q, qdot, u).0, u),
        )
    }
}

impl Holonomic<3, 2> for Pendulum {
    fn holonomic_names(&self) -> [&str; 2] {
        ["rod_x", "rod_y"]
    }
    fn holonomic_residual(&self, q: &[f64; 3]) -> [f64; 2] {
        let (sin, cos) = q[0].sin_cos();
        [q[1] - self.l * sin, q[2] + self.l * cos]
    }
    fn holonomic_jacobian(&self, q: &[f64; 3]) -> [[f64; 3]; 2] {
        self.constraint_rows(q)
    }
}

/// No guarded expressions: the defaults.
impl Domain for Pendulum {}

impl ModelNames for Pendulum {
    fn coordinate_names(&self) -> &[&str] {
        &["theta", "x", "y"]
    }
    fn momentum_names(&self) -> &[&str] {
        &["p"]
    }
    fn input_names(&self) -> &[&str] {
        &["torque"]
    }
    fn constraint_names(&self) -> &[&str] {
        &["rod_x", "rod_y"]
    }
}

/// About `theta = theta0` the pendulum is `(j + m l^2) theta'' = -m g l
/// sin theta + u`: hanging (`theta0 = 0`) the eigenvalues are `+-i w`,
/// inverted (`pi`) `+-w`, with `w^2 = m g l / (j + m l^2)`; `x` and `y`
/// follow from the configuration constraints, solved by Newton's method.
#[test]
fn the_pendulums_coordinates_follow_its_configuration_constraints() {
    let pendulum = Pendulum {
        m: 2.0,
        l: 0.8,
        j: 0.05,
        gravity: 9.81,
    };
    let model = Compiled::holonomic(&pendulum);
    let w = (pendulum.m * pendulum.gravity * pendulum.l
        / (pendulum.j + pendulum.m * pendulum.l.powi(2)))
    .sqrt();
    for theta in [0.0, std::f64::consts::PI] {
        let point =
            OperatingPoint::solve(&model, &[Some(theta), None, None], &[Some(0.0), None, None])
                .expect("x and y solved");
        let (sin, cos) = theta.sin_cos();
        assert!(
            (point.q[1] - pendulum.l * sin).abs() < 1e-14,
            "{:?}",
            point.q
        );
        assert!(
            (point.q[2] + pendulum.l * cos).abs() < 1e-14,
            "{:?}",
            point.q
        );
        let linear = linearize(&model, &point, &[0.0], &[]).expect("an equilibrium");
        assert_eq!(linear.state, ["theta", "dot(theta)"]);
        let [first, second] = [linear.eigenvalues[0], linear.eigenvalues[1]];
        if theta == 0.0 {
            assert!(
                first.re.abs() < 1e-10 && (first.im - w).abs() < 1e-9,
                "{first}"
            );
            assert!(
                second.re.abs() < 1e-10 && (second.im + w).abs() < 1e-9,
                "{second}"
            );
        } else {
            assert!((first.re - w).abs() < 1e-9 && first.im == 0.0, "{first}");
            assert!((second.re + w).abs() < 1e-9 && second.im == 0.0, "{second}");
        }
        // Neither is asymptotically stable: hanging is a centre.
        assert!(!linear.is_stable());
        // The torque enters as 1 / (j + m l^2).
        let b = linear.b[(1, 0)];
        assert!((b - 1.0 / (pendulum.j + pendulum.m * pendulum.l.powi(2))).abs() < 1e-9);
    }
    let swinging =
        OperatingPoint::solve(&model, &[Some(0.3), None, None], &[Some(0.0), None, None])
            .expect("at rest");
    assert!(matches!(
        linearize(&model, &swinging, &[0.0], &[]),
        Err(SteadyError::NotSteady { quantity, .. }) if quantity == "dot(theta)"
    ));
    // Every coordinate given, on the rod: nothing is left to solve, and the
    // point stands.
    let given = [Some(0.0), Some(0.0), Some(-pendulum.l)];
    let hanging = OperatingPoint::solve(&model, &given, &[Some(0.0), None, None])
        .expect("the given configuration meets the constraints");
    assert_eq!(hanging.q, [0.0, 0.0, -pendulum.l]);
    let inconsistent = OperatingPoint::solve(&model, &[Some(0.0), Some(0.5), None], &[None; 3]);
    assert_eq!(
        inconsistent,
        Err(PointError::HolonomicFixed {
            constraint: "rod_x".into(),
            residual: 0.5
        })
    );
}

chaplygin::model! {
    /// A thin uniform disk rolling without slipping on the plane: contact
    /// point (x, y), heading psi, lean phi, spin theta. The frame
    /// `Rz(psi) Rx(phi)` has the disk's axis as its y axis; the centre is at
    /// `(x + r sin psi sin phi, y - r cos psi sin phi, r cos phi)`; the
    /// angular velocity in that frame is
    /// `(dot(phi), dot(psi) sin phi + dot(theta), dot(psi) cos phi)` with
    /// inertia `diag(i1, i3, i1)`. The material point at the contact has
    /// velocity `(xdot, ydot) - r dot(theta) (cos psi, sin psi)`.
    pub struct TiltingDisk {
        coordinates: [x, y, psi, phi, theta],
        parameters: [m = 1.0, r = 0.5, g = 9.81],
        define: [i1 = m*r^2/4, i3 = m*r^2/2],
        kinetic_energy: m/2*((dot(x) + r*(cos(psi)*sin(phi)*dot(psi) + sin(psi)*cos(phi)*dot(phi)))^2
            + (dot(y) + r*(sin(psi)*sin(phi)*dot(psi) - cos(psi)*cos(phi)*dot(phi)))^2
            + (r*sin(phi)*dot(phi))^2)
            + i1/2*dot(phi)^2 + i3/2*(sin(phi)*dot(psi) + dot(theta))^2
            + i1/2*(cos(phi)*dot(psi))^2,
        potential_energy: m*g*r*cos(phi),
        constraints: [
            roll_x = dot(x) - r*cos(psi)*dot(theta),
            roll_y = dot(y) - r*sin(psi)*dot(theta),
        ],
        symmetry: se2(x, y, psi) * rotation(theta),
    }
}

/// The thin disk rolling upright at speed `v = r Omega` (spin `Omega`):
/// the classical result (e.g. Neimark & Fufaev, *Dynamics of Nonholonomic
/// Systems*, the rolling disk) is that the lean oscillates,
/// `phi'' + ((i3 (i3 + m r^2) Omega^2 - m g r i1) / (i1 (i1 + m r^2))) phi = 0`
/// after the yaw rate (tied to the lean by the conserved quantities) is
/// eliminated; for the thin disk (`i3 = 2 i1 = m r^2 / 2`) that is
/// `phi'' + (12/5 Omega^2 - 4/5 g/r) phi = 0`: upright rolling is stable
/// (purely imaginary eigenvalues, the motion conserves energy) exactly for
/// `v^2 > g r / 3`, and below it a real eigenvalue pair splits off.
#[test]
fn the_upright_disk_rolls_stably_above_the_critical_speed() {
    let disk = TiltingDisk::default();
    let model = Compiled::new(&disk);
    let critical = (disk.g * disk.r / 3.0).sqrt();
    for v in [
        0.3 * critical,
        0.9 * critical,
        1.1 * critical,
        3.0 * critical,
    ] {
        let omega = v / disk.r;
        let point = OperatingPoint::solve(
            &model,
            &[None; 5],
            &[None, None, Some(0.0), Some(0.0), Some(omega)],
        )
        .expect("rolling straight");
        let linear = linearize(&model, &point, &[], &[]).expect("a relative equilibrium");
        let square = -(12.0 / 5.0 * omega * omega - 4.0 / 5.0 * disk.g / disk.r);
        let nonzero: Vec<_> = linear
            .eigenvalues
            .iter()
            .filter(|&&e| !linear.is_zero(e))
            .collect();
        assert_eq!(
            nonzero.len(),
            2,
            "{:?} in {:?}",
            linear.eigenvalues,
            linear.state
        );
        for eigenvalue in nonzero {
            let squared = eigenvalue * eigenvalue;
            assert!(
                (squared.re - square).abs() < 1e-9 && squared.im.abs() < 1e-9,
                "v = {v}: {eigenvalue}^2 vs {square}"
            );
        }
    }
}
