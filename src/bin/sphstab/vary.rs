//! Side-by-side comparisons (`--vary NAME=V1,V2,…`, and comma lists in `--form` and
//! `--kernel`) for `query`, `timestep` and `dispersion`: one question per value (the product
//! when several parameters vary), each answered by the same library call as a single question.

use crate::common::Config;
use anyhow::Result;
use sphstab::error::Error;

/// Largest number of series of one comparison.
pub const MAX_SERIES: usize = 12;

/// The parameters `--vary` takes (the flag of the same name gives the meaning and range).
pub const VARY_NAMES: [&str; 16] = [
    "form",
    "kernel",
    "h",
    "support",
    "stress",
    "c",
    "shape",
    "material",
    "poisson",
    "lattice",
    "delta",
    "delta-form",
    "art-eps",
    "av-alpha",
    "alpha-s",
    "integrator",
];

/// `--vary`.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct VaryArgs {
    /// Compare values of a parameter side by side: NAME=V1,V2,… with NAME one of form, kernel,
    /// h, support, stress, c, shape, material, poisson, lattice, delta, delta-form, art-eps,
    /// av-alpha, alpha-s, integrator (query and timestep); `off` removes an optional one
    /// (delta=off,0.1). Repeat the flag to vary several (their product, at most 12 series).
    /// --form and --kernel also take comma lists (--form classical,nonlocal).
    #[arg(long, value_name = "NAME=V1,V2,…")]
    pub vary: Vec<String>,
}

/// One series: its label ("h = 1.5, delta = off"), its configuration and, when varied, its
/// integrator name.
#[derive(Clone, Debug)]
pub struct Series {
    /// What distinguishes it.
    pub label: String,
    /// The flags of the question.
    pub cfg: Config,
    /// `--vary integrator=…`: the integrator's name.
    pub integrator: Option<String>,
}

fn bad(flag: &str, msg: String) -> anyhow::Error {
    Error::Incompatible(format!("{flag}: {msg}").into()).into()
}

fn number(name: &str, v: &str) -> Result<f64> {
    v.trim().parse::<f64>().map_err(|_| {
        bad(
            "--vary",
            format!("{name}={v}: not a number (or `off` where the parameter is optional)"),
        )
    })
}

/// `off` → None, else the number.
fn optional(name: &str, v: &str) -> Result<Option<f64>> {
    if v.trim() == "off" {
        Ok(None)
    } else {
        number(name, v).map(Some)
    }
}

/// Sets parameter `name` of `s` to `v`.
fn set(s: &mut Series, name: &str, v: &str, integrator_ok: bool) -> Result<()> {
    let c = &mut s.cfg;
    match name {
        "form" => c.form = v.into(),
        "kernel" => c.kernel = v.into(),
        "h" => {
            c.h = Some(number(name, v)?);
            c.support = None;
        }
        "support" => {
            c.support = Some(number(name, v)?);
            c.h = None;
        }
        "stress" => c.stress = number(name, v)?,
        "c" => c.c = Some(number(name, v)?),
        "alpha-s" => c.alpha_s = Some(number(name, v)?),
        "shape" => c.shape = Some(v.into()),
        "material" => c.material = Some(v.into()),
        "poisson" => c.poisson = optional(name, v)?,
        "lattice" => c.lattice = Some(v.into()),
        "delta" => c.diffusion.delta = optional(name, v)?,
        "delta-form" => c.diffusion.delta_form = Some(v.into()),
        "art-eps" => c.art_eps = optional(name, v)?,
        "av-alpha" => c.av_alpha = optional(name, v)?,
        "integrator" if integrator_ok => s.integrator = Some(v.into()),
        "integrator" => {
            return Err(crate::query::not_in(
                "--vary integrator",
                "dispersion (the semi-discrete system has no integrator)",
            ));
        }
        _ => {
            return Err(Error::UnknownName {
                what: "--vary parameter".into(),
                given: name.into(),
                valid: VARY_NAMES.join(", ").into(),
            }
            .into());
        }
    }
    Ok(())
}

/// The axes of the comparison: `--form a,b`, `--kernel a,b`, then each `--vary`.
fn axes(cfg: &Config, vary: &VaryArgs) -> Result<Vec<(String, Vec<String>)>> {
    let mut out = Vec::new();
    for (name, v) in [("form", &cfg.form), ("kernel", &cfg.kernel)] {
        if v.contains(',') {
            out.push((name.to_string(), v.split(',').map(str::to_string).collect()));
        }
    }
    for spec in &vary.vary {
        let Some((name, values)) = spec.split_once('=') else {
            return Err(bad(
                "--vary",
                format!("`{spec}`: expected NAME=V1,V2,… (e.g. h=1.2,1.5)"),
            ));
        };
        let name = name.trim().to_string();
        let values: Vec<String> = values.split(',').map(|v| v.trim().to_string()).collect();
        if values.iter().any(String::is_empty) {
            return Err(bad("--vary", format!("`{spec}`: an empty value")));
        }
        if out.iter().any(|(n, _)| *n == name) {
            return Err(bad(
                "--vary",
                format!("{name} is varied twice (give its values in one list)"),
            ));
        }
        out.push((name, values));
    }
    Ok(out)
}

/// Whether the flags ask for a comparison.
pub fn active(cfg: &Config, vary: &VaryArgs) -> bool {
    !vary.vary.is_empty() || cfg.form.contains(',') || cfg.kernel.contains(',')
}

/// The series of a comparison (the product of the axes, first axis slowest), at most
/// [`MAX_SERIES`]. `integrator_ok`: whether `integrator` may vary.
pub fn series(cfg: &Config, vary: &VaryArgs, integrator_ok: bool) -> Result<Vec<Series>> {
    let axes = axes(cfg, vary)?;
    let count: usize = axes.iter().map(|a| a.1.len()).product();
    if count > MAX_SERIES {
        return Err(bad(
            "--vary",
            format!("{count} series; at most {MAX_SERIES} fit one comparison"),
        ));
    }
    let mut out = vec![Series {
        label: String::new(),
        cfg: cfg.clone(),
        integrator: None,
    }];
    for (name, values) in &axes {
        let mut next = Vec::with_capacity(out.len() * values.len());
        for s in &out {
            for v in values {
                let mut t = s.clone();
                set(&mut t, name, v, integrator_ok)?;
                if !t.label.is_empty() {
                    t.label += ", ";
                }
                t.label += &format!("{name} = {v}");
                next.push(t);
            }
        }
        out = next;
    }
    Ok(out)
}

/// The questions of `list`, every one checked before any is answered; the integrator of a
/// series that varies it replaces `--integrator` (with the same `--euler-every` checks).
pub fn questions<const D: usize>(
    list: &[Series],
    integ: &crate::common::IntegratorArgs,
    budget: &sphstab::budget::Budget,
) -> Result<Vec<sphstab::analysis::Query<D>>> {
    list.iter()
        .map(|s| {
            let mut q = s.cfg.query::<D>(budget)?;
            let mut i = integ.clone();
            if let Some(name) = &s.integrator {
                i.integrator = name.clone();
            }
            q.integrator = i.integrator()?;
            Ok(q)
        })
        .collect()
}

/// A number for a comparison table: 6 significant digits, "—" for none.
pub fn cell(v: Option<f64>) -> String {
    v.map_or("—".into(), |x| sphstab::display::num_sig(x, 6))
}
