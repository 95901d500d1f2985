//! Output formats as pure functions returning strings: CSV time histories and legacy-VTK
//! particle snapshots (POLYDATA with vertices, readable by ParaView).

use crate::forms::{FormKind, State, Tensor};
use std::fmt::Write;

/// CSV with a header row.
pub fn csv(header: &[&str], rows: impl IntoIterator<Item = Vec<f64>>) -> String {
    let mut s = header.join(",");
    s.push('\n');
    for r in rows {
        let line: Vec<String> = r.iter().map(|v| format!("{v:e}")).collect();
        s.push_str(&line.join(","));
        s.push('\n');
    }
    s
}

fn vtk<const D: usize>(
    title: &str,
    pts: &[[f64; D]],
    scalars: &[(String, Vec<f64>)],
    vectors: &[(&str, Vec<[f64; D]>)],
) -> String {
    // x y z with the missing coordinates 0
    let xyz = |p: &[f64; D]| {
        let mut c = [0.0; 3];
        c[..D].copy_from_slice(p);
        c
    };
    let n = pts.len();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# vtk DataFile Version 3.0\n{}\nASCII\nDATASET POLYDATA\nPOINTS {n} double",
        title.replace('\n', " ")
    );
    for p in pts {
        let [x, y, z] = xyz(p);
        let _ = writeln!(s, "{x:e} {y:e} {z:e}");
    }
    let _ = writeln!(s, "VERTICES {n} {}", 2 * n);
    for i in 0..n {
        let _ = writeln!(s, "1 {i}");
    }
    let _ = writeln!(s, "POINT_DATA {n}");
    for (name, v) in scalars {
        let _ = writeln!(s, "SCALARS {name} double 1\nLOOKUP_TABLE default");
        for x in v {
            let _ = writeln!(s, "{x:e}");
        }
    }
    for (name, v) in vectors {
        let _ = writeln!(s, "VECTORS {name} double");
        for p in v {
            let [x, y, z] = xyz(p);
            let _ = writeln!(s, "{x:e} {y:e} {z:e}");
        }
    }
    s
}

/// The final particle state of a run, in its dimension.
#[derive(Clone, Debug)]
pub enum FinalState {
    /// A 1D run.
    One(State<f64, 1>),
    /// A 2D run.
    Two(State<f64, 2>),
    /// A 3D run.
    Three(State<f64, 3>),
}

impl FinalState {
    /// Legacy VTK of the particles of a run of `form` with partition coefficient
    /// `c_partition` ([`vtk_state`]; 3D points in every dimension).
    pub fn vtk(&self, title: &str, form: FormKind, c_partition: f64) -> String {
        match self {
            FinalState::One(z) => vtk_state(title, z, form, c_partition),
            FinalState::Two(z) => vtk_state(title, z, form, c_partition),
            FinalState::Three(z) => vtk_state(title, z, form, c_partition),
        }
    }

    /// The velocity's first (x) component of every particle.
    pub fn axial_velocity(&self) -> Vec<f64> {
        match self {
            FinalState::One(z) => z.v.iter().map(|v| v[0]).collect(),
            FinalState::Two(z) => z.v.iter().map(|v| v[0]).collect(),
            FinalState::Three(z) => z.v.iter().map(|v| v[0]).collect(),
        }
    }

    /// The dimension.
    pub fn dim(&self) -> usize {
        match self {
            FinalState::One(_) => 1,
            FinalState::Two(_) => 2,
            FinalState::Three(_) => 3,
        }
    }
}

impl From<State<f64, 1>> for FinalState {
    fn from(z: State<f64, 1>) -> Self {
        FinalState::One(z)
    }
}

impl From<State<f64, 2>> for FinalState {
    fn from(z: State<f64, 2>) -> Self {
        FinalState::Two(z)
    }
}

impl From<State<f64, 3>> for FinalState {
    fn from(z: State<f64, 3>) -> Self {
        FinalState::Three(z)
    }
}

/// The names of the two stress parts of a mixed form (σ, τ): lnl mixes the nonlocal and the
/// local stress, cll the classical and the local one; None for the other forms.
pub fn stress_part_names(form: FormKind) -> Option<(&'static str, &'static str)> {
    match form {
        FormKind::Lnl => Some(("nonlocal", "local")),
        FormKind::Cll => Some(("classical", "local")),
        _ => None,
    }
}

/// Legacy VTK of a state of `form` in D dimensions (points with the missing coordinates 0;
/// density when carried). The stress written is the one the form's momentum equation
/// integrates ([`State::total_stress`]): σ, or for lnl and cll (1 − c)σ + cτ with c =
/// `c_partition`, followed by the two parts, named after [`stress_part_names`]
/// (`stress_nonlocal`/`stress_classical` and `stress_local` in 1D, `sigma_xx_local`, … in 2D
/// and 3D). In 2D and 3D the velocity is a vector and the stress its independent components
/// `sigma_xx`, …; in 1D they are the scalars `velocity` and `stress`. A form without a stress
/// state (the Lagrangian forms, hydrodynamic materials) writes none; the stress-point forms
/// write the particles' σ (their stress points' σ is not at the particles).
pub fn vtk_state<const D: usize>(
    title: &str,
    z: &State<f64, D>,
    form: FormKind,
    c_partition: f64,
) -> String {
    vtk_state_with_stress(title, z, form, &z.total_stress(c_partition))
}

/// [`vtk_state`] with `stress` (one per particle, or empty) written as the stress: a form
/// whose stress is not a state, the total-Lagrangian one, passes its law's
/// ([`crate::forms::Model::particle_stress`]).
pub fn vtk_state_with_stress<const D: usize>(
    title: &str,
    z: &State<f64, D>,
    form: FormKind,
    total: &[Tensor<f64, D>],
) -> String {
    const NAMES: [&str; 6] = [
        "sigma_xx", "sigma_yy", "sigma_xy", "sigma_zz", "sigma_xz", "sigma_yz",
    ];
    let mut sc: Vec<(String, Vec<f64>)> = Vec::new();
    if D == 1 {
        sc.push(("velocity".into(), z.v.iter().map(|v| v[0]).collect()));
    }
    if !z.rho.is_empty() {
        sc.push(("density".into(), z.rho.clone()));
    }
    let mut stress = |suffix: &str, t: &[Tensor<f64, D>]| {
        if t.is_empty() {
            return;
        }
        if D == 1 {
            sc.push((
                format!("stress{suffix}"),
                t.iter().map(|s| s[0][0]).collect(),
            ));
        } else {
            for (k, name) in NAMES.iter().enumerate().take(crate::forms::n_sym(D)) {
                let (a, b) = crate::forms::voigt(k);
                sc.push((
                    format!("{name}{suffix}"),
                    t.iter().map(|s| s[a][b]).collect(),
                ));
            }
        }
    };
    stress("", total);
    if !z.tau.is_empty() {
        let (ps, pt) = stress_part_names(form).unwrap_or(("sigma", "tau"));
        stress(&format!("_{ps}"), &z.sigma);
        stress(&format!("_{pt}"), &z.tau);
    }
    if D == 1 {
        vtk(title, &z.x, &sc, &[])
    } else {
        vtk(title, &z.x, &sc, &[("velocity", z.v.clone())])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vtk_has_consistent_counts() {
        let z = State::<f64, 1> {
            x: vec![[0.0], [1.0], [2.0]],
            v: vec![[0.1], [0.2], [0.3]],
            ..Default::default()
        };
        let s = vtk_state("t", &z, FormKind::Classical, 0.5);
        assert!(
            s.contains("POINTS 3 double")
                && s.contains("VERTICES 3 6")
                && s.contains("POINT_DATA 3")
        );
        assert_eq!(s.lines().filter(|l| l.starts_with("1 ")).count(), 3);
        let c = csv(&["t", "v"], [vec![0.0, 1.0], vec![1.0, 2.0]]);
        assert_eq!(c.lines().count(), 3);
    }

    /// A 2D lnl state with σ = diag(1, 2) + 3 (xy), τ = diag(5, 6) + 7 (xy) and c = 0.75:
    /// the stress written is 0.25σ + 0.75τ = (4, 5, 6) by hand, then the parts.
    #[test]
    fn vtk_writes_the_mixed_total_and_its_parts() {
        let z = State::<f64, 2> {
            x: vec![[0.0, 0.0]],
            v: vec![[0.0, 0.0]],
            rho: vec![1.0],
            sigma: vec![[[1.0, 3.0], [3.0, 2.0]]],
            tau: vec![[[5.0, 7.0], [7.0, 6.0]]],
            ..Default::default()
        };
        let s = vtk_state("t", &z, FormKind::Lnl, 0.75);
        let field = |name: &str| {
            let mut l = s.lines();
            l.find(|l| *l == format!("SCALARS {name} double 1"));
            l.nth(1).map(|v| v.parse::<f64>().unwrap())
        };
        for (name, want) in [
            ("sigma_xx", 4.0),
            ("sigma_yy", 5.0),
            ("sigma_xy", 6.0),
            ("sigma_xx_nonlocal", 1.0),
            ("sigma_xy_local", 7.0),
        ] {
            assert_eq!(field(name), Some(want), "{name}");
        }
    }
}
