//! The print geometry of every figure, in one place: page widths in millimetres, the drawing
//! scale (canvas pixels per millimetre), type sizes and line widths in points at print size,
//! one font family, and [`finish`], which sets an assembled SVG in points to print at 85 or
//! 170 mm.
//!
//! Every plot is laid out in points on a page of the printed width ([`page_pt`]: 481.9 pt for
//! 170 mm, 240.9 pt for 85 mm), so a type size or line width given here is what prints: the
//! root `<svg>` carries `width="170mm"` and a `viewBox` in points ([`super::canvas`] writes
//! every coordinate in points to 0.01 pt).

use crate::error::{Error, Result};

/// Millimetres per point (1 pt = 1/72 inch).
pub const MM_PER_PT: f64 = 25.4 / 72.0;

/// The one font family of every figure: DejaVu Sans where installed, else the metric-alike
/// sans serifs every system has.
pub const FONT_FAMILY: &str = "DejaVu Sans, Arial, Helvetica, sans-serif";

/// Tick labels, pt.
pub const TICK_PT: f64 = 7.0;
/// Axis labels and titles, pt.
pub const LABEL_PT: f64 = 8.0;
/// Legend entries, pt.
pub const LEGEND_PT: f64 = 7.0;
/// Figure titles, pt.
pub const TITLE_PT: f64 = 9.0;
/// Panel letters (a), (b), …, pt.
pub const PANEL_LETTER_PT: f64 = 9.0;
/// Legend notes (coincidence, clipping) and caption lines, pt.
pub const NOTE_PT: f64 = 6.5;
/// No text anywhere is smaller, pt.
pub const MIN_TEXT_PT: f64 = 6.0;

/// Line pitch of legend entries, pt.
pub const LEGEND_LINE: f64 = LEGEND_PT * 1.3;
/// Line pitch of notes, pt.
pub const NOTE_LINE: f64 = NOTE_PT * 1.3;
/// Margin round a figure and inside a legend frame, pt.
pub const PAD: f64 = 4.0;
/// Length of a legend sample, pt.
pub const SAMPLE_W: f64 = 16.0;

/// Lines of data series, pt.
pub const SERIES_LINE_PT: f64 = 1.0;
/// Frames, ticks and reference lines, pt.
pub const FRAME_LINE_PT: f64 = 0.5;
/// No line anywhere is thinner, pt.
pub const MIN_LINE_PT: f64 = 0.5;

/// The printed width of a figure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Width {
    /// One journal column, 85 mm: a single small panel, legend under the data.
    Single,
    /// Two columns, 170 mm: multi-panel figures, studies, plots with a legend column.
    #[default]
    Double,
}

impl Width {
    /// Width in millimetres.
    pub fn mm(self) -> f64 {
        match self {
            Width::Single => 85.0,
            Width::Double => 170.0,
        }
    }
}

/// The width in points of a page `width` wide: every plot is laid out in points on a page
/// this wide (the layout unit is the point at print size).
pub fn page_pt(width: Width) -> f64 {
    width.mm() / MM_PER_PT
}

/// The opening tag of the root `<svg …>` element and the rest of the document.
fn split_root(svg: &str) -> Result<(&str, &str)> {
    let bad = || Error::Incompatible("not an SVG document with a root <svg> element".into());
    let start = svg.find("<svg").ok_or_else(bad)?;
    let end = start + svg[start..].find('>').ok_or_else(bad)?;
    Ok((&svg[start..end], &svg[end..]))
}

/// The value of attribute `name` in an opening tag.
pub fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    tag[i..].split('"').next()
}

/// Width and height in user units (points) of an SVG drawn by this layer: its `viewBox`
/// when it has one, else its `width` and `height`.
pub fn canvas_size(svg: &str) -> Result<(f64, f64)> {
    let (tag, _) = split_root(svg)?;
    let bad = || Error::Incompatible("SVG without a viewBox or pixel width and height".into());
    if let Some(vb) = attr(tag, "viewBox") {
        let v: Vec<f64> = vb
            .split([' ', ','])
            .filter(|s| !s.is_empty())
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| bad())?;
        return match v[..] {
            [_, _, w, h] => Ok((w, h)),
            _ => Err(bad()),
        };
    }
    let num = |n: &str| -> Result<f64> {
        attr(tag, n)
            .and_then(|s| s.trim_end_matches("px").parse().ok())
            .ok_or_else(bad)
    };
    Ok((num("width")?, num("height")?))
}

/// Rewrites the root element's `width`, `height` and `viewBox` (the other attributes, and
/// everything else, unchanged).
pub fn set_root_size(svg: &str, width: &str, height: &str, view_box: &str) -> Result<String> {
    let (tag, rest) = split_root(svg)?;
    let start = svg.len() - rest.len() - tag.len();
    let mut kept = String::from("<svg");
    // attributes as name="value" pairs; plotters writes no '"' inside values
    let mut parts = tag["<svg".len()..].split('"');
    while let (Some(name), Some(value)) = (parts.next(), parts.next()) {
        let name = name.trim().trim_end_matches('=');
        if !matches!(name, "width" | "height" | "viewBox") {
            kept.push_str(&format!(" {name}=\"{value}\""));
        }
    }
    Ok(format!(
        "{}{kept} width=\"{width}\" height=\"{height}\" viewBox=\"{view_box}\"{rest}",
        &svg[..start]
    ))
}

/// Sets the root `<svg>` of a document in points to `width` millimetres wide, its height in
/// proportion, with a `viewBox` of its size in points (what [`super::canvas::Canvas`] writes;
/// [`super::stack_svg`] uses it for the figure it assembles).
pub fn finish(svg: &str, width: Width) -> Result<String> {
    let (w, h) = canvas_size(svg)?;
    let height_mm = width.mm() * h / w;
    set_root_size(
        svg,
        &format!("{}mm", width.mm()),
        &format!("{}mm", (height_mm * 100.0).round() / 100.0),
        &format!("0 0 {w} {h}"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finish_sets_millimetres_and_keeps_the_canvas_as_view_box() {
        let svg = "<svg width=\"3400\" height=\"1700\" viewBox=\"0 0 3400 1700\" \
                   xmlns=\"http://www.w3.org/2000/svg\">\n<rect x=\"0\"/>\n</svg>\n";
        let out = finish(svg, Width::Double).unwrap();
        assert!(out.starts_with(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"170mm\" height=\"85mm\" \
             viewBox=\"0 0 3400 1700\">"
        ));
        assert!(out.ends_with("<rect x=\"0\"/>\n</svg>\n"));
        assert_eq!(canvas_size(&out).unwrap(), (3400.0, 1700.0));
        assert_eq!(finish(&out, Width::Double).unwrap(), out);
    }

    #[test]
    fn pages_are_measured_in_points() {
        assert!((page_pt(Width::Double) - 170.0 * 72.0 / 25.4).abs() < 1e-9);
        assert!((page_pt(Width::Single) - 85.0 / MM_PER_PT).abs() < 1e-9);
    }
}
