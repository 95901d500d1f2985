//! Figures of several panels: a title strip and the panels' own SVGs stacked top to bottom,
//! each panel kept whole (its frame, legend and caption) as a nested `<svg>`.

use super::canvas::Canvas;
use super::print::{TITLE_PT, Width, font_size, pt};
use super::style::{plot_err, text_at, wrap};
use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Width and height (canvas pixels) of an SVG drawn by this module's plots: its `viewBox`
/// (see [`canvas_size`](super::print::canvas_size)), rounded to whole pixels.
pub fn svg_size(svg: &str) -> Result<(u32, u32)> {
    let (w, h) = super::print::canvas_size(svg)
        .map_err(|_| Error::Incompatible("panel: not an SVG with width and height".into()))?;
    Ok((w.round() as u32, h.round() as u32))
}

/// One SVG of `title` ([`TITLE_PT`], wrapped, centred) above `panels` stacked top to bottom, each
/// left-aligned at its own size; the figure is as wide as the widest panel.
pub fn stack_svg(title: &str, panels: &[String]) -> Result<String> {
    let sizes = panels
        .iter()
        .map(|p| svg_size(p))
        .collect::<Result<Vec<_>>>()?;
    // the panels are at print resolution (zoom 1): the title is set in points
    let width = sizes.iter().map(|s| s.0).max().unwrap_or(3400);
    let fs = font_size(TITLE_PT);
    let lines = wrap(
        title,
        ((f64::from(width) - pt(12.0)) / (0.56 * fs)) as usize,
    );
    let strip = (pt(4.0) + fs * lines.len() as f64 + pt(2.0)).round() as u32;
    let height = strip + sizes.iter().map(|s| s.1).sum::<u32>();
    let mut head = String::new();
    {
        let root = Canvas::new(
            &mut head,
            Width::Double,
            (f64::from(width), f64::from(height)),
        )
        .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in lines.iter().enumerate() {
            text_at(
                &root,
                line,
                (f64::from(width) / 2.0, pt(4.0) + fs * k as f64),
                fs.round() as u32,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        root.present().map_err(plot_err)?;
    }
    let head = head.trim_end();
    let mut out = head
        .strip_suffix("</svg>")
        .ok_or_else(|| Error::Incompatible("title strip: unterminated SVG".into()))?
        .to_string();
    let mut y = strip;
    for (p, &(w, h)) in panels.iter().zip(&sizes) {
        // the panel nested at its canvas size (its print size is the figure's)
        let px = super::print::set_root_size(
            p,
            &w.to_string(),
            &h.to_string(),
            &format!("0 0 {w} {h}"),
        )?;
        let body = px.trim_end().strip_prefix("<svg ").unwrap_or(&px);
        out.push_str(&format!("<svg x=\"0\" y=\"{y}\" {body}\n"));
        y += h;
    }
    out.push_str("</svg>\n");
    super::print::finish(&out, super::print::Width::Double)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{Curve, LinePlot};

    fn panel(t: &str) -> String {
        let c = Curve {
            label: "a".into(),
            x: vec![0.0, 1.0],
            y: vec![0.0, 1.0],
            dashed: false,
        };
        LinePlot::new(t, "x", "y", vec![c]).svg().unwrap()
    }

    #[test]
    fn panels_keep_their_size_and_order() {
        let (a, b) = (panel("(a) first"), panel("(b) second"));
        let (wa, ha) = svg_size(&a).unwrap();
        let s = stack_svg("both", &[a, b]).unwrap();
        let (w, h) = svg_size(&s).unwrap();
        assert_eq!(w, wa);
        assert!(h > 2 * ha, "{h} {ha}");
        let i = s.find("(a) first").unwrap();
        assert!(s[i..].contains("(b) second"));
        assert_eq!(s.matches("<svg ").count(), 3);
        assert_eq!(s.matches("</svg>").count(), 3);
        assert!(svg_size("<rect/>").is_err());
    }
}
