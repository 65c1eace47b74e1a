//! The trajectory plots on synthetic trajectories whose shape is known: a
//! unit circle traversed with the heading along the tangent, an energy with
//! a small oscillating error, a residual that is zero on every other row,
//! and a Figure 4 curve placed on its ellipsoid. Checks the files written,
//! their PNG signature and size, and the structured errors of bad input.
#![cfg(feature = "cli")]

use crate::support::scratch;
use chaplygin::plot::{
    Figure4, GaitCurve, PlanarPath, PlotError, PlotSpec, Table, Track, write_gait_comparison,
    write_plots,
};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

const COLUMNS: [&str; 9] = [
    "t",
    "x",
    "y",
    "theta",
    "group",
    "torso",
    "xt",
    "energy",
    "constraint_residual",
];

/// Figure 4's parameters for the synthetic curve.
const M: f64 = 1.0;
const JT: f64 = 0.3;
const KT: f64 = 2.0;

/// A sample of the synthetic trajectory at time `t`.
fn sample(row: usize, t: f64) -> Vec<f64> {
    let energy = 0.8;
    let (polar, azimuth) = (1.0 + 0.3 * t.sin(), t);
    let alpha1 = (2.0 * M * energy).sqrt() * polar.sin() * azimuth.cos();
    let alpha2 = (2.0 * JT * energy).sqrt() * polar.sin() * azimuth.sin();
    let xt = (2.0 * energy / KT).sqrt() * polar.cos();
    let residual = if row.is_multiple_of(2) {
        0.0
    } else {
        1e-12 * t
    };
    vec![
        t,
        t.cos(),
        t.sin(),
        t + FRAC_PI_2,
        alpha1,
        alpha2,
        xt,
        1.0 + 1e-6 * t.sin(),
        residual,
    ]
}

/// The synthetic trajectory over `rows` samples on `[0, 2 pi]`.
fn trajectory(rows: usize) -> Table {
    let mut table = Table::new(COLUMNS.map(String::from).to_vec()).unwrap();
    for row in 0..rows {
        let t = 2.0 * std::f64::consts::PI * row as f64 / (rows - 1) as f64;
        table.push_row(sample(row, t)).unwrap();
    }
    table
}

fn figure4() -> Figure4 {
    Figure4 {
        alpha1: "group".into(),
        alpha2: "torso".into(),
        xt: "xt".into(),
        m: M,
        jt: JT,
        kt: KT,
    }
}

/// The width and height in a PNG's IHDR chunk, after checking the signature.
fn png_size(file: &Path) -> (u32, u32) {
    let bytes = std::fs::read(file).unwrap();
    assert_eq!(
        &bytes[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is not a PNG",
        file.display()
    );
    assert_eq!(&bytes[12..16], b"IHDR");
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

/// The number of pixels of exactly this colour in a PNG.
fn pixels_of(file: &Path, color: [u8; 3]) -> usize {
    let decoder = png::Decoder::new(std::fs::File::open(file).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buffer).unwrap();
    assert_eq!(frame.color_type, png::ColorType::Rgb, "{}", file.display());
    buffer[..frame.buffer_size()]
        .chunks_exact(3)
        .filter(|pixel| *pixel == color)
        .count()
}

const BLUE: [u8; 3] = [0, 0, 255];
const GREEN: [u8; 3] = [0, 255, 0];
const RED: [u8; 3] = [255, 0, 0];

#[test]
fn the_curves_and_their_ends_are_drawn() {
    let dir = scratch("plot-pixels");
    let spec = PlotSpec::default().with_figure4(figure4());
    let written = write_plots(&trajectory(400), &spec, dir.path()).unwrap();
    let [path, energy, residual, figure4] = [0, 1, 2, 3].map(|i| written[i].as_path());
    for file in [path, figure4] {
        let (curve, start, end) = (
            pixels_of(file, BLUE),
            pixels_of(file, GREEN),
            pixels_of(file, RED),
        );
        // a 2-pixel curve hundreds of pixels long; discs of radius 9 and 5,
        // the end's drawn over the start's (the synthetic curves are closed)
        assert!(curve > 1000, "{}: {curve} curve pixels", file.display());
        assert!(
            start > 100 && end > 30,
            "{}: start {start}, end {end}",
            file.display()
        );
    }
    for file in [energy, residual] {
        let curve = pixels_of(file, BLUE);
        assert!(curve > 500, "{}: {curve} curve pixels", file.display());
    }
}

#[test]
fn every_plot_is_a_png_of_the_requested_size() {
    let dir = scratch("plot-all");
    let spec = PlotSpec::default()
        .with_figure4(figure4())
        .with_unit("t", "s");
    let written = write_plots(&trajectory(400), &spec, dir.path()).unwrap();
    let names: Vec<_> = written
        .iter()
        .map(|file| file.file_name().unwrap().to_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "path.png",
            "energy.png",
            "constraint_residual.png",
            "figure4.png"
        ]
    );
    for file in &written {
        assert_eq!(file.parent(), Some(dir.path()));
        assert_eq!(png_size(file), (1024, 768), "{}", file.display());
    }
}

#[test]
fn the_image_size_follows_the_spec() {
    let dir = scratch("plot-size");
    let spec = PlotSpec {
        size: (640, 480),
        ..PlotSpec::default()
    };
    for file in write_plots(&trajectory(50), &spec, dir.path()).unwrap() {
        assert_eq!(png_size(&file), (640, 480));
    }
}

#[test]
fn plots_without_their_columns_are_left_out_by_for_table() {
    let dir = scratch("plot-subset");
    let mut table = Table::new(vec!["t".into(), "energy".into()]).unwrap();
    for row in 0..20 {
        table.push_row(vec![row as f64, 2.0]).unwrap();
    }
    let spec = PlotSpec::for_table(&table);
    assert_eq!(spec.path, None);
    assert_eq!(spec.constraint_residual, None);
    let written = write_plots(&table, &spec, dir.path()).unwrap();
    assert_eq!(written, [dir.path().join("energy.png")]);
}

#[test]
fn for_table_draws_the_path_without_arrows_when_there_is_no_heading() {
    let table = Table::new(["t", "x", "y"].map(String::from).to_vec()).unwrap();
    let path = PlotSpec::for_table(&table).path.unwrap();
    assert_eq!(
        (path.x.as_str(), path.y.as_str(), path.heading),
        ("x", "y", None)
    );
}

#[test]
fn a_missing_column_is_named_and_nothing_is_written() {
    let parent = scratch("plot-missing");
    let dir = parent.path().join("plots");
    let spec = PlotSpec {
        path: Some(PlanarPath {
            x: "x".into(),
            y: "y".into(),
            heading: Some("heading".into()),
            tracks: Vec::new(),
        }),
        ..PlotSpec::default()
    };
    let error = write_plots(&trajectory(10), &spec, &dir).unwrap_err();
    match &error {
        PlotError::MissingColumn { name, available } => {
            assert_eq!(name, "heading");
            assert_eq!(available, &COLUMNS.map(String::from));
        }
        other => panic!("expected a missing column, got {other:?}"),
    }
    assert!(error.to_string().contains("`heading`"), "{error}");
    assert!(!dir.exists(), "nothing is written when a column is missing");
}

#[test]
fn a_track_names_its_columns_and_one_missing_is_an_error() {
    let parent = scratch("plot-track");
    let dir = parent.path().join("plots");
    let track = Track {
        point: "contact".into(),
        x: "contact.x".into(),
        y: "contact.y".into(),
    };
    let spec = PlotSpec::for_table(&trajectory(10)).with_tracks(vec![track.clone()]);
    assert_eq!(spec.path.as_ref().unwrap().tracks, [track]);
    match write_plots(&trajectory(10), &spec, &dir).unwrap_err() {
        PlotError::MissingColumn { name, .. } => assert_eq!(name, "contact.x"),
        other => panic!("expected a missing column, got {other:?}"),
    }
    assert!(!dir.exists(), "nothing is written when a column is missing");
    let planeless = Table::new(["t", "energy"].map(String::from).to_vec()).unwrap();
    let no_path = PlotSpec::for_table(&planeless).with_tracks(vec![Track {
        point: "p".into(),
        x: "p.x".into(),
        y: "p.y".into(),
    }]);
    assert_eq!(no_path.path, None, "no tracks without a path");
}

#[test]
fn rows_must_match_the_columns() {
    let mut table = Table::new(vec!["t".into(), "x".into()]).unwrap();
    table.push_row(vec![0.0, 1.0]).unwrap();
    let error = table.push_row(vec![1.0]).unwrap_err();
    assert!(
        matches!(
            error,
            PlotError::RowLength {
                row: 1,
                expected: 2,
                found: 1
            }
        ),
        "{error:?}"
    );
    assert_eq!(table.rows().len(), 1);
}

#[test]
fn column_names_are_distinct() {
    let error = Table::new(["t", "x", "t"].map(String::from).to_vec()).unwrap_err();
    assert!(
        matches!(&error, PlotError::DuplicateColumn { name } if name == "t"),
        "{error:?}"
    );
}

#[test]
fn an_empty_table_is_an_error() {
    let table = Table::new(COLUMNS.map(String::from).to_vec()).unwrap();
    let dir = scratch("plot-empty");
    let error = write_plots(&table, &PlotSpec::default(), dir.path()).unwrap_err();
    assert!(matches!(error, PlotError::EmptyTable), "{error:?}");
}

#[test]
fn figure4_parameters_must_be_positive() {
    let spec = PlotSpec::default().with_figure4(Figure4 {
        kt: 0.0,
        ..figure4()
    });
    let dir = scratch("plot-kt");
    let error = write_plots(&trajectory(10), &spec, dir.path()).unwrap_err();
    assert!(
        matches!(
            error,
            PlotError::NonPositiveParameter {
                name: "kt",
                value: 0.0
            }
        ),
        "{error:?}"
    );
}

#[test]
fn image_sizes_outside_200_to_8192_pixels_are_errors() {
    for (width, height) in [(100, 768), (1024, 100_000)] {
        let spec = PlotSpec {
            size: (width, height),
            ..PlotSpec::default()
        };
        let dir = scratch("plot-size-limits");
        let error = write_plots(&trajectory(10), &spec, dir.path()).unwrap_err();
        assert!(
            matches!(error, PlotError::ImageSize { width: w, height: h } if (w, h) == (width, height)),
            "{error:?}"
        );
    }
}

#[test]
fn a_column_without_finite_values_is_an_error() {
    let mut table = Table::new(["t", "energy"].map(String::from).to_vec()).unwrap();
    table.push_row(vec![0.0, f64::NAN]).unwrap();
    let dir = scratch("plot-nan");
    let error = write_plots(&table, &PlotSpec::for_table(&table), dir.path()).unwrap_err();
    assert!(
        matches!(&error, PlotError::NoFiniteValue { name } if name == "energy"),
        "{error:?}"
    );
}

#[test]
fn an_output_path_that_is_a_file_is_an_io_error() {
    let dir = scratch("plot-file");
    let file = dir.path().join("file");
    std::fs::write(&file, b"not a directory").unwrap();
    let error = write_plots(&trajectory(10), &PlotSpec::default(), &file).unwrap_err();
    assert!(
        matches!(&error, PlotError::Io { path, .. } if *path == file),
        "{error:?}"
    );
}

#[test]
fn zero_initial_energy_and_non_finite_samples_still_plot() {
    let dir = scratch("plot-degenerate");
    let smooth = trajectory(100);
    let mut table = Table::new(smooth.columns().to_vec()).unwrap();
    for (row, values) in smooth.rows().iter().enumerate() {
        let mut values = values.clone();
        values[7] -= 1.0; // E(0) = 0
        if (40..45).contains(&row) {
            values[1] = f64::NAN;
            values[8] = f64::INFINITY;
        }
        table.push_row(values).unwrap();
    }
    let written = write_plots(&table, &PlotSpec::default(), dir.path()).unwrap();
    assert_eq!(written.len(), 3);
    for file in written {
        assert_eq!(png_size(&file), (1024, 768));
    }
}

/// Two gaits side by side: an 1800 x 800 PNG with each gait's colour (the
/// first red, the second blue) in both panels; no gait, or a gait without
/// points, is an error and writes nothing.
#[test]
fn gaits_are_compared_in_their_colours() {
    let dir = scratch("plot-gaits");
    let circle = |radius: f64| -> Vec<(f64, f64)> {
        (0..=200)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 200.0;
                (radius * t.cos(), radius * t.sin())
            })
            .collect()
    };
    let gait = |label: &str, radius: f64| GaitCurve {
        label: label.to_string(),
        shape: circle(radius),
        path: circle(2.0 * radius)
            .iter()
            .map(|&(x, y)| (x + 2.0 * radius, y))
            .collect(),
    };
    let file = dir.path().join("gaits.png");
    let curves = [gait("small", 0.5), gait("large", 1.0)];
    write_gait_comparison("Two gaits", &curves, ["a", "b"], &file).unwrap();
    assert_eq!(png_size(&file), (1800, 800));
    let (red, blue) = (
        pixels_of(&file, [214, 39, 40]),
        pixels_of(&file, [31, 119, 180]),
    );
    assert!(red > 1000 && blue > 1000, "red {red}, blue {blue}");
    let empty = GaitCurve {
        path: Vec::new(),
        ..gait("empty", 1.0)
    };
    let other = dir.path().join("none.png");
    for curves in [&[][..], &[empty][..]] {
        let error = write_gait_comparison("", curves, ["a", "b"], &other).unwrap_err();
        assert!(matches!(error, PlotError::EmptyTable), "{error:?}");
        assert!(!other.exists());
    }
}
