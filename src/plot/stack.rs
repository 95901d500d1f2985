//! Figures of several panels: a title strip and the panels' own SVGs in rows (two 85 mm
//! panels side by side, or one 170 mm panel), each panel kept whole (its frame, legend and
//! notes) as a nested `<svg>`.

use super::canvas::{Canvas, num};
use super::print::{PAD, TITLE_PT, Width, page_pt};
use super::style::{plot_err, text, wrap};
use crate::error::{Error, Result};
use plotters::prelude::*;

/// Width and height (points) of an SVG drawn by this module's plots: its `viewBox` (see
/// [`canvas_size`](super::print::canvas_size)).
pub fn svg_size(svg: &str) -> Result<(f64, f64)> {
    super::print::canvas_size(svg)
        .map_err(|_| Error::Incompatible("panel: not an SVG with width and height".into()))
}

/// One SVG of `title` ([`TITLE_PT`], wrapped; none when empty) above `panels` in rows:
/// two 85 mm panels side by side, a 170 mm panel alone, each panel kept whole (its frame,
/// legend and notes) as a nested `<svg>`. The figure is 170 mm wide unless it is one 85 mm
/// panel.
pub fn stack_svg(title: &str, panels: &[String]) -> Result<String> {
    let sizes = panels
        .iter()
        .map(|p| svg_size(p))
        .collect::<Result<Vec<_>>>()?;
    let half = page_pt(Width::Single) + 0.01;
    // rows of panels: (first panel, count)
    let mut rows: Vec<Vec<usize>> = Vec::new();
    for (i, s) in sizes.iter().enumerate() {
        match rows.last_mut() {
            Some(r) if r.len() == 1 && sizes[r[0]].0 <= half && s.0 <= half => r.push(i),
            _ => rows.push(vec![i]),
        }
    }
    let width = if rows.iter().all(|r| r.len() == 1 && sizes[r[0]].0 <= half) {
        Width::Single
    } else {
        Width::Double
    };
    let page = page_pt(width);
    let lines = if title.is_empty() {
        Vec::new()
    } else {
        wrap(title, ((page - 2.0 * PAD) / (0.6 * TITLE_PT)) as usize)
    };
    let strip_pt = if lines.is_empty() {
        0.0
    } else {
        PAD + TITLE_PT * 1.25 * lines.len() as f64
    };
    let strip = strip_pt;
    let row_h: Vec<f64> = rows
        .iter()
        .map(|r| r.iter().map(|&i| sizes[i].1).fold(0.0, f64::max))
        .collect();
    let height = strip + row_h.iter().sum::<f64>();
    let mut head = String::new();
    {
        let root = Canvas::new(&mut head, width, (page, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in lines.iter().enumerate() {
            text(
                &root,
                line,
                (PAD, PAD + TITLE_PT * 1.25 * k as f64),
                TITLE_PT,
                BLACK,
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
    for (r, h) in rows.iter().zip(&row_h) {
        let mut x = 0.0;
        for &i in r {
            let (w, ph) = sizes[i];
            // the panel nested at its size in points (its print size is the figure's)
            let (ws, hs) = (num(w), num(ph));
            let px = super::print::set_root_size(&panels[i], &ws, &hs, &format!("0 0 {ws} {hs}"))?;
            let body = px.trim_end().strip_prefix("<svg ").unwrap_or(&px);
            out.push_str(&format!("<svg x=\"{}\" y=\"{}\" {body}\n", num(x), num(y)));
            x += w;
        }
        y += h;
    }
    out.push_str("</svg>\n");
    super::print::finish(&out, width)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{Curve, LinePlot};

    fn panel(t: &str, width: Width) -> String {
        let c = Curve {
            label: "a".into(),
            x: vec![0.0, 1.0],
            y: vec![0.0, 1.0],
            dashed: false,
        };
        LinePlot {
            width,
            ..LinePlot::new(t, "x", "y", vec![c])
        }
        .svg()
        .unwrap()
    }

    #[test]
    fn panels_keep_their_size_and_order() {
        let (a, b) = (
            panel("(a) first", Width::Double),
            panel("(b) second", Width::Double),
        );
        let (wa, ha) = svg_size(&a).unwrap();
        let s = stack_svg("both", &[a, b]).unwrap();
        let (w, h) = svg_size(&s).unwrap();
        assert_eq!(w, wa);
        assert!(h > 2.0 * ha, "{h} {ha}");
        let i = s.find("(a) first").unwrap();
        assert!(s[i..].contains("(b) second"));
        assert_eq!(s.matches("<svg ").count(), 3);
        assert_eq!(s.matches("</svg>").count(), 3);
        assert!(svg_size("<rect/>").is_err());
        // 85 mm panels side by side, a third under them; no title strip without a title
        let p: Vec<String> = ["(a)", "(b)", "(c)"]
            .iter()
            .map(|t| panel(t, Width::Single))
            .collect();
        let (ws, hs) = svg_size(&p[0]).unwrap();
        let s = stack_svg("", &p).unwrap();
        let (w, h) = svg_size(&s).unwrap();
        assert!(
            (w - 2.0 * ws).abs() < 0.02 && (h - 2.0 * hs).abs() < 0.02,
            "{w} {h}"
        );
        assert!(s.contains(&format!("<svg x=\"{}\" y=\"0\"", num(ws))));
        assert!(s.contains(&format!("<svg x=\"0\" y=\"{}\"", num(hs))));
        assert!(s[..200].contains("width=\"170mm\""));
    }
}
