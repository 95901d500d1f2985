//! Golden data of the 2D/3D solver (issue 13, item 4): the compact-stencil rewrite of the rate
//! evaluation must reproduce the solver's results of the code before it.
//!
//! Each case is a [`Run`] (open elastic block of `sphstab throughput` with AV and artificial
//! stress; a jittered periodic hydro patch with AV, artificial stress and δ-SPH density
//! diffusion (Antuono); the lnl, cll and local forms; a 3D periodic box with AV and
//! Molteni–Colagrossi diffusion; the total-Lagrangian form). For each, the test stores the
//! full rate ([`Model::rate`]: ẋ, v̇, ρ̇, σ̇, τ̇) of the initial state, and the state (x, v,
//! ρ, σ, τ) after a few `kdk` steps. The new code must agree **per field to 1e-12 relative to
//! the largest magnitude of that field** (|new − old| ≤ 1e-12 · max_i |old_i| for every
//! entry), except that a field below 1e-4 of the largest field of its record (cancellation
//! noise, such as ρ̇ ≈ 1e-19 of a divergence-free velocity field) is compared at 1e-12 of
//! 1e-4 × that largest field: reordering a sum changes the rounding at the 1e-16 level,
//! nothing more is allowed.
//!
//! Where the numbers came from: `tests/golden/solver2d.json` was written by
//! `SPHSTAB_WRITE_GOLDEN=1 cargo test --release --test it -- golden_solver2d::` at commit c708382 (the
//! solver before the compact stencils), and is compared against, never rewritten, by the plain
//! `cargo test`. It is a regression oracle, not an independent check (those are in
//! solver2d.rs, swegle.rs, vonneumann2d.rs and friends).

// Small-tensor loops read best with explicit indices.
#![allow(clippy::needless_range_loop)]

use serde_json::{Value, json};
use sphstab::forms::{
    ArtificialStress, ArtificialViscosity, DensityDiffusion, DiffusionForm, FormKind, Material,
    Model, ModelParams, ObjectiveRate, State,
};
use sphstab::kernel;
use sphstab::shape::KernelParams;
use sphstab::solver::{BoundaryDensity, Run};
use sphstab::studies::throughput::{
    BlockMaterial, Domain, ThroughputConfig, build_block, build_block_nd,
};
use std::path::PathBuf;

const TOL: f64 = 1e-12;
/// A field smaller than this fraction of the largest field of its record is cancellation
/// noise (ρ̇ of a divergence-free velocity field is ~1e-19, its terms ~1e-3): it is compared
/// at TOL relative to FLOOR × that largest field instead of to itself.
const FLOOR: f64 = 1e-4;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden/solver2d.json")
}

/// Every field of a state, flattened (x, v, ρ, σ, τ).
fn fields<const D: usize>(z: &State<f64, D>) -> Value {
    json!({
        "x": z.x.as_flattened(),
        "v": z.v.as_flattened(),
        "rho": z.rho,
        "sigma": z.sigma.as_flattened().as_flattened(),
        "tau": z.tau.as_flattened().as_flattened(),
    })
}

/// The rate of the initial state and the state after `steps` steps of `dt`.
fn record<const D: usize>(mut run: Run<D>, steps: usize, dt: f64) -> Value {
    let mut r = State::default();
    run.model.rate(&run.z, &mut r).unwrap();
    for _ in 0..steps {
        run.step(dt).unwrap();
    }
    json!({ "rate0": fields(&r), "state": fields(&run.z), "steps": steps, "dt": dt })
}

fn m4() -> &'static dyn kernel::Kernel {
    kernel::by_name("m4").unwrap()
}

fn params(form: FormKind, material: Material) -> ModelParams {
    ModelParams {
        form,
        shape: form.default_shape_in(2),
        kp: KernelParams {
            kernel: m4(),
            h: 1.3,
        },
        material,
        rho0: 1.0,
        c_partition: 0.4,
        av: Some(ArtificialViscosity {
            alpha: 1.0,
            beta: 1.0,
            sound_speed: 1.0,
            approaching_only: true,
        }),
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    }
}

/// Deterministic pseudo-random numbers in [−1, 1) (a 64-bit LCG).
fn jitter(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

/// An n^D lattice (Δx = 1) jittered by ±`amp`, velocities ±`vamp` (random), density 1 ± 1 %.
fn jittered<const D: usize>(
    p: ModelParams,
    n: usize,
    periodic: bool,
    amp: f64,
    vamp: f64,
) -> Run<D> {
    let count = n.pow(D as u32);
    let mut seed = 12345u64 + D as u64;
    let mut x = Vec::with_capacity(count);
    for k in 0..count {
        let mut q = [0.0; D];
        let mut rest = k;
        for a in (0..D).rev() {
            q[a] = (rest % n) as f64 + amp * jitter(&mut seed);
            rest /= n;
        }
        x.push(q);
    }
    let period = periodic.then(|| {
        let mut l = [[0.0; D]; D];
        for (a, row) in l.iter_mut().enumerate() {
            row[a] = n as f64;
        }
        l
    });
    let model = Model::<D>::new(p, x, vec![1.0; count], 1.0, 0.0, period).unwrap();
    let mut z = model.rest_state(1.0);
    for v in z.v.iter_mut() {
        for c in v.iter_mut() {
            *c = vamp * jitter(&mut seed);
        }
    }
    for r in z.rho.iter_mut() {
        *r = 1.0 + 0.01 * jitter(&mut seed);
    }
    for s in z.sigma.iter_mut().chain(z.tau.iter_mut()) {
        for a in 0..D {
            for b in a..D {
                let e = 0.01 * jitter(&mut seed);
                s[a][b] = e;
                s[b][a] = e;
            }
        }
    }
    Run::new(model, z, vec![false; count], BoundaryDensity::Evolve).unwrap()
}

/// Every case, by name.
fn cases() -> Vec<(&'static str, Value)> {
    let jaumann = Material::elastic(1.0, 0.3, ObjectiveRate::Jaumann).unwrap();
    let truesdell = Material::elastic(1.0, 0.25, ObjectiveRate::Truesdell).unwrap();
    let hydro = Material::Hydro { bulk: 1.0 };
    let art = Some(ArtificialStress {
        eps: 0.3,
        n: 4,
        spacing: 1.0,
    });
    let mut out = Vec::new();

    // the throughput block (classical, elastic Jaumann, AV, artificial stress), larger amplitude
    let mut cfg = ThroughputConfig::new(m4());
    cfg.amplitude = 0.02;
    out.push((
        "throughput_block_2d",
        record(build_block(&cfg, 20).unwrap(), 12, 0.2),
    ));

    // the same block periodic, hydro
    let mut cfg_h = cfg;
    cfg_h.domain = Domain::Periodic;
    cfg_h.material = BlockMaterial::Hydro;
    out.push((
        "throughput_box_hydro_2d",
        record(build_block(&cfg_h, 16).unwrap(), 10, 0.2),
    ));

    // periodic hydro patch, jittered, AV + art. stress + δ-SPH (Antuono)
    let mut p = params(FormKind::Classical, hydro);
    p.art_stress = art;
    p.diffusion = Some(DensityDiffusion {
        delta: 0.1,
        form: DiffusionForm::Antuono,
        sound_speed: 1.0,
    });
    out.push((
        "periodic_hydro_av_art_antuono_2d",
        record(jittered::<2>(p, 14, true, 0.05, 0.01), 10, 0.2),
    ));

    // open elastic (Truesdell) classical + Molteni–Colagrossi diffusion + art. stress
    let mut p = params(FormKind::Classical, truesdell);
    p.art_stress = art;
    p.diffusion = Some(DensityDiffusion {
        delta: 0.2,
        form: DiffusionForm::MolteniColagrossi,
        sound_speed: 1.0,
    });
    out.push((
        "open_truesdell_art_molteni_2d",
        record(jittered::<2>(p, 14, false, 0.05, 0.01), 10, 0.2),
    ));

    // mixed and corrected forms
    out.push((
        "lnl_elastic_av_2d",
        record(
            jittered::<2>(params(FormKind::Lnl, jaumann), 14, true, 0.03, 0.01),
            8,
            0.2,
        ),
    ));
    let mut p = params(FormKind::Cll, jaumann);
    p.art_stress = art;
    out.push((
        "cll_elastic_av_art_2d",
        record(jittered::<2>(p, 14, false, 0.03, 0.01), 8, 0.2),
    ));
    out.push((
        "local_elastic_av_2d",
        record(
            jittered::<2>(params(FormKind::Local, jaumann), 14, true, 0.03, 0.01),
            8,
            0.2,
        ),
    ));
    let mut p = params(FormKind::Nonlocal, hydro);
    p.av = None;
    out.push((
        "nonlocal_hydro_2d",
        record(jittered::<2>(p, 14, true, 0.03, 0.01), 8, 0.2),
    ));
    out.push((
        "total_lagrangian_elastic_av_2d",
        record(
            jittered::<2>(
                params(FormKind::TotalLagrangian, jaumann),
                12,
                true,
                0.0,
                0.01,
            ),
            8,
            0.2,
        ),
    ));

    // 3D: the throughput box (periodic, elastic, AV) and a jittered hydro box with δ-SPH
    let mut cfg3 = ThroughputConfig::new(m4()).with_dim(3);
    cfg3.amplitude = 0.02;
    out.push((
        "throughput_box_3d",
        record(build_block_nd::<3>(&cfg3, 7).unwrap(), 6, 0.2),
    ));
    let mut p = params(FormKind::Classical, hydro);
    p.diffusion = Some(DensityDiffusion {
        delta: 0.1,
        form: DiffusionForm::MolteniColagrossi,
        sound_speed: 1.0,
    });
    out.push((
        "periodic_hydro_av_molteni_3d",
        record(jittered::<3>(p, 7, true, 0.05, 0.01), 6, 0.2),
    ));
    out
}

/// |new − old| ≤ TOL · max(max|old|, FLOOR · record max) entrywise, per field.
fn compare(case: &str, what: &str, old: &Value, new: &Value) {
    const FIELDS: [&str; 5] = ["x", "v", "rho", "sigma", "tau"];
    let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let get = |r: &Value, f: &str| -> Vec<f64> { serde_json::from_value(r[f].clone()).unwrap() };
    let record = FIELDS
        .iter()
        .map(|f| max_abs(&get(old, f)))
        .fold(0.0, f64::max);
    for field in FIELDS {
        let o = get(old, field);
        let n = get(new, field);
        assert_eq!(o.len(), n.len(), "{case} {what}.{field}: length");
        let scale = max_abs(&o).max(FLOOR * record);
        let worst = o
            .iter()
            .zip(&n)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        let bound = (TOL * scale).max(1e-300);
        assert!(
            worst <= bound,
            "{case} {what}.{field}: max |new − old| = {worst:e} > {bound:e} (max |old| = {scale:e})"
        );
    }
}

#[test]
fn solver_reproduces_golden_data() {
    let now = cases();
    if std::env::var_os("SPHSTAB_WRITE_GOLDEN").is_some() {
        let commit = std::process::Command::new("git")
            .args(["rev-parse", "--short", "HEAD"])
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
            .unwrap_or_default();
        let obj: serde_json::Map<String, Value> = now
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect();
        let doc = json!({
            "generated_at_commit": commit,
            "command": "SPHSTAB_WRITE_GOLDEN=1 cargo test --release --test it -- golden_solver2d::",
            "tolerance": "per field: |new - old| <= 1e-12 * max|old|",
            "cases": obj,
        });
        std::fs::create_dir_all(path().parent().unwrap()).unwrap();
        std::fs::write(path(), serde_json::to_string(&doc).unwrap()).unwrap();
        eprintln!("wrote {}", path().display());
        return;
    }
    let text = std::fs::read_to_string(path()).expect("tests/golden/solver2d.json");
    let doc: Value = serde_json::from_str(&text).unwrap();
    let cases = doc["cases"].as_object().unwrap();
    assert_eq!(cases.len(), now.len(), "number of golden cases");
    for (name, new) in &now {
        let old = &cases[*name];
        for what in ["rate0", "state"] {
            compare(name, what, &old[what], &new[what]);
        }
    }
}
