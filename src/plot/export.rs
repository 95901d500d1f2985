//! A finished figure (an SVG string of [`super::print::finish`]: `width="170mm"` or `"85mm"`, a
//! `viewBox` in canvas pixels) in the formats a paper needs: the SVG itself, a vector PDF for
//! `\includegraphics` (svg2pdf) and a PNG at a chosen resolution (resvg). Both conversions
//! read the SVG into one usvg tree and set its text in the DejaVu Sans bundled with the crate
//! (the first family of [`super::print::FONT_FAMILY`] and the `sans-serif` of every figure),
//! so a figure looks the same on every machine; the fonts installed on the machine serve only
//! for a character DejaVu Sans lacks.
//!
//! Built with the `export` feature (on by default, through `cli`).
#![cfg(feature = "export")]

use crate::error::{Error, Result, check_range, field};
use resvg::{tiny_skia, usvg};
use std::sync::{Arc, OnceLock};

/// An output format of a figure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// The SVG as drawn.
    Svg,
    /// Vector PDF, one page the size of the figure, text embedded (subset DejaVu Sans).
    Pdf,
    /// Raster PNG at a given resolution (dots per inch), on a white background.
    Png,
}

/// Every format with its name (also the file extension).
pub const FORMATS: [(Format, &str); 3] = [
    (Format::Svg, "svg"),
    (Format::Pdf, "pdf"),
    (Format::Png, "png"),
];

/// The PNG resolution when none is given, dots per inch.
pub const DEFAULT_DPI: u32 = 300;

/// The allowed PNG resolutions, dots per inch (screen to print).
pub const DPI_RANGE: (u32, u32) = (72, 1200);

impl Format {
    /// The name of the format, also its file extension (`svg`, `pdf`, `png`).
    pub fn extension(self) -> &'static str {
        crate::error::name_in(&FORMATS, self)
    }

    /// A comma-separated list of format names (`svg,pdf,png`), in the order given, each once;
    /// the error names the field `formats` and the valid names.
    pub fn parse_list(text: &str) -> Result<Vec<Format>> {
        let mut list = Vec::new();
        for name in text.split(',').map(str::trim) {
            let f = FORMATS
                .iter()
                .find(|(_, n)| *n == name)
                .map(|(f, _)| *f)
                .ok_or_else(|| Error::UnknownName {
                    what: field("formats") + " entry",
                    given: name.to_string(),
                    valid: FORMATS
                        .iter()
                        .map(|(_, n)| *n)
                        .collect::<Vec<_>>()
                        .join(", ")
                        .into(),
                })?;
            if list.contains(&f) {
                return Err(Error::Incompatible(
                    field("formats") + format!(": `{name}` is given twice"),
                ));
            }
            list.push(f);
        }
        Ok(list)
    }
}

/// Checks a PNG resolution (field `dpi`) against [`DPI_RANGE`].
pub fn check_dpi(dpi: f64) -> Result<f64> {
    check_range(
        "dpi",
        dpi,
        f64::from(DPI_RANGE.0),
        f64::from(DPI_RANGE.1),
        true,
        true,
    )
}

/// The figure `svg` in `format`: the SVG's own bytes, a PDF, or a PNG at `dpi` (checked).
pub fn convert(svg: &str, format: Format, dpi: f64) -> Result<Vec<u8>> {
    match format {
        Format::Svg => Ok(svg.as_bytes().to_vec()),
        Format::Pdf => to_pdf(svg),
        Format::Png => to_png(svg, dpi),
    }
}

/// The DejaVu Sans faces bundled with the crate (the `dejavu` crate's copy of release 2.37).
fn bundled_faces() -> [&'static [u8]; 4] {
    [
        dejavu::sans::regular(),
        dejavu::sans::bold(),
        dejavu::sans::oblique(),
        dejavu::sans::bold_oblique(),
    ]
}

/// The font database of every conversion, built once: the bundled DejaVu Sans first (the
/// family of `sans-serif`), then the machine's fonts less their own DejaVu Sans, for the
/// characters the bundled faces lack (usvg falls back to the first face that has one, in
/// this order).
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| Arc::new(database(true))).clone()
}

/// The bundled DejaVu Sans, and with `machine` the machine's fonts after it ([`fonts`]).
fn database(machine: bool) -> usvg::fontdb::Database {
    let mut db = usvg::fontdb::Database::new();
    for face in bundled_faces() {
        db.load_font_source(usvg::fontdb::Source::Binary(Arc::new(face)));
    }
    db.set_sans_serif_family("DejaVu Sans");
    if machine {
        let bundled: Vec<_> = db.faces().map(|f| f.id).collect();
        db.load_system_fonts();
        let machine_dejavu: Vec<_> = db
            .faces()
            .filter(|f| {
                !bundled.contains(&f.id) && f.families.iter().any(|(n, _)| n == "DejaVu Sans")
            })
            .map(|f| f.id)
            .collect();
        for id in machine_dejavu {
            db.remove_face(id);
        }
    }
    db
}

/// The SVG read by usvg with the bundled fonts, lengths in CSS pixels (96 per inch).
fn tree(svg: &str) -> Result<usvg::Tree> {
    tree_with(svg, fonts())
}

fn tree_with(svg: &str, fontdb: Arc<usvg::fontdb::Database>) -> Result<usvg::Tree> {
    let opt = usvg::Options {
        font_family: "DejaVu Sans".into(),
        fontdb,
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &opt).map_err(|e| Error::Export {
        format: "svg",
        problem: format!("the SVG cannot be read: {e}"),
    })
}

/// CSS pixels per inch: usvg's unit (`170mm` is 170/25.4 · 96 px in its tree).
const CSS_PX_PER_INCH: f64 = 96.0;

/// The figure `svg` as a one-page vector PDF of its printed size (a `170mm` wide figure makes a
/// 170 mm wide page), text embedded as subset fonts.
pub fn to_pdf(svg: &str) -> Result<Vec<u8>> {
    let tree = tree(svg)?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions {
            dpi: CSS_PX_PER_INCH as f32,
        },
    )
    .map_err(|e| Error::Export {
        format: "pdf",
        problem: e.to_string(),
    })
}

/// Pixel size of the figure `svg` rasterised at `dpi`: its printed width and height in
/// inches times `dpi`, rounded (85 mm at 300 dpi: 1004 px; 170 mm: 2008 px).
pub fn png_size(svg: &str, dpi: f64) -> Result<(u32, u32)> {
    let size = tree(svg)?.size();
    Ok(pixels(size, dpi))
}

fn pixels(size: usvg::Size, dpi: f64) -> (u32, u32) {
    let px = |css: f32| (f64::from(css) / CSS_PX_PER_INCH * dpi).round().max(1.0) as u32;
    (px(size.width()), px(size.height()))
}

/// The figure `svg` as a PNG at `dpi` dots per inch of its printed size, on white: 8-bit
/// RGB with its resolution recorded (pHYs, pixels per metre), so it is placed at its printed
/// size.
pub fn to_png(svg: &str, dpi: f64) -> Result<Vec<u8>> {
    let dpi = check_dpi(dpi)?;
    let pixmap = raster(&tree(svg)?, dpi)?;
    // opaque (drawn on white): premultiplied RGBA is plain RGBA; the alpha is dropped
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let per_metre = (dpi / 0.0254).round() as u32;
    enc.set_pixel_dims(Some(png::PixelDimensions {
        xppu: per_metre,
        yppu: per_metre,
        unit: png::Unit::Meter,
    }));
    let mut w = enc.write_header().map_err(|e| png_error(e.to_string()))?;
    w.write_image_data(&rgb)
        .map_err(|e| png_error(e.to_string()))?;
    w.finish().map_err(|e| png_error(e.to_string()))?;
    Ok(out)
}

fn png_error(problem: String) -> Error {
    Error::Export {
        format: "png",
        problem,
    }
}

/// The tree drawn at `dpi` on white.
fn raster(tree: &usvg::Tree, dpi: f64) -> Result<tiny_skia::Pixmap> {
    let (w, h) = pixels(tree.size(), dpi);
    let mut pixmap = tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| png_error(format!("cannot allocate a {w}×{h} image")))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let sx = w as f32 / tree.size().width();
    let sy = h as f32 / tree.size().height();
    resvg::render(
        tree,
        tiny_skia::Transform::from_scale(sx, sy),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figure(width_mm: f64, body: &str) -> String {
        let (w, h) = (width_mm * 20.0, width_mm * 10.0);
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width_mm}mm\" height=\"{}mm\" \
             viewBox=\"0 0 {w} {h}\">\n<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" \
             fill=\"#FFFFFF\"/>\n{body}</svg>\n",
            width_mm / 2.0
        )
    }

    fn text(s: &str) -> String {
        format!(
            "<text x=\"100\" y=\"400\" font-family=\"{}\" font-size=\"200\" fill=\"#000000\">{s}</text>\n",
            crate::plot::print::FONT_FAMILY
        )
    }

    /// (width, height, number of dark pixels) of a PNG.
    fn decode(png: &[u8]) -> (u32, u32, usize) {
        let p = tiny_skia::Pixmap::decode_png(png).unwrap();
        let dark = p
            .pixels()
            .iter()
            .filter(|c| c.red() < 128 && c.green() < 128 && c.blue() < 128)
            .count();
        (p.width(), p.height(), dark)
    }

    #[test]
    fn formats_parse_from_a_list() {
        assert_eq!(
            Format::parse_list("svg,pdf,png").unwrap(),
            vec![Format::Svg, Format::Pdf, Format::Png]
        );
        assert_eq!(Format::parse_list(" png ").unwrap(), vec![Format::Png]);
        let e = Format::parse_list("svg,tif").unwrap_err().to_string();
        assert!(
            e.contains("formats") && e.contains("tif") && e.contains("svg, pdf, png"),
            "{e}"
        );
        assert!(Format::parse_list("").is_err());
        assert!(Format::parse_list("pdf,pdf").is_err());
        assert_eq!(Format::Png.extension(), "png");
        assert!(check_dpi(71.0).is_err() && check_dpi(1201.0).is_err());
        assert_eq!(check_dpi(300.0).unwrap(), 300.0);
    }

    #[test]
    fn pdf_is_a_pdf_of_the_printed_size() {
        let pdf = to_pdf(&figure(85.0, &text("ω² σ̄"))).unwrap();
        assert!(pdf.starts_with(b"%PDF"));
        // MediaBox of 85 mm = 240.94 pt
        let s = String::from_utf8_lossy(&pdf);
        assert!(
            s.contains("/MediaBox [0 0 240.9"),
            "{}",
            &s[..s.len().min(2000)]
        );
    }

    #[test]
    fn png_has_the_printed_size_at_the_dpi() {
        for (mm, dpi, px) in [
            (85.0, 300.0, 1004),
            (170.0, 300.0, 2008),
            (85.0, 150.0, 502),
        ] {
            let png = to_png(&figure(mm, ""), dpi).unwrap();
            let (w, h, _) = decode(&png);
            assert_eq!(
                (w, h),
                (px, (px as f64 / 2.0).round() as u32),
                "{mm} mm at {dpi}"
            );
            // the resolution is recorded: 300 dpi = 11811 pixels per metre (300 / 0.0254)
            let reader = png::Decoder::new(&png[..]).read_info().unwrap();
            let dims = reader.info().pixel_dims.expect("a pHYs chunk");
            assert_eq!(dims.unit, png::Unit::Meter);
            let per_metre = (dpi / 0.0254_f64).round() as u32;
            assert_eq!((dims.xppu, dims.yppu), (per_metre, per_metre));
            // printed width from pixels and resolution: the figure's millimetres
            assert!((f64::from(w) / f64::from(dims.xppu) * 1000.0 - mm).abs() < 0.1);
        }
        assert!(to_png(&figure(85.0, ""), 5.0).is_err());
    }

    #[test]
    fn text_is_drawn_with_every_glyph_of_the_figures() {
        let blank = decode(&to_png(&figure(85.0, ""), 150.0).unwrap());
        assert_eq!(blank.2, 0);
        let drawn = decode(&to_png(&figure(85.0, &text("Abc")), 150.0).unwrap());
        assert!(drawn.2 > 200, "{drawn:?}");
        // the bundled DejaVu Sans alone (no machine fonts to fall back on) draws every
        // symbol the figures write
        let bundled = Arc::new(database(false));
        for s in [
            "⁻", "²", "σ̄", "κ", "θ", "ω", "Γ", "▲", "▼", "×", "−", "√", "…", "³",
        ] {
            let t = tree_with(&figure(85.0, &text(s)), bundled.clone()).unwrap();
            let ink = decode(&raster(&t, 150.0).unwrap().encode_png().unwrap()).2;
            assert!(ink > 10, "{s}: {ink} dark pixels");
        }
    }

    #[test]
    fn nested_svgs_are_placed_at_their_offsets() {
        let inner = "<svg x=\"850\" y=\"0\" width=\"850\" height=\"850\" viewBox=\"0 0 850 850\">\
                     <rect x=\"0\" y=\"0\" width=\"850\" height=\"850\" fill=\"#000000\"/></svg>\n";
        let png = to_png(&figure(85.0, inner), 150.0).unwrap();
        let p = tiny_skia::Pixmap::decode_png(&png).unwrap();
        let at = |x: u32, y: u32| p.pixel(x, y).unwrap().red();
        assert_eq!(at(100, 100), 255, "left half white");
        assert_eq!(at(400, 100), 0, "right half black");
    }
}
