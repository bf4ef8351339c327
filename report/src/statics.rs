//! Static references: tip-loaded cantilever (elastica, α = PL²/EI) and cantilever under its own
//! weight (γ = qL³/EI), error vs number of ANCF elements, against the tables of
//! docs/references.md §4a/§4b and against an extensible-elastica shooting solution computed here.

use super::common::{self, e3, md_table, Progress};
use super::plot::{self, Axes, Extras, Series};
use hybeam::model::Planar;
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use hybeam_references::{Deflection, ELASTICA, SELF_WEIGHT};
use std::fmt::Write as _;

/// Slender square steel cantilever of the physics tests: L = 1 m, b = 1 cm.
const L: f64 = 1.0;
const B: f64 = 0.01;
const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;

fn ei() -> f64 {
    E * B.powi(4) / 12.0
}

fn ea() -> f64 {
    E * B * B
}

/// Planar elastica of a cantilever clamped horizontally at the origin, with tip force `f` and
/// load `q` per undeformed length, axial stretch 1 + N/EA (`ea` = ∞ for inextensible).
/// Shooting on the root moment with bisection; RK4 along the arc length. Returns the tip.
pub fn elastica(ea: f64, ei: f64, f: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    let n = 4000;
    let ds = L / n as f64;
    // y = [θ, m, x, y]
    let rhs = |s: f64, y: [f64; 4]| -> [f64; 4] {
        let r = [f[0] + q[0] * (L - s), f[1] + q[1] * (L - s)];
        let (sn, cs) = y[0].sin_cos();
        let lam = 1.0 + (r[0] * cs + r[1] * sn) / ea;
        [
            y[1] / ei,
            -lam * (cs * r[1] - sn * r[0]),
            lam * cs,
            lam * sn,
        ]
    };
    let shoot = |m0: f64| -> [f64; 4] {
        let mut y = [0.0, m0, 0.0, 0.0];
        for k in 0..n {
            let s = k as f64 * ds;
            let add = |a: [f64; 4], b: [f64; 4], h: f64| {
                [
                    a[0] + h * b[0],
                    a[1] + h * b[1],
                    a[2] + h * b[2],
                    a[3] + h * b[3],
                ]
            };
            let k1 = rhs(s, y);
            let k2 = rhs(s + ds / 2.0, add(y, k1, ds / 2.0));
            let k3 = rhs(s + ds / 2.0, add(y, k2, ds / 2.0));
            let k4 = rhs(s + ds, add(y, k3, ds));
            for i in 0..4 {
                y[i] += ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    };
    // the root moment lies between 0 and the linear (straight-beam) value
    let lin = L * f[1] + q[1] * L * L / 2.0;
    let (mut a, mut b) = (lin * 1.01, 0.0);
    let ga = shoot(a)[1];
    for _ in 0..80 {
        let mid = 0.5 * (a + b);
        let gm = shoot(mid)[1];
        if (gm > 0.0) == (ga > 0.0) {
            a = mid;
        } else {
            b = mid;
        }
    }
    let y = shoot(0.5 * (a + b));
    [y[2], y[3]]
}

fn beam_scene(header: &str, elements: usize) -> Result<Scene, String> {
    let text = format!(
        "name = \"static\"\n{header}\n[[segments]]\nname = \"rod\"\nkind = \"ancf\"\nlength = {L:e}\n\
         section = \"rectangle\"\nwidth = {B:e}\nheight = {B:e}\nyoungs_modulus = {E:e}\n\
         density = {RHO:e}\nelements = {elements}\n"
    );
    Scene::from_toml(&text).map_err(|e| e.0)
}

/// Runs the static study; returns the markdown section.
pub fn run(quick: bool) -> Result<String, String> {
    let ns: &[usize] = if quick {
        &[2, 4, 8, 16, 32, 64]
    } else {
        &[2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]
    };
    let mut prog = Progress::new("statics", 8 * ns.len());
    let rho_a = RHO * B * B;
    let mut csv = Vec::new();
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Static references (docs/references.md §4a, §4b)\n\nSquare steel cantilever L = 1 m, b = 1 cm \
         (EA·L²/EI = {:.0}), all-ANCF, `Simulator::solve_static()` after loading through the scene \
         (`tip.force` for the elastica, `gravity` for the self-weight). Errors are max(|Δv|, |Δu|)/L of \
         the tip. *vs table*: against the 5-digit tables (inextensible theory; their rounding and \
         the rod's extensibility limit the attainable error to about 1e-5…1e-4). *vs shooting*: against \
         an extensible-elastica shooting solution with this rod's EA and EI (computed by the report, \
         RK4 with 4000 steps; its inextensible variant is checked against the table below).\n",
        ea() * L * L / ei()
    );
    let mut check_rows = Vec::new();
    let mut at32 = Vec::new();
    let mut plots: Vec<(String, Vec<Series>)> = Vec::new();
    for (kind, table) in [("tip load", ELASTICA), ("self-weight", SELF_WEIGHT)] {
        let mut series = Vec::new();
        for Deflection {
            load: p,
            v: v_tab,
            u: u_tab,
        } in table
        {
            let (header, f, q) = if kind == "tip load" {
                let fy = -p * ei() / (L * L);
                (
                    format!("[tip]\nforce = [0.0, {fy:e}]"),
                    [0.0, fy],
                    [0.0, 0.0],
                )
            } else {
                let g = p * ei() / (rho_a * L.powi(3));
                (
                    format!("gravity = [0.0, {:e}]", -g),
                    [0.0, 0.0],
                    [0.0, -rho_a * g],
                )
            };
            let ext = elastica(ea(), ei(), f, q);
            let inext = elastica(f64::INFINITY, ei(), f, q);
            let (v_ext, u_ext) = (-ext[1] / L, (L - ext[0]) / L);
            let (v_in, u_in) = (-inext[1] / L, (L - inext[0]) / L);
            let sym = if kind == "tip load" { "α" } else { "γ" };
            check_rows.push(vec![
                kind.to_string(),
                format!("{sym} = {p}"),
                format!("{v_tab:.5} / {u_tab:.5}"),
                format!("{v_in:.6} / {u_in:.6}"),
                e3((v_in - v_tab).abs().max((u_in - u_tab).abs())),
                format!("{v_ext:.6} / {u_ext:.6}"),
            ]);
            let mut pts = Vec::new();
            for &n in ns {
                prog.item(&format!("{kind} {sym}={p} {n} el."));
                let s = beam_scene(&header, n)?;
                let mut sim = Simulator::<Planar>::new(s).map_err(|e| e.to_string())?;
                let (it, tip, status) = match sim.solve_static() {
                    Ok(it) => (it, sim.outputs().tip_position, "ok".to_string()),
                    Err(e) => (0, [f64::NAN; 2], format!("refused: {e}")),
                };
                let (v, u) = (-tip[1] / L, (L - tip[0]) / L);
                let err_tab = (v - v_tab).abs().max((u - u_tab).abs());
                let err_ext = (v - v_ext).abs().max((u - u_ext).abs());
                pts.push((n as f64, err_ext));
                if n == 32 {
                    at32.push(vec![
                        kind.to_string(),
                        format!("{sym} = {p}"),
                        format!("{v:.6}"),
                        format!("{u:.6}"),
                        e3(err_tab),
                        e3(err_ext),
                        it.to_string(),
                    ]);
                }
                csv.push(vec![
                    kind.to_string(),
                    p.to_string(),
                    n.to_string(),
                    format!("{v:.10}"),
                    format!("{u:.10}"),
                    format!("{v_tab}"),
                    format!("{u_tab}"),
                    format!("{v_ext:.10}"),
                    format!("{u_ext:.10}"),
                    format!("{err_tab:e}"),
                    format!("{err_ext:e}"),
                    it.to_string(),
                    status,
                ]);
            }
            series.push(Series::marked(&format!("{sym} = {p}"), pts));
        }
        plots.push((kind.to_string(), series));
    }
    prog.finish();
    common::write_csv(
        "statics.csv",
        &[
            "load",
            "parameter",
            "elements",
            "v_over_L",
            "u_over_L",
            "v_table",
            "u_table",
            "v_shooting_ext",
            "u_shooting_ext",
            "err_vs_table",
            "err_vs_shooting",
            "newton_iterations",
            "status",
        ],
        &csv,
    )?;
    for (kind, series) in &plots {
        let file = format!("statics_{}.svg", kind.replace([' ', '-'], "_"));
        plot::plot(
            &file,
            &Axes {
                title: &format!("Static {kind}: tip error vs elements (vs extensible elastica)"),
                x: "ANCF elements",
                y: "max(|dv|, |du|) / L",
                log_x: true,
                log_y: true,
            },
            series,
            &Extras::default(),
        )?;
        let _ = writeln!(md, "![{kind}](report/{file})\n");
    }
    let _ = writeln!(
        md,
        "At 32 elements:\n\n{}",
        md_table(
            &[
                "load",
                "parameter",
                "v/L",
                "u/L",
                "error vs table",
                "error vs extensible shooting",
                "Newton it."
            ],
            &at32,
        )
    );
    let _ = writeln!(
        md,
        "Shooting check (v/L / u/L):\n\n{}\nCSV: `docs/report/statics.csv`.\n",
        md_table(
            &[
                "load",
                "parameter",
                "table",
                "inextensible shooting",
                "\\|shooting − table\\|",
                "extensible shooting (this rod)"
            ],
            &check_rows,
        )
    );
    Ok(md)
}
