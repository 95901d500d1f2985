//! Series styles shared by every figure: the Okabe–Ito colours, marker shapes and dash
//! patterns, and the drawing of a style (line, marker, legend sample) — one definition, so a
//! legend sample is drawn exactly like its series.

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

/// Dash pattern of a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dash {
    /// Continuous.
    Solid,
    /// 9 px on, 5 px off.
    Dashed,
    /// 2 px on, 4 px off.
    Dotted,
    /// 9 on, 4 off, 2 on, 4 off.
    DashDot,
}

impl Dash {
    /// On/off lengths in pixels (empty: solid).
    pub fn pattern(self) -> &'static [f64] {
        match self {
            Dash::Solid => &[],
            Dash::Dashed => &[9.0, 5.0],
            Dash::Dotted => &[2.0, 4.0],
            Dash::DashDot => &[9.0, 4.0, 2.0, 4.0],
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
    /// Line width in pixels.
    pub width: u32,
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
        width: 2,
    }
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

fn px(p: (f64, f64)) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
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
        fine(
            area,
            piece,
            style.color,
            FineKind::Path(f64::from(style.width)),
        )?;
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

/// Draws the marker of `style` at pixel `at` (radius ~4 px), filled or hollow.
pub fn draw_marker(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    at: (f64, f64),
    style: &Style,
) -> Result<()> {
    let c = style.color;
    let r = 4.0;
    match marker_polygon(style.marker, r) {
        None => {
            let stroke = (!style.filled).then_some(2.0);
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
                fine(area, closed, c, FineKind::Path(2.0))?;
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
            fine(
                area,
                piece,
                style.color,
                FineKind::Path(f64::from(style.width)),
            )?;
        }
    }
    if marker {
        draw_marker(area, (x + w / 2.0, y), style)?;
    }
    Ok(())
}

/// Draws text with its top-left corner at `(x, y)`.
pub fn text(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    s: &str,
    (x, y): (f64, f64),
    size: u32,
    color: RGBColor,
) -> Result<()> {
    let style = TextStyle::from((super::print::FONT_FAMILY, size).into_font()).color(&color);
    area.draw(&Text::new(s.to_string(), px((x, y)), style))
        .map_err(plot_err)
}

/// Draws text anchored at `(x, y)` by `h`, `v`, optionally rotated (270: reads upwards).
pub fn text_at(
    area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
    s: &str,
    (x, y): (f64, f64),
    size: u32,
    anchor: (
        plotters::style::text_anchor::HPos,
        plotters::style::text_anchor::VPos,
    ),
    rotate: bool,
) -> Result<()> {
    let mut style = TextStyle::from((super::print::FONT_FAMILY, size).into_font())
        .pos(plotters::style::text_anchor::Pos::new(anchor.0, anchor.1));
    if rotate {
        style = style.transform(FontTransform::Rotate270);
    }
    area.draw(&Text::new(s.to_string(), px((x, y)), style))
        .map_err(plot_err)
}

/// Approximate width in pixels of `s` in a sans-serif font of `size` px.
pub fn text_width(s: &str, size: u32) -> f64 {
    s.chars().count() as f64 * 0.56 * size as f64
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
        let dense: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 * 0.7, 3.0)).collect();
        let a = dash_polyline(&dense, Dash::Dashed.pattern());
        let b = dash_polyline(&[(0.0, 3.0), (70.0, 3.0)], Dash::Dashed.pattern());
        assert_eq!(a.len(), b.len());
        assert_eq!(a.len(), 5); // 70 px of (9 on, 5 off)
        for (p, q) in a.iter().zip(&b) {
            assert!((length(p) - length(q)).abs() < 1e-9);
            assert!((p[0].0 - q[0].0).abs() < 1e-9);
        }
        assert!((length(&a[0]) - 9.0).abs() < 1e-9);
        assert!((a[1][0].0 - 14.0).abs() < 1e-9);
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
