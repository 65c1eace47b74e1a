//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab
//! (2007), read from its declaration (`models/bicycle.model`, compiled to
//! native code at run time), linearized about upright straight running at
//! speeds from 0 to 10 m/s: its eigenvalues, and the speeds between which
//! it balances itself, the weave speed and the capsize speed.
//!
//! ```text
//! cargo run --release --example bicycle_stability
//! ```
//!
//! The paper gives 4.292382536341 and 6.024262015388 m/s (section 6); the
//! command line's `chaplygin linearize bicycle ... --sweep` is the same
//! analysis.

use chaplygin::driver::Failure;
use chaplygin::driver::catalog::lookup;
use chaplygin::driver::engine::{EngineChoice, load};
use chaplygin::driver::linearize::sweep;
use chaplygin::driver::setup::{Asked, resolve};
use std::io::Write;

/// Upright straight running at the forward speed `v`: the rear wheel
/// rolling at `-v / rR`, no lean, no steer.
const UPRIGHT: [(&str, &str); 5] = [
    ("dot(theta_r)", "-v/rR"),
    ("dot(phi)", "0"),
    ("dot(delta)", "0"),
    ("phi", "0"),
    ("delta", "0"),
];

fn main() -> Result<(), Failure> {
    report(&mut std::io::stdout().lock())
}

/// Linearizes the bicycle at every half metre per second and writes its
/// eigenvalues and self-stable speeds to `out`.
///
/// # Errors
/// The model does not load, a point is not a steady motion, a failed write.
pub fn report(out: &mut impl Write) -> Result<(), Failure> {
    let bicycle = load(&lookup("bicycle")?, EngineChoice::Jit)?.model;
    let at: Vec<(String, String)> = (UPRIGHT.iter())
        .map(|(name, value)| (name.to_string(), value.to_string()))
        .collect();
    let upright = Asked {
        state_flag: "--at",
        state: &at,
        variables: &["v"],
        ..Asked::default()
    };
    let setup = resolve(bicycle, &upright)?;
    let speeds: Vec<f64> = (0..=20).map(|i| 0.5 * f64::from(i)).collect();
    let analysis = sweep(&setup, ("v", &speeds))?;
    writeln!(
        out,
        "The benchmark bicycle upright and straight ahead at speed v: the eigenvalues of its"
    )?;
    writeln!(
        out,
        "lean and steer (the front wheel's spin rate, a conserved quantity, left out)"
    )?;
    for (v, linear) in speeds.iter().zip(&analysis.systems) {
        let free = (linear.free_eigenvalues(analysis.conserved))
            .ok_or("the conserved zeros are not separable")?;
        let modes: Vec<String> = (free.iter())
            .map(|e| format!("{:+10.6} {:+10.6}i", e.re, e.im))
            .collect();
        writeln!(out, "v = {v:4.1} m/s: {}", modes.join("   "))?;
    }
    for interval in &analysis.stable {
        let (weave, capsize) = interval.refined;
        writeln!(
            out,
            "self-stable from the weave speed {weave:.10} m/s to the capsize speed {capsize:.10} m/s"
        )?;
    }
    Ok(())
}
