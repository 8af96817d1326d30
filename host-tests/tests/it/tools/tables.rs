//! The experiments' tables (src/experiments/common.rs): CSV and Markdown
//! output.

use abtrack_host_tests::experiments::common::*;
use std::fs;

#[test]
fn csv_quotes_only_what_needs_it() {
    let mut t = Table::new(["method", "rmse"]);
    t.push(["M1, fixed", "1.5"]);
    t.push(["say \"hi\"", "2"]);
    assert_eq!(
        t.to_csv(),
        "method,rmse\n\"M1, fixed\",1.5\n\"say \"\"hi\"\"\",2\n"
    );
}

#[test]
fn markdown_has_a_separator_per_column() {
    let mut t = Table::new(["a", "b"]);
    t.push(["1", "2"]);
    assert_eq!(t.to_markdown(), "| a | b |\n|---|---|\n| 1 | 2 |\n");
}

#[test]
fn plot_writes_an_svg_and_refuses_empty_input() {
    let dir = std::env::temp_dir().join(format!("abtrack-plot-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let path = dir.join("p.svg");
    let spec = PlotSpec {
        title: "t",
        x_label: "x",
        y_label: "y",
        equal_aspect: false,
        y_max: None,
    };
    plot(
        &path,
        &spec,
        &[Series::line("a", vec![(0.0, 1.0), (1.0, 2.0)])],
    )
    .unwrap();
    let svg = fs::read_to_string(&path).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains(">\na\n</text>"),
        "legend text missing"
    );
    assert!(plot(&path, &spec, &[Series::line("nan", vec![(f64::NAN, 1.0)])]).is_err());
    fs::remove_dir_all(&dir).unwrap();
}
