//! The artificial-stress report: per (h, f) the predicted growth over ε, the Swegle runs and
//! another code's stored runs, and the table `sphstab art-stress` prints.

use super::config::ArtStressConfig;
use super::run::{close, trim};
use crate::solver::BoundaryDensity;
use serde::{Deserialize, Serialize};

/// One ε of the prediction grid.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Point {
    /// ε.
    pub eps: f64,
    /// Infinite-lattice growth rate (c/Δx).
    pub infinite: f64,
    /// Wave vector (κΔx per axis) of the infinite lattice's fastest mode.
    pub infinite_kappa: Vec<f64>,
    /// Its longitudinal fraction |p·κ̂|² (1 longitudinal, 0 transverse).
    pub longitudinal: f64,
    /// Growth rate of the finite box (c/Δx).
    pub in_box: f64,
}

/// One Swegle run.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct RunPoint {
    /// ε.
    pub eps: f64,
    /// Measured growth rate (c/Δx); None when nothing grew into the fit window.
    pub measured: Option<f64>,
    /// The box prediction at this ε (c/Δx).
    pub predicted_box: f64,
    /// measured / box.
    pub ratio_box: Option<f64>,
    /// Dominant standing mode of the growing pattern (κΔx per axis) and its power share.
    pub dominant_kappa: Option<(Vec<f64>, f64)>,
    /// Time steps taken.
    pub steps: usize,
}

/// Another code's measured growth rate at one ε.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct ComparePoint {
    /// ε.
    pub eps: f64,
    /// Measured growth rate (c/Δx); None when nothing grew into the fit window.
    pub measured: Option<f64>,
}

/// One (h, f) panel.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct Case {
    /// h/Δx.
    pub h: f64,
    /// f = ρ/ρ0.
    pub density_ratio: f64,
    /// σ̄ = 1 − f (tension positive).
    pub sigma_bar: f64,
    /// The prediction grid.
    pub points: Vec<Point>,
    /// ε of the smallest infinite-lattice growth on the grid, and that growth.
    pub min_infinite: (f64, f64),
    /// ε of the smallest box growth on the grid, and that growth.
    pub min_box: (f64, f64),
    /// Smallest ε of the grid from which the infinite lattice's fastest mode is transverse
    /// (longitudinal fraction < 1/2) at every larger grid ε; None if it never is.
    pub transverse_from: Option<f64>,
    /// The Swegle runs.
    pub runs: Vec<RunPoint>,
    /// Another code's runs (empty without `compare`).
    #[serde(default)]
    pub compare: Vec<ComparePoint>,
}

/// Another code's measurements, as read from `compare` (the command line reads the file).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
pub struct Comparison {
    /// Name in the legend (e.g. "PySPH 1.0b2").
    pub label: String,
    /// (h, f, ε, measured rate).
    pub points: Vec<(f64, f64, f64, Option<f64>)>,
}

/// The study's report (also the stored data the figure is redrawn from).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
pub struct ArtStressReport {
    /// The config.
    pub config: ArtStressConfig,
    /// Legend name of the compared code (empty: none).
    #[serde(default)]
    pub compare_label: String,
    /// One per (h, f), h-major.
    pub cases: Vec<Case>,
}

/// The report as a table (one line per grid ε, runs and compared measurements beside it).
pub fn table(r: &ArtStressReport) -> String {
    let mut s = String::new();
    let c = &r.config;
    s += &format!(
        "# artificial stress: {} {} (n = {}), Swegle box {}×{} ({} boundary density); rates in c/Δx, σ̄ = σ/K = 1 − f, h in Δx\n",
        c.form,
        c.kernel,
        c.art_n,
        c.size,
        c.size,
        match c.boundary_density {
            BoundaryDensity::Frozen => "frozen",
            BoundaryDensity::Evolve => "evolving",
        }
    );
    let other = if r.compare_label.is_empty() {
        String::new()
    } else {
        format!("  {:>10}", short(&r.compare_label))
    };
    for case in &r.cases {
        s += &format!(
            "\nh = {}Δx, f = {} (σ̄ = {:.3}): least growth at ε = {} (infinite lattice, {:.4}) and ε = {} (box, {:.4}); fastest mode transverse from ε = {}\n",
            case.h,
            case.density_ratio,
            case.sigma_bar,
            trim(case.min_infinite.0),
            case.min_infinite.1,
            trim(case.min_box.0),
            case.min_box.1,
            case.transverse_from.map_or("never".to_string(), trim)
        );
        s += &format!(
            "{:>6}  {:>9}  {:>18}  {:>6}  {:>9}  {:>9}  {:>6}{other}\n",
            "ε", "infinite", "κΔx/π of fastest", "long.", "box", "run", "run/box"
        );
        let mut eps: Vec<f64> = case
            .points
            .iter()
            .map(|p| p.eps)
            .chain(case.runs.iter().map(|p| p.eps))
            .chain(case.compare.iter().map(|p| p.eps))
            .collect();
        eps.sort_by(f64::total_cmp);
        eps.dedup_by(|a, b| close(*a, *b));
        let rate = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
        for e in eps {
            let p = case.points.iter().find(|p| close(p.eps, e));
            let run = case.runs.iter().find(|p| close(p.eps, e));
            let cmp = case.compare.iter().find(|p| close(p.eps, e));
            let k = p.map_or("".to_string(), |p| {
                p.infinite_kappa
                    .iter()
                    .map(|k| format!("{:.3}", k / std::f64::consts::PI))
                    .collect::<Vec<_>>()
                    .join(", ")
            });
            s += &format!(
                "{:>6}  {:>9}  {:>18}  {:>6}  {:>9}  {:>9}  {:>6}",
                trim(e),
                rate(p.map(|p| p.infinite)),
                k,
                p.map_or("".into(), |p| format!("{:.2}", p.longitudinal)),
                rate(p.map(|p| p.in_box)),
                rate(run.and_then(|r| r.measured)),
                run.and_then(|r| r.ratio_box)
                    .map_or("-".into(), |x| format!("{x:.3}")),
            );
            if !r.compare_label.is_empty() {
                s += &format!("  {:>10}", rate(cmp.and_then(|c| c.measured)));
            }
            s += "\n";
        }
    }
    s
}

fn short(label: &str) -> String {
    label.split_whitespace().next().unwrap_or(label).to_string()
}
