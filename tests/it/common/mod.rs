//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod exact;

use sphstab::analysis::MaterialSpec;
use sphstab::forms::{FormKind, Material, ModelParams, ObjectiveRate};
use sphstab::kernel::{self, Kernel};
use sphstab::lattice::Lattice;
use sphstab::shape::{KernelParams, ShapeFamily, lattice_shape};
use sphstab::vonneumann::derived::{Sums, omega2_1d, sums};
use sphstab::vonneumann::linearise::{Lattice1D, Linearisation};
use std::f64::consts::PI;

pub fn k(name: &str) -> &'static dyn Kernel {
    kernel::by_name(name).unwrap()
}

/// The parameters of a 1D bar (C = 1, ρ0 = 1, Δx = 1) for `form`, kernel `kern` at h.
pub fn params(form: FormKind, kern: &str, shape: ShapeFamily, h: f64) -> ModelParams {
    ModelParams {
        form,
        shape,
        kp: KernelParams { kernel: k(kern), h },
        material: Material::bar(1.0),
        rho0: 1.0,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: 1.0,
        hourglass: None,
    }
}

pub fn lin(
    form: FormKind,
    kern: &str,
    shape: ShapeFamily,
    h: f64,
    sigma_bar: f64,
) -> Linearisation {
    Linearisation::new(
        params(form, kern, shape, h),
        sigma_bar,
        Lattice1D::default(),
    )
    .unwrap()
}

/// κΔx grid πk/n, k = 1..n.
pub fn grid(n: usize) -> Vec<f64> {
    (1..=n).map(|i| PI * i as f64 / n as f64).collect()
}

/// (max ω², κ at max) over the grid.
pub fn max_omega2(l: &Linearisation, n: usize) -> (f64, f64) {
    grid(n)
        .into_iter()
        .map(|kap| (l.omega2(kap).0, kap))
        .fold((f64::MIN, 0.0), |a, b| if b.0 > a.0 { b } else { a })
}

/// The uniform-lattice shape closure used by the closed forms.
pub fn shape_fn(fam: ShapeFamily, kern: &str, h: f64) -> impl Fn(f64) -> [f64; 3] {
    let kp = KernelParams { kernel: k(kern), h };
    move |x| lattice_shape(fam, kp, x).unwrap()
}

/// The 1D chain sums S1, S2, M1 of the `sph` lattice shape (kernel `kern`, h), at κ.
pub fn chain_sums(kern: &str, h: f64, kappa: f64) -> Sums<1> {
    let kp = KernelParams { kernel: k(kern), h };
    sums(&Lattice::chain(), ShapeFamily::Sph, kp, [kappa]).unwrap()
}

/// The derived 1D closed-form ω² of `form` (`vonneumann::derived::omega2_1d`, D = 1, sph chain
/// sums, partition c = 0.5 as in [`params`]).
pub fn derived_omega2(form: FormKind, kern: &str, h: f64, sigma_bar: f64, kappa: f64) -> f64 {
    omega2_1d(form, &chain_sums(kern, h, kappa), sigma_bar, 0.5).unwrap()
}

/// The materials of the 2D and 3D Bloch checks: hydro (K = 1), elastic Jaumann (C = 1,
/// ν = 0.3), elastic Truesdell (C = 1, ν = 0.25), with their names.
pub fn material_specs() -> [(&'static str, MaterialSpec); 3] {
    [
        ("hydro", MaterialSpec::Hydro),
        (
            "jaumann",
            MaterialSpec::Elastic {
                poisson: 0.3,
                rate: ObjectiveRate::Jaumann,
            },
        ),
        (
            "truesdell",
            MaterialSpec::Elastic {
                poisson: 0.25,
                rate: ObjectiveRate::Truesdell,
            },
        ),
    ]
}

/// A small atlas (2 forms × m4 × 3 h/Δx × 7 σ̄ at 64 κ: 42 cells, a few milliseconds) with
/// growing and stable cells; 7 σ̄ values, so that the atlas interpolates the Jacobian in σ̄ (from
/// 5 on) while a shard holds only some cells of each (form, kernel, h).
pub const SMALL_ATLAS: [&str; 11] = [
    "atlas",
    "--forms",
    "classical,nonlocal",
    "--kernels",
    "m4",
    "--h-points",
    "3",
    "--stress-points",
    "7",
    "--kappas",
    "64",
];

/// Runs the built `sphstab` binary: (exit code, stdout, stderr).
pub fn sphstab(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sphstab"))
        .args(args)
        .output()
        .expect("run sphstab");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `sphstab` expecting success and a JSON document on stdout.
pub fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = sphstab(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

/// Asserts every bad input exits 2 with one line on stderr naming `flag` and nothing on stdout.
pub fn assert_bad_inputs(cases: &[(&[&str], &str)]) {
    for (args, flag) in cases {
        let (code, out, err) = sphstab(args);
        assert_eq!(code, 2, "{args:?}: exit {code}, stderr {err}");
        assert!(out.is_empty(), "{args:?}: stdout {out}");
        assert!(
            err.contains(flag),
            "{args:?}: stderr does not name {flag}: {err}"
        );
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
    }
}
