//! What the benchmarks that compile generated code share: `rustc -O` on a
//! source file linked against this build's `chaplygin`, and the operation
//! counts a generated `REPORT` states.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// `rustc -O` on `source` as a crate of `crate_type` (`bin`, `lib`), linked
/// against this build's `chaplygin`: the seconds it took and the artifact.
pub fn compile(source: &Path, crate_type: &str) -> Result<(f64, PathBuf), String> {
    let deps = std::env::current_exe()
        .map_err(|e| e.to_string())?
        .parent()
        .map(Path::to_path_buf)
        .ok_or("no directory of the running benchmark")?;
    let library = newest_rlib(&deps, "libchaplygin-")?;
    let artifact = source.with_extension(crate_type);
    let start = Instant::now();
    let status = Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .args(["-O", "--edition", "2024", "--crate-type", crate_type, "-o"])
        .arg(&artifact)
        .arg("-L")
        .arg(format!("dependency={}", deps.display()))
        .arg("--extern")
        .arg(format!("chaplygin={}", library.display()))
        .arg(source)
        .status()
        .map_err(|e| format!("rustc: {e}"))?;
    if !status.success() {
        return Err(format!("rustc failed on {}", source.display()));
    }
    Ok((start.elapsed().as_secs_f64(), artifact))
}

/// The most recently built `<prefix>*.rlib` in `directory`.
fn newest_rlib(directory: &Path, prefix: &str) -> Result<PathBuf, String> {
    std::fs::read_dir(directory)
        .map_err(|e| e.to_string())?
        .filter_map(Result::ok)
        .filter(|entry| {
            let name = entry.file_name().to_string_lossy().into_owned();
            name.starts_with(prefix) && name.ends_with(".rlib")
        })
        .max_by_key(|entry| entry.metadata().and_then(|m| m.modified()).ok())
        .map(|entry| entry.path())
        .ok_or_else(|| format!("no {prefix}*.rlib in {}", directory.display()))
}

/// `(before, after)` CSE from the generated REPORT line
/// `  name: before -> after`.
pub fn operations(code: &str, name: &str) -> Result<(f64, f64), String> {
    let marker = format!("\\n  {name}: ");
    let start = code
        .find(&marker)
        .ok_or_else(|| format!("no operation count for {name}"))?
        + marker.len();
    let counts: Vec<f64> = code[start..]
        .split("\\n")
        .next()
        .unwrap_or_default()
        .split(" -> ")
        .filter_map(|count| count.trim().parse().ok())
        .collect();
    match counts[..] {
        [before, after] => Ok((before, after)),
        _ => Err(format!("unreadable operation count for {name}")),
    }
}
