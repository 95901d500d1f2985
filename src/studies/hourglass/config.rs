//! The tensile-or-hourglass study's config (`analysis/configs/tensile_or_hourglass.json` or the
//! bare command's [`HourglassConfig::quick`]), checked field by field.

use crate::analysis::QuerySpec;
use crate::budget::Budget;
use crate::error::{Error, Result, check_range, field};
use crate::forms::PrestressKind;
use serde::{Deserialize, Serialize};

/// A pre-stress state of the study: a shape ([`PrestressKind`]) and a sign.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum StressState {
    /// σ0 = σ̄ C I, σ̄ > 0.
    IsotropicTension,
    /// σ0 = σ̄ C e_x ⊗ e_x, σ̄ > 0.
    UniaxialTension,
    /// σ0 = σ̄ C (e_x ⊗ e_y + e_y ⊗ e_x): principal stresses ±σ̄ C.
    Shear,
    /// σ0 = −σ̄ C I.
    IsotropicCompression,
    /// σ0 = −σ̄ C e_x ⊗ e_x.
    UniaxialCompression,
}

impl StressState {
    /// The names, as the config spells them.
    pub const ALL: [(StressState, &'static str); 5] = [
        (StressState::IsotropicTension, "isotropic-tension"),
        (StressState::UniaxialTension, "uniaxial-tension"),
        (StressState::Shear, "shear"),
        (StressState::IsotropicCompression, "isotropic-compression"),
        (StressState::UniaxialCompression, "uniaxial-compression"),
    ];

    /// The name.
    pub fn name(self) -> &'static str {
        crate::error::name_in(&Self::ALL, self)
    }

    /// A short label (figure panels).
    pub fn short(self) -> &'static str {
        match self {
            StressState::IsotropicTension => "iso. tension",
            StressState::UniaxialTension => "uniax. tension",
            StressState::Shear => "pure shear",
            StressState::IsotropicCompression => "iso. compr.",
            StressState::UniaxialCompression => "uniax. compr.",
        }
    }

    /// The pre-stress shape and the sign of σ̄.
    pub fn prestress(self) -> (PrestressKind, f64) {
        match self {
            StressState::IsotropicTension => (PrestressKind::Isotropic, 1.0),
            StressState::UniaxialTension => (PrestressKind::Uniaxial, 1.0),
            StressState::Shear => (PrestressKind::Shear, 1.0),
            StressState::IsotropicCompression => (PrestressKind::Isotropic, -1.0),
            StressState::UniaxialCompression => (PrestressKind::Uniaxial, -1.0),
        }
    }
}

/// One remedy: a label and the question that defines it (form, kernel, h, shape, artificial
/// stress, hourglass coefficient, lattice, …); the study sets its dimension, pre-stress,
/// Poisson ratio and sampling.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Remedy {
    /// Label in the table, the figure and the note.
    pub label: String,
    /// The question's parameters by name (as `query`'s flags; `dim`, `stress`, `prestress`,
    /// `poisson`, `grid` and `dt` are the study's).
    pub query: QuerySpec,
}

/// A study config; unknown fields are rejected by name.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct HourglassConfig {
    /// The remedies (1 to 12), each a question.
    pub remedies: Vec<Remedy>,
    /// The pre-stress states (1 to 5; default: isotropic and uniaxial tension, shear,
    /// isotropic compression).
    #[serde(default = "default_states")]
    pub states: Vec<StressState>,
    /// |σ̄| of the growth curves and the maps, ascending, 2 to 64 values in [1e-6, 2].
    pub stress: Vec<f64>,
    /// Poisson ratios ν of the maps (G/K = 3(1 − 2ν)/(2(1 + ν))), 1 to 16 values in
    /// [−0.99, 0.5).
    pub poisson: Vec<f64>,
    /// ν of the growth curves, the onsets and the dispersion costs (default 0.3).
    #[serde(default = "default_poisson")]
    pub reference_poisson: f64,
    /// Wave vectors per reciprocal direction of each question, 4 to 64 (default 16; even, so
    /// that the zero-energy wave vectors, half a reciprocal vector, are on the grid).
    #[serde(default = "default_grid")]
    pub grid: usize,
    /// Dimension, 2 or 3 (default 2).
    #[serde(default = "default_dim")]
    pub dim: u8,
    /// Lattice of every remedy: 2D square (default) or hex; 3D sc (default), bcc or fcc.
    #[serde(default)]
    pub lattice: Option<String>,
    /// Figure written to figures/ (with its data next to it as .json).
    #[serde(default)]
    pub output: Option<String>,
    /// What the figure shows (kept with the config and the data).
    #[serde(default)]
    pub note: String,
    /// The budget the questions must stay within (not read from the file).
    #[serde(skip)]
    pub budget: Budget,
}

fn default_states() -> Vec<StressState> {
    vec![
        StressState::IsotropicTension,
        StressState::UniaxialTension,
        StressState::Shear,
        StressState::IsotropicCompression,
    ]
}
fn default_poisson() -> f64 {
    0.3
}
fn default_grid() -> usize {
    16
}
fn default_dim() -> u8 {
    2
}

/// The remedies of the bare command in dimension `dim`: the classical form alone, with
/// Monaghan–Gray artificial stress (ε = 0.3, n = 4, PySPH's; 2D only), with the corrected
/// (Bonet–Lok) gradient, SPH-ENOG, the total-Lagrangian form alone, with Ganzenmüller's control
/// (α = 10, LAMMPS's example) and tl-enog; m4, h = 1.2Δx.
pub fn default_remedies(dim: u8) -> Vec<Remedy> {
    let r = |label: &str, form: &str, f: &dyn Fn(&mut QuerySpec)| {
        let mut q = QuerySpec {
            form: Some(form.into()),
            ..QuerySpec::default()
        };
        f(&mut q);
        Remedy {
            label: label.into(),
            query: q,
        }
    };
    let art = r("art. stress ε = 0.3", "classical", &|q| {
        q.art_eps = Some(0.3)
    });
    vec![
        Some(r("classical", "classical", &|_| {})),
        (dim == 2).then_some(art),
        Some(r("Bonet–Lok", "classical", &|q| {
            q.shape = Some("corrected".into())
        })),
        Some(r("SPH-ENOG", "enog", &|_| {})),
        Some(r("TLSPH", "total-lagrangian", &|_| {})),
        Some(r("Ganzenmüller α = 10", "total-lagrangian", &|q| {
            q.hourglass = Some(10.0)
        })),
        Some(r("TL-ENOG", "tl-enog", &|_| {})),
    ]
    .into_iter()
    .flatten()
    .collect()
}

impl HourglassConfig {
    /// The bare command's study in dimension `dim`: [`default_remedies`], the default states,
    /// |σ̄| from 1e-3 to 0.5 (10 values), ν = 0.3, 0.45, 0.49, 0.499 for the maps, grid 12
    /// (2D) or 6 (3D).
    pub fn quick(dim: u8) -> Self {
        Self {
            remedies: default_remedies(dim),
            states: default_states(),
            stress: (0..10)
                .map(|i| 1e-3 * 500f64.powf(i as f64 / 9.0))
                .collect(),
            poisson: vec![0.3, 0.45, 0.49, 0.499],
            reference_poisson: default_poisson(),
            grid: if dim == 3 { 6 } else { 12 },
            dim,
            lattice: None,
            output: None,
            note: String::new(),
            budget: Budget::default(),
        }
    }

    /// Checks every field; errors name the field.
    pub fn validate(&self) -> Result<()> {
        let count = crate::studies::config::check_len;
        count("remedies", self.remedies.len(), 1, 12)?;
        count("states", self.states.len(), 1, 5)?;
        count("stress", self.stress.len(), 2, 64)?;
        count("poisson", self.poisson.len(), 1, 16)?;
        let labels: Vec<&str> = self.remedies.iter().map(|r| r.label.as_str()).collect();
        crate::studies::config::no_duplicates("remedies", &labels)?;
        let states: Vec<&str> = self.states.iter().map(|s| s.name()).collect();
        crate::studies::config::no_duplicates("states", &states)?;
        for w in self.stress.windows(2) {
            if w[1] <= w[0] {
                return Err(Error::Incompatible(
                    field("stress") + ": the values must ascend",
                ));
            }
        }
        for &s in &self.stress {
            check_range("stress", s, 1e-6, 2.0, true, true)?;
        }
        for &nu in self.poisson.iter().chain([&self.reference_poisson]) {
            check_range("poisson", nu, -0.99, 0.5, true, false)?;
        }
        if !(4..=64).contains(&self.grid) || !self.grid.is_multiple_of(2) {
            return Err(Error::OutOfRange {
                field: "grid",
                value: self.grid as f64,
                range:
                    "an even number in [4, 64] (the zero-energy wave vectors lie on an even grid)"
                        .into(),
            });
        }
        if !(2..=3).contains(&self.dim) {
            return Err(Error::OutOfRange {
                field: "dim",
                value: self.dim as f64,
                range: "must be 2 or 3".into(),
            });
        }
        for r in &self.remedies {
            let q = &r.query;
            let set = [
                ("dim", q.dim.is_some()),
                ("stress", q.stress.is_some()),
                ("prestress", q.prestress.is_some()),
                ("poisson", q.poisson.is_some()),
                ("grid", q.grid.is_some()),
                ("dt", q.dt.is_some()),
                ("lattice", q.lattice.is_some()),
            ];
            if let Some((name, _)) = set.iter().find(|s| s.1) {
                return Err(Error::Incompatible(
                    field("remedies")
                        + format!(" `{}`: ", r.label)
                        + field(name)
                        + " is set by the study (its states, stresses, Poisson ratios, grid and lattice)",
                ));
            }
            // each remedy must be a valid question of the study's dimension
            let spec = self.spec(r, 0.0, PrestressKind::Isotropic, self.reference_poisson);
            let checked = match self.dim {
                2 => spec.query::<2>(&self.budget).map(|_| ()),
                _ => spec.query::<3>(&self.budget).map(|_| ()),
            };
            checked.map_err(|e| Error::Config {
                file: format!("remedy `{}`", r.label),
                msg: e.to_string(),
            })?;
        }
        if let Some(o) = &self.output {
            crate::studies::config::check_output("tensile-or-hourglass config", Some(o))?;
        }
        Ok(())
    }

    /// The question of remedy `r` at σ̄ = `stress` (signed) of shape `kind`, Poisson ratio `nu`.
    pub fn spec(&self, r: &Remedy, stress: f64, kind: PrestressKind, nu: f64) -> QuerySpec {
        let material = r.query.material.as_deref().unwrap_or("elastic");
        QuerySpec {
            dim: Some(self.dim),
            stress: Some(stress),
            prestress: Some(kind.name().into()),
            poisson: (material != "hydro").then_some(nu),
            grid: Some(self.grid),
            lattice: self.lattice.clone(),
            ..r.query.clone()
        }
    }
}

/// Parses a config (errors name the file and the field) and validates it.
pub fn parse_config(file: &str, text: &str) -> Result<HourglassConfig> {
    let c: HourglassConfig = crate::studies::config::parse_json(file, text)?;
    c.validate().map_err(|e| Error::Config {
        file: file.into(),
        msg: e.to_string(),
    })?;
    Ok(c)
}
