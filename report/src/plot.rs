//! SVG plots with plotters (SVG backend only: text is written as SVG text, no fonts needed).

use super::common::out_dir;
use plotters::prelude::*;

/// One curve.
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// Points (x, y).
    pub pts: Vec<(f64, f64)>,
    /// Draw markers at the points.
    pub markers: bool,
    /// Join only the points on this series' own Pareto front (lower x and lower y both
    /// better), not every point in order; with `markers`, every point keeps its marker.
    pub front_only: bool,
}

impl Series {
    /// A curve with markers.
    pub fn marked(name: &str, pts: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            pts,
            markers: true,
            front_only: false,
        }
    }

    /// A plain line.
    pub fn line(name: &str, pts: Vec<(f64, f64)>) -> Self {
        Self {
            markers: false,
            ..Self::marked(name, pts)
        }
    }

    /// A cloud of runs (x cost, y error): a marker at every point, a line through the cloud's
    /// Pareto front only (a grid of runs joined in order zig-zags).
    pub fn cloud(name: &str, pts: Vec<(f64, f64)>) -> Self {
        Self {
            front_only: true,
            ..Self::marked(name, pts)
        }
    }
}

/// Axis options of a plot.
pub struct Axes<'a> {
    /// Title.
    pub title: &'a str,
    /// x label.
    pub x: &'a str,
    /// y label.
    pub y: &'a str,
    /// Logarithmic x.
    pub log_x: bool,
    /// Logarithmic y.
    pub log_y: bool,
}

fn color(i: usize) -> RGBColor {
    const C: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = C[i % C.len()];
    RGBColor(r, g, b)
}

fn range(vals: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return if log { (1e-3, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        if hi <= lo * 1.01 {
            hi = lo * 10.0;
        }
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            lo.abs().max(1.0) * 0.1
        };
        (lo - pad, hi + pad)
    }
}

fn label(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-2..1e4).contains(&a) {
        format!("{v:.0e}")
    } else {
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// Extras drawn over the series.
#[derive(Default)]
pub struct Extras {
    /// Points circled and joined as the Pareto front.
    pub pareto: Vec<(f64, f64)>,
    /// Horizontal reference lines (y, label).
    pub hlines: Vec<(f64, String)>,
    /// Vertical reference lines (x, label).
    pub vlines: Vec<(f64, String)>,
}

/// Draws `series` into `docs/report/<file>`.
pub fn plot(file: &str, ax: &Axes, series: &[Series], extras: &Extras) -> Result<(), String> {
    let path = out_dir().join(file);
    let all_x = series.iter().flat_map(|s| s.pts.iter().map(|p| p.0));
    let xs = range(all_x.chain(extras.vlines.iter().map(|v| v.0)), ax.log_x);
    let all_y = series.iter().flat_map(|s| s.pts.iter().map(|p| p.1));
    let ys = range(all_y.chain(extras.hlines.iter().map(|v| v.0)), ax.log_y);
    let area = SVGBackend::new(&path, (960, 620)).into_drawing_area();
    area.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut b = ChartBuilder::on(&area);
    b.caption(ax.title, ("sans-serif", 20))
        .margin(18)
        .x_label_area_size(50)
        .y_label_area_size(80);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart.map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc(ax.x)
                .y_desc(ax.y)
                .x_label_formatter(&|v| label(*v))
                .y_label_formatter(&|v| label(*v))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(|e| e.to_string())?;
            for (i, s) in series.iter().enumerate() {
                let c = color(i);
                let pts: Vec<(f64, f64)> = s
                    .pts
                    .iter()
                    .copied()
                    .filter(|p| {
                        p.0.is_finite()
                            && p.1.is_finite()
                            && (!ax.log_x || p.0 > 0.0)
                            && (!ax.log_y || p.1 > 0.0)
                    })
                    .collect();
                let line: Vec<(f64, f64)> = if s.front_only {
                    pareto(&pts).into_iter().map(|i| pts[i]).collect()
                } else {
                    pts.clone()
                };
                chart
                    .draw_series(LineSeries::new(line, c.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(s.name.clone())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                    });
                if s.markers {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                        .map_err(|e| e.to_string())?;
                }
            }
            for (y, name) in &extras.hlines {
                let l = vec![(xs.0, *y), (xs.1, *y)];
                chart
                    .draw_series(DashedLineSeries::new(l, 6, 4, BLACK.stroke_width(1)))
                    .map_err(|e| e.to_string())?;
                chart
                    .draw_series(std::iter::once(Text::new(
                        name.clone(),
                        (xs.0, *y),
                        ("sans-serif", 13),
                    )))
                    .map_err(|e| e.to_string())?;
            }
            for (x, name) in &extras.vlines {
                let l = vec![(*x, ys.0), (*x, ys.1)];
                chart
                    .draw_series(DashedLineSeries::new(
                        l,
                        6,
                        4,
                        RGBColor(120, 120, 120).stroke_width(1),
                    ))
                    .map_err(|e| e.to_string())?;
                chart
                    .draw_series(std::iter::once(Text::new(
                        name.clone(),
                        (*x, ys.1),
                        ("sans-serif", 13),
                    )))
                    .map_err(|e| e.to_string())?;
            }
            if !extras.pareto.is_empty() {
                let front = extras.pareto.clone();
                chart
                    .draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(1)))
                    .map_err(|e| e.to_string())?
                    .label("Pareto front")
                    .legend(|(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(1))
                    });
                chart
                    .draw_series(
                        front
                            .iter()
                            .map(|&p| Circle::new(p, 7, BLACK.stroke_width(2))),
                    )
                    .map_err(|e| e.to_string())?;
            }
            chart
                .configure_series_labels()
                .border_style(BLACK)
                .background_style(WHITE.mix(0.85))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| e.to_string())?;
        }};
    }
    match (ax.log_x, ax.log_y) {
        (true, true) => {
            draw!(b.build_cartesian_2d((xs.0..xs.1).log_scale(), (ys.0..ys.1).log_scale()))
        }
        (false, true) => draw!(b.build_cartesian_2d(xs.0..xs.1, (ys.0..ys.1).log_scale())),
        (true, false) => draw!(b.build_cartesian_2d((xs.0..xs.1).log_scale(), ys.0..ys.1)),
        (false, false) => draw!(b.build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)),
    }
    area.present().map_err(|e| e.to_string())?;
    Ok(())
}

/// Indices of the Pareto-optimal points (lower cost and lower error both better), sorted by
/// cost.
pub fn pareto(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    idx.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0));
    let mut best = f64::INFINITY;
    let mut out = Vec::new();
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            out.push(i);
        }
    }
    out
}
