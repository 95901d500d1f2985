//! `antiplane` series of the figure configs: the anti-plane Galerkin wave of \[B00\] §4.4
//! along a direction θ ([`AntiPlaneSeries`]).

use crate::error::{Error, Result};
use crate::kernel;
use crate::lattice::{Lattice, LatticeKind};
use crate::plot::Curve;
use crate::shape::{KernelParams, ShapeFamily};
use crate::vonneumann::antiplane::{AntiPlane, Mass, Quadrature};
use serde::Deserialize;
use std::f64::consts::PI;

/// How an anti-plane curve is computed.
#[derive(Clone, Copy, Debug, Default, Deserialize, serde::Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum AntiPlaneRoute {
    /// The Galerkin anti-plane system of [`crate::vonneumann::antiplane`] (as `sphstab
    /// stiffness --theta`): ωΔx/c of every branch.
    #[default]
    Engine,
    /// The continuum ü = c²Δu (\[B00\] eq 110): ωΔx/c = κΔx in every direction.
    Continuum,
}

/// One anti-plane curve (\[B00\] §4.4): ωΔx/c along the direction θ for κΔx from 0 to the
/// first-zone boundary along θ.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntiPlaneSeries {
    /// Route (default: engine).
    #[serde(default)]
    pub route: AntiPlaneRoute,
    /// Quadrature (`sphstab stiffness --quadrature`); engine route only, required there.
    pub quadrature: Option<String>,
    /// Propagation angle θ in degrees, in [−360, 360].
    pub theta: f64,
    /// Node lattice, `square` (default) or `hex` (Δx = nearest-neighbour distance).
    pub lattice: Option<String>,
    /// Kernel name; engine route only, required there.
    pub kernel: Option<String>,
    /// Support radius R/Δx (\[B00\]'s D_mx); engine route only, required there.
    pub support: Option<f64>,
    /// Shape family (default mls).
    pub shape: Option<String>,
    /// Consistent mass (default: lumped, as \[B00\] eq 119).
    #[serde(default)]
    pub consistent: bool,
    /// Legend label (default: generated).
    pub label: Option<String>,
    /// Draw dashed.
    #[serde(default)]
    pub dashed: bool,
}

/// Ordinate description of the anti-plane figures.
pub const OMEGA_DESC: &str = "ωΔx/c (frequency in units of c/Δx)";
/// Abscissa description of the anti-plane figures.
pub const KAPPA_THETA_DESC: &str = "wave number κΔx/π along θ (dotted: the cut-off along θ)";

impl AntiPlaneSeries {
    fn lattice(&self) -> Result<Lattice<2>> {
        Lattice::<2>::by_name(self.lattice.as_deref().unwrap_or("square"), 1.0)
    }

    /// The cut-off κΔx along θ (the first-zone boundary of the node lattice).
    fn cutoff(&self) -> Result<f64> {
        crate::error::check_range("theta", self.theta, -360.0, 360.0, true, true)?;
        Ok(self.lattice()?.zone_boundary(self.theta.to_radians()))
    }

    /// The curve: ωΔx/c against κΔx/π at `points` wave numbers in (0, cut-off]. A pattern of
    /// several nodes per periodic cell (the star pattern's 2×2 supercell) has one branch per
    /// node (the plane wave's band folded into the smaller zone of the supercell, mixed where
    /// the folded branches meet): all are drawn, as `sphstab stiffness --theta` prints them,
    /// in one curve with gaps between branches. ω² < 0 (not met for K = ∫∇φ·∇φ) would be drawn
    /// as ω = 0, as `sphstab stiffness` prints it.
    pub(super) fn curve(&self, points: usize) -> Result<Curve> {
        let lat = self.lattice()?;
        let kcut = self.cutoff()?;
        let (c, s) = (self.theta.to_radians().cos(), self.theta.to_radians().sin());
        let kappas: Vec<f64> = (1..=points)
            .map(|i| kcut * i as f64 / points as f64)
            .collect();
        let hex = matches!(lat.kind, LatticeKind::Hexagonal);
        let missing = |f: &str| {
            Error::Incompatible(format!("antiplane series: the engine route needs `{f}`").into())
        };
        let (x, y, label) = match self.route {
            AntiPlaneRoute::Continuum => (
                kappas.iter().map(|k| k / PI).collect(),
                kappas.clone(),
                "continuum ωΔx/c = κΔx [B00 eq 110]".to_string(),
            ),
            AntiPlaneRoute::Engine => {
                let q =
                    Quadrature::by_name(self.quadrature.as_deref().ok_or(missing("quadrature"))?)?;
                let k = kernel::by_name(self.kernel.as_deref().ok_or(missing("kernel"))?)?;
                let r = self.support.ok_or(missing("support"))?;
                crate::error::check_range("support", r, 0.0, 50.0, false, true)?;
                let fam = ShapeFamily::by_name(self.shape.as_deref().unwrap_or("mls"))?;
                let ap = AntiPlane::new(
                    &lat,
                    q,
                    fam,
                    KernelParams {
                        kernel: k,
                        h: r / k.zeta(),
                    },
                )?;
                let mass = if self.consistent {
                    Mass::Consistent
                } else {
                    Mass::Lumped
                };
                let w2 = kappas
                    .iter()
                    .map(|&kap| ap.omega2([kap * c, kap * s], mass))
                    .collect::<Result<Vec<_>>>()?;
                let nb = ap.pattern.sites.len();
                let (mut x, mut y) = (Vec::new(), Vec::new());
                for b in 0..nb {
                    if b > 0 {
                        x.push(f64::NAN);
                        y.push(f64::NAN);
                    }
                    x.extend(kappas.iter().map(|k| k / PI));
                    y.extend(w2.iter().map(|w| w[b].max(0.0).sqrt()));
                }
                let mut label = format!("{}, θ = {}°", q.name(), self.theta);
                if nb > 1 {
                    label += &format!(
                        " (all {nb} branches: {nb} nodes per periodic cell, the band folded into its smaller zone)"
                    );
                }
                if hex {
                    label += ", hex lattice";
                }
                (x, y, label)
            }
        };
        Ok(Curve {
            label: self.label.clone().unwrap_or(label),
            x,
            y,
            dashed: self.dashed,
        })
    }
}

/// The cut-off marks of anti-plane curves: one per distinct cut-off, naming every θ (and the
/// lattice when hexagonal) that ends there.
pub(super) fn cutoff_marks(series: &[AntiPlaneSeries]) -> Result<Vec<(f64, String)>> {
    let mut marks: Vec<(f64, Vec<String>)> = Vec::new();
    for a in series {
        let k = a.cutoff()? / PI;
        let name = format!("{}°", a.theta);
        match marks.iter_mut().find(|m| (m.0 - k).abs() < 1e-9) {
            Some(m) if !m.1.contains(&name) => m.1.push(name),
            Some(_) => {}
            None => marks.push((k, vec![name])),
        }
    }
    Ok(marks
        .into_iter()
        .map(|(k, names)| (k, format!("cut-off θ = {}", names.join(", "))))
        .collect())
}
