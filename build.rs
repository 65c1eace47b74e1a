//! Generates the built-in models for the `chaplygin` command line from the
//! models crate's `.model` files (the command line compiles them itself: the
//! models crate depends on this package, so this package cannot depend on it).

fn main() {
    if std::env::var_os("CARGO_FEATURE_CLI").is_none() {
        return;
    }
    let models = [
        "snakeboard",
        "sleigh",
        "rolling_disk",
        "differential_drive",
        "rolling_disk_3d",
        "sleigh_bodies",
        "snakeboard_bodies",
        "caster_robot",
        "bicycle",
    ];
    let builder = models
        .iter()
        .fold(chaplygin_codegen::Builder::new(), |b, m| {
            b.model_file(format!("models/{m}.model"))
        });
    if let Err(error) = builder.write_to_out_dir() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
