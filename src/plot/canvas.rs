//! The drawing backend of every figure: plotters' SVG backend on a canvas of the printed
//! width times [`PX_PER_MM`](super::print::PX_PER_MM), driven in the plot's own layout pixels.
//! Every layout coordinate, line width and text size is multiplied by the zoom
//! `canvas px / layout px`; curves and markers ([`Fine`]) keep their fractional layout
//! coordinates up to the canvas pixel (0.05 mm at print size), so they are not staircases.
//! No line is thinner than [`MIN_LINE_PT`].

use super::print::{MIN_LINE_PT, Width, pt};
use plotters::backend::DrawingBackend;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::{RGBColor, SVGBackend};
use plotters_backend::text_anchor::Pos;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontFamily,
    FontStyle, FontTransform,
};

/// plotters' SVG backend at print resolution, addressed in layout pixels.
pub struct Canvas<'a> {
    inner: SVGBackend<'a>,
    zoom: f64,
    layout: (u32, u32),
}

impl<'a> Canvas<'a> {
    /// A canvas printed `width` wide for a layout of `size` pixels: the canvas is
    /// `width.px()` pixels wide, the height in proportion.
    pub fn new(out: &'a mut String, width: Width, size: (f64, f64)) -> Self {
        let zoom = width.px() / size.0;
        let h = (size.1 * zoom).round() as u32;
        Canvas {
            inner: SVGBackend::with_string(out, (width.px().round() as u32, h)),
            zoom,
            layout: (size.0.round() as u32, size.1.round() as u32),
        }
    }

    fn at(&self, p: BackendCoord) -> BackendCoord {
        self.fine((f64::from(p.0), f64::from(p.1)))
    }

    fn fine(&self, p: (f64, f64)) -> BackendCoord {
        (
            (p.0 * self.zoom).round() as i32,
            (p.1 * self.zoom).round() as i32,
        )
    }

    fn stroke(&self, w: f64) -> u32 {
        (w * self.zoom).max(pt(MIN_LINE_PT)).round() as u32
    }
}

/// A backend style with its stroke width replaced.
struct Stroke {
    color: BackendColor,
    width: u32,
}

impl BackendStyle for Stroke {
    fn color(&self) -> BackendColor {
        self.color
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

/// A text style with its size multiplied by the zoom.
struct Zoomed<'s, T: BackendTextStyle> {
    inner: &'s T,
    zoom: f64,
}

impl<T: BackendTextStyle> BackendTextStyle for Zoomed<'_, T> {
    type FontError = T::FontError;
    fn color(&self) -> BackendColor {
        self.inner.color()
    }
    fn size(&self) -> f64 {
        self.inner.size() * self.zoom
    }
    fn transform(&self) -> FontTransform {
        self.inner.transform()
    }
    fn style(&self) -> FontStyle {
        self.inner.style()
    }
    fn anchor(&self) -> Pos {
        self.inner.anchor()
    }
    fn family(&self) -> FontFamily<'_> {
        self.inner.family()
    }
    fn layout_box(&self, text: &str) -> Result<((i32, i32), (i32, i32)), T::FontError> {
        self.inner.layout_box(text)
    }
    fn draw<E, F: FnMut(i32, i32, BackendColor) -> Result<(), E>>(
        &self,
        text: &str,
        pos: BackendCoord,
        draw: F,
    ) -> Result<Result<(), E>, T::FontError> {
        self.inner.draw(text, pos, draw)
    }
}

type Res = Result<(), DrawingErrorKind<std::io::Error>>;

impl DrawingBackend for Canvas<'_> {
    type ErrorType = std::io::Error;

    fn get_size(&self) -> (u32, u32) {
        self.layout
    }
    fn ensure_prepared(&mut self) -> Res {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Res {
        self.inner.present()
    }
    fn draw_pixel(&mut self, p: BackendCoord, color: BackendColor) -> Res {
        let p = self.at(p);
        self.inner.draw_pixel(p, color)
    }
    fn draw_line<S: BackendStyle>(&mut self, a: BackendCoord, b: BackendCoord, s: &S) -> Res {
        let st = self.zoomed(s);
        let (a, b) = (self.at(a), self.at(b));
        self.inner.draw_line(a, b, &st)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Res {
        let st = self.zoomed(s);
        let (a, b) = (self.at(a), self.at(b));
        if fill {
            self.inner.draw_rect(a, b, &st, true)
        } else {
            // plotters writes an outlined rect without stroke-width: a closed path has one
            let ring = [a, (b.0, a.1), b, (a.0, b.1), a];
            self.inner.draw_path(ring, &st)
        }
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Res {
        let st = self.zoomed(s);
        let v: Vec<BackendCoord> = path.into_iter().map(|p| self.at(p)).collect();
        self.inner.draw_path(v, &st)
    }
    fn draw_circle<S: BackendStyle>(&mut self, c: BackendCoord, r: u32, s: &S, fill: bool) -> Res {
        let st = self.zoomed(s);
        let c = self.at(c);
        let r = (f64::from(r) * self.zoom).round() as u32;
        self.inner.draw_circle(c, r, &st, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        s: &S,
    ) -> Res {
        let v: Vec<BackendCoord> = vert.into_iter().map(|p| self.at(p)).collect();
        self.inner.fill_polygon(v, s)
    }
    fn draw_text<T: BackendTextStyle>(&mut self, text: &str, s: &T, pos: BackendCoord) -> Res {
        let z = Zoomed {
            inner: s,
            zoom: self.zoom,
        };
        let pos = self.at(pos);
        self.inner.draw_text(text, &z, pos)
    }
}

impl Canvas<'_> {
    fn zoomed<S: BackendStyle>(&self, s: &S) -> Stroke {
        Stroke {
            color: s.color(),
            width: self.stroke(f64::from(s.stroke_width())),
        }
    }
}

/// What a [`Fine`] element draws.
#[derive(Clone, Debug)]
pub enum FineKind {
    /// An open polyline of this width (layout px).
    Path(f64),
    /// A filled polygon.
    Fill,
    /// A circle of this radius (layout px), filled when `true` else stroked `width`.
    Circle(f64, Option<f64>),
}

/// A curve, polygon or circle at fractional layout coordinates, drawn to the canvas pixel.
#[derive(Clone, Debug)]
pub struct Fine {
    /// Vertices (layout px; the centre of a circle).
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

impl Drawable<Canvas<'_>> for Fine {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut pos: I,
        c: &mut Canvas<'_>,
        _: (u32, u32),
    ) -> Res {
        let o = pos.next().unwrap_or(ORIGIN);
        let (ox, oy) = (f64::from(o.0), f64::from(o.1));
        let v: Vec<BackendCoord> = self
            .pts
            .iter()
            .map(|&(x, y)| c.fine((x + ox, y + oy)))
            .collect();
        let color = BackendColor {
            alpha: 1.0,
            rgb: (self.color.0, self.color.1, self.color.2),
        };
        match self.kind {
            FineKind::Path(w) => {
                let st = Stroke {
                    color,
                    width: c.stroke(w),
                };
                c.inner.draw_path(v, &st)
            }
            FineKind::Fill => c.inner.fill_polygon(v, &Stroke { color, width: 0 }),
            FineKind::Circle(r, stroke) => {
                let r = (r * c.zoom).round() as u32;
                let st = Stroke {
                    color,
                    width: stroke.map_or(0, |w| c.stroke(w)),
                };
                match v.first() {
                    Some(&p) => c.inner.draw_circle(p, r, &st, stroke.is_none()),
                    None => Ok(()),
                }
            }
        }
    }
}

/// Text at fractional layout coordinates (points), drawn to the canvas pixel: `size` points,
/// the one font family of every figure.
#[derive(Clone)]
pub struct FineText {
    /// The text.
    pub text: String,
    /// Anchor point (layout units).
    pub at: (f64, f64),
    /// Size in points.
    pub size: f64,
    /// Colour.
    pub color: RGBColor,
    /// Horizontal and vertical anchoring.
    pub anchor: (
        plotters::style::text_anchor::HPos,
        plotters::style::text_anchor::VPos,
    ),
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
        mut pos: I,
        c: &mut Canvas<'_>,
        _: (u32, u32),
    ) -> Res {
        use plotters::style::{IntoFont, TextStyle};
        let o = pos.next().unwrap_or(ORIGIN);
        let at = c.fine((self.at.0 + f64::from(o.0), self.at.1 + f64::from(o.1)));
        // plotters' SVG backend writes font-size = size / 1.24
        let font = (super::print::FONT_FAMILY, self.size * 1.24 * c.zoom).into_font();
        let mut style = TextStyle::from(font)
            .color(&self.color)
            .pos(Pos::new(self.anchor.0, self.anchor.1));
        if self.rotate {
            style = style.transform(FontTransform::Rotate270);
        }
        c.inner.draw_text(&self.text, &style, at)
    }
}

#[cfg(test)]
mod tests {
    use crate::plot::print::{MIN_LINE_PT, PX_PER_MM, pt};
    use crate::plot::{Curve, LinePlot, svg_size};

    #[test]
    fn plots_are_drawn_at_print_resolution_with_lines_of_half_a_point() {
        let c = Curve {
            label: "a".into(),
            x: (0..50).map(|i| f64::from(i) * 0.1).collect(),
            y: (0..50).map(|i| (f64::from(i) * 0.1).sin()).collect(),
            dashed: false,
        };
        let svg = LinePlot::new("t", "x", "y", vec![c]).svg().unwrap();
        assert!(svg.starts_with("<svg") && svg[..200].contains("width=\"170mm\""));
        assert_eq!(svg_size(&svg).unwrap().0, (170.0 * PX_PER_MM) as u32);
        let widths: Vec<f64> = svg
            .match_indices("stroke-width=\"")
            .filter_map(|(i, m)| svg[i + m.len()..].split('"').next()?.parse().ok())
            .filter(|&w: &f64| w > 0.0)
            .collect();
        assert!(!widths.is_empty());
        for w in widths {
            assert!(w >= pt(MIN_LINE_PT) - 0.5, "stroke {w} px");
        }
        // outlined rectangles carry their width (plotters writes none for <rect>)
        assert!(!svg.contains("fill=\"none\" stroke=\"#000000\"/>"));
    }
}
