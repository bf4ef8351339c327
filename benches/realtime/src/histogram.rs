//! The histogram of the per-step thread CPU time as an SVG (plotters, SVG backend only).

use std::path::Path;

use plotters::prelude::*;

use crate::stats::Summary;

/// Number of bins.
const BINS: usize = 120;

/// Writes the histogram of `cpu_us` (per-step thread CPU time [µs]) to `path`: equal bins from
/// just below the fastest step to past the slowest step and the budget, log-scaled counts, the median, p99, p99.9, the maximum and the step
/// budget `budget_us` [µs] marked as vertical lines.
pub fn write(
    path: &Path,
    title: &str,
    cpu_us: &[f64],
    summary: &Summary,
    budget_us: f64,
) -> Result<(), String> {
    let lo = cpu_us.iter().copied().fold(f64::INFINITY, f64::min);
    if !lo.is_finite() {
        return Err("no CPU time to plot".into());
    }
    let (x0, x1) = (lo * 0.9, summary.max.max(budget_us) * 1.05);
    let edge = |i: usize| x0 + (x1 - x0) * i as f64 / BINS as f64;
    let mut counts = vec![0usize; BINS];
    for v in cpu_us {
        let i = ((v - x0) / (x1 - x0) * BINS as f64).max(0.0) as usize;
        counts[i.min(BINS - 1)] += 1;
    }
    let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64 * 3.0;

    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let area = SVGBackend::new(path, (960, 560)).into_drawing_area();
    area.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&area)
        .caption(title, ("sans-serif", 18))
        .margin(18)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, (0.7f64..top).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("thread CPU time per step [µs] (SetReal + DoStep + GetReal)")
        .y_desc("steps")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| err(&e))?;
    let bar = RGBColor(70, 110, 170);
    chart
        .draw_series(
            counts
                .iter()
                .enumerate()
                .filter(|(_, c)| **c > 0)
                .map(|(i, c)| {
                    Rectangle::new([(edge(i), 0.7), (edge(i + 1), *c as f64)], bar.filled())
                }),
        )
        .map_err(|e| err(&e))?;
    let marks = [
        (summary.median, "median", RGBColor(0, 150, 0)),
        (summary.p99, "p99", RGBColor(230, 140, 0)),
        (summary.p999, "p99.9", RGBColor(200, 60, 0)),
        (summary.max, "max", RGBColor(150, 0, 150)),
        (budget_us, "step (budget)", RGBColor(200, 0, 0)),
    ];
    for (x, name, color) in marks {
        chart
            .draw_series(LineSeries::new(
                vec![(x, 0.7), (x, top)],
                color.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(format!("{name} {x:.0} µs"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(3))
            });
    }
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.85))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    area.present().map_err(|e| err(&e))?;
    Ok(())
}
