//! Figures fit for print (issue 26): every SVG in figures/ and a `dispersion --plot` are 85 or
//! 170 mm wide, no text in them is smaller than 6 pt at that width or longer than 120
//! characters (paragraphs belong in captions), their coordinates are not rounded to whole
//! units, and a form, kernel or integrator name has one colour in every figure that compares
//! such names. The checks read the SVG text as a renderer would; they share no code with the
//! plot layer except the print constants.

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

/// Panics with `what` unless `svg` is 85 or 170 mm wide with no text below 6 pt, no text
/// longer than 120 characters, and not every coordinate a whole number.
pub fn check_print(what: &str, svg: &str) {
    let s = print_size(svg).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        s.min_text_pt >= MIN_TEXT_PT - 1e-9,
        "{what}: text of {:.2} pt at {} mm (at least {MIN_TEXT_PT} pt)",
        s.min_text_pt,
        s.width_mm
    );
    for t in texts(svg) {
        assert!(
            t.chars().count() <= 120,
            "{what}: a text of {} characters (a caption's job): {t}",
            t.chars().count()
        );
    }
    // lines: at least 0.5 pt at print size (user units × the viewBox scale)
    let pt_per_unit = s.width_mm / view_box_width(svg) / MM_PER_PT;
    for (i, m) in svg.match_indices(" stroke-width=\"") {
        let w: f64 = svg[i + m.len()..]
            .split('"')
            .next()
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0);
        assert!(
            // the viewBox is written to 0.01 pt (481.89 for 481.8898): 2e-5 relative
            w * pt_per_unit >= 0.5 * (1.0 - 1e-4),
            "{what}: a line of {:.2} pt (at least 0.5 pt)",
            w * pt_per_unit
        );
    }
    let coords = coordinates(svg);
    assert!(coords.len() > 10, "{what}: {} coordinates", coords.len());
    assert!(
        coords.iter().any(|c| c.fract() != 0.0),
        "{what}: every coordinate is a whole number (staircase curves)"
    );
}

/// Width of the root `viewBox` (user units across the printed width).
fn view_box_width(svg: &str) -> f64 {
    let start = svg.find("<svg").unwrap_or(0);
    let root = &svg[start..start + svg[start..].find('>').unwrap_or(0)];
    attr(root, "viewBox")
        .and_then(|v| v.split_whitespace().nth(2)?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// The contents of every `<text>` element, unescaped.
fn texts(svg: &str) -> Vec<String> {
    svg.match_indices("<text")
        .filter_map(|(i, _)| {
            let rest = &svg[i..];
            let open = rest.find('>')? + 1;
            let close = rest.find("</text>")?;
            Some(
                rest[open..close]
                    .trim()
                    .replace("&lt;", "<")
                    .replace("&gt;", ">")
                    .replace("&quot;", "\"")
                    .replace("&amp;", "&"),
            )
        })
        .collect()
}

/// Every number in `points`, `x`, `y`, `cx`, `cy`, `x1`, `y1`, `x2`, `y2` attributes.
fn coordinates(svg: &str) -> Vec<f64> {
    let mut out = Vec::new();
    for name in ["points", "x", "y", "cx", "cy", "x1", "y1", "x2", "y2"] {
        let key = format!(" {name}=\"");
        for (i, m) in svg.match_indices(&key) {
            let v = svg[i + m.len()..].split('"').next().unwrap_or("");
            out.extend(v.split([' ', ',']).filter_map(|n| n.parse::<f64>().ok()));
        }
    }
    out
}

/// The paint of a drawing element: its stroke, else its fill (None: text or unpainted).
fn paint(tag: &str) -> Option<String> {
    let name = tag.trim_start_matches('<').split([' ', '>', '/']).next()?;
    if !matches!(
        name,
        "polyline" | "polygon" | "circle" | "rect" | "path" | "line"
    ) {
        return None;
    }
    attr(tag, "stroke")
        .filter(|c| *c != "none")
        .or_else(|| attr(tag, "fill"))
        .map(str::to_uppercase)
}

/// Frames, grids, bands and backgrounds: white and greys no series is drawn in (the
/// reference grey #505050 is a series colour).
fn is_decoration(c: &str) -> bool {
    c == "#FFFFFF" || c == "#6E6E6E" || {
        let h = |k: usize| u8::from_str_radix(c.get(k..k + 2).unwrap_or("00"), 16).unwrap_or(0);
        h(1) == h(3) && h(3) == h(5) && h(1) >= 0xC0
    }
}

/// The legend entries of a figure: (name, colour of its sample) for every text that starts
/// with a form, kernel, integrator or reference name (the library's lists; after "form = " or
/// another one-word key), the sample being the last series-coloured element drawn before the
/// text (legend samples precede their labels).
fn named_entries(svg: &str) -> Vec<(String, String)> {
    let names: Vec<&str> = sphstab::studies::series_names()
        .0
        .into_iter()
        .flatten()
        .chain(["continuum", "analytic", "exact"])
        .collect();
    let mut last: Option<String> = None;
    let mut out = Vec::new();
    for (i, _) in svg.match_indices('<') {
        let tag = &svg[i..i + svg[i..].find('>').unwrap_or(0)];
        if let Some(c) = paint(tag) {
            if !is_decoration(&c) {
                last = Some(c);
            }
            continue;
        }
        if !tag.starts_with("<text") {
            continue;
        }
        let body = &svg[i + tag.len() + 1..];
        let content = body[..body.find("</text>").unwrap_or(0)].trim();
        let content = match content.split_once(" = ") {
            Some((k, v)) if !k.contains(' ') => v,
            _ => content,
        };
        let first = content
            .split([' ', ',', ':', '(', '|'])
            .next()
            .unwrap_or_default();
        if let (true, Some(c)) = (names.contains(&first), &last) {
            out.push((first.to_string(), c.clone()));
        }
    }
    out
}

#[test]
fn the_check_reads_millimetres_and_points() {
    // 85 mm = 240.94 pt across a viewBox 240.94 wide: user units are points
    let svg = |w: &str, fs: f64, pts: &str, text: &str| {
        format!(
            "<svg width=\"{w}\" height=\"50mm\" viewBox=\"0 0 240.94 141.73\">\
             <polyline points=\"{pts}\"/><text x=\"1\" y=\"2\" font-size=\"{fs}\">{text}</text></svg>"
        )
    };
    let curve = "0,0 1.5,2.25 3,4.5 4.5,6.75 6,9 7.5,11.25";
    let s = print_size(&svg("85mm", 6.0, curve, "a")).unwrap();
    assert_eq!(s.width_mm, 85.0);
    assert!((s.min_text_pt - 6.0).abs() < 1e-3);
    check_print("6 pt", &svg("85mm", 6.0, curve, "a"));
    // twice the viewBox: half the size
    let wide = svg("170mm", 6.0, curve, "a");
    assert!((print_size(&wide).unwrap().min_text_pt - 12.0).abs() < 1e-2);
    assert!(print_size(&svg("100mm", 6.0, curve, "a")).is_err());
    assert!(print_size(&svg("1200", 6.0, curve, "a")).is_err());
    let fails = |s: String| std::panic::catch_unwind(|| check_print("bad", &s)).is_err();
    assert!(fails(svg("85mm", 5.9, curve, "a")));
    assert!(fails(svg("85mm", 7.0, "0,0 1,2 3,4 5,6 7,8 9,10", "a")));
    assert!(fails(svg("85mm", 7.0, curve, &"x".repeat(121))));
    let thin =
        svg("85mm", 7.0, curve, "a").replace("<polyline ", "<polyline stroke-width=\"0.4\" ");
    assert!(fails(thin));
    // legend entries: the sample's colour before each name
    let legend = "<polyline stroke=\"#0072B2\" points=\"0,0 1,1\"/><text>classical (sum)</text>\
                  <polyline stroke=\"#6E6E6E\" points=\"0,0 1,1\"/>\
                  <circle fill=\"#D55E00\" cx=\"1\" cy=\"1\" r=\"2\"/><text>form = nonlocal</text>\
                  <text>(a) lnl</text>";
    assert_eq!(
        named_entries(legend),
        [
            ("classical".to_string(), "#0072B2".to_string()),
            ("nonlocal".to_string(), "#D55E00".to_string())
        ]
    );
}

#[test]
fn dispersion_plot_is_print_sized() {
    let dir = std::env::temp_dir().join(format!("sphstab-print-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("d.svg");
    let (code, _, err) = sphstab(&[
        "dispersion",
        "--form",
        "classical,nonlocal",
        "--kernel",
        "m4",
        "--support",
        "2.4",
        "--stress",
        "0.1",
        "--points",
        "32",
        "--plot",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    check_print("dispersion --plot", &svg);
    // the two forms in their colours, the continuum in its own
    let e = named_entries(&svg);
    let names: Vec<&str> = e.iter().map(|p| p.0.as_str()).collect();
    assert_eq!(names, ["classical", "nonlocal", "continuum"], "{e:?}");
    assert!(e[0].1 != e[1].1 && e[1].1 != e[2].1);
}

/// Every committed figure (figures/*.svg, as `figures` and the studies' `--plot` draw them)
/// is print-ready, and every name a legend compares (two or more different form, kernel or
/// integrator names in one legend) has one colour across all such legends and figures.
#[test]
fn every_figure_is_print_ready_with_one_colour_per_name() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("figures");
    let mut seen: std::collections::BTreeMap<String, Vec<(String, String)>> = Default::default();
    let (mut n, mut legends) = (0, 0);
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "svg") {
            continue;
        }
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        let svg = std::fs::read_to_string(&p).unwrap();
        check_print(&name, &svg);
        // each legend is a group <g class="legend">: a sample precedes its label
        for legend in svg.split("<g class=\"legend\">").skip(1) {
            legends += 1;
            let legend = &legend[..legend.find("</g>").expect("a closed legend")];
            let entries = named_entries(legend);
            let mut distinct: Vec<&str> = entries
                .iter()
                .map(|e| e.0.as_str())
                .filter(|n| !matches!(*n, "continuum" | "analytic" | "exact"))
                .collect();
            distinct.sort_unstable();
            distinct.dedup();
            if distinct.len() >= 2 {
                for (k, c) in entries {
                    seen.entry(k).or_default().push((c, name.clone()));
                }
            }
        }
        n += 1;
    }
    assert!(n >= 22, "{n} figures");
    assert!(legends >= 22, "{legends} legends");
    for (k, v) in &seen {
        assert!(
            v.iter().all(|c| c.0 == v[0].0),
            "{k} is drawn in more than one colour: {v:?}"
        );
    }
    // the check is not vacuous: the forms, the integrators and references are compared
    assert!(
        seen.len() >= 15,
        "{} names compared: {:?}",
        seen.len(),
        seen.keys()
    );
}
