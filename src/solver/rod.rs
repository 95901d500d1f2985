//! The pre-stressed rod of \[B00 §4.1.2\]: a rod fixed at both ends with an initial tensile
//! stress σ0 = 1 GPa, E = 10 GPa, ρ = 2450 kg/m³, length 0.04 m; the centre node starts with
//! v0 = 40 m/s. B00 (Figs 6–7, EFG nodal integration, D_mx = 1.5): the Eulerian kernel is
//! unstable, the Lagrangian kernel is not. Fixed ends are `layers` particles thick so that every
//! free particle has a complete support.

use super::run::Run;
use crate::error::Result;
use crate::forms::{FormKind, Material, Model, ModelParams};
use crate::kernel::Kernel;
use crate::shape::{KernelParams, ShapeFamily};
use serde::Serialize;

/// Rod configuration.
#[derive(Clone, Copy, Debug)]
pub struct RodConfig {
    /// Form.
    pub form: FormKind,
    /// Kernel.
    pub kernel: &'static dyn Kernel,
    /// Shape family.
    pub shape: ShapeFamily,
    /// h/Δx.
    pub h_over_dx: f64,
    /// Nodes along the rod (odd, so that there is a centre node).
    pub nodes: usize,
    /// Fixed layers at each end.
    pub layers: usize,
    /// Length (m).
    pub length: f64,
    /// Initial stress σ0 (Pa), + tension.
    pub sigma0: f64,
    /// Young's modulus (Pa).
    pub modulus: f64,
    /// Density (kg/m³).
    pub rho: f64,
    /// Centre-node initial velocity (m/s).
    pub v0: f64,
    /// End time (s).
    pub t_end: f64,
    /// Time step Δt in Δx/c (the CFL number c Δt/h is dt/(h/Δx)).
    pub dt: f64,
}

impl RodConfig {
    /// B00's rod with `nodes` nodes.
    pub fn new(form: FormKind, kernel: &'static dyn Kernel, h_over_dx: f64, nodes: usize) -> Self {
        Self {
            form,
            kernel,
            shape: form.default_shape(),
            h_over_dx,
            nodes,
            layers: 3,
            length: 0.04,
            sigma0: 1e9,
            modulus: 1e10,
            rho: 2450.0,
            v0: 40.0,
            t_end: 1e-4,
            dt: 0.2,
        }
    }
}

/// Outcome of a rod run.
#[derive(Clone, Debug, Serialize)]
pub struct RodReport {
    /// Form.
    pub form: &'static str,
    /// Shape.
    pub shape: &'static str,
    /// Largest |v| over the run (m/s).
    pub max_velocity: f64,
    /// max |v| exceeded 2 v0, or the run diverged.
    pub unstable: bool,
    /// Time reached (s).
    pub t: f64,
}

/// Runs the rod.
pub fn run_rod(cfg: &RodConfig) -> Result<RodReport> {
    let n = cfg.nodes;
    let dx = cfg.length / (n - 1) as f64;
    let x: Vec<[f64; 1]> = (0..n).map(|i| [i as f64 * dx]).collect();
    let p = ModelParams {
        form: cfg.form,
        shape: cfg.shape,
        kp: KernelParams {
            kernel: cfg.kernel,
            h: cfg.h_over_dx * dx,
        },
        material: Material::bar(cfg.modulus),
        rho0: cfg.rho,
        c_partition: 0.5,
        av: None,
        art_stress: None,
        diffusion: None,
        alpha_s: 0.0,
        ls_length: dx,
        hourglass: None,
    };
    let model = Model::new(p, x, vec![dx; n], cfg.rho, cfg.sigma0, None)?;
    let mut z = model.rest_state(cfg.rho);
    z.v[n / 2] = [cfg.v0];
    let prescribed: Vec<Option<[f64; 1]>> = (0..n)
        .map(|i| {
            if i < cfg.layers || i >= n - cfg.layers {
                Some([0.0])
            } else {
                None
            }
        })
        .collect();
    let mut run = Run::with_prescribed(model, z, &prescribed)?;
    let c = (cfg.modulus / cfg.rho).sqrt();
    let dt = cfg.dt * dx / c;
    let mut vmax: f64 = cfg.v0;
    let mut diverged = false;
    while run.t < cfg.t_end {
        if run.step(dt).is_err() {
            diverged = true;
            break;
        }
        vmax = vmax.max(run.z.v.iter().fold(0.0f64, |m, [v]| m.max(v.abs())));
        if vmax > 1e3 * cfg.v0 {
            break;
        }
    }
    Ok(RodReport {
        form: cfg.form.name(),
        shape: cfg.shape.name(),
        max_velocity: vmax,
        unstable: diverged || vmax > 2.0 * cfg.v0,
        t: run.t,
    })
}
