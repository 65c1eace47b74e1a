//! Generates the models declared in `.model` files, and the wheeled snakes
//! of two and three links from the text `snake::n_link_snake` writes (the
//! three-link one's reduced form is derived structured).

#[path = "src/snake.rs"]
mod snake;

fn main() {
    if let Err(error) = generate() {
        eprintln!("{error}");
        std::process::exit(1);
    }
}

fn generate() -> Result<(), Box<dyn std::error::Error>> {
    chaplygin_codegen::Builder::new()
        .model_file("snakeboard.model")
        .model_file("sleigh.model")
        .model_file("rolling_disk.model")
        .model_file("differential_drive.model")
        .model_file("rolling_disk_3d.model")
        .model_file("sleigh_bodies.model")
        .model_file("snakeboard_bodies.model")
        .model_file("caster_robot.model")
        .model_file("bicycle.model")
        .model_file("three_link_snake.model")
        .write_to_out_dir()?;
    println!("cargo:rerun-if-changed=src/snake.rs");
    let out_dir = std::path::PathBuf::from(std::env::var("OUT_DIR")?);
    for links in [2, 3] {
        let code = chaplygin_codegen::generate(&snake::n_link_snake(links))
            .map_err(|diagnostics| diagnostics.render(&format!("n_link_snake({links})")))?;
        std::fs::write(out_dir.join(format!("snake{links}.rs")), code)?;
    }
    Ok(())
}
