//! `sphstab throughput`: speed and memory of the solver on a square (2D) or cubic (3D) block.

use anyhow::Result;
use sphstab::budget::Budget;
use sphstab::display::num;
use sphstab::error::Error;
use sphstab::forms::{FormKind, ObjectiveRate};
use sphstab::studies::throughput::{BlockMaterial, Domain, ThroughputConfig, run_throughput};

/// Flags of `throughput`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dimension: 2 (N = size² particles) or 3 (N = size³).
    #[arg(long, default_value_t = 2)]
    dim: usize,
    /// open (free surfaces) or periodic (period size·Δx per axis). Default: open in 2D,
    /// periodic in 3D.
    #[arg(long)]
    domain: Option<String>,
    /// Particles per side of the block, in [4, 3000] (2D) or [4, 200] (3D); a periodic box must
    /// be wider than two support radii. Default 200 in 2D (4 × 10⁴ particles), 22 in 3D
    /// (~10⁴ particles).
    #[arg(long)]
    size: Option<usize>,
    /// Several sizes, comma-separated (e.g. 100,316,1000 in 2D, 22,46,100 in 3D), to fit the
    /// scaling exponent p of time per step ∝ N^p; instead of --size.
    #[arg(long, value_delimiter = ',', num_args = 1..)]
    sizes: Option<Vec<usize>>,
    /// classical, nonlocal, local, lnl, cll, total-lagrangian.
    #[arg(long, default_value = "classical")]
    form: String,
    /// Shape family (default: the form's).
    #[arg(long)]
    shape: Option<String>,
    /// Kernel name (m4 = cubic spline).
    #[arg(long, default_value = "m4")]
    kernel: String,
    /// Smoothing length h/Δx in the kernel's own convention, in (0, 10].
    #[arg(long, default_value_t = 1.3, allow_hyphen_values = true)]
    h: f64,
    /// hydro (p = K(ρ/ρ0 − 1)) or elastic (hypo-elastic, P-wave modulus 1).
    #[arg(long, default_value = "elastic")]
    material: String,
    /// Elastic Poisson ratio ν (plane strain in 2D), in [−0.99, 0.5) (default 0.3; elastic
    /// only).
    #[arg(long, allow_hyphen_values = true)]
    poisson: Option<f64>,
    /// Elastic objective stress rate: jaumann (default) or truesdell (elastic only).
    #[arg(long)]
    rate: Option<String>,
    /// Monaghan artificial viscosity "α,β" (dimensionless, each in [0, 100]), or "off".
    #[arg(long, default_value = "1,1", allow_hyphen_values = true)]
    av: String,
    /// Monaghan–Gray artificial stress ε, dimensionless, in [0, 10] (classical and cll, 2D
    /// only; 0: off).
    /// Default 0.3 for classical and cll in 2D, off otherwise.
    #[arg(long = "art-eps", allow_hyphen_values = true)]
    art_eps: Option<f64>,
    /// Artificial-stress exponent n, in [1, 12] (default 4; only where artificial stress is on).
    #[arg(long = "art-n", allow_hyphen_values = true)]
    art_n: Option<i32>,
    /// Time step Δt in Δx/c, in (0, 2] (the CFL number c Δt/h is dt/(h/Δx)).
    #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
    dt: f64,
    /// Amplitude A of the initial velocity field v_a = A c sin(k x_{a+1}), in units of c, in
    /// [0, 0.1]. Default 1e-3: a near-static block, where the pairs rarely change; 0.1 moves the
    /// particles as a real run does, so the neighbour lists change (the regime to measure).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    amplitude: f64,
    /// Skin of the neighbour pair list, as a fraction of the support radius, in [0, 1]
    /// (default 0.05 in 2D, 0.1 in 3D): a full search lists the pairs within (1 + skin) r,
    /// later builds reuse them while no particle has moved half the skin. Bitwise the same
    /// results for every skin.
    #[arg(long)]
    skin: Option<f64>,
    /// Timed steps per repeat (after one warm-up step), in [1, 10⁶]. Default 20: the default
    /// run (4 × 10⁴ particles, 3 repeats) then takes ~7 s of CPU, under the 10 s every default
    /// command keeps to.
    #[arg(long, default_value_t = 20)]
    steps: usize,
    /// Repeats; the median time is reported. In [1, 1000].
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Threads of the rayon pool (default: one per core), in [1, 1024].
    #[arg(long)]
    threads: Option<usize>,
    /// Make every stencil build a full neighbour search (by default a build keeps the pairs of
    /// the last full one while they provably have not changed; bitwise the same results).
    #[arg(long)]
    no_pair_reuse: bool,
    /// JSON on stdout (times in wall-clock s and ns, dt in Δx/c, max_speed_end in c; its
    /// "units" name the unit of every field).
    #[arg(long)]
    json: bool,
}

fn parse_av(s: &str) -> Result<Option<(f64, f64)>> {
    if s == "off" {
        return Ok(None);
    }
    let bad = || {
        Error::Incompatible(format!("--av `{s}`: expected \"alpha,beta\" (e.g. 1,1) or off").into())
    };
    let mut it = s.split(',').map(|t| t.trim().parse::<f64>());
    match (it.next(), it.next(), it.next()) {
        (Some(Ok(a)), Some(Ok(b)), None) => Ok(Some((a, b))),
        _ => Err(bad().into()),
    }
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let form = FormKind::by_name(&a.form)?;
    let kernel = sphstab::kernel::by_name(&a.kernel)?;
    if !(2..=3).contains(&a.dim) {
        return Err(Error::OutOfRange {
            field: "dim",
            value: a.dim as f64,
            range: "2 or 3".into(),
        }
        .into());
    }
    let mut cfg = ThroughputConfig::new(kernel).with_dim(a.dim);
    cfg.budget = *budget;
    if let Some(d) = &a.domain {
        cfg.domain = match d.as_str() {
            "open" => Domain::Open,
            "periodic" => Domain::Periodic,
            d => {
                return Err(Error::UnknownName {
                    what: "--domain".into(),
                    given: d.into(),
                    valid: "open, periodic".into(),
                }
                .into());
            }
        };
    }
    cfg.form = form;
    cfg.shape = match &a.shape {
        Some(s) => sphstab::shape::ShapeFamily::by_name(s)?,
        None => form.default_shape_in(2),
    };
    cfg.h_over_dx = a.h;
    if a.size.is_some() && a.sizes.is_some() {
        return Err(crate::query::not_in("--size", "--sizes (give one of them)"));
    }
    if a.material == "hydro" && (a.poisson.is_some() || a.rate.is_some()) {
        return Err(crate::query::not_in(
            "--poisson/--rate",
            "--material hydro (G = 0)",
        ));
    }
    let rate = match a.rate.as_deref().unwrap_or("jaumann") {
        "jaumann" => ObjectiveRate::Jaumann,
        "truesdell" => ObjectiveRate::Truesdell,
        r => {
            return Err(Error::UnknownName {
                what: "--rate".into(),
                given: r.into(),
                valid: "jaumann, truesdell".into(),
            }
            .into());
        }
    };
    cfg.material = match a.material.as_str() {
        "hydro" => BlockMaterial::Hydro,
        "elastic" => BlockMaterial::Elastic {
            poisson: a.poisson.unwrap_or(0.3),
            rate,
        },
        m => {
            return Err(Error::UnknownName {
                what: "--material".into(),
                given: m.into(),
                valid: "hydro, elastic".into(),
            }
            .into());
        }
    };
    cfg.av = parse_av(&a.av)?;
    let art_form = matches!(form, FormKind::Classical | FormKind::Cll);
    let art_n = a.art_n.unwrap_or(4);
    cfg.art_stress = match a.art_eps {
        Some(0.0) => None,
        Some(e) => Some((e, art_n)),
        None if art_form && a.dim == 2 => Some((0.3, art_n)),
        None => None,
    };
    if a.art_n.is_some() && cfg.art_stress.is_none() {
        return Err(crate::query::not_in(
            "--art-n",
            &format!(
                "no artificial stress (--form {} in {}D{}: it is the exponent of the artificial stress)",
                form.name(),
                a.dim,
                if a.art_eps == Some(0.0) {
                    ", --art-eps 0"
                } else {
                    ""
                }
            ),
        ));
    }
    cfg.dt = a.dt;
    cfg.amplitude = a.amplitude;
    if let Some(s) = a.skin {
        cfg.skin = s;
    }
    cfg.steps = a.steps;
    cfg.repeats = a.repeats;
    if a.no_pair_reuse && form.is_lagrangian() {
        return Err(crate::query::not_in(
            "--no-pair-reuse",
            &format!(
                "--form {} (a Lagrangian kernel keeps its reference neighbours: there is no search to repeat)",
                form.name()
            ),
        ));
    }
    cfg.pair_reuse = !a.no_pair_reuse;
    cfg.validate()?;
    let default_size = if a.dim == 3 { 22 } else { 200 };
    let sizes = a
        .sizes
        .clone()
        .unwrap_or_else(|| vec![a.size.unwrap_or(default_size)]);
    let pb = crate::progress::Bar::new(crate::progress::wanted(a.json));
    let probe = crate::alloc::Probe;
    let r = run_throughput(&cfg, &sizes, a.threads, Some(&probe), pb.clone())?;
    pb.finish();
    if a.json {
        println!(
            "{}",
            sphstab::units::json(&r, sphstab::units::System::Normalised, true)?
        );
        return Ok(());
    }
    let material = match r.poisson {
        Some(nu) => format!("{} ν = {}", r.material, num(nu)),
        None => r.material.clone(),
    };
    let av = match r.av {
        Some([al, be]) => format!("AV α = {}, β = {}", num(al), num(be)),
        None => "no AV".into(),
    };
    let art = match (r.art_eps, r.art_n) {
        (Some(e), Some(n)) => format!("artificial stress ε = {}, n = {n}", num(e)),
        _ => "no artificial stress".into(),
    };
    println!(
        "sphstab throughput: {}D {} {}, {} / {} / {} h = {}Δx, {material}, {av}, {art}",
        r.dim,
        r.domain.name(),
        if r.domain == Domain::Open {
            "block"
        } else {
            "box"
        },
        r.form,
        r.shape,
        r.kernel,
        num(r.h_over_dx)
    );
    println!(
        "Δt = {} Δx/c, initial velocity amplitude {} c; {} timed steps × {} repeats (median) after 1 warm-up step; {} thread{}",
        num(r.dt),
        num(r.amplitude),
        r.steps,
        r.repeats,
        r.threads,
        if r.threads == 1 { "" } else { "s" }
    );
    println!(
        "{:>6} {:>10} {:>14} {:>18} {:>11} {:>15} {:>12}",
        "size",
        "particles",
        "ns/particle-step",
        "particle-steps/s",
        "neighbours",
        "bytes/particle",
        "allocs/step"
    );
    for b in &r.blocks {
        println!(
            "{:>6} {:>10} {:>16.1} {:>18.4e} {:>11.2} {:>15} {:>12}",
            b.size,
            b.particles,
            b.ns_per_particle_step,
            b.particle_steps_per_second,
            b.neighbours_per_particle,
            b.bytes_per_particle
                .map_or("-".into(), |x| format!("{x:.0}")),
            b.allocations_per_step
                .map_or("-".into(), |x| format!("{x:.2}")),
        );
    }
    for b in &r.blocks {
        println!(
            "size {}: per timed step {:.2} full neighbour searches and {:.2} pair refreshes{}",
            b.size,
            b.full_builds_per_step,
            b.pair_refreshes_per_step,
            if a.no_pair_reuse {
                " (--no-pair-reuse)"
            } else {
                ""
            }
        );
    }
    if let Some(p) = r.scaling_exponent {
        println!(
            "scaling: time per step ∝ N^p with p = {p:.3} (least squares on log–log over {} sizes)",
            r.blocks.len()
        );
    }
    Ok(())
}
