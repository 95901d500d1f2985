//! Output formats as pure functions returning strings: CSV time histories and legacy-VTK
//! particle snapshots (POLYDATA with vertices, readable by ParaView).

use crate::forms::State;
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
    scalars: &[(&str, Vec<f64>)],
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

/// Legacy VTK of a state in D dimensions (points with the missing coordinates 0; density and
/// the independent σ components when carried). In 2D and 3D the velocity is a vector; in 1D it
/// is the scalar `velocity` and the stress the scalar `stress`.
pub fn vtk_state<const D: usize>(title: &str, z: &State<f64, D>) -> String {
    const NAMES: [&str; 6] = [
        "sigma_xx", "sigma_yy", "sigma_xy", "sigma_zz", "sigma_xz", "sigma_yz",
    ];
    let mut sc = Vec::new();
    if D == 1 {
        sc.push(("velocity", z.v.iter().map(|v| v[0]).collect()));
    }
    if !z.rho.is_empty() {
        sc.push(("density", z.rho.clone()));
    }
    if !z.sigma.is_empty() {
        if D == 1 {
            sc.push(("stress", z.sigma.iter().map(|s| s[0][0]).collect()));
        } else {
            for (k, name) in NAMES.iter().enumerate().take(crate::forms::n_sym(D)) {
                let (a, b) = crate::forms::voigt(k);
                sc.push((*name, z.sigma.iter().map(|s| s[a][b]).collect()));
            }
        }
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
        let s = vtk_state("t", &z);
        assert!(
            s.contains("POINTS 3 double")
                && s.contains("VERTICES 3 6")
                && s.contains("POINT_DATA 3")
        );
        assert_eq!(s.lines().filter(|l| l.starts_with("1 ")).count(), 3);
        let c = csv(&["t", "v"], [vec![0.0, 1.0], vec![1.0, 2.0]]);
        assert_eq!(c.lines().count(), 3);
    }
}
