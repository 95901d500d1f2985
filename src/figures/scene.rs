//! `scene` series of the figure configs: a 1D scene's profile along the bar, run or
//! analytic ([`SceneSeries`]).

use crate::budget::Budget;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::plot::Curve;
use crate::solver::scene::{Scene1D, builtin};
use serde::Deserialize;

/// How a scene curve is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneRoute {
    /// The scene run by [`Scene1D::run`].
    #[default]
    Run,
    /// The scene's analytic solution at its end time ([`Scene1D::exact_profile`]).
    Analytic,
}

/// Quantity of a scene profile.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneQuantity {
    /// The stress the form reports ([`Scene1D::stress_profile`]).
    #[default]
    Stress,
    /// The particle velocity.
    Velocity,
}

/// A 1D scene's profile at its end time against the reference position X of every particle
/// (end layers included), multiplied by `x_scale` and `y_scale` (e.g. 1e3 for mm, 1e−9 for GPa).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSeries {
    /// Built-in scene name (`uniform-bar`, `compressive-wave`, `tensile-wave`, `rod`).
    pub scene: String,
    /// Form (default: the scene's).
    pub form: Option<String>,
    /// Partition coefficient c (default: the scene's).
    pub c: Option<f64>,
    /// End time (s; default: the scene's).
    pub t_end: Option<f64>,
    /// Route (default: run).
    #[serde(default)]
    pub route: SceneRoute,
    /// Quantity (default: stress).
    #[serde(default)]
    pub quantity: SceneQuantity,
    /// Factor on the position.
    #[serde(default = "one")]
    pub x_scale: f64,
    /// Factor on the quantity.
    #[serde(default = "one")]
    pub y_scale: f64,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

fn one() -> f64 {
    1.0
}

impl SceneSeries {
    /// The scene: the built-in with this series' form, c and end time.
    pub fn scene(&self) -> Result<Scene1D> {
        let mut s = builtin(&self.scene)?;
        if let Some(f) = &self.form {
            s.form = f.clone();
        }
        if let Some(c) = self.c {
            s.c_partition = c;
        }
        if let Some(t) = self.t_end {
            s.t_end = t;
        }
        s.validate()?;
        Ok(s)
    }

    /// The profile (the run within `budget`, or the analytic solution).
    pub(super) fn curve(&self, budget: &Budget) -> Result<Curve> {
        crate::error::check_range("x_scale", self.x_scale, 0.0, f64::MAX, false, true)?;
        crate::error::check_range("y_scale", self.y_scale, 0.0, f64::MAX, false, true)?;
        let s = Scene1D {
            budget: *budget,
            ..self.scene()?
        };
        let x: Vec<f64> = s
            .reference_positions()
            .iter()
            .map(|x| x * self.x_scale)
            .collect();
        let (q, label) = match self.route {
            SceneRoute::Analytic => {
                let (v, sigma) = s.exact_profile(s.t_end).ok_or_else(|| {
                    Error::Incompatible(
                        format!("scene series: `{}` has no analytic solution", self.scene).into(),
                    )
                })?;
                let q = match self.quantity {
                    SceneQuantity::Stress => sigma,
                    SceneQuantity::Velocity => v,
                };
                (q, "analytic".to_string())
            }
            SceneRoute::Run => {
                let mut r = s.run(())?;
                let z = r
                    .final_state
                    .take()
                    .ok_or(Error::NonFinite("scene series: no final state"))?;
                let q = match self.quantity {
                    SceneQuantity::Stress => s.stress_profile(&z),
                    SceneQuantity::Velocity => z.v.iter().map(|[v]| *v).collect(),
                };
                let mut l = s.form.clone();
                if matches!(FormKind::by_name(&s.form)?, FormKind::Lnl | FormKind::Cll) {
                    l += &format!(" (c = {})", s.c_partition);
                }
                (q, l)
            }
        };
        Ok(Curve {
            label: self.label.clone().unwrap_or(label),
            x,
            y: q.iter().map(|v| v * self.y_scale).collect(),
            dashed: self.dashed,
        })
    }
}
