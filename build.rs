//! Generates the built-in models the `chaplygin` command line compiles with
//! rustc from the models crate's `.model` files (the models crate depends on
//! this package, so this package cannot depend on it). The heavy built-ins,
//! the caster robot and the bicycle, run from their text on the JIT.

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
