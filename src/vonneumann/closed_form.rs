//! Closed-form dispersion relations printed in the papers, implemented literally.
//!
//! These are the *paper's* formulas, kept independent of the numeric engine so that the two can
//! be compared; where a paper's algebra is internally inconsistent the correction is stated in
//! the function's `# Errata` section, with the size of the difference.
//!
//! # Units and inputs
//!
//! - Lengths in units of the lattice spacing (Δx = 1); the wave number is κ = kΔx ∈ [0, π].
//! - \[B00\] results are ω² in units of C/(ρΔx²), with C the tangent modulus of the form (the
//!   Truesdell modulus C^{σF} for Eulerian kernels, C^{SE} for Lagrangian kernels, E for eq. 108)
//!   and σ̄ = σ/C, positive in tension (SPEC §1).
//! - A uniform-lattice shape function is passed as a [`ShapeFn`]: `phi(x)` returns
//!   `[φ(x), φ'(x), φ''(x)]` of the shape function of the node at 0, x in units of Δx, together
//!   with `support`, the radius (in Δx) beyond which φ ≡ 0. Lattice sums run over every integer
//!   `|j| ≤ ceil(support) + 1` and, for stress points, over `x = j + ½` with
//!   `−ceil(support) − 2 ≤ j ≤ ceil(support) + 1` (a set symmetric about 0).
//! - Every `1 − cos θ` of the papers is evaluated as `2 sin²(θ/2)` (no cancellation as κ → 0).
//!
//! The \[V21\] Appendix B functions (Swegle's analysis) keep the paper's dimensional quantities;
//! see [`SwegleParams`].

use num_complex::Complex64;

/// Shape function of the node at 0 on a uniform lattice: `x ↦ [φ(x), φ'(x), φ''(x)]`, x in Δx.
pub type ShapeFn<'a> = &'a dyn Fn(f64) -> [f64; 3];

/// Largest support radius (in Δx) honoured by the lattice sums; larger (or infinite) values are
/// clamped so that a sum always terminates. A NaN or negative support is read as 0.
pub const MAX_LATTICE_SUPPORT: f64 = 1.0e4;

/// `ceil(support) + 1`, the half-width of the lattice sums.
fn half_width(support: f64) -> i64 {
    let r = if support.is_nan() {
        0.0
    } else {
        support.clamp(0.0, MAX_LATTICE_SUPPORT)
    };
    r.ceil() as i64 + 1
}

/// `2 sin²(θ/2)`, the cancellation-free form of `1 − cos θ`.
#[inline]
fn one_minus_cos(theta: f64) -> f64 {
    let s = (0.5 * theta).sin();
    2.0 * s * s
}

/// The lattice sums of \[B00\] eqs. (74), (82), (93)–(98), (103) and (108) for one wave number.
///
/// Master points are x = j, stress points x = j + ½ (units of Δx); `s_M(j) = sin κj`,
/// `c_M(j) = cos κj`, `s_S(j) = sin κ(j+½)`, `c_S(j) = cos κ(j+½)` (eqs. 94–95). Sums that
/// contain a cosine are accumulated as `Σ a − Σ a · 2 sin²(θ/2)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LatticeSums {
    /// `S_M = Σ_j φ'(j) sin κj` (the bracket of eqs. 74, 82, 93, 103, 108).
    pub s1_master: f64,
    /// `Σ_j φ''(j) [1 − cos κj]` (eqs. 74, 93).
    pub s2_master: f64,
    /// `Σ_j φ(j) cos κj` (eq. 108).
    pub phi_cos_master: f64,
    /// `Σ_j φ''(j) cos κj` (eq. 108).
    pub phi2_cos_master: f64,
    /// `S_S = Σ_j φ'(j+½) sin κ(j+½)` (eqs. 93, 103).
    pub s1_stress: f64,
    /// `Σ_j φ''(j+½)`, no trigonometric factor (eq. 93, third line).
    pub phi2_stress: f64,
    /// `Σ_j φ''(j+½) cos κ(j+½)` (eq. 93).
    pub phi2_cos_stress: f64,
    /// `Σ_j φ(j+½) cos κ(j+½)` (eq. 93).
    pub phi_cos_stress: f64,
    /// `Σ_j (j+½) φ'(j+½) cos κ(j+½)` (eq. 93, (F−1) term).
    pub xphi1_cos_stress: f64,
    /// `Σ_j (j+½) φ''(j+½) sin κ(j+½)` (eq. 93, (F−1) term).
    pub xphi2_sin_stress: f64,
}

/// Evaluates every [`LatticeSums`] entry for the shape `phi` of radius `support` at κ = `kappa`.
pub fn lattice_sums(phi: ShapeFn, support: f64, kappa: f64) -> LatticeSums {
    let n = half_width(support);
    let mut s = LatticeSums {
        s1_master: 0.0,
        s2_master: 0.0,
        phi_cos_master: 0.0,
        phi2_cos_master: 0.0,
        s1_stress: 0.0,
        phi2_stress: 0.0,
        phi2_cos_stress: 0.0,
        phi_cos_stress: 0.0,
        xphi1_cos_stress: 0.0,
        xphi2_sin_stress: 0.0,
    };
    // Master points x = j.
    let (mut phi_sum, mut phi_omc, mut phi2_sum) = (0.0, 0.0, 0.0);
    for j in -n..=n {
        let x = j as f64;
        let [p0, p1, p2] = phi(x);
        let th = kappa * x;
        let omc = one_minus_cos(th);
        s.s1_master += p1 * th.sin();
        s.s2_master += p2 * omc;
        phi_sum += p0;
        phi_omc += p0 * omc;
        phi2_sum += p2;
    }
    s.phi_cos_master = phi_sum - phi_omc;
    s.phi2_cos_master = phi2_sum - s.s2_master;
    // Stress points x = j + ½, symmetric set −n−½ … n+½.
    let (mut p_sum, mut p_omc, mut p2_omc) = (0.0, 0.0, 0.0);
    for j in (-n - 1)..=n {
        let x = j as f64 + 0.5;
        let [p0, p1, p2] = phi(x);
        let th = kappa * x;
        let omc = one_minus_cos(th);
        let c = 1.0 - omc;
        s.s1_stress += p1 * th.sin();
        s.phi2_stress += p2;
        p2_omc += p2 * omc;
        p_sum += p0;
        p_omc += p0 * omc;
        s.xphi1_cos_stress += x * p1 * c;
        s.xphi2_sin_stress += x * p2 * th.sin();
    }
    s.phi2_cos_stress = s.phi2_stress - p2_omc;
    s.phi_cos_stress = p_sum - p_omc;
    s
}

/// Continuum dispersion, \[B00\] eq. (32): ω²Δx²/c² = (1 + σ̄) κ².
///
/// Eq. (32) reads ω² = C̄ κ²/ρ with C̄ = C + σ (eq. 34 in the current configuration; C is B00's
/// Truesdell modulus C^{σF}, or C^{SE} at F = 1), so with c² = C/ρ and σ̄ = σ/C the normalised
/// form is (1 + σ̄) κ². Stable iff C̄ > 0, i.e. σ̄ > −1 (eq. 33–34).
pub fn b00_eq32_continuum(sigma_bar: f64, kappa: f64) -> f64 {
    (1.0 + sigma_bar) * kappa * kappa
}

/// Eulerian kernel, nodal integration, \[B00\] eq. (74):
/// ω² = (1 + σ̄) S₁² − σ̄ (S₂ − S₁²), S₁ = Σ φ'(j) sin κj, S₂ = Σ φ''(j)(1 − cos κj).
///
/// Assumptions of the paper: infinite uniform lattice, identical particles, symmetric weight
/// function, current configuration = reference (F = 1, so V_J = m_J/ρ), uniform Cauchy stress σ.
/// C̃^{σF} = C^{σF} + σ (eq. 75), normalised by C^{σF}; ω² in units of C^{σF}/(ρΔx²).
pub fn b00_eq74_eulerian_nodal(phi: ShapeFn, support: f64, sigma_bar: f64, kappa: f64) -> f64 {
    let s = lattice_sums(phi, support, kappa);
    let s1sq = s.s1_master * s.s1_master;
    (1.0 + sigma_bar) * s1sq - sigma_bar * (s.s2_master - s1sq)
}

/// Lagrangian kernel, nodal integration, \[B00\] eq. (82): ω² = (1 + σ̄) S₁².
///
/// C̄^{SE} = C^{SE}F² + S (eq. 81) is taken at F = 1, where it equals C + σ; ω² in units of
/// C^{SE}/(ρ₀ΔX²). Assumptions: uniform lattice, identical particles, symmetric weight function.
pub fn b00_eq82_lagrangian_nodal(phi: ShapeFn, support: f64, sigma_bar: f64, kappa: f64) -> f64 {
    let s1 = lattice_sums(phi, support, kappa).s1_master;
    (1.0 + sigma_bar) * s1 * s1
}

/// Eulerian kernel with stress points at the mid-intervals, \[B00\] eq. (93), printed form:
///
/// ```text
/// ω² = (1+σ̄)/2 { S_M² + S_S² }
///    − σ̄/2 { Σφ''_M (1 − c_M) − S_M² + Σφ''_S − S_S²
///            − F Σφ''_S c_S Σφ_S c_S
///            + (F−1)Δx Σφ''_S c_S Σ(j+½)φ'_S c_S
///            + (F−1)Δx Σ(j+½)φ''_S s_S Σφ'_S s_S }
/// ```
///
/// with `S_M = Σφ'_M s_M`, `S_S = Σφ'_S s_S` and s, c, φ_M, φ_S as in eqs. (94)–(98), Δx = 1
/// (the *current* spacing: the kernel is Eulerian). `f_def` is the deformation gradient F of the
/// pre-stressed state (1.0: the current configuration is the reference). C̄^{σF} = C + σ, ω² in
/// units of C^{σF}/(ρΔx²) with ρ the current density.
///
/// Assumptions of the paper: 1D, uniform lattice with stress points at j + ½, identical
/// particles, symmetric weight function, V^M = V^S = V/2 (eq. 84), stress-point displacements
/// interpolated from the masters (eq. 90), displacement of the node I taken as 0 in eq. (92).
///
/// # Ambiguities and the choice made
///
/// - Third line, `Σ φ''_S(j)` carries no `(1 − c_S)` factor, unlike its master counterpart.
///   Kept literally: at F = 1 it is right. The stress-point displacement is interpolated,
///   ũ_S = Σ_K φ_K(x_S) ũ_K, so the kernel-variation term of eq. (89) becomes
///   `Σ_J φ''(x_J^S − x_I)(ũ_J^S − ũ_I) = e^{iκI}[Σφ''_S c_S Σφ_S c_S − Σφ''_S]`, i.e. exactly
///   the `Σφ''_S − F Σφ''_S c_S Σφ_S c_S` pair printed (for a partition of unity Σφ''_S = 0).
/// - The F-dependence (the `F` factor and the two `(F−1)` terms, from eqs. 91–92) is reproduced
///   as printed, not re-derived. The prefactor C̄^{σF}/(2ρ) is also as printed, although eqs.
///   (86)–(88) carry further powers of F; at F ≠ 1 this closed form is the paper's, not a
///   re-derivation.
/// - `(F−1)Δx` multiplies the index `(j+½)` (a length once multiplied by Δx); with Δx = 1 the
///   factor is `(F−1)`.
///
/// At σ̄ = 0 (and any F) the relation reduces to eq. (103); see [`b00_table2`] for what that
/// implies for Table II.
pub fn b00_eq93_eulerian_stress_points(
    phi: ShapeFn,
    support: f64,
    sigma_bar: f64,
    f_def: f64,
    kappa: f64,
) -> f64 {
    let s = lattice_sums(phi, support, kappa);
    let sm2 = s.s1_master * s.s1_master;
    let ss2 = s.s1_stress * s.s1_stress;
    let brace =
        s.s2_master - sm2 + s.phi2_stress - ss2 - f_def * s.phi2_cos_stress * s.phi_cos_stress
            + (f_def - 1.0) * s.phi2_cos_stress * s.xphi1_cos_stress
            + (f_def - 1.0) * s.xphi2_sin_stress * s.s1_stress;
    0.5 * (1.0 + sigma_bar) * (sm2 + ss2) - 0.5 * sigma_bar * brace
}

/// Lagrangian kernel with stress points at the mid-intervals, \[B00\] eq. (103):
/// ω² = (1 + σ̄)/2 { [Σ φ'(j) sin κj]² + [Σ φ'(j+½) sin κ(j+½)]² }.
///
/// C̄^{SE} at F = 1 (= C + σ), V^{0M} = V^{0S} = V⁰/2; ω² in units of C^{SE}/(ρ₀ΔX²).
/// Assumptions: uniform lattice, identical particles, symmetric weight function.
pub fn b00_eq103_lagrangian_stress_points(
    phi: ShapeFn,
    support: f64,
    sigma_bar: f64,
    kappa: f64,
) -> f64 {
    let s = lattice_sums(phi, support, kappa);
    0.5 * (1.0 + sigma_bar) * (s.s1_master * s.s1_master + s.s1_stress * s.s1_stress)
}

/// Numerator and denominator of \[B00\] eq. (108), in that order (see
/// [`b00_eq108_least_squares`]): `(S₁² + β [Σφ'' c]², [Σφ c]² − β Σφ'' c Σφ c)`.
pub fn b00_eq108_terms(phi: ShapeFn, support: f64, alpha_s: f64, kappa: f64) -> (f64, f64) {
    let s = lattice_sums(phi, support, kappa);
    let beta = alpha_s; // β = α_s l_c², l_c = Δx = 1
    let num = s.s1_master * s.s1_master + beta * s.phi2_cos_master * s.phi2_cos_master;
    let den = s.phi_cos_master * s.phi_cos_master - beta * s.phi2_cos_master * s.phi_cos_master;
    (num, den)
}

/// Beissel–Belytschko least-squares stabilised nodal integration, \[B00\] eq. (108):
///
/// ```text
/// (ω/c)² = { [Σφ'(j) sin κj]² + β [Σφ''(j) cos κj]² }
///        / { [Σφ(j) cos κj]² − β Σφ''(j) cos κj Σφ(j) cos κj }
/// ```
///
/// with β = α_s l_c², l_c = Δx = 1, c² = E/ρ; ω² in units of E/(ρΔx²).
///
/// Assumptions of the paper: σ = 0 (the weak form (104) has no initial-stress term), identical
/// uniformly spaced nodes, symmetric weight, nodal integration of the *consistent* matrices
/// (106)–(107). Because the mass is consistent, α_s = 0 gives S₁²/(Σφ cos κj)², which equals
/// eq. (82) only for an interpolating shape (φ(j) = δ_j0). B00 §4.3 says the denominator
/// changes sign for large α_s at D_mx ≥ 2.5; with the exact φ'' on the nodes it stays positive
/// for the EFG weights (ERRATA E9), but for a shape where it does vanish the returned ω² is
/// negative or ±∞ — use [`b00_eq108_terms`] to inspect it.
pub fn b00_eq108_least_squares(phi: ShapeFn, support: f64, alpha_s: f64, kappa: f64) -> f64 {
    let (num, den) = b00_eq108_terms(phi, support, alpha_s, kappa);
    num / den
}

/// \[B00\] Table II, "Maximum eigenvalues for uniformly spaced particles based on Fourier
/// analysis": `(method, λ_max Δx²/c²)` as printed (σ = 0, D_max = 1.5, MLS/EFG shapes).
///
/// Note (not corrected, reported): at σ = 0 eq. (93) is identical to eq. (103), term by term
/// (every σ̄-independent term is `(S_M² + S_S²)/2`), so the same shape functions cannot give the
/// printed 4.0 (Eulerian stress points) and 2.0 (Lagrangian stress points) from eqs. (93) and
/// (103); the two rows differ by a factor of 2 that the equations do not contain.
pub fn b00_table2() -> [(&'static str, f64); 3] {
    [
        ("Nodal integration with both kernels", 1.0),
        ("Stress points with Eulerian kernel", 4.0),
        ("Stress points with Lagrangian kernel", 2.0),
    ]
}

/// Continuum (continuous-kernel) dispersion of the mixed local–nonlocal SPH, \[V21\] eq. (A.72):
/// ω²/(k²v²) = c + (1 − c)|W*(k)|², returned as κ²(c + (1 − c) (W*/W*(0))²).
///
/// `c_partition` is the partition coefficient c ∈ [0, 1] (c = 1 local, c = 0 nonlocal);
/// `w_star_over_w0` is the kernel transform at the same wave number, normalised so that
/// W*(0) = 1 (see [`crate::vonneumann::transform`]); ω² in units of v²/Δx², v² = E/ρ.
/// Assumptions: 1D infinite linear-elastic continuum, small strain, no initial stress.
pub fn v21_a72_continuum(c_partition: f64, w_star_over_w0: f64, kappa: f64) -> f64 {
    kappa * kappa * (c_partition + (1.0 - c_partition) * w_star_over_w0 * w_star_over_w0)
}

/// Inputs of Swegle's nearest-neighbour analysis as restated in \[V21\] Appendix B.
///
/// Dimensional, in any consistent unit system (1D: mass per unit length, density per unit
/// length as in V21 after eq. B.75). Assumptions of the paper: uniform lattice with spacing
/// ΔX = h, only nearest neighbours interact, density frozen except through the equation of state
/// σ = K(ρ₀/ρ − 1) (B.78, second line), h not perturbed, uniform total stress T.
///
/// # Sign conventions (what they must be)
///
/// - `w1` is V21's W'(|x_I − x_{I+1}|) = ∂W(|x_I − x_{I+1}|, h)/∂x_I at the nearest neighbour,
///   i.e. **−dW/dr(ΔX)**, which is **positive** for a bell-shaped kernel. Only with W' > 0 is
///   the stress-variation term of eq. (B.96), `(ρ₀K/2m) W' (E² + E⁻² − 2) = −(2ρ₀K/m) W' sin²κ`,
///   stabilising (s < 0). With W' = dW/dr < 0 (derivative with respect to the argument) it
///   would make the unstressed lattice unstable at every κ ∉ {0, π}.
/// - `w2` is **d²W/dr²(ΔX)**, "the second derivative of W with respect to its argument" (V21
///   text after B.83): positive beyond the kernel's inflection point. This is the W'' of
///   Swegle's criterion and of V21 Fig. 7. (V21's B.84 also calls it "the slope of W'", which
///   with the W' above is −d²W/dr²; the two readings differ in sign — see the errata of
///   [`swegle_s_rate`].)
/// - `t_stress` is the total stress T = σ + Q, positive in tension (V21 after B.116).
/// - `alpha` is the linear viscosity coefficient α of δQ_{I+½} = α(δẋ_{I+1} − δẋ_I) (B.83).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwegleParams {
    /// Particle mass m (per unit cross-section in 1D).
    pub m: f64,
    /// Current density ρ.
    pub rho: f64,
    /// Reference density ρ₀.
    pub rho0: f64,
    /// Bulk modulus K.
    pub k_bulk: f64,
    /// W' = ∂W(|x_I − x_{I+1}|)/∂x_I = −dW/dr at r = ΔX (> 0 for a bell-shaped kernel).
    pub w1: f64,
    /// W'' = d²W/dr² at r = ΔX (> 0 beyond the inflection point).
    pub w2: f64,
    /// Total stress T = σ + Q, positive in tension.
    pub t_stress: f64,
    /// Linear artificial-viscosity coefficient α.
    pub alpha: f64,
}

/// `s` of the semi-discrete perturbation equation δẍ = s δx − r δẋ, from \[V21\] eq. (B.96):
///
/// ```text
/// s = (m/ρ²) { W'' T (E + E⁻¹ − 2) + (ρ₀K/2m) W' (E² + E⁻² − 2) }
///   = −(4m/ρ²) W'' T sin²(κ/2) − (2ρ₀K/ρ²) W' sin²κ,          E = e^{iκ}, κ = kΔX
/// ```
///
/// i.e. (B.96) divided by Δt, with `W'' = p.w2` and `W' = p.w1` in the conventions of
/// [`SwegleParams`]. This is V21's analysis of its "difference" (nonlocal) form, eq. (B.77):
/// s(π) = −4mW''T/ρ² > 0 iff W''T < 0, V21's reversed criterion
/// ([`swegle_difference_unstable`]). Units: 1/time².
///
/// # Errata
///
/// - (B.96) → (B.98): B.98 multiplies the stress-variation term by an extra 2
///   (`2ρ₀KW'/2m` where (B.96)–(B.97) give `ρ₀KW'/2m` inside `2mΔt/ρ²{…}`): factor **2** on
///   that term. The kernel-variation and viscous terms of B.98 agree with B.96.
/// - (B.96) → (B.100): B.100's s lacks the factor 2 of (E + E⁻¹ − 2) = 2(cos − 1) on both
///   terms (factor **1/2**) and contains a Δt (`mΔt/ρ²`), although B.99 multiplies s by Δt
///   itself: B.100 is (Δt/2)·s. B.100 also writes δW'' for W''.
/// - (B.115): printed s(π) = −2mΔtW''T/ρ² inherits both B.100 errors; from (B.96)
///   s(π) = −4mW''T/ρ² (factor **2**, and Δt). The criterion (B.116) is unaffected.
/// - (B.84)/(B.96) and the sign of W'': B.84 writes δW'_{I+½} = W''(δx_{I+1} − δx_I), so the
///   W'' of B.84–B.96 is the slope of W' with respect to the separation, −d²W/dr² for the
///   W' = −dW/dr that makes the stress term stabilising. Read that way, (B.96) is exactly the
///   consistent linearisation of the σ_J-only form (B.74)/(B.75), and B.116 becomes Swegle's
///   criterion d²W/dr²·T > 0 — not a reversal. V21's reversed criterion needs W'' = d²W/dr² here
///   (as stated in V21's text), which is what this function uses; the numeric engine decides.
/// - (B.76): the "difference" form is obtained by dropping σ_I before linearising; keeping it,
///   the kernel-variation coefficient is σ_J − σ_I = 0 (no W''T term at all), while the
///   symmetric sum form (B.73, σ_I + σ_J) doubles it (2T, not T as V21's "B.75 would be the
///   same" says).
/// - (B.78): first line σ = −Kη = ρ₀c²(1 − ρ₀/ρ) is positive in compression; the second line
///   σ = −K[1 − ρ₀(x_{I+1} − x_{I−1})/2m] = K(ρ₀/ρ − 1) and (B.83) are positive in tension.
///   The second line is used (sign).
pub fn swegle_s_rate(p: &SwegleParams, kappa: f64) -> f64 {
    let sh = (0.5 * kappa).sin();
    let s1 = kappa.sin();
    let rho2 = p.rho * p.rho;
    -4.0 * p.m * p.w2 * p.t_stress * sh * sh / rho2
        - 2.0 * p.rho0 * p.k_bulk * p.w1 * s1 * s1 / rho2
}

/// `r` of δẍ = s δx − r δẋ (artificial viscosity), from \[V21\] eqs. (B.83)/(B.86):
///
/// ```text
/// r = −(αmW'/ρ²)(E + E⁻¹ − 2) = (4αmW'/ρ²) sin²(κ/2)        (≥ 0 for α, W' ≥ 0: damping)
/// ```
///
/// Units: 1/time.
///
/// # Errata
///
/// - Sign: (B.83) δQ_{I+½} = +α(δẋ_{I+1} − δẋ_I) inserted in (B.86) gives
///   `+(αmW'Δt/ρ²)(E + E⁻¹ − 2) δẋ`; (B.87), (B.93), (B.96) and (B.98) print the opposite sign
///   (from the substitution Q = −α(ẋ_{I+1} − ẋ_I) after B.76), which with the W' > 0 required
///   by the stress term makes the viscosity anti-damping. The (B.83)/(B.86) sign is used:
///   factor **−1** relative to B.96.
/// - (B.100) prints r = (αmW'Δt/ρ²)(cos − 1) δẋ: besides the sign, it lacks the factor 2 of
///   (E + E⁻¹ − 2) (factor **1/2**), contains Δt although B.99 multiplies r by Δt, and carries
///   a stray δẋ_{n−½} (a coefficient cannot contain the unknown).
pub fn swegle_r_rate(p: &SwegleParams, kappa: f64) -> f64 {
    let sh = (0.5 * kappa).sin();
    4.0 * p.alpha * p.m * p.w1 * sh * sh / (p.rho * p.rho)
}

/// Amplification factors of the leapfrog scheme (B.99) for one mode: the two roots of
///
/// ```text
/// λ² + (rΔt − sΔt² − 2) λ + 1 − rΔt = 0,
/// ```
///
/// det(R − λL) = 0 with L, R of (B.104); s = [`swegle_s_rate`], r = [`swegle_r_rate`].
/// Returned with the larger modulus first. Unstable when |λ| > 1 (+ tolerance, SPEC §1).
///
/// # Errata
///
/// - (B.108) prints the constant term as `1 + rΔt`; expanding (B.107),
///   (1 − rΔt − λ)(1 − λ) − sΔt²λ, gives `1 − rΔt` (= det A, A = L⁻¹R). Sign of rΔt.
///   With the printed constant a damped mode (r > 0) would have |λ₁λ₂| = 1 + rΔt > 1.
/// - (B.110) θ = (rΔt + sΔt²)/2 does not match the linear coefficient of (B.108), which gives
///   θ = (sΔt² − rΔt)/2; (B.113) D = sΔt² + θ² holds for the corrected pair (θ, C = 1 − rΔt).
pub fn swegle_amplification(p: &SwegleParams, kappa: f64, dt: f64) -> [Complex64; 2] {
    let s = swegle_s_rate(p, kappa);
    let r = swegle_r_rate(p, kappa);
    // λ² − 2Bλ + C = 0
    let b = 1.0 + 0.5 * (s * dt * dt - r * dt);
    let c = 1.0 - r * dt;
    quadratic_roots(b, c)
}

/// Roots of λ² − 2bλ + c = 0, larger modulus first, without cancellation.
fn quadratic_roots(b: f64, c: f64) -> [Complex64; 2] {
    let d = b * b - c;
    if d >= 0.0 {
        let q = b + b.signum() * d.sqrt();
        if q == 0.0 {
            // b = 0 and c = 0: double root 0.
            return [Complex64::new(0.0, 0.0); 2];
        }
        let l1 = q;
        let l2 = c / q;
        if l1.abs() >= l2.abs() {
            [Complex64::new(l1, 0.0), Complex64::new(l2, 0.0)]
        } else {
            [Complex64::new(l2, 0.0), Complex64::new(l1, 0.0)]
        }
    } else {
        let im = (-d).sqrt();
        [Complex64::new(b, im), Complex64::new(b, -im)]
    }
}

/// Swegle's instability criterion for the sum ("classical") form, as V21 states it (§4 and
/// Fig. 7a): unstable when W''σ > 0, here `w2 · t > 0` with w2 = d²W/dr² at the nearest
/// neighbour and t the total stress, positive in tension. (V21's own B.116 for its form B.77 is
/// the reverse, [`swegle_difference_unstable`].)
pub fn swegle_sum_unstable(w2: f64, t: f64) -> bool {
    w2 * t > 0.0
}

/// V21's reversed criterion for the difference (nonlocal) form, eq. (B.116) and Fig. 7b:
/// unstable when W''T < 0 (w2 = d²W/dr², t positive in tension). See the errata of
/// [`swegle_s_rate`] for why this hinges on the sign given to W''.
pub fn swegle_difference_unstable(w2: f64, t: f64) -> bool {
    w2 * t < 0.0
}

/// Semi-discrete ω² = −s of the sum form (σ_J-only B.74/B.75, Swegle's analysis):
///
/// ```text
/// ω² = (2ρ₀K/ρ²) W' sin²κ − (4m/ρ²) W'' T sin²(κ/2)
/// ```
///
/// Sign used: the kernel-variation term enters s with **+4mW''T sin²(κ/2)/ρ²** (opposite to
/// [`swegle_s_rate`]), so ω²(π) = −4mW''T/ρ² < 0 exactly when W''T > 0 — Swegle's criterion
/// ([`swegle_sum_unstable`]). Why: linearising ẍ_I = Σ_J (m/ρ²) σ_J ∂W(x_I − x_J)/∂x_I (σ
/// positive in tension) about the uniform lattice gives
/// δẍ_I = (m/ρ²)[W'(δσ_{I+1} − δσ_{I−1}) − T W''(δx_{I+1} − 2δx_I + δx_{I−1})] with W' = −dW/dr
/// and W'' = d²W/dr², i.e. s = (m/ρ²)[4W''T sin²(κ/2) − (2ρ₀K/m)W' sin²κ]. The stress term is the
/// same as in [`swegle_s_rate`] (it must be stabilising in both forms). The symmetric form B.73
/// (σ_I + σ_J) would double the W''T term. Units: 1/time².
pub fn swegle_omega2_sum(p: &SwegleParams, kappa: f64) -> f64 {
    let sh = (0.5 * kappa).sin();
    let s1 = kappa.sin();
    let rho2 = p.rho * p.rho;
    2.0 * p.rho0 * p.k_bulk * p.w1 * s1 * s1 / rho2 - 4.0 * p.m * p.w2 * p.t_stress * sh * sh / rho2
}
