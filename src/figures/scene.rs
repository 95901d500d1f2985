//! `scene` series of the figure configs: a scene's profile along the bar (its central row in
//! 2D and 3D), run or analytic, or a probe's history ([`SceneSeries`]).

use crate::budget::Budget;
use crate::error::{Error, Result};
use crate::forms::FormKind;
use crate::plot::Curve;
use crate::solver::scene::{Scene, builtin};
use serde::Deserialize;

/// How a scene curve is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneRoute {
    /// The scene run by [`Scene::run`].
    #[default]
    Run,
    /// The scene's analytic solution at its end time ([`Scene::exact_profile`]).
    Analytic,
}

/// Quantity of a scene profile or probe history.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum SceneQuantity {
    /// The stress the form reports ([`crate::solver::scene::SceneReport::final_stress`]).
    #[default]
    Stress,
    /// The particle velocity.
    Velocity,
    /// The displacement (probes only).
    Displacement,
    /// The stretch F (probes of the total-Lagrangian form only).
    Stretch,
    /// A `round` bar's length against time ([`crate::solver::scene::SceneReport::extent_length`];
    /// no probe).
    Length,
    /// A `round` bar's radius at its left end against time (`extent_radius`; no probe).
    Radius,
}

/// The abscissa of a probe series.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum ProbeAbscissa {
    /// Time (s, times `x_scale`).
    #[default]
    Time,
    /// The probe's stretch F (total-Lagrangian); the analytic route draws the material's
    /// uniaxial-strain Cauchy stress T11(F) over the run's range of F.
    Stretch,
    /// The stretch applied to a bar whose left end is held: 1 + u_k/(X_k − origin), u_k the
    /// displacement of probe k = `stretch_probe` (the pulled end); the analytic route as for
    /// `stretch`.
    AppliedStretch,
}

/// A scene's profile at its end time against the reference position X of every particle of
/// its central row (end layers included; every particle in 1D), or a probe's history,
/// multiplied by `x_scale` and `y_scale` (e.g. 1e3 for mm, 1e−9 for GPa).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSeries {
    /// Built-in scene name (`uniform-bar`, `compressive-wave`, `tensile-wave`, `rod`) or a
    /// scene file (a path ending in `.json`, relative to the working directory, e.g.
    /// `analysis/scenes/thesis-traction-pulse.json`).
    pub scene: String,
    /// Keys merged into the scene before it runs (objects key by key, e.g.
    /// `{"left": {"traction": {"smoothing": 2e-6}}}`), validated as the scene's own.
    #[serde(default)]
    pub overrides: Option<serde_json::Value>,
    /// Index of the scene's probe whose history is drawn (instead of a profile at the end
    /// time).
    #[serde(default)]
    pub probe: Option<usize>,
    /// Abscissa of a probe history (default: time).
    #[serde(default)]
    pub against: ProbeAbscissa,
    /// The probe at the pulled end, for `against: applied-stretch`.
    #[serde(default)]
    pub stretch_probe: Option<usize>,
    /// The transverse stretch λ2 of the analytic T11(λ1) (plane strain, λ3 = 1; default 1:
    /// uniaxial strain), for `against: stretch` or `applied-stretch` with `route: analytic`.
    #[serde(default)]
    pub transverse_stretch: Option<f64>,
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

/// A round bar's extent histories (t, length, radius), each scene run once per process: a
/// figure's panels draw the length and the radius of one run (deterministic).
fn extents(s: &Scene) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    type Extents = (Vec<f64>, Vec<f64>, Vec<f64>);
    static CACHE: std::sync::OnceLock<
        std::sync::Mutex<std::collections::HashMap<String, Extents>>,
    > = std::sync::OnceLock::new();
    let key = serde_json::to_string(s).map_err(|e| Error::Config {
        file: s.name.clone(),
        msg: e.to_string(),
    })?;
    let cache = CACHE.get_or_init(Default::default);
    if let Some(e) = cache
        .lock()
        .map_err(|_| Error::NonFinite("scene cache"))?
        .get(&key)
    {
        return Ok(e.clone());
    }
    let r = s.run(())?;
    let e = (r.extent_t, r.extent_length, r.extent_radius);
    cache
        .lock()
        .map_err(|_| Error::NonFinite("scene cache"))?
        .insert(key, e.clone());
    Ok(e)
}

impl SceneSeries {
    /// The scene: the built-in or file with this series' overrides, form, c and end time.
    pub fn scene(&self) -> Result<Scene> {
        let mut s = if self.scene.ends_with(".json") {
            let text = std::fs::read_to_string(&self.scene).map_err(|e| Error::Config {
                file: self.scene.clone(),
                msg: format!("cannot read the scene file: {e}"),
            })?;
            crate::solver::scene::parse(&self.scene, &text)?
        } else {
            builtin(&self.scene)?
        };
        if let Some(o) = &self.overrides {
            let mut doc = serde_json::to_value(&s).map_err(|e| Error::Config {
                file: self.scene.clone(),
                msg: e.to_string(),
            })?;
            merge(&mut doc, o);
            let text = doc.to_string();
            s = crate::solver::scene::parse(&format!("{} with overrides", self.scene), &text)?;
        }
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
        let s = Scene {
            budget: *budget,
            ..self.scene()?
        };
        if let Some(p) = self.probe {
            return self.probe_curve(&s, p);
        }
        if matches!(self.quantity, SceneQuantity::Length | SceneQuantity::Radius) {
            if self.route == SceneRoute::Analytic || !s.round {
                return Err(Error::Incompatible(
                    "scene series: `length` and `radius` are the run of a `round` bar".into(),
                ));
            }
            let (t, length, radius) = extents(&s)?;
            let (y, what) = if self.quantity == SceneQuantity::Length {
                (length, "length")
            } else {
                (radius, "radius")
            };
            return Ok(Curve {
                label: self
                    .label
                    .clone()
                    .unwrap_or_else(|| format!("{} {what}", s.form)),
                x: t.iter().map(|t| t * self.x_scale).collect(),
                y: y.iter().map(|v| v * self.y_scale).collect(),
                dashed: self.dashed,
            });
        }
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
                    _ => return Err(self.probes_only()),
                };
                (q, "analytic".to_string())
            }
            SceneRoute::Run => {
                let mut r = s.run(())?;
                let z = r
                    .final_state
                    .take()
                    .ok_or(Error::NonFinite("scene series: no final state"))?;
                // along the row nearest to the axis (every particle in 1D)
                let q: Vec<f64> = match self.quantity {
                    SceneQuantity::Stress => std::mem::take(&mut r.final_stress),
                    SceneQuantity::Velocity => z.axial_velocity(),
                    _ => return Err(self.probes_only()),
                };
                let q = r.centre_row.iter().map(|&i| q[i]).collect::<Vec<_>>();
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

/// Merges `over` into `doc`: objects key by key (recursively), anything else replaced.
fn merge(doc: &mut serde_json::Value, over: &serde_json::Value) {
    match (doc, over) {
        (serde_json::Value::Object(d), serde_json::Value::Object(o)) => {
            for (k, v) in o {
                merge(d.entry(k.clone()).or_insert(serde_json::Value::Null), v);
            }
        }
        (d, o) => *d = o.clone(),
    }
}

impl SceneSeries {
    fn probes_only(&self) -> Error {
        Error::Incompatible(
            format!(
                "scene series `{}`: the displacement and the stretch are drawn for a `probe`, not along the bar",
                self.scene
            )
            .into(),
        )
    }

    /// The history of probe `p` of scene `s`: the run's, or the analytic solution's
    /// ([`Scene::end_waves_at`] at the run's record times; T11(F) of the material against
    /// the stretch).
    fn probe_curve(&self, s: &Scene, p: usize) -> Result<Curve> {
        if p >= s.probes.len() {
            return Err(Error::OutOfRange {
                field: "probe",
                value: p as f64,
                range: format!("the scene has {} probes", s.probes.len()).into(),
            });
        }
        let r = s.run(())?;
        let h = &r.probes[p];
        let pick = |q: SceneQuantity, exact: bool| -> Result<Vec<f64>> {
            let v = match (q, exact) {
                (SceneQuantity::Stress, false) => h.stress.clone(),
                (SceneQuantity::Velocity, false) => h.velocity.clone(),
                (SceneQuantity::Displacement, false) => h.displacement.clone(),
                (SceneQuantity::Stretch, _) => h.stretch.clone(),
                (SceneQuantity::Stress, true) => h.exact_stress.clone(),
                (SceneQuantity::Velocity, true) => h.exact_velocity.clone(),
                (SceneQuantity::Displacement, true) => Vec::new(),
                // the bar's extent is not a probe's
                (SceneQuantity::Length | SceneQuantity::Radius, _) => Vec::new(),
            };
            if v.is_empty() {
                return Err(Error::Incompatible(
                    format!(
                        "scene series `{}`: probe {p} has no {}{} (the form or the scene's `analytic` does not give it)",
                        self.scene,
                        if exact { "analytic " } else { "" },
                        match q {
                            SceneQuantity::Stress => "stress",
                            SceneQuantity::Velocity => "velocity",
                            SceneQuantity::Displacement => "displacement",
                            SceneQuantity::Stretch => "stretch",
                            SceneQuantity::Length => "length (a bar's, not a probe's)",
                            SceneQuantity::Radius => "radius (a bar's, not a probe's)",
                        }
                    )
                    .into(),
                ));
            }
            Ok(v)
        };
        let exact = self.route == SceneRoute::Analytic;
        let (x, y) = match self.against {
            ProbeAbscissa::Time => (r.probe_t.clone(), pick(self.quantity, exact)?),
            ProbeAbscissa::Stretch | ProbeAbscissa::AppliedStretch => {
                let f = if self.against == ProbeAbscissa::Stretch {
                    pick(SceneQuantity::Stretch, false)?
                } else {
                    let k = self
                        .stretch_probe
                        .filter(|&k| k < r.probes.len())
                        .ok_or_else(|| Error::OutOfRange {
                            field: "stretch_probe",
                            value: self.stretch_probe.map_or(-1.0, |k| k as f64),
                            range: format!(
                                "against applied-stretch needs the pulled end's probe, one of 0..{}",
                                r.probes.len()
                            )
                            .into(),
                        })?;
                    let span = r.probes[k].reference_position - s.origin;
                    r.probes[k]
                        .displacement
                        .iter()
                        .map(|u| 1.0 + u / span)
                        .collect()
                };
                if exact {
                    let m = s.material_model()?;
                    let (lo, hi) = f
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                            (a.min(v), b.max(v))
                        });
                    let xs: Vec<f64> = (0..=200)
                        .map(|i| lo + (hi - lo) * i as f64 / 200.0)
                        .collect();
                    let l2 = self.transverse_stretch.unwrap_or(1.0);
                    crate::error::check_range("transverse_stretch", l2, 0.01, 100.0, true, true)?;
                    let ys = xs.iter().map(|&l| uniaxial_cauchy(&m, l, l2)).collect();
                    (xs, ys)
                } else {
                    (f, pick(self.quantity, false)?)
                }
            }
        };
        let label = match (exact, self.against) {
            (true, ProbeAbscissa::Time) => "analytic".to_string(),
            (true, _) => "material law T11(λ1)".to_string(),
            (false, _) => format!("X = {} m", crate::display::num(h.reference_position)),
        };
        Ok(Curve {
            label: self.label.clone().unwrap_or(label),
            x: x.iter().map(|v| v * self.x_scale).collect(),
            y: y.iter().map(|v| v * self.y_scale).collect(),
            dashed: self.dashed,
        })
    }
}

/// The Cauchy stress T11 of material `m` at the stretches (λ1, λ2) = (`l`, `l2`), λ3 = 1: the
/// neo-Hookean law's ([`crate::forms::neo_hookean_cauchy`]; with λ2 = 1 the uniaxial-strain
/// curve), or the 1D linear law's P = C(F − 1) without pre-stress (T = P in 1D; λ2 unused).
fn uniaxial_cauchy(m: &crate::forms::Material, l: f64, l2: f64) -> f64 {
    match *m {
        crate::forms::Material::NeoHookean { lambda, shear } => {
            crate::forms::neo_hookean_cauchy([l, l2], lambda, shear)[0]
        }
        other => other.modulus() * (l - 1.0),
    }
}
