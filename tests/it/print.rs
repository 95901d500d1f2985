//! Print geometry of the figures (issue 26): an SVG is 85 or 170 mm wide and no text in it is
//! smaller than 6 pt at that width. [`check_print`] is the check; it is applied here to one
//! `dispersion --plot` and one `figures` config (all of figures/ once they are regenerated).

use crate::common::sphstab;
use sphstab::plot::print::{MIN_TEXT_PT, MM_PER_PT, attr};

/// What the check found in one SVG: its printed width in mm and its smallest text in pt.
#[derive(Debug)]
pub struct PrintSize {
    /// Width of the root element, mm.
    pub width_mm: f64,
    /// Size of the smallest `<text>` at print size, pt (infinite without text).
    pub min_text_pt: f64,
}

/// Parses `svg`: the root `width` must be "85mm" or "170mm" with a `viewBox`; every `<text>`
/// font-size, converted through the viewBox to the printed width, is measured. Nested `<svg>`
/// elements are assumed to be at their canvas size (width = viewBox width, as `stack_svg`
/// nests them).
pub fn print_size(svg: &str) -> Result<PrintSize, String> {
    let start = svg.find("<svg").ok_or("no <svg> element")?;
    let root = &svg[start..start + svg[start..].find('>').ok_or("unterminated <svg>")?];
    let width = attr(root, "width").ok_or("root <svg> without width")?;
    let width_mm: f64 = match width {
        "85mm" => 85.0,
        "170mm" => 170.0,
        w => return Err(format!("width {w:?}: not 85mm or 170mm")),
    };
    let vb = attr(root, "viewBox").ok_or("root <svg> without viewBox")?;
    let vb_w: f64 = vb
        .split_whitespace()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("viewBox {vb:?}"))?;
    let pt_per_px = width_mm / vb_w / MM_PER_PT;
    let mut min_text_pt = f64::INFINITY;
    for (i, _) in svg.match_indices("<text") {
        let tag = &svg[i..i + svg[i..].find('>').ok_or("unterminated <text>")?];
        let size: f64 = attr(tag, "font-size")
            .ok_or_else(|| format!("<text> without font-size: {tag}"))?
            .trim_end_matches("px")
            .parse()
            .map_err(|_| format!("font-size in {tag}"))?;
        min_text_pt = min_text_pt.min(size * pt_per_px);
    }
    Ok(PrintSize {
        width_mm,
        min_text_pt,
    })
}

/// Panics with `what` unless `svg` is 85 or 170 mm wide with no text below 6 pt.
pub fn check_print(what: &str, svg: &str) {
    let s = print_size(svg).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        s.min_text_pt >= MIN_TEXT_PT - 1e-9,
        "{what}: text of {:.2} pt at {} mm (at least {MIN_TEXT_PT} pt)",
        s.min_text_pt,
        s.width_mm
    );
}

#[test]
fn the_check_reads_millimetres_and_points() {
    // 1700 px for 85 mm: 20 px/mm; 6 pt = 6·25.4/72·20 ≈ 42.33 px
    let svg = |w: &str, fs: f64| {
        format!(
            "<svg width=\"{w}\" height=\"50mm\" viewBox=\"0 0 1700 1000\">\
             <text x=\"1\" y=\"2\" font-size=\"{fs}\">a</text></svg>"
        )
    };
    let s = print_size(&svg("85mm", 42.4)).unwrap();
    assert_eq!(s.width_mm, 85.0);
    assert!((s.min_text_pt - 42.4 / 20.0 / MM_PER_PT).abs() < 1e-9);
    check_print("6 pt", &svg("85mm", 42.4));
    assert!(print_size(&svg("100mm", 50.0)).is_err());
    assert!(print_size(&svg("1200", 50.0)).is_err());
    let small = std::panic::catch_unwind(|| check_print("5.9 pt", &svg("85mm", 41.6)));
    assert!(small.is_err());
}

#[test]
fn dispersion_plot_is_print_sized() {
    let dir = std::env::temp_dir().join(format!("sphstab-print-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("d.svg");
    let (code, _, err) = sphstab(&[
        "dispersion",
        "--form",
        "classical",
        "--kernel",
        "m4",
        "--support",
        "2.4",
        "--stress",
        "0",
        "--points",
        "32",
        "--plot",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    check_print("dispersion --plot", &svg);
}

#[test]
fn figure_config_is_print_sized() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let p = root.join("analysis/configs/b00_fig3a_eq74.json");
    let cfg = sphstab::figures::parse(
        &p.display().to_string(),
        &std::fs::read_to_string(&p).unwrap(),
    )
    .unwrap();
    let svg = sphstab::figures::render(&cfg).unwrap();
    check_print(&cfg.output, &svg);
}
