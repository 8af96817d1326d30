//! Shared output helpers for the experiment groups: the run context, tables
//! written as CSV and Markdown, and SVG line/scatter plots (plotters' SVG
//! backend, which writes text as `<text>` elements and needs no fonts).

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::metrics::MeanCi;

/// What every group gets from the command line.
#[derive(Debug, Clone)]
pub struct Context {
    /// Root of the results tree (default `results/` in the repository).
    pub out_dir: PathBuf,
    /// Overrides each group's documented Monte Carlo run count (for quick
    /// looks; the committed results use the documented counts).
    pub runs_override: Option<usize>,
}

impl Context {
    /// The group's output folder, created if missing.
    pub fn group_dir(&self, group: &str) -> Result<PathBuf, String> {
        let dir = self.out_dir.join(group);
        fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        Ok(dir)
    }

    /// `documented` unless `--runs` overrides it.
    pub fn runs(&self, documented: usize) -> usize {
        self.runs_override.unwrap_or(documented)
    }
}

/// Writes `contents` to `path`, with the path in the error.
pub fn write_file(path: &Path, contents: &str) -> Result<(), String> {
    fs::write(path, contents).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// A results table, written both as CSV (machine-readable) and Markdown (for
/// the documents that quote it).
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub headers: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    pub fn new<I: IntoIterator<Item = S>, S: Into<String>>(headers: I) -> Self {
        Table {
            headers: headers.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    pub fn push<I: IntoIterator<Item = S>, S: Into<String>>(&mut self, row: I) {
        self.rows.push(row.into_iter().map(Into::into).collect());
    }

    pub fn to_csv(&self) -> String {
        let quote = |c: &String| {
            if c.contains([',', '"', '\n']) {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.clone()
            }
        };
        let mut out = String::new();
        for line in std::iter::once(&self.headers).chain(&self.rows) {
            let cells: Vec<String> = line.iter().map(quote).collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }

    pub fn to_markdown(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "| {} |", self.headers.join(" | "));
        let _ = writeln!(out, "|{}", "---|".repeat(self.headers.len()));
        for row in &self.rows {
            let _ = writeln!(out, "| {} |", row.join(" | "));
        }
        out
    }

    /// Writes `<stem>.csv` and `<stem>.md` into `dir`.
    pub fn write(&self, dir: &Path, stem: &str) -> Result<(), String> {
        write_file(&dir.join(format!("{stem}.csv")), &self.to_csv())?;
        write_file(&dir.join(format!("{stem}.md")), &self.to_markdown())
    }
}

/// "mean ± half-width" with `digits` decimals.
pub fn fmt_ci(ci: &MeanCi, digits: usize) -> String {
    format!("{:.*} ± {:.*}", digits, ci.mean, digits, ci.half_width)
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Line,
    Points,
}

/// One named series of (x, y) points.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

impl Series {
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::Line,
        }
    }
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::Points,
        }
    }
}

/// Axis labels and options of a plot.
#[derive(Debug, Clone)]
pub struct PlotSpec<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    /// Same scale on both axes (track pictures).
    pub equal_aspect: bool,
    /// Clip the y axis at this value (a divergent method would squash the
    /// others); `None` fits all points.
    pub y_max: Option<f64>,
}

/// Draws `series` into an SVG file at `path` (800 × 560 px).
pub fn plot(path: &Path, spec: &PlotSpec<'_>, series: &[Series]) -> Result<(), String> {
    plot_inner(path, spec, series).map_err(|e| format!("cannot draw {}: {e}", path.display()))
}

fn plot_inner(
    path: &Path,
    spec: &PlotSpec<'_>,
    series: &[Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let finite = |v: &&(f64, f64)| v.0.is_finite() && v.1.is_finite();
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().filter(finite).copied())
        .collect();
    if all.is_empty() {
        return Err("no finite points to plot".into());
    }
    let (mut x0, mut x1) = min_max(all.iter().map(|p| p.0));
    let (mut y0, mut y1) = min_max(all.iter().map(|p| p.1));
    if let Some(cap) = spec.y_max {
        y1 = y1.min(cap);
    }
    if spec.equal_aspect {
        let half = 0.5 * (x1 - x0).max(y1 - y0);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (x0, x1, y0, y1) = (cx - half, cx + half, cy - half, cy + half);
    }
    let pad = |a: f64, b: f64| {
        let p = if b > a { 0.04 * (b - a) } else { 1.0 };
        (a - p, b + p)
    };
    let (x0, x1) = pad(x0, x1);
    let (y0, y1) = pad(y0, y1);
    let size = if spec.equal_aspect {
        (720, 720)
    } else {
        (800, 560)
    };
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(spec.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(spec.x_label)
        .y_desc(spec.y_label)
        .draw()?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter(finite)
            .map(|&(x, y)| (x, y.clamp(y0, y1)))
            .collect();
        let legend_color = color;
        match s.style {
            Style::Line => chart
                .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
                .label(s.name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], legend_color.stroke_width(2))
                }),
            Style::Points => chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 2, color.filled())))?
                .label(s.name.as_str())
                .legend(move |(x, y)| Circle::new((x + 10, y), 3, legend_color.filled())),
        };
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

/// The least and the most of `values` (∞ and −∞ when there are none).
pub fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}
