//! The Whipple-Carvallo bicycle linearized about upright straight running,
//! in closed form.
//!
//! Source: J. P. Meijaard, J. M. Papadopoulos, A. Ruina and A. L. Schwab
//! (2007), "Linearized dynamics equations for the balance and steer of a
//! bicycle: a benchmark and review", Proc. R. Soc. A 463:1955-1982,
//! appendix A. Axes x forward, y right, z down; q = (roll phi, steer delta);
//! forward speed v; gravity g:
//!
//! ```text
//! M qdd + v C1 qd + (g K0 + v^2 K2) q = 0.
//! ```
//!
//! Four bodies: rear wheel R, rear frame B, front frame H, front wheel F.
//! The wheels' polar moments equal their diametral ones (`IRzz = IRxx`,
//! `IFzz = IFxx`).
//!
//! The whole bicycle T (mass, centre of mass, inertia about the rear contact):
//!
//! ```text
//! mT = mR + mB + mH + mF
//! xT = (xB mB + xH mH + w mF) / mT
//! zT = (-rR mR + zB mB + zH mH - rF mF) / mT
//! ITxx = IRxx + IBxx + IHxx + IFxx + mR rR^2 + mB zB^2 + mH zH^2 + mF rF^2
//! ITxz = IBxz + IHxz - mB xB zB - mH xH zH + mF w rF
//! ITzz = IRzz + IBzz + IHzz + IFzz + mB xB^2 + mH xH^2 + mF w^2
//! ```
//!
//! The front assembly A = H + F, about its own centre of mass, and its
//! moments about the steer axis (tilted back by lam from the vertical, `uA`
//! the perpendicular distance of A's centre of mass from it):
//!
//! ```text
//! mA = mH + mF,  xA = (xH mH + w mF) / mA,  zA = (zH mH - rF mF) / mA
//! IAxx = IHxx + IFxx + mH (zH - zA)^2 + mF (rF + zA)^2
//! IAxz = IHxz - mH (xH - xA)(zH - zA) + mF (w - xA)(rF + zA)
//! IAzz = IHzz + IFzz + mH (xH - xA)^2 + mF (w - xA)^2
//! uA = (xA - w - c) cos lam - zA sin lam
//! IAll = mA uA^2 + IAxx sin^2 lam + 2 IAxz sin lam cos lam + IAzz cos^2 lam
//! IAlx = -mA uA zA + IAxx sin lam + IAxz cos lam
//! IAlz = mA uA xA + IAxz sin lam + IAzz cos lam
//! ```
//!
//! With the trail ratio `mu = (c / w) cos lam`, the wheels' gyrostatic
//! coefficients `SR = IRyy / rR`, `SF = IFyy / rF`, `ST = SR + SF`, and the
//! static moment `SA = mA uA + mu mT xT`:
//!
//! ```text
//! M  = [[ITxx, IAlx + mu ITxz], [IAlx + mu ITxz, IAll + 2 mu IAlz + mu^2 ITzz]]
//! K0 = [[mT zT, -SA], [-SA, -SA sin lam]]
//! K2 = [[0, (ST - mT zT) cos lam / w], [0, (SA + SF sin lam) cos lam / w]]
//! C1 = [[0, mu ST + SF cos lam + ITxz cos lam / w - mu mT zT],
//!       [-(mu ST + SF cos lam), IAlz cos lam / w + mu (SA + ITzz cos lam / w)]]
//! ```
//!
//! The eigenvalues at speed v are the roots s of
//! `det(M s^2 + v C1 s + g K0 + v^2 K2) = 0`, computed as the eigenvalues of
//! the first-order matrix `[[0, I], [-M^-1 (g K0 + v^2 K2), -M^-1 v C1]]`.
//! Above a low speed they are the weave pair (complex), the capsize root and
//! the castering root (real, the capsize root the larger); the weave and
//! capsize speeds are where the weave pair's and the capsize root's real
//! parts cross zero.

use nalgebra::{Complex, Matrix2, Matrix3, Matrix4, Vector3};

/// The paper's table 1 (its 25 parameters and gravity g), in SI units. Field
/// names are the paper's in snake case: `w, c, lam, g`, then per body
/// `r_r = rR, m_r = mR, i_rxx = IRxx, ...`, `x_b = xB, i_bxz = IBxz, ...`,
/// `x_h = xH, i_hxz = IHxz, ...`, `r_f = rF, i_fyy = IFyy, ...`.
#[derive(Clone, Copy, Debug)]
pub struct BenchmarkParameters {
    /// Wheel base.
    pub w: f64,
    /// Trail.
    pub c: f64,
    /// Steer axis tilt from the vertical.
    pub lam: f64,
    /// Gravity.
    pub g: f64,
    pub r_r: f64,
    pub m_r: f64,
    pub i_rxx: f64,
    pub i_ryy: f64,
    pub x_b: f64,
    pub z_b: f64,
    pub m_b: f64,
    pub i_bxx: f64,
    pub i_byy: f64,
    pub i_bzz: f64,
    pub i_bxz: f64,
    pub x_h: f64,
    pub z_h: f64,
    pub m_h: f64,
    pub i_hxx: f64,
    pub i_hyy: f64,
    pub i_hzz: f64,
    pub i_hxz: f64,
    pub r_f: f64,
    pub m_f: f64,
    pub i_fxx: f64,
    pub i_fyy: f64,
}

/// The canonical matrices of the linearized equations.
#[derive(Clone, Copy, Debug)]
pub struct CanonicalMatrices {
    pub m: Matrix2<f64>,
    pub c1: Matrix2<f64>,
    pub k0: Matrix2<f64>,
    pub k2: Matrix2<f64>,
}

/// The eigenvalues at a speed where the weave pair is complex.
#[derive(Clone, Copy, Debug)]
pub struct Modes {
    /// The weave eigenvalue with positive imaginary part.
    pub weave: Complex<f64>,
    pub capsize: f64,
    pub castering: f64,
}

/// The whole bicycle's mass, centre of mass and inertia about the rear contact.
struct WholeBicycle {
    m_t: f64,
    x_t: f64,
    z_t: f64,
    i_txx: f64,
    i_txz: f64,
    i_tzz: f64,
}

/// The front assembly's mass, centre of mass and moments about the steer axis.
struct FrontAssembly {
    m_a: f64,
    u_a: f64,
    i_all: f64,
    i_alx: f64,
    i_alz: f64,
}

/// Speeds are searched in (0, `SPEED_LIMIT`) on a grid of `SPEED_STEPS` intervals.
const SPEED_LIMIT: f64 = 10.0;
const SPEED_STEPS: usize = 1000;

impl BenchmarkParameters {
    /// The benchmark bicycle: the paper's table 1, with g = 9.81.
    pub fn benchmark() -> Self {
        Self {
            w: 1.02,
            c: 0.08,
            lam: std::f64::consts::PI / 10.0,
            g: 9.81,
            r_r: 0.3,
            m_r: 2.0,
            i_rxx: 0.0603,
            i_ryy: 0.12,
            x_b: 0.3,
            z_b: -0.9,
            m_b: 85.0,
            i_bxx: 9.2,
            i_byy: 11.0,
            i_bzz: 2.8,
            i_bxz: 2.4,
            x_h: 0.9,
            z_h: -0.7,
            m_h: 4.0,
            i_hxx: 0.05892,
            i_hyy: 0.06,
            i_hzz: 0.00708,
            i_hxz: -0.00756,
            r_f: 0.35,
            m_f: 3.0,
            i_fxx: 0.1405,
            i_fyy: 0.28,
        }
    }

    /// The central inertia tensors of the rear wheel, rear frame, front
    /// frame and front wheel, in that order, in the paper's axes.
    pub fn inertia_tensors(&self) -> [Matrix3<f64>; 4] {
        let wheel = |i_xx: f64, i_yy: f64| Matrix3::from_diagonal(&Vector3::new(i_xx, i_yy, i_xx));
        let frame = |i_xx: f64, i_yy: f64, i_zz: f64, i_xz: f64| {
            Matrix3::new(i_xx, 0.0, i_xz, 0.0, i_yy, 0.0, i_xz, 0.0, i_zz)
        };
        [
            wheel(self.i_rxx, self.i_ryy),
            frame(self.i_bxx, self.i_byy, self.i_bzz, self.i_bxz),
            frame(self.i_hxx, self.i_hyy, self.i_hzz, self.i_hxz),
            wheel(self.i_fxx, self.i_fyy),
        ]
    }

    fn whole_bicycle(&self) -> WholeBicycle {
        let m_t = self.m_r + self.m_b + self.m_h + self.m_f;
        let (i_rzz, i_fzz) = (self.i_rxx, self.i_fxx);
        WholeBicycle {
            m_t,
            x_t: (self.x_b * self.m_b + self.x_h * self.m_h + self.w * self.m_f) / m_t,
            z_t: (-self.r_r * self.m_r + self.z_b * self.m_b + self.z_h * self.m_h
                - self.r_f * self.m_f)
                / m_t,
            i_txx: self.i_rxx
                + self.i_bxx
                + self.i_hxx
                + self.i_fxx
                + self.m_r * self.r_r.powi(2)
                + self.m_b * self.z_b.powi(2)
                + self.m_h * self.z_h.powi(2)
                + self.m_f * self.r_f.powi(2),
            i_txz: self.i_bxz + self.i_hxz
                - self.m_b * self.x_b * self.z_b
                - self.m_h * self.x_h * self.z_h
                + self.m_f * self.w * self.r_f,
            i_tzz: i_rzz
                + self.i_bzz
                + self.i_hzz
                + i_fzz
                + self.m_b * self.x_b.powi(2)
                + self.m_h * self.x_h.powi(2)
                + self.m_f * self.w.powi(2),
        }
    }

    fn front_assembly(&self) -> FrontAssembly {
        let m_a = self.m_h + self.m_f;
        let x_a = (self.x_h * self.m_h + self.w * self.m_f) / m_a;
        let z_a = (self.z_h * self.m_h - self.r_f * self.m_f) / m_a;
        let i_fzz = self.i_fxx;
        let i_axx = self.i_hxx
            + self.i_fxx
            + self.m_h * (self.z_h - z_a).powi(2)
            + self.m_f * (self.r_f + z_a).powi(2);
        let i_axz = self.i_hxz - self.m_h * (self.x_h - x_a) * (self.z_h - z_a)
            + self.m_f * (self.w - x_a) * (self.r_f + z_a);
        let i_azz = self.i_hzz
            + i_fzz
            + self.m_h * (self.x_h - x_a).powi(2)
            + self.m_f * (self.w - x_a).powi(2);
        let (sin, cos) = self.lam.sin_cos();
        let u_a = (x_a - self.w - self.c) * cos - z_a * sin;
        FrontAssembly {
            m_a,
            u_a,
            i_all: m_a * u_a.powi(2)
                + i_axx * sin.powi(2)
                + 2.0 * i_axz * sin * cos
                + i_azz * cos.powi(2),
            i_alx: -m_a * u_a * z_a + i_axx * sin + i_axz * cos,
            i_alz: m_a * u_a * x_a + i_axz * sin + i_azz * cos,
        }
    }

    /// M, C1, K0, K2 of appendix A.
    pub fn canonical(&self) -> CanonicalMatrices {
        let t = self.whole_bicycle();
        let a = self.front_assembly();
        let (sin, cos) = self.lam.sin_cos();
        let mu = self.c / self.w * cos;
        let s_r = self.i_ryy / self.r_r;
        let s_f = self.i_fyy / self.r_f;
        let s_t = s_r + s_f;
        let s_a = a.m_a * a.u_a + mu * t.m_t * t.x_t;

        let m_roll_steer = a.i_alx + mu * t.i_txz;
        let c1_steer_roll = -(mu * s_t + s_f * cos);
        CanonicalMatrices {
            m: Matrix2::new(
                t.i_txx,
                m_roll_steer,
                m_roll_steer,
                a.i_all + 2.0 * mu * a.i_alz + mu.powi(2) * t.i_tzz,
            ),
            c1: Matrix2::new(
                0.0,
                -c1_steer_roll + t.i_txz * cos / self.w - mu * t.m_t * t.z_t,
                c1_steer_roll,
                a.i_alz * cos / self.w + mu * (s_a + t.i_tzz * cos / self.w),
            ),
            k0: Matrix2::new(t.m_t * t.z_t, -s_a, -s_a, -s_a * sin),
            k2: Matrix2::new(
                0.0,
                (s_t - t.m_t * t.z_t) * cos / self.w,
                0.0,
                (s_a + s_f * sin) * cos / self.w,
            ),
        }
    }

    /// The first-order matrix of x = (phi, delta, phid, deltad) at speed v.
    fn state_matrix(&self, v: f64) -> Matrix4<f64> {
        let CanonicalMatrices { m, c1, k0, k2 } = self.canonical();
        let m_inverse = m.try_inverse().expect("M is positive definite");
        let stiffness = -m_inverse * (k0 * self.g + k2 * v.powi(2));
        let damping = -m_inverse * c1 * v;
        let mut a = Matrix4::zeros();
        a.fixed_view_mut::<2, 2>(0, 2).fill_with_identity();
        a.fixed_view_mut::<2, 2>(2, 0).copy_from(&stiffness);
        a.fixed_view_mut::<2, 2>(2, 2).copy_from(&damping);
        a
    }

    /// The four eigenvalues at speed v, by decreasing real part (a complex
    /// pair: positive imaginary part first).
    pub fn eigenvalues(&self, v: f64) -> [Complex<f64>; 4] {
        let mut eigenvalues: [Complex<f64>; 4] = self
            .state_matrix(v)
            .complex_eigenvalues()
            .as_slice()
            .try_into()
            .expect("four eigenvalues");
        eigenvalues.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
        eigenvalues
    }

    /// The weave, capsize and castering eigenvalues, if at speed v there are
    /// exactly one complex pair and two real roots.
    pub fn modes(&self, v: f64) -> Option<Modes> {
        let eigenvalues = self.eigenvalues(v);
        let (complex, real): (Vec<Complex<f64>>, Vec<Complex<f64>>) =
            eigenvalues.iter().partition(|s| s.im != 0.0);
        match (complex.as_slice(), real.as_slice()) {
            ([upper, lower], [larger, smaller]) if upper.im > 0.0 && *lower == upper.conj() => {
                Some(Modes {
                    weave: *upper,
                    capsize: larger.re,
                    castering: smaller.re,
                })
            }
            _ => None,
        }
    }

    /// The speeds in (0, 10) m/s where the weave pair's real part crosses zero.
    pub fn weave_speeds(&self) -> Vec<f64> {
        zero_crossings(|v| self.modes(v).map(|modes| modes.weave.re))
    }

    /// The speeds in (0, 10) m/s where the capsize root crosses zero.
    pub fn capsize_speeds(&self) -> Vec<f64> {
        zero_crossings(|v| self.modes(v).map(|modes| modes.capsize))
    }

    /// The speed at which s = 0 is a root: `det(g K0 + v^2 K2) = 0`. Since
    /// K2's first column is zero the determinant is linear in v^2.
    pub fn zero_root_speed(&self) -> f64 {
        let CanonicalMatrices { k0, k2, .. } = self.canonical();
        let constant = k0.determinant() * self.g.powi(2);
        let slope = self.g * (k0[(0, 0)] * k2[(1, 1)] - k0[(1, 0)] * k2[(0, 1)]);
        (-constant / slope).sqrt()
    }
}

/// The zeros of `f` in (0, 10): sign changes on the grid, each refined by
/// bisection to the resolution of f64. `f` is `None` where it is undefined.
fn zero_crossings(f: impl Fn(f64) -> Option<f64>) -> Vec<f64> {
    let speed = |i: usize| SPEED_LIMIT * i as f64 / SPEED_STEPS as f64;
    (1..SPEED_STEPS)
        .filter_map(|i| {
            let (low, high) = (speed(i), speed(i + 1));
            let (f_low, f_high) = (f(low)?, f(high)?);
            (f_low.signum() != f_high.signum()).then(|| bisect(&f, low, high, f_low))
        })
        .collect()
}

fn bisect(f: &impl Fn(f64) -> Option<f64>, mut low: f64, mut high: f64, f_low: f64) -> f64 {
    loop {
        let middle = 0.5 * (low + high);
        if middle <= low || middle >= high {
            return middle;
        }
        match f(middle) {
            Some(value) if value.signum() == f_low.signum() => low = middle,
            Some(_) => high = middle,
            None => panic!("the mode is undefined at {middle} m/s inside a bracket"),
        }
    }
}
