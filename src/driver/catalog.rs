//! The built-in models: their names, sources, default motions, and the
//! listing of `chaplygin list`. The sources are the files of `models/`,
//! linked into `catalog/` so that the crate's package holds them.

use chaplygin_codegen::interpret::InterpretedModel;

/// A built-in model's default motion, from its default configuration.
#[derive(Clone, Copy, Debug)]
pub enum Motion {
    /// `velocities(q, alpha)` with these momenta `alpha`.
    Momenta(&'static [f64]),
    /// These `dot(q)` assignments (expressions of the parameters, as
    /// `--initial` takes them), the other velocities solved from the
    /// constraints; used when `--initial` gives no velocity.
    Velocities(&'static [(&'static str, &'static str)]),
}

/// A built-in model.
#[derive(Clone, Copy, Debug)]
pub struct BuiltIn {
    /// Its name on the command line.
    pub name: &'static str,
    /// What it is.
    pub about: &'static str,
    /// Its model-language source.
    pub source: &'static str,
    /// The default configuration.
    pub q: &'static [f64],
    /// The default motion.
    pub motion: Motion,
}

/// The built-in models.
pub const BUILT_IN: [BuiltIn; 10] = [
    BuiltIn {
        name: "snakeboard",
        about: "snakeboard of Duindam & Stramigioli (2004), paper's momentum basis",
        source: include_str!("catalog/snakeboard.model"),
        q: &[0.0, 0.0, 0.0, 0.0, 0.3],
        motion: Motion::Momenta(&[1.0, 0.5, 0.025]),
    },
    BuiltIn {
        name: "sleigh",
        about: "Chaplygin sleigh: a knife edge with the centre of mass ahead of it",
        source: include_str!("catalog/sleigh.model"),
        q: &[0.0, 0.0, -0.5],
        motion: Motion::Momenta(&[1.0, 0.5]),
    },
    BuiltIn {
        name: "rolling-disk",
        about: "vertical disk rolling without slipping (Bloch 2003, chapter 1)",
        source: include_str!("catalog/rolling_disk.model"),
        q: &[0.0, 0.0, 0.0, 0.0],
        motion: Motion::Momenta(&[0.5, 0.2]),
    },
    BuiltIn {
        name: "differential-drive",
        about: "two-wheeled differential-drive robot",
        source: include_str!("catalog/differential_drive.model"),
        q: &[0.0, 0.0, 0.0, 0.0, 0.0],
        motion: Motion::Momenta(&[0.2, 0.1]),
    },
    BuiltIn {
        name: "rolling-disk-3d",
        about: "leaning disk rolling under gravity, declared as a mechanism",
        source: include_str!("catalog/rolling_disk_3d.model"),
        q: &[0.0, 0.0, 0.0, 0.1, 0.0],
        motion: Motion::Momenta(&[0.1, 0.0, 2.0]),
    },
    BuiltIn {
        name: "sleigh-bodies",
        about: "Chaplygin sleigh declared as a body on a blade",
        source: include_str!("catalog/sleigh_bodies.model"),
        q: &[0.0, 0.0, -0.5],
        motion: Motion::Momenta(&[1.0, 0.5]),
    },
    BuiltIn {
        name: "snakeboard-bodies",
        about: "snakeboard declared as bodies and wheel contacts",
        source: include_str!("catalog/snakeboard_bodies.model"),
        q: &[0.0, 0.0, 0.0, 0.0, 0.3],
        motion: Motion::Momenta(&[1.0, 0.5, 0.025]),
    },
    BuiltIn {
        name: "caster-robot",
        about: "wheeled mobile robot with a passive caster, declared as a mechanism",
        source: include_str!("catalog/caster_robot.model"),
        q: &[0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.0],
        motion: Motion::Momenta(&[0.5, 0.2]),
    },
    BuiltIn {
        name: "three-link-snake",
        about: "three-link kinematic snake in joint angles (Hatton & Choset 2011)",
        source: include_str!("catalog/three_link_snake.model"),
        q: &[0.0, 0.0, 0.0, 0.5, -0.5],
        motion: Motion::Momenta(&[0.2, 0.1]),
    },
    BuiltIn {
        name: "bicycle",
        about: "benchmark bicycle of Meijaard et al. (2007), declared as a mechanism",
        source: include_str!("catalog/bicycle.model"),
        q: &[0.0; 8],
        // Upright at 5 m/s, in the self-stable speed range, pushed sideways:
        // the lean oscillation decays.
        motion: Motion::Velocities(&[
            ("dot(theta_r)", "-5/rR"),
            ("dot(phi)", "0.5"),
            ("dot(delta)", "0"),
        ]),
    },
];

/// The built-in model called `name`.
pub fn built_in(name: &str) -> Option<&'static BuiltIn> {
    BUILT_IN.iter().find(|model| model.name == name)
}

/// The names of the built-in models, comma-separated.
pub fn names() -> String {
    let names: Vec<&str> = BUILT_IN.iter().map(|model| model.name).collect();
    names.join(", ")
}

/// The classification line of a derivation report.
fn classification(report: &str) -> &str {
    report
        .lines()
        .find_map(|line| line.trim().strip_prefix("classification: "))
        .unwrap_or("unknown")
}

/// Sizes `(n, c, k, p)` and the derivation report of a built-in model,
/// derived from its text.
fn facts(model: &BuiltIn) -> ([usize; 4], String) {
    match InterpretedModel::from_source(model.source) {
        Ok(derived) => {
            let sizes = derived.sizes();
            let report = derived.report().to_string();
            ([sizes.n, sizes.c, sizes.k, sizes.p], report)
        }
        Err(_) => ([0; 4], String::new()),
    }
}

/// The table printed by `chaplygin list`.
pub fn listing() -> String {
    let mut text = format!(
        "{:<20} {:>2} {:>2} {:>2} {:>2}  {:<30} {}\n",
        "model", "n", "c", "k", "p", "classification", "about"
    );
    for model in &BUILT_IN {
        let ([n, c, k, p], report) = facts(model);
        text.push_str(&format!(
            "{:<20} {n:>2} {c:>2} {k:>2} {p:>2}  {:<30} {}\n",
            model.name,
            classification(&report),
            model.about
        ));
    }
    text
}

/// What MODEL on the command line names.
pub enum Source {
    /// A built-in model.
    BuiltIn(&'static BuiltIn),
    /// A `.model` file and its text.
    File {
        /// The path as given.
        path: String,
        /// The file's text.
        text: String,
    },
}

/// MODEL is neither a built-in model nor a readable file.
#[derive(Debug, thiserror::Error)]
#[error("unknown model `{name}`: not a built-in model ({known}) nor a readable .model file")]
pub struct UnknownModel {
    /// What was given.
    pub name: String,
    /// The built-in names.
    pub known: String,
}

/// The built-in model called `model`, else the file at that path.
///
/// # Errors
/// [`UnknownModel`] when it is neither.
pub fn lookup(model: &str) -> Result<Source, UnknownModel> {
    if let Some(built_in) = built_in(model) {
        return Ok(Source::BuiltIn(built_in));
    }
    std::fs::read_to_string(model)
        .map(|text| Source::File {
            path: model.to_string(),
            text,
        })
        .map_err(|_| UnknownModel {
            name: model.to_string(),
            known: names(),
        })
}

impl Source {
    /// The model-language text.
    pub fn text(&self) -> &str {
        match self {
            Source::BuiltIn(built_in) => built_in.source,
            Source::File { text, .. } => text,
        }
    }

    /// The name errors are reported against (`file:line:col`).
    pub fn file_name(&self) -> String {
        match self {
            Source::BuiltIn(built_in) => format!("{}.model", built_in.name),
            Source::File { path, .. } => path.clone(),
        }
    }
}
