//! Generates the models declared in `.model` files.

fn main() {
    if let Err(error) = chaplygin_codegen::Builder::new()
        .model_file("snakeboard.model")
        .model_file("sleigh.model")
        .model_file("rolling_disk.model")
        .model_file("differential_drive.model")
        .write_to_out_dir()
    {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
