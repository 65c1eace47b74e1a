//! Model texts for the tests and fuzz targets: the built-in models, read from
//! the `models` crate's `.model` files.

/// The Chaplygin sleigh of the `models` crate.
pub const SLEIGH: &str = include_str!("../../../models/sleigh.model");

/// Every built-in model as `(name, text)`: snakeboard, rolling disk,
/// differential drive, sleigh.
pub fn built_in() -> Vec<(String, String)> {
    [
        (
            "Snakeboard",
            include_str!("../../../models/snakeboard.model"),
        ),
        (
            "RollingDisk",
            include_str!("../../../models/rolling_disk.model"),
        ),
        (
            "DifferentialDrive",
            include_str!("../../../models/differential_drive.model"),
        ),
        ("Sleigh", SLEIGH),
    ]
    .into_iter()
    .map(|(name, text)| (name.to_string(), text.to_string()))
    .collect()
}
