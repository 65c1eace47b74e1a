//! The generated code, measured: for every built-in model and the N-link
//! snake (`CHAPLYGIN_EMITTED_SNAKE` links, default 12), the Rust
//! `chaplygin_codegen::generate` writes, which `chaplygin derive MODEL
//! --format rust` prints. For each emitted function it prints its
//! operations after CSE (the generated `REPORT`'s count) and its bytes,
//!
//! ```text
//! EMITTED bicycle reduced_rhs_jacobian_shared 60242 ops 1069334 bytes (17.8 bytes/op)
//! ```
//!
//! (a function that only calls the body computing it, a shared body or in
//! a trait's impl the inherent item, prints its bytes alone), then the
//! model's total bytes and the seconds `rustc -O` takes on it as a library
//! (`TOTAL bicycle 2060188 bytes, rustc -O 20.8 s`).
//! `CHAPLYGIN_EMITTED_MODELS=bicycle,snake` restricts the run to the
//! models named.
//!
//! Run with `cargo bench -p chaplygin-models --bench emitted`.

mod rustc;

use chaplygin_models::{
    bicycle, caster_robot, differential_drive, rolling_disk, rolling_disk_3d, sleigh,
    sleigh_bodies, snake, snakeboard, snakeboard_bodies, three_link_snake,
};
use rustc::{compile, operations};

fn main() {
    let links = std::env::var("CHAPLYGIN_EMITTED_SNAKE")
        .ok()
        .and_then(|text| text.parse().ok())
        .unwrap_or(12);
    let chosen = std::env::var("CHAPLYGIN_EMITTED_MODELS").ok();
    let workspace = std::env::temp_dir().join("chaplygin-emitted");
    if let Err(error) = std::fs::create_dir_all(&workspace) {
        println!("cannot create {}: {error}", workspace.display());
        return;
    }
    for (name, text) in models(links) {
        if chosen
            .as_ref()
            .is_some_and(|chosen| !chosen.split(',').any(|c| c.trim() == name))
        {
            continue;
        }
        let code = match chaplygin_codegen::generate(&text) {
            Ok(code) => code,
            Err(diagnostics) => {
                println!("{name}: {}", diagnostics.render(name));
                continue;
            }
        };
        for (function, text) in functions(&code) {
            let bytes = text.len();
            let ops = (!forwards(&function, &text))
                .then(|| {
                    operations(&code, &function)
                        .or_else(|_| operations(&code, &format!("{function} (shared body)")))
                        .ok()
                })
                .flatten();
            match ops {
                Some((_, after)) => println!(
                    "EMITTED {name} {function} {after} ops {bytes} bytes ({:.1} bytes/op)",
                    bytes as f64 / after.max(1.0)
                ),
                None => println!("EMITTED {name} {function} {bytes} bytes"),
            }
        }
        let source = workspace.join(format!("{name}.rs"));
        let compiled = std::fs::write(&source, &code)
            .map_err(|e| e.to_string())
            .and_then(|()| compile(&source, "lib"));
        match compiled {
            Ok((seconds, _)) => {
                println!("TOTAL {name} {} bytes, rustc -O {seconds:.1} s", code.len())
            }
            Err(reason) => println!("TOTAL {name} {} bytes, {reason}", code.len()),
        }
    }
}

/// The built-in models' texts and the snake of `links` links.
fn models(links: usize) -> Vec<(&'static str, String)> {
    vec![
        ("snakeboard", snakeboard::MODEL_TEXT.to_string()),
        ("sleigh", sleigh::MODEL_TEXT.to_string()),
        ("rolling_disk", rolling_disk::MODEL_TEXT.to_string()),
        (
            "differential_drive",
            differential_drive::MODEL_TEXT.to_string(),
        ),
        ("rolling_disk_3d", rolling_disk_3d::MODEL_TEXT.to_string()),
        ("sleigh_bodies", sleigh_bodies::MODEL_TEXT.to_string()),
        (
            "snakeboard_bodies",
            snakeboard_bodies::MODEL_TEXT.to_string(),
        ),
        ("caster_robot", caster_robot::MODEL_TEXT.to_string()),
        ("bicycle", bicycle::MODEL_TEXT.to_string()),
        ("three_link_snake", three_link_snake::MODEL_TEXT.to_string()),
        ("snake", snake::n_link_snake(links)),
    ]
}

/// Each function of the formatted items (`fn` at the impl's indentation)
/// with its text, from its signature to its closing brace.
fn functions(code: &str) -> Vec<(String, String)> {
    let mut found = Vec::new();
    let mut open: Option<(String, String)> = None;
    for line in code.lines() {
        let signature = line
            .strip_prefix("    pub fn ")
            .or_else(|| line.strip_prefix("    fn "));
        if let Some(rest) = signature {
            let name = rest.split(['(', '<']).next().unwrap_or(rest).to_string();
            open = Some((name, String::new()));
        }
        if let Some((_, text)) = &mut open {
            text.push_str(line);
            text.push('\n');
        }
        if line == "    }"
            && let Some(function) = open.take()
        {
            found.push(function);
        }
    }
    found
}

/// Whether `function` only calls the body that computes it: a shared body
/// (`self.{members}_shared(..)`) or, in a trait's impl, the inherent item
/// (`Model::function(self, ..)`); its operations are that body's.
fn forwards(function: &str, text: &str) -> bool {
    let calls_shared = !function.ends_with("_shared") && text.contains("_shared(");
    calls_shared || text.contains(&format!("::{function}(self"))
}
