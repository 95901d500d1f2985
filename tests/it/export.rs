//! `--format` and `--dpi` (issue 26): every figure also as a vector PDF and a PNG of its printed
//! width at the chosen resolution, from `figures` (configs and study data, with the captions
//! file README.md) and from a command's `--plot`; bad lists and resolutions are one-line
//! errors naming the flag.

use crate::common::{assert_bad_inputs, sphstab};
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sphstab-export-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Pixel width and height of a PNG (its IHDR chunk).
fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        &b[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is not a PNG",
        path.display()
    );
    let n = |i: usize| u32::from_be_bytes(b[i..i + 4].try_into().unwrap());
    (n(16), n(20))
}

/// The printed width (mm) of an SVG figure: its root's `width="…mm"`.
fn width_mm(svg: &Path) -> f64 {
    let text = std::fs::read_to_string(svg).unwrap();
    let tag = &text[text.find("<svg").unwrap()..];
    let tag = &tag[..tag.find('>').unwrap()];
    let w = tag
        .split(" width=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    w.strip_suffix("mm")
        .unwrap_or_else(|| panic!("{}: width {w} is not in mm", svg.display()))
        .parse()
        .unwrap()
}

fn assert_pdf(path: &Path) {
    let b = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(b.starts_with(b"%PDF"), "{} is not a PDF", path.display());
}

/// `figures --format svg,pdf,png` on one config and one study's stored data: every figure in
/// the three formats (the PNG 300 dpi of its printed width), and README.md with the captions
/// and the commands.
#[test]
fn figures_writes_pdf_png_and_captions() {
    let d = scratch("figures");
    for sub in ["configs", "data", "studies"] {
        std::fs::create_dir_all(d.join(sub)).unwrap();
    }
    let copy = |from: &str, to: &str| std::fs::copy(root().join(from), d.join(to)).unwrap();
    copy(
        "analysis/configs/b00_fig3a_eq74.json",
        "configs/b00_fig3a_eq74.json",
    );
    copy("figures/tradeoff2d.json", "data/tradeoff2d.json");
    copy("analysis/tradeoff2d.json", "studies/tradeoff2d.json");
    let out = d.join("out");
    let arg = |p: PathBuf| p.display().to_string();
    let (code, stdout, err) = sphstab(&[
        "figures",
        "--configs",
        &arg(d.join("configs")),
        "--data",
        &arg(d.join("data")),
        "--studies",
        &arg(d.join("studies")),
        "--out",
        &arg(out.clone()),
        "--format",
        "svg,pdf,png",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("README.md"), "{stdout}");
    for name in ["b00_fig3a_eq74", "tradeoff2d"] {
        let svg = out.join(format!("{name}.svg"));
        assert_pdf(&out.join(format!("{name}.pdf")));
        let (w, h) = png_size(&out.join(format!("{name}.png")));
        let mm = width_mm(&svg);
        assert_eq!(
            w,
            (mm / 25.4 * 300.0).round() as u32,
            "{name}: {mm} mm at 300 dpi"
        );
        assert!(h > 100 && h < 8 * w, "{name}: {w}×{h}");
    }
    let mut files: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files.len(), 7, "{files:?}");
    let readme = std::fs::read_to_string(out.join("README.md")).unwrap();
    let config: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(d.join("configs/b00_fig3a_eq74.json")).unwrap(),
    )
    .unwrap();
    let study: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("studies/tradeoff2d.json")).unwrap())
            .unwrap();
    let fig = readme
        .find("## b00_fig3a_eq74.svg")
        .expect("the config figure's heading");
    let stu = readme
        .find("## tradeoff2d.svg")
        .expect("the study figure's heading");
    assert!(fig < stu, "figures in file-name order");
    for shown in [
        "![](b00_fig3a_eq74.svg)",
        config["title"].as_str().unwrap(),
        config["note"].as_str().unwrap(),
        "![](tradeoff2d.svg)",
        study["note"].as_str().unwrap(),
        "sphstab tradeoff --from ",
        "sphstab tradeoff --config ",
        "sphstab figures --configs ",
    ] {
        assert!(
            readme.contains(shown),
            "README.md lacks {shown:?}:\n{readme}"
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// `--plot x.svg --format svg,png --dpi 150` writes x.svg and a 150-dpi x.png; the derived
/// files need --force like --plot itself.
#[test]
fn plot_writes_every_format_with_the_plot_checks() {
    let d = scratch("plot");
    let plot = d.join("x.svg").display().to_string();
    let args = [
        "dispersion",
        "--points",
        "16",
        "--plot",
        &plot,
        "--format",
        "svg,png",
        "--dpi",
        "150",
    ];
    let (code, _, err) = sphstab(&args);
    assert_eq!(code, 0, "{err}");
    let mm = width_mm(&d.join("x.svg"));
    let (w, _) = png_size(&d.join("x.png"));
    assert_eq!(w, (mm / 25.4 * 150.0).round() as u32);
    std::fs::remove_file(d.join("x.svg")).unwrap();
    let (code, _, err) = sphstab(&args);
    assert_eq!(code, 2, "an existing x.png is refused: {err}");
    assert!(
        err.contains("--plot (as png)") && err.contains("--force"),
        "{err}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_formats_and_resolutions_name_the_flag() {
    let plot = std::env::temp_dir()
        .join(format!("sphstab-export-bad-{}.svg", std::process::id()))
        .display()
        .to_string();
    let p = plot.as_str();
    assert_bad_inputs(&[
        (&["dispersion", "--plot", p, "--format", "tif"], "--format"),
        (
            &["dispersion", "--plot", p, "--format", "svg,svg"],
            "--format",
        ),
        (
            &["dispersion", "--plot", p, "--format", "png", "--dpi", "5"],
            "--dpi",
        ),
        (
            &[
                "dispersion",
                "--plot",
                p,
                "--format",
                "png",
                "--dpi",
                "5000",
            ],
            "--dpi",
        ),
        (
            &["dispersion", "--plot", p, "--format", "pdf", "--dpi", "150"],
            "--dpi",
        ),
        (&["dispersion", "--format", "pdf"], "--format"),
        (&["map", "--dim", "2", "--dpi", "300"], "--dpi"),
        (&["figures", "--format", "tif"], "--format"),
        (&["figures", "--format", "png", "--dpi", "5"], "--dpi"),
        (
            &[
                "tradeoff",
                "--from",
                "figures/tradeoff.json",
                "--plot",
                p,
                "--format",
                "jpg",
            ],
            "--format",
        ),
    ]);
    assert!(!Path::new(p).exists());
}
