//! PNG plots of a simulated trajectory, as `chaplygin simulate --out DIR`
//! writes them next to `trajectory.csv`.
//!
//! The input is a [`Table`] whose columns follow the CSV layout of
//! docs/INTERFACE.md section 3 (`t`, the coordinates, the rest of the state,
//! controller states, inputs, `energy`, `constraint_residual`); a
//! [`PlotSpec`] names the columns each plot reads. [`write_plots`] writes:
//!
//! - `path.png`: the planar path `(x(t), y(t))` with equal axis scales,
//!   heading arrows along `theta` at regular time intervals, start and end
//!   marked;
//! - `energy.png`: the relative energy error `(E(t) - E(0)) / |E(0)|`
//!   against `t` (the absolute error `E(t) - E(0)` when `E(0) = 0`, as the
//!   axis label then says);
//! - `constraint_residual.png`: the residual against `t` on a logarithmic
//!   scale, values below [`RESIDUAL_FLOOR`] (zeros included) drawn at the
//!   floor, as the axis label then says;
//! - `figure4.png`: Figure 4 of Duindam & Stramigioli (2004) for the
//!   snakeboard under the energy-based controller of MATH.md 3.2: the curve
//!   `(alpha1, alpha2, xt)(t)` in a 3-D projection on the wireframe of the
//!   constant-energy ellipsoid
//!   `alpha1^2/(2m) + alpha2^2/(2Jt) + kt xt^2/2 = E0`;
//! - `NAME.png` for each [`Series`]: its columns against `t`, one curve
//!   each, named in the legend (`chaplygin plan`'s `states.png` and
//!   `inputs.png`).
//!
//! And for `chaplygin linearize --sweep`, [`write_eigenvalue_plot`] writes
//! `eigenvalues.png`: the real and imaginary parts of the eigenvalues
//! against the swept variable; for `chaplygin steady --trace`,
//! [`write_steady_plot`] `steady.png`: a family of steady motions, its
//! stable points marked; for `chaplygin map`, [`write_design_map`]
//! `map.png`: the self-stable speeds over one or two parameters; for `chaplygin gait`, [`write_path_plot`]
//! the planar path alone and, for a principally kinematic model,
//! [`write_curvature_plot`] `curvature.png`: its constraint curvature
//! functions over the shape plane with the loop drawn on them; and
//! [`write_gait_comparison`] gaits side by side, their loops in the shape
//! plane and the paths they drive.
//!
//! Non-finite samples (a diverged run) break the curves instead of being
//! drawn. Text uses DejaVu Sans (Bitstream Vera license, shipped in
//! `assets/fonts` with its license), embedded in the binary and registered
//! with plotters' `ab_glyph` renderer, so no system font library is needed.

mod curvature;
mod design_map;
mod eigenvalues;
mod error;
mod figure4;
mod gaits;
mod path;
mod series;
mod spec;
mod steady;
mod style;

pub use curvature::{CurvatureField, write_curvature_plot};
pub use design_map::{DesignMapPlot, write_design_map};
pub use eigenvalues::{EigenvalueSweep, write_eigenvalue_plot};
pub use error::PlotError;
pub use gaits::{GaitCurve, write_gait_comparison};
pub use spec::{Figure4, PlanarPath, PlotSpec, Series, Table, Track};
pub use steady::{SteadyFamily, write_steady_plot};

use plotters::style::FontStyle;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Residuals below this value (zeros included) are drawn at it on the
/// logarithmic axis of `constraint_residual.png`.
pub const RESIDUAL_FLOOR: f64 = 1e-18;

/// The font every plot's text uses, registered as plotters' `sans-serif`.
const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The image edges allowed, in pixels: room for titles and labels at the
/// low end, a bounded pixel buffer at the high end.
const EDGES: std::ops::RangeInclusive<u32> = 200..=8192;

/// Writes the plots `spec` asks for into `dir` (created if absent) and
/// returns the files written, in the order of the module docs.
///
/// Every named column is checked before anything is drawn.
pub fn write_plots(table: &Table, spec: &PlotSpec, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    spec.validate()?;
    let columns = named_columns(table, spec)?;
    register_font()?;
    std::fs::create_dir_all(dir).map_err(|source| PlotError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let time = &columns[&spec.time];
    let mut written = Vec::new();
    if let Some(planar) = &spec.path {
        let file = dir.join("path.png");
        path::draw(&file, spec, planar, &columns)?;
        written.push(file);
    }
    if let Some(name) = &spec.energy {
        let file = dir.join("energy.png");
        series::draw_energy(&file, spec, time, &columns[name])?;
        written.push(file);
    }
    if let Some(name) = &spec.constraint_residual {
        let file = dir.join("constraint_residual.png");
        series::draw_residual(&file, spec, name, time, &columns[name])?;
        written.push(file);
    }
    if let Some(figure4) = &spec.figure4 {
        let file = dir.join("figure4.png");
        figure4::draw(&file, spec, figure4, &columns)?;
        written.push(file);
    }
    for series in &spec.series {
        let file = dir.join(format!("{}.png", series.name));
        series::draw_series(&file, spec, series, time, &columns)?;
        written.push(file);
    }
    Ok(written)
}

/// Writes the planar path of `table` (columns `x`, `y` and, if present,
/// the heading `theta`) to `file`, as `path.png` is drawn.
///
/// # Errors
/// A missing `x` or `y` column, an empty table, or an I/O error.
pub fn write_path_plot(table: &Table, file: &Path) -> Result<(), PlotError> {
    let spec = PlotSpec {
        energy: None,
        constraint_residual: None,
        ..PlotSpec::for_table(table)
    };
    let missing = |name: &str| PlotError::MissingColumn {
        name: name.to_string(),
        available: table.columns().to_vec(),
    };
    let planar = spec
        .path
        .clone()
        .ok_or_else(|| missing(if table.has_column("x") { "y" } else { "x" }))?;
    let columns = named_columns(table, &spec)?;
    register_font()?;
    path::draw(file, &spec, &planar, &columns)
}

/// The values of every column the spec names, each with a finite value.
fn named_columns(table: &Table, spec: &PlotSpec) -> Result<BTreeMap<String, Vec<f64>>, PlotError> {
    let mut columns = BTreeMap::new();
    for name in spec.named_columns() {
        columns.insert(name.to_string(), table.column(name)?);
    }
    if table.rows().is_empty() {
        return Err(PlotError::EmptyTable);
    }
    match columns
        .iter()
        .find(|(_, values)| !values.iter().any(|v| v.is_finite()))
    {
        Some((name, _)) => Err(PlotError::NoFiniteValue { name: name.clone() }),
        None => Ok(columns),
    }
}

/// Registers the embedded font as `sans-serif`, once per process.
fn register_font() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let registered = REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok()
    });
    if *registered {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}
