//! The particle model in D ∈ {1, 2, 3} dimensions ([`Model`]): parameters, materials and state.
//!
//! Vectors are `[S; D]`; the stress is a symmetric `[[S; D]; D]` (the rates are computed
//! symmetric, so an integrated stress stays exactly symmetric); its independent components are
//! numbered in the nested Voigt order of [`voigt`] (xx, yy, xy, zz, xz, yz: the first one in 1D,
//! the first three in 2D). Materials:
//! - `Hydro`: p = K(ρ/ρ0 − 1), σ = −p I, density by continuity (the Swegle test); tangent
//!   modulus C = K.
//! - `Elastic`: hypo-elastic σ̇ = λ tr(d) I + 2G d + (objective terms), with the Jaumann rate
//!   (Wσ − σW) or the Truesdell rate (Lσ + σLᵀ − tr(L)σ, which in 1D is the law of the 1D
//!   forms); tangent modulus C = λ + 2G (P-wave modulus; plane strain in 2D).
//! - total-Lagrangian forms: hydro is the fluid P = −p(J) cof F; elastic is St Venant–Kirchhoff
//!   about the pre-stress with the moduli that give the Eulerian law's tangent (see
//!   `rates::rate_tl`).

// Small-tensor algebra (D × D, D ≤ 3) reads best with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::chain_data::{ChainData, MassOperator};
use super::kind::FormKind;
use super::params::{Material, ModelParams};
use super::state::{Comp, State};
use crate::error::{Error, Result, field};
use crate::lattice::Lattice;
use crate::scalar::Scalar;

/// A particle model in D dimensions: parameters plus the constant per-particle data.
#[derive(Clone, Debug)]
pub struct Model<const D: usize> {
    /// Parameters.
    pub p: ModelParams,
    /// Periodic cell vectors (rows; None: open).
    pub period: Option<[[f64; D]; D]>,
    /// Inverse of the periodic cell matrix (fractional coordinates s = d · period_inv).
    period_inv: [[f64; D]; D],
    /// Whether the periodic cell is a rectangular box (off-diagonal entries of it and of its
    /// inverse exactly zero): [`Model::rel`] then works per component.
    period_diagonal: bool,
    /// Masses.
    pub mass: Vec<f64>,
    /// Reference positions.
    pub x_ref: Vec<[f64; D]>,
    /// Reference volumes.
    pub vol_ref: Vec<f64>,
    /// Isotropic pre-stress σ0 of the total-Lagrangian law (the 1D forms' σ0).
    pub sigma0: f64,
    /// The pre-stress tensor: σ0 I unless [`Model::set_prestress`] gave another; the stress of
    /// [`Model::rest_state`] and of the total-Lagrangian law at F = I.
    pub prestress: [[f64; D]; D],
    /// The particles whose momentum equation takes the classical (plus) form of the stress
    /// divergence instead of the difference form: the boundary layer of the difference forms
    /// (nonlocal, local, lnl), which alone do not see a free surface \[V21 §7.4, Fig 18(b)\].
    /// Empty: none. Set it with [`Model::set_classical_layer`].
    pub(crate) classical_layer: Vec<bool>,
    /// Reference stencils (total-Lagrangian): (master, φ, ∇φ) at each master.
    pub(crate) ref_master: Vec<Vec<(usize, f64, [f64; D])>>,
    /// The reference pairs of a total-Lagrangian form with a pairwise term (`tl-enog`,
    /// Ganzenmüller's control): per particle its neighbours L ≠ K within the support.
    pub(crate) ref_pairs: Vec<Vec<RefPair<D>>>,
    /// The data of the 1D-only forms of \[B00\] (stress points, Lagrangian reference
    /// stencils, least-squares matrices); `None` for the forms of every dimension.
    pub(crate) chain: Option<ChainData>,
}

/// One reference pair (K, L) of a total-Lagrangian form with a pairwise term.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RefPair<const D: usize> {
    /// The neighbour L.
    pub l: usize,
    /// X_L − X_K (minimum image).
    pub d0: [f64; D],
    /// |X_L − X_K|.
    pub r0: f64,
    /// W(r0).
    pub w0: f64,
    /// W′(r0).
    pub dw: f64,
    /// V_K V_L.
    pub vv: f64,
}

/// The checks of the solid stabilisations of issue 30 and of `hourglass`: `enog` and
/// `tl-enog` need D ≥ 2 (their terms are a solid's shear) and a material with shear (elastic;
/// tl-enog also neo-Hookean); `hourglass` is their coefficient (ζ, κ) or Ganzenmüller's α of
/// `total-lagrangian`, in [0, 1000], and refused for every other form.
fn check_solid_form(p: &ModelParams, dim: usize) -> Result<()> {
    let form = p.form;
    if form.needs_2d() {
        if dim < 2 {
            return Err(Error::Incompatible(
                field("form")
                    + format!(" {} needs ", form.name())
                    + field("dim")
                    + " 2 or 3 (its shear terms are those of a solid)",
            ));
        }
        let shear = match p.material {
            Material::Elastic { .. } => true,
            Material::NeoHookean { .. } => form == FormKind::TlEnog,
            Material::Hydro { .. } => false,
        };
        if !shear {
            return Err(Error::Incompatible(
                field("form")
                    + format!(" {} needs ", form.name())
                    + field("material")
                    + if form == FormKind::Enog {
                        " elastic"
                    } else {
                        " elastic or neo-hookean"
                    },
            ));
        }
    }
    if let Some(c) = p.hourglass {
        if !matches!(
            form,
            FormKind::Enog | FormKind::TlEnog | FormKind::TotalLagrangian
        ) {
            return Err(Error::Incompatible(
                field("hourglass")
                    + " (the hourglass-control coefficient) applies to enog, tl-enog and total-lagrangian, not "
                    + field("form")
                    + format!(" {}", form.name()),
            ));
        }
        crate::error::check_range("hourglass", c, 0.0, 1000.0, true, true)?;
        if matches!(p.material, Material::Hydro { .. }) {
            return Err(Error::Incompatible(
                field("hourglass")
                    + " needs a material with shear stiffness (elastic or neo-hookean), not hydro",
            ));
        }
        if form == FormKind::TotalLagrangian && dim < 2 {
            return Err(Error::Incompatible(
                field("hourglass")
                    + " (Ganzenmüller's control of total-lagrangian) needs "
                    + field("dim")
                    + " 2 or 3",
            ));
        }
    }
    Ok(())
}

impl<const D: usize> Model<D> {
    /// A model of particles at `x_ref` with volumes `vol_ref` and current density `rho`
    /// (masses ρ V); `sigma0` is the isotropic pre-stress of the total-Lagrangian law (and of
    /// the 1D-only forms of \[B00\]: the least-squares stiffness uses C + σ0).
    ///
    /// The 1D-only forms (`eulerian-stress-points`, `lagrangian-stress-points`,
    /// `least-squares`, `eulerian-nodal`) need D = 1 and an elastic material (their law is
    /// σ̇ = (C + σ) ∂v/∂x, the Truesdell rate with C = λ + 2G); for D > 1 they are refused with
    /// an error naming the form and the dimension.
    ///
    /// Particle order is kept as given, and it matters for speed: the rate loops read each
    /// neighbour's state by index, so particles that are neighbours in space should be near in
    /// `x_ref`. Lattice order (one axis after another, as every built-in scene makes) is as fast
    /// as a Morton (Z-curve) order; an arbitrary order made the moving 2D block (160,000
    /// particles) 7.3× and the 3D box (64,000) 4.6× slower per step (docs/benchmarks.md,
    /// "Particle order").
    pub fn new(
        p: ModelParams,
        x_ref: Vec<[f64; D]>,
        vol_ref: Vec<f64>,
        rho: f64,
        sigma0: f64,
        period: Option<[[f64; D]; D]>,
    ) -> Result<Self> {
        if !p.form.in_every_dimension() && D > 1 {
            return Err(Error::Incompatible(
                field("form")
                    + format!(" {} is not available with ", p.form.name())
                    + field("dim")
                    + format!(
                        " {D} (classical, nonlocal, local, lnl, cll, total-lagrangian, enog, tl-enog)"
                    ),
            ));
        }
        p.form.check_shape(p.shape)?;
        check_solid_form(&p, D)?;
        if let Material::NeoHookean { .. } = p.material {
            if !p.form.is_total_lagrangian() {
                return Err(Error::Incompatible(
                    field("material")
                        + " neo-hookean needs "
                        + field("form")
                        + " total-lagrangian or tl-enog",
                ));
            }
            if sigma0 != 0.0 {
                return Err(Error::OutOfRange {
                    field: "stress",
                    value: sigma0,
                    range: "neo-hookean: the reference state is unstressed, σ̄ must be 0".into(),
                });
            }
        }
        if let Some(d) = p.diffusion {
            d.check("delta", p.form)?;
        }
        if D == 3 && p.art_stress.is_some() {
            return Err(Error::Incompatible(
                field("art_eps")
                    + " (artificial stress) is available with "
                    + field("dim")
                    + " 2 only",
            ));
        }
        let chain_form = !p.form.in_every_dimension();
        if chain_form {
            if !matches!(p.material, Material::Elastic { .. }) {
                return Err(Error::Incompatible(
                    field("form")
                        + format!(" {} needs ", p.form.name())
                        + field("material")
                        + " elastic (the 1D law σ̇ = (C + σ) ∂v/∂x)",
                ));
            }
            if p.av.is_some() {
                return Err(Error::Incompatible(
                    field("av_alpha")
                        + " (artificial viscosity) is available for classical, nonlocal, local, \
                           lnl and cll, not "
                        + field("form")
                        + format!(" {}", p.form.name()),
                ));
            }
            if p.diffusion.is_some() {
                return Err(Error::Incompatible(
                    field("delta")
                        + " (density diffusion) is available for classical, nonlocal, local, lnl \
                           and cll, not "
                        + field("form")
                        + format!(" {}", p.form.name()),
                ));
            }
            if p.art_stress.is_some() {
                return Err(Error::Incompatible(
                    field("art_eps")
                        + " (artificial stress) is available for classical and cll, not "
                        + field("form")
                        + format!(" {}", p.form.name()),
                ));
            }
        }
        let period_inv = match period {
            Some(l) => {
                let inv = invert(&l);
                if inv.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(Error::Incompatible(
                        "periodic cell: the cell vectors are linearly dependent".into(),
                    ));
                }
                inv
            }
            None => [[0.0; D]; D],
        };
        let mass = vol_ref.iter().map(|v| rho * v).collect();
        let off_zero = |a: &[[f64; D]; D]| (0..D).all(|i| (0..D).all(|j| i == j || a[i][j] == 0.0));
        let period_diagonal = period.is_some_and(|l| off_zero(&l) && off_zero(&period_inv));
        let mut m = Model {
            p,
            period,
            period_inv,
            period_diagonal,
            mass,
            x_ref,
            vol_ref,
            sigma0,
            prestress: std::array::from_fn(|a| {
                std::array::from_fn(|b| if a == b { sigma0 } else { 0.0 })
            }),
            classical_layer: Vec::new(),
            ref_master: Vec::new(),
            ref_pairs: Vec::new(),
            chain: None,
        };
        if chain_form {
            let x: Vec<f64> = m.x_ref.iter().map(|x| x[0]).collect();
            m.chain = Some(ChainData::new(
                &p,
                p.material.modulus(),
                sigma0,
                &x,
                &m.vol_ref,
                period.map(|l| l[0][0]),
            )?);
            return Ok(m);
        }
        if p.form.is_total_lagrangian() {
            let mut out = Vec::new();
            let mut st = Vec::with_capacity(m.x_ref.len());
            let kp = crate::shape::KernelParams {
                kernel: p.kp.kernel,
                h: p.kp.h,
            };
            for i in 0..m.x_ref.len() {
                let (nodes, idx) = m.neighbours_ref(m.x_ref[i]);
                crate::shape::eval_d(p.shape, kp, &nodes, m.x_ref[i][0], &mut out)?;
                st.push(
                    idx.into_iter()
                        .zip(&out)
                        .map(|(j, &(phi, g))| (j, phi, g))
                        .collect(),
                );
            }
            m.ref_master = st;
            if p.form == FormKind::TlEnog || p.hourglass.is_some() {
                m.ref_pairs = m.reference_pairs();
            }
        }
        Ok(m)
    }

    /// [`Model::ref_pairs`] from the reference stencils.
    fn reference_pairs(&self) -> Vec<Vec<RefPair<D>>> {
        let (kern, h) = (self.p.kp.kernel, self.p.kp.h);
        self.ref_master
            .iter()
            .enumerate()
            .map(|(k, st)| {
                st.iter()
                    .filter(|e| e.0 != k)
                    .map(|&(l, _, _)| {
                        let d0 = self.rel(self.x_ref[k], self.x_ref[l]);
                        let r0 = d0.iter().map(|c| c * c).sum::<f64>().sqrt();
                        let (w0, gr) = crate::kernel::w_and_grad(kern, h, d0);
                        // ∇_K W(X_K − X_L) = −W′(r0) d0/r0 with d0 = X_L − X_K
                        let dw = -gr.iter().zip(&d0).map(|(a, b)| a * b).sum::<f64>() / r0;
                        RefPair {
                            l,
                            d0,
                            r0,
                            w0,
                            dw,
                            vv: self.vol_ref[k] * self.vol_ref[l],
                        }
                    })
                    .collect()
            })
            .collect()
    }

    /// A periodic patch of n_1 × … × n_D primitive cells of `lat` (spacing `dx`), at rest.
    pub fn periodic_patch(
        p: ModelParams,
        lat: &Lattice<D>,
        dx: f64,
        n: [usize; D],
        rho: f64,
        sigma0: f64,
    ) -> Result<Self> {
        let a = lat.a;
        let count: usize = n.iter().product();
        let mut x = Vec::with_capacity(count);
        for idx in 0..count {
            // first index slowest
            let mut m = [0usize; D];
            let mut rest = idx;
            for c in (0..D).rev() {
                m[c] = rest % n[c];
                rest /= n[c];
            }
            let mut q = [0.0; D];
            for c in 0..D {
                let mut s = 0.0;
                for i in 0..D {
                    s += m[i] as f64 * a[i][c];
                }
                q[c] = dx * s;
            }
            x.push(q);
        }
        let vol = vec![lat.area() * dx.powi(D as i32); x.len()];
        let mut period = [[0.0; D]; D];
        for i in 0..D {
            for c in 0..D {
                period[i][c] = n[i] as f64 * dx * a[i][c];
            }
        }
        Self::new(p, x, vol, rho, sigma0, Some(period))
    }

    /// Minimum-image relative position b − a (exact for displacements within half a period of
    /// the cell; the rounding to the nearest image is the only non-smooth step, at half a
    /// period, never inside a support).
    #[inline]
    pub fn rel<S: Scalar>(&self, a: [S; D], b: [S; D]) -> [S; D] {
        let mut d = [S::zero(); D];
        for c in 0..D {
            d[c] = b[c] - a[c];
        }
        let Some(l) = self.period else { return d };
        if self.period_diagonal {
            // rectangular box: the same arithmetic as below without the zero terms (x + 0·y
            // is x), one component at a time
            for c in 0..D {
                let f = d[c].re() * self.period_inv[c][c];
                if f.abs() >= 0.5 {
                    d[c] = d[c] - f.round() * l[c][c];
                }
            }
            return d;
        }
        let mut s = [0.0; D];
        let mut any = false;
        for i in 0..D {
            let mut f = 0.0;
            for c in 0..D {
                f += d[c].re() * self.period_inv[c][i];
            }
            s[i] = f.round();
            any |= s[i] != 0.0;
        }
        if !any {
            return d;
        }
        for c in 0..D {
            let mut shift = 0.0;
            for i in 0..D {
                shift += s[i] * l[i][c];
            }
            d[c] = d[c] - shift;
        }
        d
    }

    fn neighbours_ref(&self, x: [f64; D]) -> (Vec<([f64; D], f64)>, Vec<usize>) {
        let r = self.p.kp.support();
        let mut nodes = Vec::new();
        let mut idx = Vec::new();
        for (j, &xj) in self.x_ref.iter().enumerate() {
            let d = self.rel(x, xj);
            let r2: f64 = d.iter().map(|c| c * c).sum();
            if r2 < r * r {
                nodes.push((d, self.vol_ref[j]));
                idx.push(j);
            }
        }
        (nodes, idx)
    }

    /// Replaces the isotropic pre-stress σ0 I by the symmetric tensor `t` (D ≥ 2; a
    /// deviatoric part needs an elastic material: a hydrodynamic one has no shear stress).
    pub fn set_prestress(&mut self, t: [[f64; D]; D]) -> Result<()> {
        let mean = (0..D).map(|a| t[a][a]).sum::<f64>() / D as f64;
        let deviatoric = (0..D).any(|a| (0..D).any(|b| t[a][b] != if a == b { mean } else { 0.0 }));
        if (0..D).any(|a| (0..D).any(|b| t[a][b] != t[b][a] || !t[a][b].is_finite())) {
            return Err(Error::Incompatible(
                field("prestress") + ": the pre-stress must be a finite symmetric tensor",
            ));
        }
        if deviatoric && !matches!(self.p.material, Material::Elastic { .. }) {
            return Err(Error::Incompatible(
                field("prestress")
                    + " with a deviatoric part needs "
                    + field("material")
                    + " elastic (hydro has no shear stress; neo-hookean's reference state is unstressed)",
            ));
        }
        if deviatoric && self.chain.is_some() {
            return Err(Error::Incompatible(
                field("prestress") + ": the 1D-only forms take an isotropic pre-stress",
            ));
        }
        self.prestress = t;
        self.sigma0 = mean;
        Ok(())
    }

    /// The state at rest at the reference positions with density `rho` and the pre-stress
    /// ([`Model::prestress`]) in every stress field the form carries.
    pub fn rest_state(&self, rho: f64) -> State<f64, D> {
        let n = self.x_ref.len();
        let comps = self.p.form.comps(D, &self.p.material);
        let mut z = State {
            x: self.x_ref.clone(),
            v: vec![[0.0; D]; n],
            ..Default::default()
        };
        if comps.contains(&Comp::Rho) {
            z.rho = vec![rho; n];
        }
        let iso = self.prestress;
        if comps.contains(&Comp::Sigma(0)) {
            z.sigma = vec![iso; n];
        }
        if comps.contains(&Comp::Tau(0)) {
            z.tau = vec![iso; n];
        }
        if comps.contains(&Comp::ShearAcc(0)) {
            z.shear_acc = vec![[0.0; D]; n];
        }
        if let Some(c) = &self.chain
            && comps.contains(&Comp::SpX(0))
        {
            z.sp_x = c.sp_x_ref.iter().map(|&x| [x; D]).collect();
            z.sp_sigma = vec![iso; c.sp_x_ref.len()];
            z.sp_vol.clone_from(&c.sp_vol_ref);
        }
        z
    }

    /// The mass operator: lumped for every form but `least-squares`, whose consistent mass
    /// \[B00 eq 106\] makes the `v` rate of [`Model::rate`] the force of M a = f.
    pub fn mass_operator(&self) -> &MassOperator {
        const LUMPED: &MassOperator = &MassOperator::Lumped;
        self.chain.as_ref().map_or(LUMPED, |c| &c.mass_op)
    }

    /// Marks the particles whose momentum equation takes the classical (plus) form
    /// (`layer[i]`; one entry per particle, or empty for none): \[V21 §7.4\]'s free-surface
    /// treatment of the difference forms. Refused for the other forms, whose momentum is
    /// already the plus form (classical, cll) or not a stress divergence of this kind.
    pub fn set_classical_layer(&mut self, layer: Vec<bool>) -> Result<()> {
        if layer.iter().any(|&b| b)
            && !matches!(
                self.p.form,
                FormKind::Nonlocal | FormKind::Local | FormKind::Lnl
            )
        {
            return Err(Error::Incompatible(
                field("classical_layers")
                    + " (a boundary layer in the classical form) applies to the difference forms nonlocal, local and lnl, not "
                    + field("form")
                    + format!(" {}", self.p.form.name()),
            ));
        }
        if !layer.is_empty() && layer.len() != self.x_ref.len() {
            return Err(Error::Incompatible(
                "classical layer: one entry per particle (or none)".into(),
            ));
        }
        self.classical_layer = layer;
        Ok(())
    }

    /// Number of stress points (stress-point forms: one per interval; 0 otherwise).
    pub fn stress_points(&self) -> usize {
        self.chain.as_ref().map_or(0, |c| c.sp_x_ref.len())
    }
}

/// Inverse of a D × D matrix, D ≤ 3 (non-finite entries when singular).
pub(crate) fn invert<const D: usize>(m: &[[f64; D]; D]) -> [[f64; D]; D] {
    let det = crate::lattice::det(m);
    let mut inv = [[0.0; D]; D];
    match D {
        1 => inv[0][0] = 1.0 / m[0][0],
        2 => {
            inv[0][0] = m[1][1] / det;
            inv[0][1] = -m[0][1] / det;
            inv[1][0] = -m[1][0] / det;
            inv[1][1] = m[0][0] / det;
        }
        _ => {
            for i in 0..3 {
                for j in 0..3 {
                    // cofactor of m[j][i]
                    let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
                    let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
                    inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
                }
            }
        }
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::forms::ArtificialStress;
    use crate::shape::{KernelParams, ShapeFamily};

    fn params(form: FormKind, material: Material) -> ModelParams {
        ModelParams {
            form,
            shape: ShapeFamily::Mls,
            kp: KernelParams {
                kernel: crate::kernel::by_name("m4").unwrap(),
                h: 1.3,
            },
            material,
            rho0: 1.0,
            c_partition: 0.5,
            av: None,
            art_stress: None,
            diffusion: None,
            alpha_s: 0.1,
            ls_length: 1.0,
            hourglass: None,
        }
    }

    /// The 1D-only forms of [B00] are forms of the one model in 1D and refused, naming the form
    /// and the dimension, in 2D and 3D; they need the 1D bar's elastic law.
    #[test]
    fn one_dimensional_forms_are_refused_above_one_dimension() {
        for form in [
            FormKind::EulerianStressPoints,
            FormKind::LagrangianStressPoints,
            FormKind::LeastSquares,
            FormKind::EulerianNodal,
        ] {
            let p = params(form, Material::bar(1.0));
            let m = Model::<1>::new(p, vec![[0.0], [1.0], [2.0]], vec![1.0; 3], 1.0, 0.0, None);
            assert!(m.is_ok(), "{}: {:?}", form.name(), m.err());
            let e2 = Model::<2>::new(p, vec![[0.0, 0.0]], vec![1.0], 1.0, 0.0, None).unwrap_err();
            let e3 =
                Model::<3>::new(p, vec![[0.0, 0.0, 0.0]], vec![1.0], 1.0, 0.0, None).unwrap_err();
            for (e, d) in [(e2, "2"), (e3, "3")] {
                let msg = e.to_string();
                assert!(
                    msg.contains(form.name()) && msg.contains(d),
                    "{}: {msg}",
                    form.name()
                );
            }
            let hydro = params(form, Material::Hydro { bulk: 1.0 });
            assert!(Model::<1>::new(hydro, vec![[0.0]], vec![1.0], 1.0, 0.0, None).is_err());
        }
    }

    /// Artificial stress in 3D is refused with an error, never silently zero (the
    /// Monaghan–Gray tensor is implemented in 1D and 2D).
    #[test]
    fn artificial_stress_is_refused_in_three_dimensions() {
        let mut p = params(FormKind::Classical, Material::Hydro { bulk: 1.0 });
        p.shape = ShapeFamily::Sph;
        p.art_stress = Some(ArtificialStress {
            eps: 0.2,
            n: 4,
            spacing: 1.0,
        });
        let x3 = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        assert!(Model::<3>::new(p, x3, vec![1.0; 2], 1.0, 0.0, None).is_err());
        let x2 = vec![[0.0, 0.0], [1.0, 0.0]];
        assert!(Model::<2>::new(p, x2, vec![1.0; 2], 1.0, 0.0, None).is_ok());
    }
}
