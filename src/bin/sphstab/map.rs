//! `sphstab map`: stability map, the growth rate over (κx, κy) (2D) or over a plane through the
//! 3D zone (`--dim 3 --plane`) as a heat map.

use crate::common::Config;
use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::display::num;

/// Flags of `map`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    cfg: Config,
    /// Wave vectors per direction over κΔx ∈ [−π, π]² (n × n), in [2, 1024].
    #[arg(long, default_value_t = 128)]
    n: usize,
    /// Print one JSON document (kx, ky as κΔx; growth in c/Δx; its "units" name them) instead
    /// of a summary.
    #[arg(long)]
    json: bool,
    /// Write the heat map SVG to this file.
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
    /// 3D: the plane through Γ: xy (k_z = 0, default), xz, yz, or diagonal (spanned by
    /// (x̂ + ŷ)/√2 and ẑ); map coordinates (u, v) ∈ [−π, π]².
    #[arg(long)]
    plane: Option<String>,
    #[command(flatten)]
    export: crate::export::ExportArgs,
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let mut cfg = a.cfg.clone();
    cfg.dim = Some(cfg.spec().map_dim()?);
    if cfg.dim == Some(3) {
        run_nd::<3>(a, cfg, budget)
    } else {
        if a.plane.is_some() {
            return Err(crate::query::not_in("--plane", "--dim 2 (it is a 3D flag)"));
        }
        run_nd::<2>(a, cfg, budget)
    }
}

fn run_nd<const D: usize>(a: Args, cfg: crate::common::Config, budget: &Budget) -> Result<()> {
    use sphstab::analysis::Plane;
    let export = a
        .export
        .resolve(a.plot.is_some(), "no --plot (it sets the plot's formats)")?;
    if let Some(p) = &a.plot {
        export
            .output(crate::files::Files::new(), "--plot", p)
            .check()?;
    }
    let plane = match &a.plane {
        Some(p) => Plane::by_name(p)?,
        None => Plane::Xy,
    };
    let q = cfg.query::<D>(budget)?;
    let t = std::time::Instant::now();
    let m = sphstab::analysis::growth_map(&q, a.n, plane, &())?;
    let (xl, yl) = if D == 3 {
        let name = a.plane.as_deref().unwrap_or("xy");
        (
            format!("uΔx/π (plane {name}, κ = u e_u + v e_v; dimensionless)"),
            "vΔx/π (dimensionless)".to_string(),
        )
    } else {
        (
            "κxΔx/π (dimensionless; ±1 = π/Δx)".to_string(),
            "κyΔx/π (dimensionless)".to_string(),
        )
    };
    let secs = t.elapsed().as_secs_f64();
    if let Some(path) = &a.plot {
        let pi = std::f64::consts::PI;
        let xs: Vec<f64> = m.kx.iter().map(|k| k / pi).collect();
        let ys: Vec<f64> = m.ky.iter().map(|k| k / pi).collect();
        let svg = sphstab::plot::heatmap_svg(
            &format!(
                "growth rate over the zone: {} / {} h = {}Δx, σ̄ = {}, {}, {} ({}D, {}×{} wave vectors)",
                q.form.name(),
                q.kernel.name(),
                num(q.h_over_dx),
                num(q.stress),
                q.material,
                q.lattice.kind,
                D,
                a.n,
                a.n
            ),
            &xl,
            &yl,
            "growth rate γ (c/Δx; 0 = stable)",
            &xs,
            &ys,
            &m.growth,
        )?;
        export.write("--plot", &svg, path)?;
    }
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&m, sphstab::units::System::Normalised, false)?
        );
        return Ok(());
    }
    let gmax = m.growth.iter().flatten().fold(0.0f64, |x, &y| x.max(y));
    println!(
        "{}×{} wave vectors (cell centres of [−π, π]², not the first-zone grid of `query --dim {D}`, so maxima differ by the resolution) in {:.3} s; max growth rate {:.6} c/Δx",
        a.n, a.n, secs, gmax
    );
    Ok(())
}
