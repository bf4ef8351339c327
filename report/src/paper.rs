//! The paper's figures for Cases 1–3: vertical deflection of the end node over 2 s (hybrid,
//! all-modal, all-ANCF on one plot) and the tip's amplitude spectrum with the Euler–Bernoulli
//! frequencies of docs/references.md §4c marked; the same for the spatial twins
//! (`scenes/caseN_3d*.toml`, tip z) beside the planar runs, and the out-of-plane strip
//! (`scenes/strip_3d.toml`, tip y and z).

use super::common::{self, e3, md_table, scene, simulate, Progress, Run};
use super::plot::{self, Axes, Extras, Series};
use hybeam_references::{PaperBeam, CASE1_BEAM, CASE3_BEAM};
use std::fmt::Write as _;

const FORMS: [(&str, &str); 3] = [
    ("hybrid", ""),
    ("all-modal", "_modal"),
    ("all-ANCF", "_ancf"),
];
const OUT: f64 = 1e-3;
const T_SPECTRUM: f64 = 10.0;

struct Case {
    key: &'static str,
    title: &'static str,
    /// The beam's Euler–Bernoulli frequencies and static sag (docs/references.md §4c).
    beam: PaperBeam,
    f_max: f64,
}

const CASES: [Case; 3] = [
    Case {
        key: "case1",
        title: "Case 1 (d = 2 mm, L = 40 cm, undamped)",
        beam: CASE1_BEAM,
        f_max: 400.0,
    },
    Case {
        key: "case2",
        title: "Case 2 (Case 1 + Kelvin-Voigt damping tau = 0.7 ms)",
        beam: CASE1_BEAM,
        f_max: 400.0,
    },
    Case {
        key: "case3",
        title: "Case 3 (2 mm x 20 cm + 1 mm x 40 cm, damped)",
        beam: CASE3_BEAM,
        f_max: 100.0,
    },
];

/// In-place radix-2 FFT of (re, im) pairs; `a.len()` must be a power of two.
fn fft(a: &mut [(f64, f64)]) {
    let n = a.len();
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            a.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let ang = -2.0 * std::f64::consts::PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (ang * k as f64).sin_cos();
                let (ur, ui) = a[start + k];
                let (vr, vi) = a[start + k + len / 2];
                let (tr, ti) = (vr * c - vi * s, vr * s + vi * c);
                a[start + k] = (ur + tr, ui + ti);
                a[start + k + len / 2] = (ur - tr, ui - ti);
            }
        }
        len <<= 1;
    }
}

/// Single-sided amplitude spectrum of `y` minus its mean, Hann window (amplitude-corrected),
/// zero-padded 4×; returns (frequency, amplitude) pairs up to `f_max`.
fn spectrum(y: &[f64], dt: f64, f_max: f64) -> Vec<(f64, f64)> {
    let n = y.len();
    let mean = y.iter().sum::<f64>() / n as f64;
    let w: Vec<f64> = (0..n)
        .map(|i| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / (n - 1) as f64).cos())
        .collect();
    let wsum: f64 = w.iter().sum();
    let m = (4 * n).next_power_of_two();
    let mut a = vec![(0.0, 0.0); m];
    for i in 0..n {
        a[i].0 = (y[i] - mean) * w[i];
    }
    fft(&mut a);
    let df = 1.0 / (m as f64 * dt);
    (0..m / 2)
        .map(|k| (k as f64 * df, 2.0 * (a[k].0.hypot(a[k].1)) / wsum))
        .take_while(|p| p.0 <= f_max)
        .collect()
}

/// Peak near `f0` (±15 %), parabolic interpolation on log amplitude; (frequency, amplitude).
/// NaN when there is no clear peak: the maximum sits at the window edge or is below 3× the
/// window's median amplitude or below 1e-6 of the spectrum's largest amplitude.
fn peak(spec: &[(f64, f64)], f0: f64) -> (f64, f64) {
    let idx: Vec<usize> = (1..spec.len().saturating_sub(1))
        .filter(|&i| (spec[i].0 - f0).abs() <= 0.15 * f0)
        .collect();
    let Some(&k) = idx
        .iter()
        .max_by(|&&a, &&b| spec[a].1.total_cmp(&spec[b].1))
    else {
        return (f64::NAN, f64::NAN);
    };
    let (a, b, c) = (spec[k - 1].1.ln(), spec[k].1.ln(), spec[k + 1].1.ln());
    let den = a - 2.0 * b + c;
    let d = if den != 0.0 { 0.5 * (a - c) / den } else { 0.0 };
    let df = spec[1].0 - spec[0].0;
    (spec[k].0 + d * df, (b - 0.25 * (a - c) * d).exp())
}

fn ys(r: &Run) -> Vec<f64> {
    comp(r, 1)
}

/// Component `k` of the tip position over a run (0 = x, 1 = y, 2 = z).
fn comp(r: &Run, k: usize) -> Vec<f64> {
    r.tip.iter().map(|p| p[k]).collect()
}

/// max |a − b| over the common samples.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// max |a|.
fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// `paper_<key>_deflection.svg`: the vertical tip component `up` (1 = y, 2 = z) of each run
/// over time, with the linear static sag of `case`.
fn plot_deflection(
    key: &str,
    case: &Case,
    runs: &[(&str, Run)],
    up: usize,
    where_: &str,
) -> Result<(), String> {
    let series: Vec<Series> = runs
        .iter()
        .map(|(f, r)| {
            Series::line(
                f,
                r.t.iter()
                    .zip(&r.tip)
                    .map(|(t, p)| (*t, p[up] * 1e3))
                    .collect(),
            )
        })
        .collect();
    plot::plot(
        &format!("paper_{key}_deflection.svg"),
        &Axes {
            title: &format!(
                "{}{where_}: vertical deflection of the end node",
                case.title
            ),
            x: "time [s]",
            y: if up == 2 { "tip z [mm]" } else { "tip y [mm]" },
            log_x: false,
            log_y: false,
        },
        &series,
        &Extras {
            hlines: vec![(-case.beam.sag * 1e3, "linear static sag".into())],
            ..Default::default()
        },
    )
}

/// An amplitude spectrum plot (log amplitude) with the Euler–Bernoulli frequencies of `case`
/// marked.
fn plot_spectrum(file: &str, title: &str, series: &[Series], case: &Case) -> Result<(), String> {
    plot::plot(
        file,
        &Axes {
            title,
            x: "frequency [Hz]",
            y: "amplitude [m]",
            log_x: false,
            log_y: true,
        },
        series,
        &Extras {
            vlines: case
                .beam
                .frequencies
                .iter()
                .map(|f| (*f, format!("EB {f}")))
                .collect(),
            ..Default::default()
        },
    )
}

/// One row of a peak table: the peak of `sp` near each frequency of `f0s`.
fn peak_row(form: &str, sp: &[(f64, f64)], f0s: &[f64]) -> Vec<String> {
    let mut row = vec![form.to_string()];
    for &f0 in f0s {
        let (f, a) = peak(sp, f0);
        row.push(format!(
            "{f:.3} ({:+.2} %), {}",
            100.0 * (f / f0 - 1.0),
            e3(a)
        ));
    }
    row
}

/// Header of a peak table.
fn peak_head(f0s: &[f64]) -> Vec<String> {
    std::iter::once("formulation".to_string())
        .chain(
            f0s.iter()
                .map(|f| format!("peak near EB {f} Hz: f [Hz] (vs EB), amplitude [m]")),
        )
        .collect()
}

/// Writes `paper_<key>_spectrum_<tag>.csv` (one amplitude column per formulation).
fn spectrum_csv(file: &str, cols: &[(&str, Vec<(f64, f64)>)]) -> Result<(), String> {
    let n = cols.iter().map(|c| c.1.len()).min().unwrap_or(0);
    let rows: Vec<Vec<String>> = (0..n)
        .map(|k| {
            let mut row = vec![format!("{:.5}", cols[0].1[k].0)];
            for c in cols {
                row.push(format!("{:.6e}", c.1[k].1));
            }
            row
        })
        .collect();
    let head: Vec<String> = std::iter::once("frequency_hz".to_string())
        .chain(
            cols.iter()
                .map(|c| format!("amp_{}_m", c.0.replace('-', "_").to_lowercase())),
        )
        .collect();
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    common::write_csv(file, &head, &rows)
}

fn run_or_err(file: &str, sets: &[String], t_end: f64) -> Result<Run, String> {
    let s = scene(file, sets)?;
    let r = simulate(&s, t_end, OUT);
    match r.err {
        Some(e) => Err(format!("{file}: {e}")),
        None => Ok(r),
    }
}

fn undamped_sets(file: &str) -> Result<Vec<String>, String> {
    let s = scene(file, &[])?;
    let mut v = Vec::new();
    for (i, g) in s.segments.iter().enumerate() {
        v.push(format!("segments.{i}.damping_time=0.0"));
        if g.damping_ratio != 0.0 {
            v.push(format!("segments.{i}.damping_ratio=0.0"));
        }
    }
    Ok(v)
}

/// Runs the paper report and writes `docs/paper-figures.md`.
pub fn run() -> Result<(), String> {
    let mut md = format!(
        "# Paper figures: Sohn & Yoo, Cases 1–3\n\nGenerated by `cargo run --release -p hybeam-report -- paper`. \
         Machine: {}.\n\nEach case is run with the shipped scenes `scenes/caseN.toml` (hybrid), \
         `caseN_modal.toml` (all-modal) and `caseN_ancf.toml` (all-ANCF), their solver settings as \
         shipped, released straight and horizontal under gravity. The plots are the vertical \
         position of the end node (tip y) over 2 s; the spectra are the single-sided amplitude \
         spectra of tip y minus its mean (Hann window, 4× zero padding) from {T_SPECTRUM} s runs \
         sampled every {OUT} s. Peaks are located by parabolic interpolation within ±15 % of each \
         Euler–Bernoulli frequency of docs/references.md §4c (steel assumed). The spatial twins \
         (`scenes/caseN_3d*.toml`) and the out-of-plane strip (`scenes/strip_3d.toml`) follow the \
         planar cases. All numbers below are measured by the command above, on a machine shared \
         with other jobs (wall times are indicative only).\n\n",
        common::machine()
    );
    let mut prog = Progress::new("paper", 3 * 3 + 3 * 3 + 2 * 3 + 3 * 3 * 2 + 2);
    let mut summary = String::new();
    let mut planar_runs = Vec::new();
    for case in &CASES {
        // deflection over 2 s
        let mut runs = Vec::new();
        for (form, suf) in FORMS {
            prog.item(&format!("{} {form} 2 s", case.key));
            let r = run_or_err(&format!("{}{suf}", case.key), &[], 2.0)?;
            runs.push((form, r));
        }
        let t = runs[0].1.t.clone();
        let csv: Vec<Vec<String>> = (0..t.len())
            .map(|k| {
                let mut row = vec![format!("{:.4}", t[k])];
                for (_, r) in &runs {
                    row.push(format!("{:.9e}", r.tip[k][1]));
                }
                row
            })
            .collect();
        common::write_csv(
            &format!("paper_{}_deflection.csv", case.key),
            &[
                "time_s",
                "tip_y_hybrid_m",
                "tip_y_all_modal_m",
                "tip_y_all_ancf_m",
            ],
            &csv,
        )?;
        plot_deflection(case.key, case, &runs, 1, "")?;
        // measured comparison
        let anc = ys(&runs[2].1);
        let peak_abs = anc.iter().fold(0.0f64, |m, y| m.max(y.abs()));
        let mut rows = Vec::new();
        for (form, r) in &runs {
            let y = ys(r);
            let (kmin, ymin) =
                y.iter().enumerate().fold(
                    (0, f64::INFINITY),
                    |a, (k, &v)| if v < a.1 { (k, v) } else { a },
                );
            let half = y.len() / 2;
            let mean2 = y[half..].iter().sum::<f64>() / (y.len() - half) as f64;
            let dmax = y
                .iter()
                .zip(&anc)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let drms = (y
                .iter()
                .zip(&anc)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                / y.len() as f64)
                .sqrt();
            let xend = r.tip.last().map(|p| p[0]).unwrap_or(f64::NAN);
            rows.push(vec![
                form.to_string(),
                format!("{:.4}", ymin * 1e3),
                format!("{:.3}", r.t[kmin]),
                format!("{:.4}", mean2 * 1e3),
                format!("{:.4}", y.last().copied().unwrap_or(f64::NAN) * 1e3),
                format!("{:.6}", xend),
                e3(dmax),
                format!("{:.2} %", 100.0 * dmax / peak_abs),
                e3(drms),
                format!("{:.3}", r.wall),
            ]);
        }
        let _ = writeln!(
            md,
            "## {}\n\n![{k} deflection](report/paper_{k}_deflection.svg)\n\nCSV: `docs/report/paper_{k}_deflection.csv`. \
             Linear static sag (docs/references.md §4c): {:.2} mm.\n\n{}",
            case.title,
            case.beam.sag * 1e3,
            md_table(
                &[
                    "formulation",
                    "lowest tip y [mm]",
                    "at t [s]",
                    "mean tip y, 1–2 s [mm]",
                    "tip y at 2 s [mm]",
                    "tip x at 2 s [m]",
                    "max \\|y − y_ANCF\\| [m]",
                    "of ANCF peak \\|y\\|",
                    "RMS (y − y_ANCF) [m]",
                    "wall [s]",
                ],
                &rows
            ),
            k = case.key
        );
        planar_runs.push(runs.clone());
        let hy = ys(&runs[0].1);
        let mo = ys(&runs[1].1);
        let maxdiff = |y: &[f64]| {
            y.iter()
                .zip(&anc)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        };
        let max_dx = |r: &Run| {
            r.tip
                .iter()
                .zip(&runs[2].1.tip)
                .map(|(a, b)| (a[0] - b[0]).abs())
                .fold(0.0, f64::max)
        };
        let _ = writeln!(
            summary,
            "| {} | {:.3} | {} ({:.2} %) | {} ({:.2} %) | {} | {} |",
            case.key,
            peak_abs * 1e3,
            e3(maxdiff(&hy)),
            100.0 * maxdiff(&hy) / peak_abs,
            e3(maxdiff(&mo)),
            100.0 * maxdiff(&mo) / peak_abs,
            e3(max_dx(&runs[0].1)),
            e3(max_dx(&runs[1].1)),
        );
        let dhm = hy
            .iter()
            .zip(&mo)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        // where in time the formulations part: first time the difference exceeds 1 % of peak
        let part = |y: &[f64]| {
            y.iter()
                .zip(&anc)
                .position(|(a, b)| (a - b).abs() > 0.01 * peak_abs)
                .map(|k| format!("{:.3} s", t[k]))
                .unwrap_or_else(|| "never within 2 s".into())
        };
        let _ = writeln!(
            md,
            "Max |hybrid − all-modal| = {} m. The difference to all-ANCF first exceeds 1 % of the \
             peak deflection at: hybrid {}, all-modal {}.\n",
            e3(dhm),
            part(&hy),
            part(&mo)
        );
        // spectra
        let variants: Vec<(&str, bool)> = if case.key == "case1" {
            vec![("as shipped (undamped)", false)]
        } else {
            vec![("as shipped (damped)", false), ("undamped twin", true)]
        };
        for (vname, undamped) in variants {
            let mut spec_series = Vec::new();
            let mut peak_rows = Vec::new();
            let mut csv_cols = Vec::new();
            for (form, suf) in FORMS {
                prog.item(&format!("{} {form} {vname} {T_SPECTRUM} s", case.key));
                let file = format!("{}{suf}", case.key);
                let sets = if undamped {
                    undamped_sets(&file)?
                } else {
                    Vec::new()
                };
                let r = run_or_err(&file, &sets, T_SPECTRUM)?;
                let sp = spectrum(&ys(&r), OUT, case.f_max);
                peak_rows.push(peak_row(form, &sp, &case.beam.frequencies));
                spec_series.push(Series::line(
                    form,
                    sp.iter().map(|p| (p.0, p.1.max(1e-12))).collect(),
                ));
                csv_cols.push((form, sp));
            }
            let tag = if undamped { "undamped" } else { "shipped" };
            spectrum_csv(&format!("paper_{}_spectrum_{tag}.csv", case.key), &csv_cols)?;
            plot_spectrum(
                &format!("paper_{}_spectrum_{tag}.svg", case.key),
                &format!("{}, {vname}: amplitude spectrum of tip y", case.title),
                &spec_series,
                case,
            )?;
            let notes = if vname.starts_with("as shipped (undamped)") || undamped {
                let h = scene(case.key, &[])?.solver.max_step;
                let mut n = format!(
                    "Expected algorithmic period elongation of the integrator at the shipped step h = {h:e} s, \
                     (ωh)²/12 (trapezoidal-rule estimate): "
                );
                let items: Vec<String> = case
                    .beam
                    .frequencies
                    .iter()
                    .map(|f| {
                        format!(
                            "{:.2} % at {f} Hz",
                            100.0 * (2.0 * std::f64::consts::PI * f * h).powi(2) / 12.0
                        )
                    })
                    .collect();
                n.push_str(&items.join(", "));
                if case.key != "case3" {
                    // uniform cantilever: f_n = f1 (λn/λ1)², λ5, λ6 from 1 + cos λ cosh λ = 0
                    let al: Vec<String> = [(5, 14.137_168), (6, 17.278_760)]
                        .iter()
                        .map(|&(k, lam)| {
                            let f = case.beam.frequencies[0] * (lam / 1.875_104_07f64).powi(2);
                            let fa = f * (1.0 - (2.0 * std::f64::consts::PI * f * h).powi(2) / 12.0);
                            format!("mode {k} (EB {f:.0} Hz, about {fa:.0} Hz after elongation) appears aliased at {:.0} Hz", (1.0 / OUT - fa).abs())
                        })
                        .collect();
                    let _ = write!(
                        n,
                        ". Sampling at {} Hz folds the modes above {} Hz: {}",
                        1.0 / OUT,
                        0.5 / OUT,
                        al.join("; ")
                    );
                }
                n.push_str(".\n\n");
                n
            } else {
                String::new()
            };
            let head = peak_head(&case.beam.frequencies);
            let head: Vec<&str> = head.iter().map(String::as_str).collect();
            let _ = writeln!(
                md,
                "### {} spectrum, {vname}\n\n![{k} spectrum](report/paper_{k}_spectrum_{tag}.svg)\n\n\
                 CSV: `docs/report/paper_{k}_spectrum_{tag}.csv`.{}\n\n{}\n{notes}",
                case.title,
                if undamped { " Damping set to zero on every segment (`segments.N.damping_time=0.0`)." } else { "" },
                md_table(&head, &peak_rows),
                k = case.key
            );
        }
    }
    let space_md = spatial(&planar_runs, &mut prog)?;
    prog.finish();
    let table = format!(
        "## Where the formulations agree and where they part (measured)\n\n\
         Over the 2 s runs, against the all-ANCF run of the same case (shipped settings):\n\n\
         | case | ANCF peak \\|y\\| [mm] | max \\|y_hybrid − y_ANCF\\| [m] | max \\|y_modal − y_ANCF\\| [m] | \
         max \\|x_hybrid − x_ANCF\\| [m] | max \\|x_modal − x_ANCF\\| [m] |\n|---|---|---|---|---|---|\n{summary}\n\
         The x columns compare the inward motion of the tip; a modal segment, planar or spatial, \
         carries the foreshortening of every point and the inextensible curvature \
         (docs/engine-findings.md); the spectra tables per case give the frequency agreement.\n\n"
    );
    let md = md.replacen("## Case 1", &format!("{table}## Case 1"), 1);
    let mut md = md;
    md.push_str(&space_md);
    md.push_str(
        "## How to read these numbers\n\n\
         - The all-ANCF run is the nonlinear reference formulation; the tables give the largest and the \
         RMS vertical difference of the other two to it, the time from which they part by more than 1 % \
         of the peak deflection, and the mean over the second second, to compare with the linear static sag.\n\
         - The spectra give each formulation's frequencies against Euler–Bernoulli; a relative \
         deviation is the discretization error of the formulation plus the resolution of the \
         spectrum (bin width 1/(4·T) before interpolation). *No clear peak*: the window's maximum is at \
         its edge, below 3× its median or below 1e-6 of the largest peak (with τ = 0.7 ms the damping ratio τω/2 of the higher modes is large, \
         so they have died out long before the 10 s window ends).\n\
         - Accuracy against a converged reference is in `docs/accuracy.md`.\n",
    );
    common::write_doc("paper-figures.md", &md)?;
    eprintln!("wrote docs/paper-figures.md");
    Ok(())
}

/// The spatial twins of Cases 1–3 (tip z; hybrid, all-modal, all-ANCF) with their agreement
/// table, the planar-vs-spatial comparison (the 3D run's z against the planar run's y) and the
/// spectra, then the out-of-plane strip. `planar[i]` are the 2 s planar runs of `CASES[i]` in
/// the order of `FORMS`. Returns the page section.
fn spatial(planar: &[Vec<(&str, Run)>], prog: &mut Progress) -> Result<String, String> {
    let mut md = String::from(
        "## Spatial twins (`scenes/caseN_3d*.toml`)\n\n\
         The same rods with `space = \"spatial\"`, z up and gravity along −z, so they bend in the \
         x–z plane; the plots show the vertical position of the end node (tip z). The 3D run must \
         reproduce the planar run of the same formulation (its z against the planar y) and stay in \
         its plane (tip y = 0).\n\n",
    );
    let mut agree = String::new();
    let mut versus = String::new();
    let mut sections = String::new();
    for (case, planar) in CASES.iter().zip(planar) {
        let key = format!("{}_3d", case.key);
        let mut runs = Vec::new();
        for (form, suf) in FORMS {
            prog.item(&format!("{key} {form} 2 s"));
            let r = run_or_err(&format!("{key}{suf}"), &[], 2.0)?;
            runs.push((form, r));
        }
        let t = runs[0].1.t.clone();
        let csv: Vec<Vec<String>> = (0..t.len())
            .map(|k| {
                let mut row = vec![format!("{:.4}", t[k])];
                for (_, r) in &runs {
                    row.push(format!("{:.9e}", r.tip[k][2]));
                }
                for (_, r) in &runs {
                    row.push(format!("{:.9e}", r.tip[k][1]));
                }
                row
            })
            .collect();
        common::write_csv(
            &format!("paper_{key}_deflection.csv"),
            &[
                "time_s",
                "tip_z_hybrid_m",
                "tip_z_all_modal_m",
                "tip_z_all_ancf_m",
                "tip_y_hybrid_m",
                "tip_y_all_modal_m",
                "tip_y_all_ancf_m",
            ],
            &csv,
        )?;
        plot_deflection(&key, case, &runs, 2, " in space")?;
        let anc = comp(&runs[2].1, 2);
        let peak_abs = max_abs(&anc);
        let pct = |d: f64| format!("{} ({:.2} %)", e3(d), 100.0 * d / peak_abs);
        let _ = writeln!(
            agree,
            "| {key} | {:.3} | {} | {} | {} | {} |",
            peak_abs * 1e3,
            pct(max_diff(&comp(&runs[0].1, 2), &anc)),
            pct(max_diff(&comp(&runs[1].1, 2), &anc)),
            e3(runs
                .iter()
                .map(|(_, r)| max_abs(&comp(r, 1)))
                .fold(0.0, f64::max)),
            runs.iter()
                .map(|(_, r)| format!("{:.3}", r.wall))
                .collect::<Vec<_>>()
                .join(" / "),
        );
        for ((form, r3), (_, r2)) in runs.iter().zip(planar) {
            let z3 = comp(r3, 2);
            let y2 = ys(r2);
            let p2 = max_abs(&y2);
            let dz = max_diff(&z3, &y2);
            let dx = max_diff(&comp(r3, 0), &comp(r2, 0));
            let _ = writeln!(
                versus,
                "| {} | {form} | {:.3} | {} ({:.1e} of peak) | {} | {} | {:.3} | {:.3} | {:.1} |",
                case.key,
                p2 * 1e3,
                e3(dz),
                dz / p2,
                e3(dx),
                e3(max_abs(&comp(r3, 1))),
                r2.wall,
                r3.wall,
                r3.wall / r2.wall
            );
        }
        // spectrum of tip z over T_SPECTRUM s, shipped settings
        let mut cols = Vec::new();
        let mut spec_series = Vec::new();
        let mut peak_rows = Vec::new();
        for (form, suf) in FORMS {
            prog.item(&format!("{key} {form} {T_SPECTRUM} s"));
            let r = run_or_err(&format!("{key}{suf}"), &[], T_SPECTRUM)?;
            let sp = spectrum(&comp(&r, 2), OUT, case.f_max);
            peak_rows.push(peak_row(form, &sp, &case.beam.frequencies));
            spec_series.push(Series::line(
                form,
                sp.iter().map(|p| (p.0, p.1.max(1e-12))).collect(),
            ));
            cols.push((form, sp));
        }
        spectrum_csv(&format!("paper_{key}_spectrum_shipped.csv"), &cols)?;
        plot_spectrum(
            &format!("paper_{key}_spectrum_shipped.svg"),
            &format!(
                "{} in space, as shipped: amplitude spectrum of tip z",
                case.title
            ),
            &spec_series,
            case,
        )?;
        let head = peak_head(&case.beam.frequencies);
        let head: Vec<&str> = head.iter().map(String::as_str).collect();
        let _ = writeln!(
            sections,
            "### {key}: {}\n\n![{key} deflection](report/paper_{key}_deflection.svg)\n\n\
             CSV: `docs/report/paper_{key}_deflection.csv` (tip z and the out-of-plane tip y of each \
             formulation).\n\n![{key} spectrum](report/paper_{key}_spectrum_shipped.svg)\n\n\
             Spectrum of tip z, {T_SPECTRUM} s as shipped (CSV: `docs/report/paper_{key}_spectrum_shipped.csv`):\n\n{}",
            case.title,
            md_table(&head, &peak_rows)
        );
    }
    let _ = writeln!(
        md,
        "### Agreement of the spatial formulations (measured)\n\n\
         Over the 2 s runs, against the all-ANCF run of the same spatial case (shipped settings):\n\n\
         | case | ANCF peak \\|z\\| [mm] | max \\|z_hybrid − z_ANCF\\| [m] (of peak) | \
         max \\|z_modal − z_ANCF\\| [m] (of peak) | largest out-of-plane \\|y\\| of the three [m] | \
         wall hybrid / modal / ANCF [s] |\n|---|---|---|---|---|---|\n{agree}\n\
         ### Planar against spatial (measured)\n\n\
         Each formulation's 3D run (`caseN_3d*.toml`, tip z) against its planar run \
         (`caseN*.toml`, tip y), same rod, same solver settings, 2 s sampled every {OUT} s:\n\n\
         | case | formulation | planar peak \\|y\\| [mm] | max \\|z_3D − y_2D\\| [m] | \
         max \\|x_3D − x_2D\\| [m] | 3D max \\|y\\| [m] | planar wall [s] | spatial wall [s] | \
         wall ratio |\n|---|---|---|---|---|---|---|---|---|\n{versus}\n{sections}"
    );
    md.push_str(&strip(prog)?);
    Ok(md)
}

/// The out-of-plane strip (`scenes/strip_3d.toml`, hybrid only): tip y and z over 2 s and the
/// spectrum of both over 10 s.
fn strip(prog: &mut Progress) -> Result<String, String> {
    prog.item("strip_3d 2 s");
    let r = run_or_err("strip_3d", &[], 2.0)?;
    let rows: Vec<Vec<String>> =
        r.t.iter()
            .zip(&r.tip)
            .map(|(t, p)| {
                vec![
                    format!("{t:.4}"),
                    format!("{:.9e}", p[0]),
                    format!("{:.9e}", p[1]),
                    format!("{:.9e}", p[2]),
                ]
            })
            .collect();
    common::write_csv(
        "paper_strip_3d_deflection.csv",
        &["time_s", "tip_x_m", "tip_y_m", "tip_z_m"],
        &rows,
    )?;
    let line = |name: &str, k: usize| {
        Series::line(
            name,
            r.t.iter()
                .zip(&r.tip)
                .map(|(t, p)| (*t, p[k] * 1e3))
                .collect(),
        )
    };
    plot::plot(
        "paper_strip_3d_deflection.svg",
        &Axes {
            title: "strip_3d (4 x 0.5 mm strip, section turned 30 deg): end node",
            x: "time [s]",
            y: "tip position [mm]",
            log_x: false,
            log_y: false,
        },
        &[line("tip y (sideways)", 1), line("tip z (vertical)", 2)],
        &Extras::default(),
    )?;
    let (y, z) = (comp(&r, 1), comp(&r, 2));
    let (ymax, zmin) = (
        y.iter().fold(f64::NEG_INFINITY, |m, v| m.max(v.abs())),
        z.iter().fold(f64::INFINITY, |m, v| m.min(*v)),
    );
    let (yend, zend) = (y[y.len() - 1], z[z.len() - 1]);
    prog.item(&format!("strip_3d {T_SPECTRUM} s"));
    let long = run_or_err("strip_3d", &[], T_SPECTRUM)?;
    let f_max = 100.0;
    let cols = vec![
        ("tip-y", spectrum(&comp(&long, 1), OUT, f_max)),
        ("tip-z", spectrum(&comp(&long, 2), OUT, f_max)),
    ];
    spectrum_csv("paper_strip_3d_spectrum_shipped.csv", &cols)?;
    let largest = |sp: &[(f64, f64)]| {
        sp.iter()
            .skip(1)
            .fold((f64::NAN, 0.0f64), |a, p| if p.1 > a.1 { *p } else { a })
    };
    let (fy, ay) = largest(&cols[0].1);
    let (fz, az) = largest(&cols[1].1);
    plot::plot(
        "paper_strip_3d_spectrum_shipped.svg",
        &Axes {
            title: "strip_3d, as shipped: amplitude spectra of tip y and tip z",
            x: "frequency [Hz]",
            y: "amplitude [m]",
            log_x: false,
            log_y: true,
        },
        &cols
            .iter()
            .map(|(n, sp)| Series::line(n, sp.iter().map(|p| (p.0, p.1.max(1e-12))).collect()))
            .collect::<Vec<_>>(),
        &Extras::default(),
    )?;
    let last = long.tip[long.tip.len() - 1];
    Ok(format!(
        "### strip_3d: a strip that can only move in 3D\n\n\
         `scenes/strip_3d.toml` (hybrid, damped): a 4 mm × 0.5 mm steel strip, 40 cm, clamped with \
         its section turned 30° about its axis and released under gravity along −z. Its weak bending \
         axis is tilted, so it falls and swings sideways (tip y) at once.\n\n\
         ![strip_3d](report/paper_strip_3d_deflection.svg)\n\n\
         CSV: `docs/report/paper_strip_3d_deflection.csv`. Measured over 2 s: largest sideways \
         |tip y| {:.3} mm, lowest tip z {:.3} mm; at 2 s tip y = {:.3} mm, tip z = {:.3} mm \
         (wall {:.3} s). After {T_SPECTRUM} s: tip = ({:.5}, {:.3e}, {:.3e}) m.\n\n\
         ![strip_3d spectrum](report/paper_strip_3d_spectrum_shipped.svg)\n\n\
         Spectra of tip y and tip z over {T_SPECTRUM} s (CSV: \
         `docs/report/paper_strip_3d_spectrum_shipped.csv`): largest peak of y at {fy:.3} Hz \
         ({} m), of z at {fz:.3} Hz ({} m) (bin maxima, no interpolation).\n\n",
        ymax * 1e3,
        zmin * 1e3,
        yend * 1e3,
        zend * 1e3,
        r.wall,
        last[0],
        last[1],
        last[2],
        e3(ay),
        e3(az),
    ))
}
