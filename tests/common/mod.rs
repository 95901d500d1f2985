//! Helpers shared by the integration tests.
#![allow(dead_code)]

use sphstab::forms::{FormKind, ModelParams};
use sphstab::kernel::{self, Kernel};
use sphstab::shape::{KernelParams, ShapeFamily, lattice_shape};
use sphstab::vonneumann::linearise::{Lattice1D, Linearisation};
use std::f64::consts::PI;

pub fn k(name: &str) -> &'static dyn Kernel {
    kernel::by_name(name).unwrap()
}

pub fn params(
    form: FormKind,
    kern: &str,
    shape: ShapeFamily,
    h: f64,
    sigma_bar: f64,
) -> ModelParams {
    ModelParams {
        form,
        shape,
        kp: KernelParams { kernel: k(kern), h },
        modulus: 1.0,
        rho0: 1.0,
        sigma0: sigma_bar,
        c_partition: 0.5,
        alpha_s: 0.0,
        av: None,
        dx: 1.0,
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
        params(form, kern, shape, h, sigma_bar),
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
