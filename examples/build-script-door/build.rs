//! Compiles `pushed_sleigh.model` into `OUT_DIR/pushed_sleigh.rs`; a model
//! error stops the build with `pushed_sleigh.model:line:col: error: ...`.

fn main() {
    if let Err(error) = chaplygin_codegen::Builder::new()
        .model_file("pushed_sleigh.model")
        .write_to_out_dir()
    {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
