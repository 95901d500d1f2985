//! The Swegle test [V21 §7.2] against the engine: every measured growth rate is compared with
//! the exact linear operator of the same 21×21 particle set (dense, src/solver/box_operator.rs)
//! and with the infinite lattice. Prints the table of measured / box / infinite rates.

use sphstab::forms::FormKind;
use sphstab::kernel;
use sphstab::studies::swegle::{SwegleConfig, SwegleReport, run_swegle};

fn run(form: FormKind, kern: &str, h: f64, f: f64) -> SwegleReport {
    let mut cfg = SwegleConfig::new(form, kernel::by_name(kern).unwrap(), h, f);
    cfg.until_window = true;
    run_swegle(&cfg, |_| {}).unwrap()
}

fn row(r: &SwegleReport) -> String {
    format!(
        "| {} | {} | {} | {} | {} | {:.5} | {:.5} | {} | {} | {} | {:.2} s |",
        r.form,
        r.kernel,
        r.h_over_dx,
        r.density_ratio,
        r.measured_growth_rate
            .map(|m| format!("{m:.5}"))
            .unwrap_or("—".into()),
        r.predicted_growth_rate_box,
        r.predicted_growth_rate_infinite,
        r.ratio_box.map(|m| format!("{m:.4}")).unwrap_or("—".into()),
        r.ratio_infinite
            .map(|m| format!("{m:.4}"))
            .unwrap_or("—".into()),
        if r.grew { "grew" } else { "no growth" },
        r.runtime_s
    )
}

const HEADER: &str = "| form | kernel | h/Δx | f | measured | box | infinite | measured/box | measured/infinite | | runtime |\n|---|---|---|---|---|---|---|---|---|---|---|";

/// The grid of the studies: both kernels, h/Δx ∈ {1.0, 1.2, 1.3}, each density ratio of `fs`.
fn grid(fs: [f64; 2]) -> Vec<(&'static str, f64, f64)> {
    let mut g = Vec::new();
    for kern in ["m4", "wendland-c2"] {
        for h in [1.0, 1.2, 1.3] {
            for f in fs {
                g.push((kern, h, f));
            }
        }
    }
    g
}

/// Tension: classical grows at 0.90–1.00 of the box prediction; nonlocal, local, lnl (c = 0.5)
/// and total-Lagrangian never exceed 2× the kick.
#[test]
#[ignore = "the full grid, 60 runs (~3 min): run by .ci/run; swegle_tension_sample checks the same claim in the default suite"]
fn swegle_tension() {
    tension(&grid([0.95, 0.99]));
}

/// [`swegle_tension`]'s claim, checked the same way on two corners of its grid (one per
/// kernel; the smallest h with the stronger tension and the largest with the weaker): each run
/// is a whole Swegle test whose measured rate is compared with the box operator of the same
/// particle set, so a corner fails exactly as it would in the full grid; the grid's other
/// points repeat that comparison at other supports (the full study, run by .ci/run).
#[test]
fn swegle_tension_sample() {
    tension(&[("m4", 1.0, 0.95), ("wendland-c2", 1.3, 0.99)]);
}

fn tension(points: &[(&str, f64, f64)]) {
    let mut table = vec![HEADER.to_string()];
    for &(kern, h, f) in points {
        let r = run(FormKind::Classical, kern, h, f);
        table.push(row(&r));
        let ratio = r
            .ratio_box
            .unwrap_or_else(|| panic!("classical {kern} h={h} f={f}: no growth measured"));
        assert!(
            (0.90..=1.00).contains(&ratio),
            "classical {kern} h={h} f={f}: measured/box {ratio}"
        );
        for form in [
            FormKind::Nonlocal,
            FormKind::Local,
            FormKind::Lnl,
            FormKind::TotalLagrangian,
        ] {
            let r = run(form, kern, h, f);
            table.push(row(&r));
            assert!(
                !r.grew,
                "{form:?} {kern} h={h} f={f} grew: max |v| {}",
                r.max_velocity_end
            );
        }
    }
    eprintln!("{}", table.join("\n"));
}

/// Compression: the run agrees with the engine's verdict for the same finite particle set —
/// growth (in the same ratio band) where the box operator has a growing mode, no growth where it
/// has none.
#[test]
#[ignore = "the full grid, 12 runs (~1 min): run by .ci/run; swegle_compression_sample checks the same claim in the default suite"]
fn swegle_compression() {
    compression(&grid([1.01, 1.05]));
}

/// [`swegle_compression`]'s claim on four points of its grid at the stronger compression: per
/// kernel the support its closing note names as stable (m4 h = 1.2, wendland-c2 h = 1.0) and
/// one with a growing transverse mode, so that both branches are exercised (asserted), each
/// run compared with the box operator of the same particle set as in the full grid (run by
/// .ci/run).
#[test]
fn swegle_compression_sample() {
    compression(&[
        ("m4", 1.2, 1.05),
        ("m4", 1.3, 1.05),
        ("wendland-c2", 1.0, 1.05),
        ("wendland-c2", 1.2, 1.05),
    ]);
}

fn compression(points: &[(&str, f64, f64)]) {
    let mut table = vec![HEADER.to_string()];
    let (mut grew, mut stable) = (0, 0);
    for &(kern, h, f) in points {
        let r = run(FormKind::Classical, kern, h, f);
        table.push(row(&r));
        if r.predicted_growth_rate_box > 1e-6 {
            let ratio = r.ratio_box.unwrap_or_else(|| {
                panic!(
                    "{kern} h={h} f={f}: engine predicts {} but nothing grew",
                    r.predicted_growth_rate_box
                )
            });
            assert!(
                (0.90..=1.00).contains(&ratio),
                "{kern} h={h} f={f}: measured/box {ratio}"
            );
            grew += 1;
        } else {
            assert!(
                !r.grew,
                "{kern} h={h} f={f}: engine predicts no growth, max |v| {}",
                r.max_velocity_end
            );
            stable += 1;
        }
    }
    eprintln!(
        "{}\ncompression: {grew} growing, {stable} stable",
        table.join("\n")
    );
    // both branches must be exercised, or the test could pass with one of them empty: the
    // engine predicts compressive (transverse) growth for some of these supports and none for
    // others (m4 h = 1.2, wendland-c2 h = 1.0; issue 3 closing note)
    assert!(grew > 0 && stable > 0, "grew {grew}, stable {stable}");
}

/// With artificial stress the solver and the engine still agree (same rate function):
/// classical m4 h = 1.2 f = 0.95, ε = 0.2: measured / box in [0.90, 1.00].
#[test]
fn swegle_with_artificial_stress() {
    let mut cfg = SwegleConfig::new(
        FormKind::Classical,
        kernel::by_name("m4").unwrap(),
        1.2,
        0.95,
    );
    cfg.art_stress = Some((0.2, 4));
    cfg.until_window = true;
    let r = run_swegle(&cfg, |_| {}).unwrap();
    eprintln!("{}", row(&r));
    let ratio = r.ratio_box.unwrap();
    assert!((0.90..=1.00).contains(&ratio), "{ratio}");
}
