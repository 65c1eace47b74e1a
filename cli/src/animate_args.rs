//! `--animate [--fps F]`, which `simulate` and `gait` share
//! (docs/INTERFACE.md section 10): the model checked for something to draw
//! before the run, and `DIR/animation.html` of the run's table written
//! after it by `chaplygin::driver::animation`, its size said.

use chaplygin::driver::Failure;
use chaplygin::driver::animation;
use chaplygin::driver::engine::Loaded;
use chaplygin::runtime::record::Table;
use chaplygin_codegen::interpret::InterpretedModel;
use std::path::Path;

/// The arguments that ask for an animation.
#[derive(Debug, clap::Args)]
pub struct AnimateArgs {
    /// Also write `animation.html`: the model moving in 3D (a mechanism's
    /// bodies, a `drawing:` section's items), one page that works offline.
    #[arg(long)]
    animate: bool,
    /// The animation's frames per second of simulated time.
    #[arg(long, default_value_t = animation::DEFAULT_FPS, requires = "animate")]
    fps: f64,
}

/// The model to draw and its name, kept from before the run.
pub struct Drawn {
    model: InterpretedModel,
    label: String,
    fps: f64,
}

impl AnimateArgs {
    /// With `--animate`, the model `loaded` runs, which has something to
    /// draw.
    ///
    /// # Errors
    /// A model with nothing to draw.
    pub fn drawn(&self, loaded: &Loaded) -> Result<Option<Drawn>, Failure> {
        if !self.animate {
            return Ok(None);
        }
        animation::check(&loaded.model, &loaded.label)?;
        Ok(Some(Drawn {
            model: loaded.model.clone(),
            label: loaded.label.clone(),
            fps: self.fps,
        }))
    }
}

impl Drawn {
    /// Writes `out/animation.html` of the run recorded in `table` at the
    /// `parameters` it ran with, and says so with its size.
    ///
    /// # Errors
    /// A scene the page refuses, or an I/O error.
    pub fn write(
        mut self,
        table: &Table,
        parameters: &[(String, f64)],
        out: &Path,
    ) -> Result<(), Failure> {
        for (name, value) in parameters {
            if self.model.names().parameters.contains(name) {
                self.model.set_parameter(name, *value)?;
            }
        }
        let html = animation::page(&self.model, &self.label, table, self.fps)?;
        std::fs::create_dir_all(out)?;
        let path = out.join("animation.html");
        std::fs::write(&path, &html)?;
        let kilobytes = html.len().div_ceil(1000);
        crate::say(&format!("wrote {} ({kilobytes} kB)\n", path.display()))?;
        Ok(())
    }
}
