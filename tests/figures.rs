//! Every config in analysis/configs renders, and the committed figures/ are exactly what the
//! configs regenerate (run `cargo run --release -- figures` after changing either).

use sphstab::figures::{parse, render};
use std::path::Path;

#[test]
fn committed_figures_are_regenerated_from_configs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut n = 0;
    for e in std::fs::read_dir(root.join("analysis/configs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_none_or(|x| x != "json") {
            continue;
        }
        let cfg = parse(
            &p.display().to_string(),
            &std::fs::read_to_string(&p).unwrap(),
        )
        .unwrap();
        assert!(
            !cfg.note.is_empty(),
            "{}: every figure needs a note",
            p.display()
        );
        let svg = render(&cfg).unwrap();
        let committed = std::fs::read_to_string(root.join("figures").join(&cfg.output))
            .unwrap_or_else(|_| panic!("figures/{} missing: run `sphstab figures`", cfg.output));
        assert!(
            svg == committed,
            "figures/{} is stale: run `cargo run --release -- figures`",
            cfg.output
        );
        n += 1;
    }
    assert!(n >= 5);
}

#[test]
fn unknown_fields_are_rejected_by_name() {
    let e = parse(
        "x.json",
        r#"{"output":"a.svg","title":"t","series":[],"colour":"red"}"#,
    )
    .unwrap_err();
    match e {
        sphstab::error::Error::Config { file, msg } => {
            assert_eq!(file, "x.json");
            assert!(msg.contains("colour"));
        }
        other => panic!("{other:?}"),
    }
    let e = parse("y.json", r#"{"output":"a.svg","title":"t","series":[{"form":"classical","kernel":"m4","stress":0,"hh":1}]}"#)
        .unwrap_err();
    assert!(e.to_string().contains("hh"));
}
