//! The drawing backend of every figure: a small SVG writer addressed in points at print size
//! (the layout unit of every plot). The root `<svg>` is `width="85mm"` or `"170mm"` wide with a
//! `viewBox` in points, and every coordinate, length and type size is written in points to
//! 0.01 pt (3.5 µm), so curves are never staircases. No line is thinner than
//! [`MIN_LINE_PT`]; text is set in the one font family of every figure ([`FONT_FAMILY`]).
//! It implements plotters' `DrawingBackend` so that plotters' drawing areas drive it; every
//! plot draws [`Fine`] and [`FineText`] elements at fractional coordinates.

use super::print::{FONT_FAMILY, MIN_LINE_PT, Width};
use plotters::backend::DrawingBackend;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::RGBColor;
use plotters::style::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};
use std::fmt::Write;

/// An SVG document `width` wide at print size, drawn in points.
pub struct Canvas<'a> {
    out: &'a mut String,
    width: Width,
    size: (f64, f64),
    body: String,
    done: bool,
}

/// A length or coordinate in points to 0.01 pt, without trailing zeros.
pub fn num(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

fn hex(c: (u8, u8, u8)) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn points(pts: &[(f64, f64)]) -> String {
    pts.iter()
        .map(|p| format!("{},{}", num(p.0), num(p.1)))
        .collect::<Vec<_>>()
        .join(" ")
}

impl<'a> Canvas<'a> {
    /// A document printed `width` wide for a layout of `size` points (`size.0` is the page
    /// width in points, [`super::print::page_pt`]); written to `out` when presented.
    pub fn new(out: &'a mut String, width: Width, size: (f64, f64)) -> Self {
        Canvas {
            out,
            width,
            size,
            body: String::new(),
            done: false,
        }
    }

    fn stroke_w(w: f64) -> f64 {
        w.max(MIN_LINE_PT)
    }

    /// An open polyline, `w` points wide.
    pub fn polyline(&mut self, pts: &[(f64, f64)], color: (u8, u8, u8), w: f64) {
        if pts.len() < 2 {
            return;
        }
        let _ = writeln!(
            self.body,
            "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\" points=\"{}\"/>",
            hex(color),
            num(Self::stroke_w(w)),
            points(pts)
        );
    }

    /// A filled polygon.
    pub fn polygon(&mut self, pts: &[(f64, f64)], color: (u8, u8, u8)) {
        if pts.len() < 3 {
            return;
        }
        let _ = writeln!(
            self.body,
            "<polygon fill=\"{}\" points=\"{}\"/>",
            hex(color),
            points(pts)
        );
    }

    /// A circle: filled, or outlined `stroke` points wide over white.
    pub fn circle(&mut self, c: (f64, f64), r: f64, color: (u8, u8, u8), stroke: Option<f64>) {
        let paint = match stroke {
            None => format!("fill=\"{}\"", hex(color)),
            Some(w) => format!(
                "fill=\"#FFFFFF\" stroke=\"{}\" stroke-width=\"{}\"",
                hex(color),
                num(Self::stroke_w(w))
            ),
        };
        let _ = writeln!(
            self.body,
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {paint}/>",
            num(c.0),
            num(c.1),
            num(r)
        );
    }

    /// Text of `size` points anchored at `at`, optionally rotated to read upwards.
    pub fn text(
        &mut self,
        s: &str,
        at: (f64, f64),
        size: f64,
        color: (u8, u8, u8),
        anchor: (HPos, VPos),
        rotate: bool,
    ) {
        let h = match anchor.0 {
            HPos::Left => "start",
            HPos::Center => "middle",
            HPos::Right => "end",
        };
        // the vertical anchor as a baseline shift (what renderers agree on)
        let dy = match anchor.1 {
            VPos::Top => "0.76em",
            VPos::Center => "0.35em",
            VPos::Bottom => "-0.24em",
        };
        let (x, y) = (num(at.0), num(at.1));
        let rot = if rotate {
            format!(" transform=\"rotate(-90 {x} {y})\"")
        } else {
            String::new()
        };
        let _ = writeln!(
            self.body,
            "<text x=\"{x}\" y=\"{y}\" dy=\"{dy}\" font-size=\"{}\" fill=\"{}\" text-anchor=\"{h}\"{rot}>{}</text>",
            num(size),
            hex(color),
            escape(s)
        );
    }
}

type Res = Result<(), DrawingErrorKind<std::io::Error>>;

fn rgb(c: BackendColor) -> (u8, u8, u8) {
    c.rgb
}

fn at(p: BackendCoord) -> (f64, f64) {
    (f64::from(p.0), f64::from(p.1))
}

impl DrawingBackend for Canvas<'_> {
    type ErrorType = std::io::Error;

    fn get_size(&self) -> (u32, u32) {
        (self.size.0.ceil() as u32, self.size.1.ceil() as u32)
    }
    fn ensure_prepared(&mut self) -> Res {
        Ok(())
    }
    fn present(&mut self) -> Res {
        if !self.done {
            self.done = true;
            let (w, h) = self.size;
            let h_mm = self.width.mm() * h / w;
            let _ = write!(
                self.out,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}mm\" height=\"{}mm\" viewBox=\"0 0 {} {}\" font-family=\"{FONT_FAMILY}\">\n{}</svg>\n",
                num(self.width.mm()),
                num(h_mm),
                num(w),
                num(h),
                self.body
            );
        }
        Ok(())
    }
    fn draw_pixel(&mut self, p: BackendCoord, color: BackendColor) -> Res {
        let (x, y) = at(p);
        self.polygon(
            &[(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)],
            rgb(color),
        );
        Ok(())
    }
    fn draw_line<S: BackendStyle>(&mut self, a: BackendCoord, b: BackendCoord, s: &S) -> Res {
        self.polyline(&[at(a), at(b)], rgb(s.color()), f64::from(s.stroke_width()));
        Ok(())
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Res {
        let (p, q) = (at(a), at(b));
        let ring = [p, (q.0, p.1), q, (p.0, q.1)];
        if fill {
            self.polygon(&ring, rgb(s.color()));
        } else {
            let mut closed = ring.to_vec();
            closed.push(p);
            self.polyline(&closed, rgb(s.color()), f64::from(s.stroke_width()));
        }
        Ok(())
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Res {
        let v: Vec<(f64, f64)> = path.into_iter().map(at).collect();
        self.polyline(&v, rgb(s.color()), f64::from(s.stroke_width()));
        Ok(())
    }
    fn draw_circle<S: BackendStyle>(&mut self, c: BackendCoord, r: u32, s: &S, fill: bool) -> Res {
        let stroke = (!fill).then(|| f64::from(s.stroke_width()));
        self.circle(at(c), f64::from(r), rgb(s.color()), stroke);
        Ok(())
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        s: &S,
    ) -> Res {
        let v: Vec<(f64, f64)> = vert.into_iter().map(at).collect();
        self.polygon(&v, rgb(s.color()));
        Ok(())
    }
    fn draw_text<T: BackendTextStyle>(&mut self, text: &str, s: &T, pos: BackendCoord) -> Res {
        let a = s.anchor();
        // plotters' sizes are 1.24 × the type size
        self.text(
            text,
            at(pos),
            s.size() / 1.24,
            rgb(s.color()),
            (a.h_pos, a.v_pos),
            matches!(s.transform(), FontTransform::Rotate270),
        );
        Ok(())
    }
}

/// What a [`Fine`] element draws.
#[derive(Clone, Debug)]
pub enum FineKind {
    /// An open polyline of this width (pt).
    Path(f64),
    /// A filled polygon.
    Fill,
    /// A circle of this radius (pt), filled when the stroke width is None.
    Circle(f64, Option<f64>),
    /// Opens a group `<g class="…">` (Some) or closes the last one (None): legends are
    /// grouped so that a reader (or a test) finds each sample with its label.
    Group(Option<&'static str>),
}

/// A curve, polygon or circle at fractional coordinates (points).
#[derive(Clone, Debug)]
pub struct Fine {
    /// Vertices (pt; the centre of a circle).
    pub pts: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// What is drawn.
    pub kind: FineKind,
}

const ORIGIN: BackendCoord = (0, 0);

impl<'a> PointCollection<'a, BackendCoord> for &'a Fine {
    type Point = &'a BackendCoord;
    type IntoIter = std::iter::Once<&'a BackendCoord>;
    fn point_iter(self) -> Self::IntoIter {
        // the origin only: its position on the canvas is the drawing area's offset
        std::iter::once(&ORIGIN)
    }
}

fn offset<I: Iterator<Item = BackendCoord>>(mut pos: I) -> (f64, f64) {
    let o = pos.next().unwrap_or(ORIGIN);
    (f64::from(o.0), f64::from(o.1))
}

impl Drawable<Canvas<'_>> for Fine {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        pos: I,
        c: &mut Canvas<'_>,
        _: (u32, u32),
    ) -> Res {
        let (ox, oy) = offset(pos);
        let v: Vec<(f64, f64)> = self.pts.iter().map(|&(x, y)| (x + ox, y + oy)).collect();
        let color = (self.color.0, self.color.1, self.color.2);
        match self.kind {
            FineKind::Path(w) => c.polyline(&v, color, w),
            FineKind::Fill => c.polygon(&v, color),
            FineKind::Circle(r, stroke) => {
                if let Some(&p) = v.first() {
                    c.circle(p, r, color, stroke);
                }
            }
            FineKind::Group(Some(class)) => {
                let _ = writeln!(c.body, "<g class=\"{class}\">");
            }
            FineKind::Group(None) => c.body.push_str("</g>\n"),
        }
        Ok(())
    }
}

/// Text at fractional coordinates (points): `size` points, the one font family of every
/// figure.
#[derive(Clone)]
pub struct FineText {
    /// The text.
    pub text: String,
    /// Anchor point (pt).
    pub at: (f64, f64),
    /// Size in points.
    pub size: f64,
    /// Colour.
    pub color: RGBColor,
    /// Horizontal and vertical anchoring.
    pub anchor: (HPos, VPos),
    /// Rotated to read upwards.
    pub rotate: bool,
}

impl<'a> PointCollection<'a, BackendCoord> for &'a FineText {
    type Point = &'a BackendCoord;
    type IntoIter = std::iter::Once<&'a BackendCoord>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&ORIGIN)
    }
}

impl Drawable<Canvas<'_>> for FineText {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        pos: I,
        c: &mut Canvas<'_>,
        _: (u32, u32),
    ) -> Res {
        let (ox, oy) = offset(pos);
        c.text(
            &self.text,
            (self.at.0 + ox, self.at.1 + oy),
            self.size,
            (self.color.0, self.color.1, self.color.2),
            self.anchor,
            self.rotate,
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::num;
    use crate::plot::print::{MIN_LINE_PT, page_pt};
    use crate::plot::{Curve, LinePlot, svg_size};

    #[test]
    fn plots_are_drawn_in_points_at_fractional_coordinates() {
        let c = Curve {
            label: "a".into(),
            x: (0..50).map(|i| f64::from(i) * 0.1).collect(),
            y: (0..50).map(|i| (f64::from(i) * 0.1).sin()).collect(),
            dashed: false,
        };
        let svg = LinePlot::new("t", "x", "y", vec![c]).svg().unwrap();
        assert!(svg.starts_with("<svg") && svg[..200].contains("width=\"170mm\""));
        let w = svg_size(&svg).unwrap().0;
        assert!((w - page_pt(crate::plot::print::Width::Double)).abs() < 0.01);
        let widths: Vec<f64> = svg
            .match_indices("stroke-width=\"")
            .filter_map(|(i, m)| svg[i + m.len()..].split('"').next()?.parse().ok())
            .collect();
        assert!(!widths.is_empty());
        for w in widths {
            assert!(w >= MIN_LINE_PT, "stroke {w} pt");
        }
        // the curve's vertices are not rounded to whole points
        let poly = svg
            .lines()
            .find(|l| l.contains("<polyline") && l.matches(',').count() > 40)
            .expect("the curve");
        assert!(poly.contains('.'));
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(2.345678), "2.35");
    }
}
