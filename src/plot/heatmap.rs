//! Heat maps with a colour bar.

use super::axes::{Frame, Scale, nice_ticks, tick_label};
use super::style::{plot_err, text_at, wrap};
use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Sequential colour map (white → yellow → orange → red → dark purple; monotone in lightness,
/// readable with colour-vision deficiencies and in greyscale): anchors at t = 0, ¼, ½, ¾, 1.
const RAMP: [(f64, f64, f64); 5] = [
    (255.0, 255.0, 255.0),
    (253.0, 219.0, 100.0),
    (240.0, 130.0, 40.0),
    (190.0, 30.0, 45.0),
    (70.0, 10.0, 80.0),
];

/// Colour of t ∈ [0, 1] on the heat-map scale (0: white).
pub fn ramp(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (RAMP.len() - 1) as f64;
    let k = (s.floor() as usize).min(RAMP.len() - 2);
    let f = s - k as f64;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    let c = |u: f64, v: f64| (u + f * (v - u)).round() as u8;
    RGBColor(c(a.0, b.0), c(a.1, b.1), c(a.2, b.2))
}

/// A heat map of z over a rectangular (x, y) grid (cell centres, z\[i\]\[j\] at (x\[i\], y\[j\])) with
/// a colour bar labelled `z_desc` (quantity and unit) from 0 to max z.
pub fn heatmap_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    z_desc: &str,
    x: &[f64],
    y: &[f64],
    z: &[Vec<f64>],
) -> Result<String> {
    if x.len() < 2 || y.len() < 2 {
        return Err(Error::Incompatible(
            "heat map: need at least 2 × 2 cells".into(),
        ));
    }
    let (dx, dy) = (x[1] - x[0], y[1] - y[0]);
    let (x0, x1) = (x[0] - 0.5 * dx, x[x.len() - 1] + 0.5 * dx);
    let (y0, y1) = (y[0] - 0.5 * dy, y[y.len() - 1] + 0.5 * dy);
    let zmax = z
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, &v| m.max(v));
    let width = 820.0;
    let title_lines = wrap(title, ((width - 40.0) / (0.56 * 17.0)) as usize);
    let top = 18.0 + 22.0 * title_lines.len() as f64 + 10.0;
    let side = 540.0;
    let frame = Frame {
        rect: (95.0, top, 95.0 + side, top + side),
        x: Scale::Linear(x0, x1),
        y: Scale::Linear(y0, y1),
        grid: false,
    };
    let height = top + side + 70.0;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, super::print::Width::Single, (width, height))
                .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in title_lines.iter().enumerate() {
            text_at(
                &root,
                line,
                (width / 2.0, 12.0 + 22.0 * k as f64),
                17,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        for (i, &xi) in x.iter().enumerate() {
            for (j, &yj) in y.iter().enumerate() {
                let v = z[i][j];
                let t = if zmax > 0.0 && v.is_finite() {
                    v / zmax
                } else {
                    0.0
                };
                let a = frame.map(xi - dx / 2.0, yj + dy / 2.0);
                let b = frame.map(xi + dx / 2.0, yj - dy / 2.0);
                root.draw(&Rectangle::new(
                    [
                        (a.0.floor() as i32, a.1.floor() as i32),
                        (b.0.ceil() as i32, b.1.ceil() as i32),
                    ],
                    ramp(t).filled(),
                ))
                .map_err(plot_err)?;
            }
        }
        frame.draw(&root, x_desc, y_desc, None)?;
        // the colour bar
        let (bl, bt, bw, bh) = (95.0 + side + 40.0, top, 24.0, side);
        let n = 200;
        for k in 0..n {
            let t = (k as f64 + 0.5) / n as f64;
            let ya = bt + bh * (1.0 - (k + 1) as f64 / n as f64);
            let yb = bt + bh * (1.0 - k as f64 / n as f64);
            root.draw(&Rectangle::new(
                [
                    (bl as i32, ya.floor() as i32),
                    ((bl + bw) as i32, yb.ceil() as i32),
                ],
                ramp(t).filled(),
            ))
            .map_err(plot_err)?;
        }
        root.draw(&Rectangle::new(
            [(bl as i32, bt as i32), ((bl + bw) as i32, (bt + bh) as i32)],
            BLACK.stroke_width(1),
        ))
        .map_err(plot_err)?;
        let zt = if zmax > 0.0 { zmax } else { 1.0 };
        let ticks = nice_ticks(0.0, zt, 8);
        let step = if ticks.len() > 1 {
            ticks[1] - ticks[0]
        } else {
            zt
        };
        for v in ticks {
            let yy = bt + bh * (1.0 - v / zt);
            root.draw(&PathElement::new(
                [
                    ((bl + bw) as i32, yy.round() as i32),
                    ((bl + bw + 5.0) as i32, yy.round() as i32),
                ],
                BLACK.stroke_width(1),
            ))
            .map_err(plot_err)?;
            text_at(
                &root,
                &tick_label(v, step),
                (bl + bw + 8.0, yy),
                12,
                (HPos::Left, VPos::Center),
                false,
            )?;
        }
        let top_label = if zmax > 0.0 {
            format!("max {}", tick_label(zmax, zmax / 1000.0))
        } else {
            "0 everywhere".to_string()
        };
        text_at(
            &root,
            &top_label,
            (bl + bw / 2.0, bt - 4.0),
            12,
            (HPos::Center, VPos::Bottom),
            false,
        )?;
        text_at(
            &root,
            z_desc,
            (bl + bw + 62.0, bt + bh / 2.0),
            14,
            (HPos::Center, VPos::Bottom),
            true,
        )?;
        root.present().map_err(plot_err)?;
    }
    super::print::finish(&svg, super::print::Width::Single)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_is_white_at_zero_and_darkens() {
        assert_eq!(ramp(0.0), RGBColor(255, 255, 255));
        let lum = |c: RGBColor| 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
        let mut last = f64::INFINITY;
        for k in 0..=20 {
            let l = lum(ramp(k as f64 / 20.0));
            assert!(l < last + 1e-9, "lightness must fall monotonically");
            last = l;
        }
        assert_eq!(ramp(f64::NAN), ramp(0.0));
    }
}
