//! Running the artificial-stress study: the engine's predictions (infinite lattice, box) over the
//! ε grid and the Swegle runs, and another code's stored runs read for comparison.

use super::config::ArtStressConfig;
use super::report::{ArtStressReport, Case, ComparePoint, Comparison, Point, RunPoint};
use super::shard::{ArtStressCell, ArtStressSetup};
use crate::error::{Error, Result};
use crate::progress::{Counter, Progress};
use crate::studies::shard::Shard;
use crate::studies::swegle::{predict_swegle, run_swegle};
use rayon::prelude::*;

/// Runs the whole study, telling `progress` the fraction of predictions and runs done; `compare`
/// is another code's stored runs. Sharded: [`ArtStressStudy`](super::ArtStressStudy).
pub fn run(
    cfg: &ArtStressConfig,
    compare: Option<&Comparison>,
    progress: impl Progress,
) -> Result<ArtStressReport> {
    let setup = ArtStressSetup {
        config: cfg.clone(),
        compare: compare.cloned(),
    };
    crate::studies::shard::run_whole(&super::ArtStressStudy, &setup, progress)
}

/// Cells per (h, f) case: the prediction grid, then the runs.
pub(super) fn cells_per_case(cfg: &ArtStressConfig) -> usize {
    cfg.eps.len() + cfg.runs.len()
}

/// The (h, f) of case `i` (h-major).
fn case(cfg: &ArtStressConfig, i: usize) -> (f64, f64) {
    let nf = cfg.density_ratio.len();
    (cfg.h[i / nf], cfg.density_ratio[i % nf])
}

/// Computes the cells of `shard` (ascending, with their indices): cell c is, in case
/// c / (predictions + runs), the prediction at the grid ε or the Swegle run it names. The
/// predictions are independent: in parallel (the dense box eigenproblem dominates); the runs
/// one after the other.
pub(super) fn compute_cells(
    setup: &ArtStressSetup,
    shard: Shard,
    progress: &dyn Progress,
) -> Result<Vec<(usize, ArtStressCell)>> {
    let cfg = &setup.config;
    cfg.validate()?;
    let per = cells_per_case(cfg);
    let total = cfg.h.len() * cfg.density_ratio.len() * per;
    let (predictions, runs): (Vec<usize>, Vec<usize>) = (0..total)
        .filter(|&c| shard.owns(c))
        .partition(|&c| c % per < cfg.eps.len());
    let done = Counter::new(progress, predictions.len() + runs.len(), 1);
    let mut out = predictions
        .par_iter()
        .map(|&c| {
            let (h, f) = case(cfg, c / per);
            let eps = cfg.eps[c % per];
            let p = predict_swegle(&cfg.swegle(h, f, eps)?)?;
            done.add(1)?;
            Ok((
                c,
                ArtStressCell::Prediction(Point {
                    eps,
                    infinite: p.infinite_rate,
                    infinite_kappa: p.infinite_kappa,
                    longitudinal: p.infinite_longitudinal,
                    in_box: p.box_rate,
                }),
            ))
        })
        .collect::<Result<Vec<_>>>()?;
    for c in runs {
        let (h, f) = case(cfg, c / per);
        let eps = cfg.runs[c % per - cfg.eps.len()];
        let r = run_swegle(&cfg.swegle(h, f, eps)?, ())?;
        out.push((
            c,
            ArtStressCell::Run(RunPoint {
                eps,
                measured: r.measured_growth_rate,
                predicted_box: r.predicted_growth_rate_box,
                ratio_box: r.ratio_box,
                dominant_kappa: r.dominant_kappa,
                steps: r.steps,
            }),
        ));
        done.add(1)?;
    }
    out.sort_by_key(|c| c.0);
    Ok(out)
}

/// The report from every cell of the study, in index order (a cell of the wrong kind for its
/// place is an error).
pub(super) fn assemble(
    setup: &ArtStressSetup,
    cells: Vec<ArtStressCell>,
) -> Result<ArtStressReport> {
    let cfg = &setup.config;
    let per = cells_per_case(cfg).max(1);
    let mut cases = Vec::new();
    for (i, chunk) in cells.chunks(per).enumerate() {
        let (h, f) = case(cfg, i);
        let mut points = Vec::with_capacity(cfg.eps.len());
        let mut runs = Vec::with_capacity(cfg.runs.len());
        for (j, c) in chunk.iter().enumerate() {
            match (c, j < cfg.eps.len()) {
                (ArtStressCell::Prediction(p), true) => points.push(p.clone()),
                (ArtStressCell::Run(r), false) => runs.push(r.clone()),
                _ => {
                    return Err(Error::Incompatible(
                        format!(
                            "art-stress cell {}: a {} where the study has a {}",
                            i * per + j,
                            if j < cfg.eps.len() {
                                "run"
                            } else {
                                "prediction"
                            },
                            if j < cfg.eps.len() {
                                "prediction"
                            } else {
                                "run"
                            }
                        )
                        .into(),
                    ));
                }
            }
        }
        let argmin = |g: &dyn Fn(&Point) -> f64| {
            points
                .iter()
                .map(|p| (p.eps, g(p)))
                .fold(
                    (f64::NAN, f64::INFINITY),
                    |a, b| if b.1 < a.1 { b } else { a },
                )
        };
        let transverse_from = points
            .iter()
            .rposition(|p| p.longitudinal >= 0.5 || p.infinite <= 0.0)
            .map_or(Some(0), |i| (i + 1 < points.len()).then_some(i + 1))
            .map(|i| points[i].eps);
        let compare = setup
            .compare
            .as_ref()
            .map(|c| {
                c.points
                    .iter()
                    .filter(|p| close(p.0, h) && close(p.1, f))
                    .map(|p| ComparePoint {
                        eps: p.2,
                        measured: p.3,
                    })
                    .collect()
            })
            .unwrap_or_default();
        cases.push(Case {
            h,
            density_ratio: f,
            sigma_bar: 1.0 - f,
            min_infinite: argmin(&|p| p.infinite),
            min_box: argmin(&|p| p.in_box),
            transverse_from,
            points,
            runs,
            compare,
        });
    }
    Ok(ArtStressReport {
        config: cfg.clone(),
        compare_label: setup
            .compare
            .as_ref()
            .map(|c| c.label.clone())
            .unwrap_or_default(),
        cases,
    })
}

pub(super) fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// The largest relative difference between the compared code's measured rates and sphstab's
/// runs at the same (h, f, ε); None without common points.
pub fn max_relative_difference(r: &ArtStressReport) -> Option<f64> {
    let mut d: Option<f64> = None;
    for case in &r.cases {
        for c in &case.compare {
            let run = case.runs.iter().find(|p| close(p.eps, c.eps));
            if let (Some(a), Some(b)) = (c.measured, run.and_then(|p| p.measured)) {
                let x = (a - b).abs() / b.abs();
                d = Some(d.map_or(x, |y| y.max(x)));
            }
        }
    }
    d
}

/// A number without trailing zeros (0.05, not 0.050000000000000044).
pub(super) fn trim(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Reads the stored PySPH measurements (`analysis/pysph/results-art-stress.json`, written by
/// `analysis/pysph/swegle_art_stress.py`): `pysph_version` and `runs[]` with `h`,
/// `density_ratio`, `art_eps` and `pysph.growth_rate` (null: nothing grew into the window).
pub fn comparison_from_pysph(file: &str, text: &str) -> Result<Comparison> {
    let bad = |msg: String| Error::Config {
        file: file.into(),
        msg,
    };
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let version = v["pysph_version"].as_str().unwrap_or("?");
    let runs = v["runs"]
        .as_array()
        .ok_or_else(|| bad("`runs` must be an array".into()))?;
    let mut points = Vec::with_capacity(runs.len());
    for (i, r) in runs.iter().enumerate() {
        let num = |k: &str| {
            r[k].as_f64()
                .ok_or_else(|| bad(format!("runs[{i}].{k} must be a number")))
        };
        let g = &r["pysph"]["growth_rate"];
        let rate = if g.is_null() {
            None
        } else {
            Some(g.as_f64().filter(|x| x.is_finite()).ok_or_else(|| {
                bad(format!(
                    "runs[{i}].pysph.growth_rate must be a number or null"
                ))
            })?)
        };
        points.push((num("h")?, num("density_ratio")?, num("art_eps")?, rate));
    }
    Ok(Comparison {
        label: format!("PySPH {version}"),
        points,
    })
}
