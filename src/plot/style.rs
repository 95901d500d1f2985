//! Series styles shared by every figure: the Okabe–Ito colours, marker shapes and dash
//! patterns, the one style of every form, kernel and integrator name ([`named_style`], the same
//! in every figure), and the drawing of a style (line, marker, legend sample) and of text — one
//! definition, so a legend sample is drawn exactly like its series. Every length is in points
//! at print size (the layout unit of every plot, see [`mod@super::print`]).

use super::canvas::{Fine, FineKind};
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The Okabe–Ito colour-blind-safe palette without its yellow (too pale on white), ordered so
/// that neighbouring series differ most: blue, vermillion, bluish green, reddish purple, black,
/// sky blue, orange.
pub const OKABE_ITO: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(0, 0, 0),
    RGBColor(86, 180, 233),
    RGBColor(230, 159, 0),
];

/// Grey of reference lines, frames of legends and clipped-curve notes.
pub const GREY: RGBColor = RGBColor(110, 110, 110);

/// Colour of reference curves (continuum, analytic and exact solutions): dark grey, dashed.
pub const REFERENCE: RGBColor = RGBColor(80, 80, 80);

/// Dash pattern of a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dash {
    /// Continuous.
    Solid,
    /// 3.5 pt on, 2 pt off.
    Dashed,
    /// 1 pt on, 1.5 pt off.
    Dotted,
    /// 3.5 on, 1.5 off, 1 on, 1.5 off.
    DashDot,
}

impl Dash {
    /// On/off lengths in points (empty: solid).
    pub fn pattern(self) -> &'static [f64] {
        match self {
            Dash::Solid => &[],
            Dash::Dashed => &[3.5, 2.0],
            Dash::Dotted => &[1.0, 1.5],
            Dash::DashDot => &[3.5, 1.5, 1.0, 1.5],
        }
    }
}

/// Marker shapes; every one can be drawn filled or hollow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// ●
    Circle,
    /// ■
    Square,
    /// ▲
    TriangleUp,
    /// ◆
    Diamond,
    /// ▼
    TriangleDown,
    /// ⬟
    Pentagon,
    /// ★
    Star,
    /// ◀
    TriangleLeft,
    /// ⬢
    Hexagon,
    /// ▶
    TriangleRight,
}

/// The marker cycle (period 10, coprime with the 7 colours).
pub const MARKERS: [Marker; 10] = [
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Pentagon,
    Marker::Star,
    Marker::TriangleLeft,
    Marker::Hexagon,
    Marker::TriangleRight,
];

/// How one series is drawn: colour, dash pattern, marker shape and fill, line width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// Colour.
    pub color: RGBColor,
    /// Dash pattern of the line.
    pub dash: Dash,
    /// Marker shape.
    pub marker: Marker,
    /// Filled (else hollow) marker.
    pub filled: bool,
    /// Line width in points.
    pub width: f64,
}

/// Style of series `i`: colour `i mod 7`, marker `i mod 10`, filled for the first ten and
/// hollow for the next ten — every combination differs up to i = 69, and neighbours differ in
/// colour and marker shape, so series stay distinguishable in greyscale.
pub fn series_style(i: usize, dash: Dash) -> Style {
    Style {
        color: OKABE_ITO[i % OKABE_ITO.len()],
        dash,
        marker: MARKERS[i % MARKERS.len()],
        filled: (i / MARKERS.len()).is_multiple_of(2),
        width: super::print::SERIES_LINE_PT,
    }
}

/// The names that carry one fixed style in every figure, by category (forms, kernels,
/// integrators: the layers above hold the lists and pass them in, the plot layer takes plain
/// data). Empty (the default): no series is styled by name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Names(pub Vec<Vec<&'static str>>);

/// Names of reference curves: drawn dashed in [`REFERENCE`] grey.
pub const REFERENCE_NAMES: [&str; 4] = ["continuum", "analytic", "exact", "reference"];

/// The style of a form, kernel or integrator name, the same in every figure: the name's
/// index i in its category of `names` gives colour `i mod 7` and marker `i mod 10`, filled for
/// i < 7 and hollow after (so two names of a category never share colour, marker and fill).
/// Reference names ([`REFERENCE_NAMES`]) are dashed dark grey. None: not a name.
pub fn named_style(name: &str, names: &Names) -> Option<Style> {
    if REFERENCE_NAMES.contains(&name) {
        return Some(Style {
            color: REFERENCE,
            dash: Dash::Dashed,
            marker: Marker::Circle,
            filled: false,
            width: super::print::SERIES_LINE_PT,
        });
    }
    names.0.iter().find_map(|cat| {
        let i = cat.iter().position(|n| *n == name)?;
        Some(Style {
            color: OKABE_ITO[i % OKABE_ITO.len()],
            dash: Dash::Solid,
            marker: MARKERS[i % MARKERS.len()],
            filled: i < OKABE_ITO.len(),
            width: super::print::SERIES_LINE_PT,
        })
    })
}

/// The name a legend label stands for: its first word (up to a space, comma, colon, bar or
/// parenthesis; after "form = " or another one-word key) when that is a form, kernel,
/// integrator or reference name.
pub fn label_name<'a>(label: &'a str, names: &Names) -> Option<&'a str> {
    // "form = classical": the value names the series
    let label = match label.split_once(" = ") {
        Some((k, v)) if !k.contains(' ') => v,
        _ => label,
    };
    let first = label
        .split([' ', ',', ':', '(', '|'])
        .next()
        .unwrap_or_default()
        .trim();
    named_style(first, names).map(|_| first)
}

/// The part of a label before its first ": " — series of one stem (a run and its fitted
/// or predicted line, the branches of one form) share a colour.
fn stem(label: &str) -> &str {
    label.split_once(": ").map_or(label, |p| p.0)
}

/// Styles of the series of one panel, by meaning. A series whose label names a form, kernel,
/// integrator or reference ([`label_name`]) has that name's [`named_style`], where the names
/// tell the series apart: several series of one name keep its colour and differ in dash
/// pattern and marker, but when every named series has the same name (a study of one form
/// over another parameter) the name is not what the panel compares and they are styled as
/// unnamed. Unnamed series take, by stem ([`stem`]: a run and its prediction share one), the
/// Okabe–Ito colours no named series of the panel uses, with the marker cycle; within a stem
/// they differ in dash pattern. `dashed[i]`: series i is a reference or prediction.
pub fn panel_styles(labels: &[&str], dashed: &[bool], registry: &Names) -> Vec<Style> {
    let mut names: Vec<Option<&str>> = labels.iter().map(|l| label_name(l, registry)).collect();
    let compared: Vec<&str> = {
        let mut d: Vec<&str> = names
            .iter()
            .flatten()
            .copied()
            .filter(|n| !REFERENCE_NAMES.contains(n))
            .collect();
        d.sort_unstable();
        d.dedup();
        d
    };
    if let [only] = compared[..]
        && names.iter().filter(|n| **n == Some(only)).count() > 1
    {
        for n in names.iter_mut().filter(|n| **n == Some(only)) {
            *n = None;
        }
    }
    let used: Vec<RGBColor> = names
        .iter()
        .flatten()
        .filter_map(|n| named_style(n, registry))
        .map(|s| s.color)
        .collect();
    let free: Vec<RGBColor> = OKABE_ITO
        .iter()
        .copied()
        .filter(|c| !used.contains(c))
        .collect();
    let free = if free.is_empty() {
        OKABE_ITO.to_vec()
    } else {
        free
    };
    let variants = [Dash::Dashed, Dash::Dotted, Dash::DashDot];
    let dash0 = |i: usize| {
        if dashed.get(i).copied().unwrap_or(false) {
            Dash::Dashed
        } else {
            Dash::Solid
        }
    };
    let mut stems: Vec<&str> = Vec::new();
    let mut out: Vec<Style> = Vec::with_capacity(labels.len());
    for i in 0..labels.len() {
        let style = match names[i] {
            Some(n) => {
                let base = named_style(n, registry).expect("a name");
                let k = names[..i].iter().filter(|m| **m == Some(n)).count();
                if REFERENCE_NAMES.contains(&n) && k == 0 {
                    base
                } else if k == 0 {
                    Style {
                        dash: dash0(i),
                        ..base
                    }
                } else {
                    let m = MARKERS.iter().position(|x| *x == base.marker).unwrap_or(0);
                    Style {
                        dash: variants[(k - 1) % variants.len()],
                        marker: MARKERS[(m + k) % MARKERS.len()],
                        ..base
                    }
                }
            }
            None => {
                let st = stem(labels[i]);
                let g = stems.iter().position(|s| *s == st).unwrap_or_else(|| {
                    stems.push(st);
                    stems.len() - 1
                });
                let base = Style {
                    color: free[g % free.len()],
                    dash: dash0(i),
                    marker: MARKERS[g % MARKERS.len()],
                    filled: (g / MARKERS.len()).is_multiple_of(2),
                    width: super::print::SERIES_LINE_PT,
                };
                // a second series of the stem with the same dash: the next variant
                let same = (0..i)
                    .filter(|&j| names[j].is_none() && stem(labels[j]) == st)
                    .filter(|&j| out[j].dash == base.dash)
                    .count();
                if same == 0 {
                    base
                } else {
                    Style {
                        dash: variants[(same - 1) % variants.len()],
                        ..base
                    }
                }
            }
        };
        out.push(style);
    }
    out
}

pub(crate) fn plot_err<E: std::fmt::Debug>(_: E) -> Error {
    Error::NonFinite("plot")
}

/// Splits a polyline (pixels) into the drawn pieces of a dash pattern (the pattern runs on
/// across vertices, so dense curves are dashed like sparse ones). Solid: the polyline itself.
pub fn dash_polyline(pts: &[(f64, f64)], pattern: &[f64]) -> Vec<Vec<(f64, f64)>> {
    if pattern.is_empty() || pts.len() < 2 {
        return if pts.len() >= 2 {
            vec![pts.to_vec()]
        } else {
            Vec::new()
        };
    }
    let mut out = Vec::new();
    let mut k = 0; // index in the pattern (even: on)
    let mut left = pattern[0]; // length left in the current piece
    let mut cur: Vec<(f64, f64)> = vec![pts[0]];
    for w in pts.windows(2) {
        let (mut a, b) = (w[0], w[1]);
        let mut len = (b.0 - a.0).hypot(b.1 - a.1);
        while len > left {
            let t = left / len;
            let p = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            if k % 2 == 0 {
                cur.push(p);
                out.push(std::mem::take(&mut cur));
            } else {
                cur = vec![p];
            }
            len -= left;
            a = p;
            k = (k + 1) % pattern.len();
            left = pattern[k];
        }
        left -= len;
        if k % 2 == 0 {
            cur.push(b);
        }
    }
    if k % 2 == 0 && cur.len() >= 2 {
        out.push(cur);
    }
    out
}

/// The pieces of a legend sample `w` pixels long at `(x, y)`: the dash pattern of `style`
/// applied to a straight line by [`dash_polyline`], as for the series.
pub fn sample_pieces(style: &Style, x: f64, y: f64, w: f64) -> Vec<Vec<(f64, f64)>> {
    dash_polyline(&[(x, y), (x + w, y)], style.dash.pattern())
}

/// Draws a [`Fine`] element: fractional layout pixels, kept to the canvas pixel.
fn fine(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    pts: Vec<(f64, f64)>,
    color: RGBColor,
    kind: FineKind,
) -> Result<()> {
    area.draw(&Fine { pts, color, kind }).map_err(plot_err)
}

/// Draws a polyline (pixels) in `style` (its dash pattern, no markers).
pub fn draw_line(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    pts: &[(f64, f64)],
    style: &Style,
) -> Result<()> {
    for piece in dash_polyline(pts, style.dash.pattern()) {
        fine(area, piece, style.color, FineKind::Path(style.width))?;
    }
    Ok(())
}

/// Vertices of a marker of radius `r` around the origin (pixels, y down); None: a circle.
fn marker_polygon(m: Marker, r: f64) -> Option<Vec<(f64, f64)>> {
    let ngon = |n: usize, rot: f64, rr: f64| -> Vec<(f64, f64)> {
        (0..n)
            .map(|k| {
                let a = rot + 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                (rr * a.sin(), -rr * a.cos())
            })
            .collect()
    };
    let pi = std::f64::consts::PI;
    Some(match m {
        Marker::Circle => return None,
        Marker::Square => ngon(4, pi / 4.0, r * 1.2),
        Marker::TriangleUp => ngon(3, 0.0, r * 1.35),
        Marker::Diamond => ngon(4, 0.0, r * 1.35),
        Marker::TriangleDown => ngon(3, pi, r * 1.35),
        Marker::Pentagon => ngon(5, 0.0, r * 1.2),
        Marker::Star => (0..10)
            .map(|k| {
                let rr = if k % 2 == 0 { r * 1.5 } else { r * 0.65 };
                let a = pi * k as f64 / 5.0;
                (rr * a.sin(), -rr * a.cos())
            })
            .collect(),
        Marker::TriangleLeft => ngon(3, -pi / 2.0, r * 1.35),
        Marker::Hexagon => ngon(6, 0.0, r * 1.2),
        Marker::TriangleRight => ngon(3, pi / 2.0, r * 1.35),
    })
}

/// Marker radius, pt.
pub const MARKER_R: f64 = 2.0;

/// Draws the marker of `style` at `at` (radius [`MARKER_R`]), filled or hollow.
pub fn draw_marker(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    at: (f64, f64),
    style: &Style,
) -> Result<()> {
    let c = style.color;
    let r = MARKER_R;
    let hollow = 0.6;
    match marker_polygon(style.marker, r) {
        None => {
            let stroke = (!style.filled).then_some(hollow);
            fine(area, vec![at], c, FineKind::Circle(r, stroke))?;
        }
        Some(poly) => {
            let v: Vec<(f64, f64)> = poly
                .into_iter()
                .map(|(x, y)| (at.0 + x, at.1 + y))
                .collect();
            if style.filled {
                fine(area, v, c, FineKind::Fill)?;
            } else {
                let mut closed = v.clone();
                closed.push(v[0]);
                fine(area, v, WHITE, FineKind::Fill)?;
                fine(area, closed, c, FineKind::Path(hollow))?;
            }
        }
    }
    Ok(())
}

/// Draws a legend sample `w` pixels wide starting at `(x, y)`: the line of `style` (when
/// `line`) with the dash pattern of its series ([`sample_pieces`]) and the marker in the middle
/// (when `marker`).
pub fn draw_sample(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    (x, y): (f64, f64),
    w: f64,
    style: &Style,
    line: bool,
    marker: bool,
) -> Result<()> {
    if line {
        for piece in sample_pieces(style, x, y, w) {
            fine(area, piece, style.color, FineKind::Path(style.width))?;
        }
    }
    if marker {
        draw_marker(area, (x + w / 2.0, y), style)?;
    }
    Ok(())
}

/// Draws text of `size` points with its top-left corner at `(x, y)`.
pub fn text(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    s: &str,
    (x, y): (f64, f64),
    size: f64,
    color: RGBColor,
) -> Result<()> {
    text_styled(
        area,
        s,
        (x, y),
        size,
        color,
        (
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Top,
        ),
        false,
    )
}

/// Draws black text of `size` points anchored at `(x, y)` by `h`, `v`, optionally rotated
/// (270: reads upwards).
pub fn text_at(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    s: &str,
    (x, y): (f64, f64),
    size: f64,
    anchor: (
        plotters::style::text_anchor::HPos,
        plotters::style::text_anchor::VPos,
    ),
    rotate: bool,
) -> Result<()> {
    text_styled(area, s, (x, y), size, BLACK, anchor, rotate)
}

/// Draws text of `size` points in `color` anchored at `(x, y)` (fractional points, kept to
/// the canvas pixel), in the one font family of every figure.
pub fn text_styled(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    s: &str,
    at: (f64, f64),
    size: f64,
    color: RGBColor,
    anchor: (
        plotters::style::text_anchor::HPos,
        plotters::style::text_anchor::VPos,
    ),
    rotate: bool,
) -> Result<()> {
    area.draw(&super::canvas::FineText {
        text: s.to_string(),
        at,
        size,
        color,
        anchor,
        rotate,
    })
    .map_err(plot_err)
}

/// A straight or broken line through `pts` (points) in `color`, `width` points wide.
pub fn stroke(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    pts: &[(f64, f64)],
    color: RGBColor,
    width: f64,
) -> Result<()> {
    fine(area, pts.to_vec(), color, FineKind::Path(width))
}

/// The outline of the rectangle (left, top, right, bottom), `width` points wide.
pub fn outline(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    (l, t, r, b): (f64, f64, f64, f64),
    color: RGBColor,
    width: f64,
) -> Result<()> {
    stroke(
        area,
        &[(l, t), (r, t), (r, b), (l, b), (l, t)],
        color,
        width,
    )
}

/// The filled rectangle (left, top, right, bottom).
pub fn fill_rect(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    (l, t, r, b): (f64, f64, f64, f64),
    color: RGBColor,
) -> Result<()> {
    fine(
        area,
        vec![(l, t), (r, t), (r, b), (l, b)],
        color,
        FineKind::Fill,
    )
}

/// The filled polygon through `pts` (points).
pub fn fill_polygon(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    pts: &[(f64, f64)],
    color: RGBColor,
) -> Result<()> {
    fine(area, pts.to_vec(), color, FineKind::Fill)
}

/// Opens (`Some(class)`) or closes (`None`) a group of elements, e.g. `"legend"`.
pub fn group(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    class: Option<&'static str>,
) -> Result<()> {
    fine(area, Vec::new(), BLACK, FineKind::Group(class))
}

/// Approximate width in points of `s` set at `size` points (DejaVu Sans: 0.55–0.64 em per
/// character; 0.6 em keeps labels from overlapping).
pub fn text_width(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * 0.6 * size
}

/// Breaks `s` into lines of at most `max` characters at spaces (a longer word stays whole).
pub fn wrap(s: &str, max: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for word in s.split(' ') {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > max {
            lines.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    if !cur.is_empty() || lines.is_empty() {
        lines.push(cur);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn length(p: &[(f64, f64)]) -> f64 {
        p.windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .sum()
    }

    #[test]
    fn dashes_follow_the_pattern_across_vertices() {
        // a straight line sampled densely is dashed like the same line in one segment
        let dense: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 * 0.21, 3.0)).collect();
        let a = dash_polyline(&dense, Dash::Dashed.pattern());
        let b = dash_polyline(&[(0.0, 3.0), (21.0, 3.0)], Dash::Dashed.pattern());
        assert_eq!(a.len(), b.len());
        assert_eq!(a.len(), 4); // 21 pt of (3.5 on, 2 off): 3 periods and a dash
        for (p, q) in a.iter().zip(&b) {
            assert!((length(p) - length(q)).abs() < 1e-9);
            assert!((p[0].0 - q[0].0).abs() < 1e-9);
        }
        assert!((length(&a[0]) - 3.5).abs() < 1e-9);
        assert!((a[1][0].0 - 5.5).abs() < 1e-9);
        assert_eq!(dash_polyline(&dense, &[]).len(), 1);
    }

    #[test]
    fn legend_sample_has_the_series_dash_pattern() {
        for dash in [Dash::Solid, Dash::Dashed, Dash::Dotted, Dash::DashDot] {
            let s = series_style(3, dash);
            let sample = sample_pieces(&s, 10.0, 5.0, 40.0);
            let series = dash_polyline(&[(10.0, 5.0), (30.0, 5.0), (50.0, 5.0)], dash.pattern());
            assert_eq!(sample.len(), series.len(), "{dash:?}");
            for (p, q) in sample.iter().zip(&series) {
                assert!((length(p) - length(q)).abs() < 1e-9);
            }
            if dash != Dash::Solid {
                assert!(sample.len() > 1, "{dash:?}: the sample shows gaps");
            }
        }
    }

    #[test]
    fn styles_are_distinct_and_colour_blind_safe() {
        let styles: Vec<Style> = (0..30).map(|i| series_style(i, Dash::Solid)).collect();
        for i in 0..styles.len() {
            for j in 0..i {
                let (a, b) = (&styles[i], &styles[j]);
                assert!(
                    (a.color, a.marker, a.filled) != (b.color, b.marker, b.filled),
                    "{i} {j}"
                );
            }
            if i > 0 {
                assert_ne!(styles[i].marker, styles[i - 1].marker);
                assert_ne!(styles[i].color, styles[i - 1].color);
            }
            assert!(OKABE_ITO.contains(&styles[i].color));
        }
    }

    #[test]
    fn wrapping_keeps_words() {
        assert_eq!(wrap("a bb ccc dd", 6), vec!["a bb", "ccc dd"]);
        assert_eq!(wrap("", 5), vec![""]);
    }
}
