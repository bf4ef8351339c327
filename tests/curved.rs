//! Initially curved ANCF segments (`initial_curvature`), each check against an independent
//! reference:
//! * the planar quarter-circle cantilever under a small tip load against Castigliano's theorem
//!   (closed form, below);
//! * the unloaded curved cantilever stays exactly at rest (a stress-free reference);
//! * the spatial 45° bend cantilever of Bathe & Bolourchi (1979) loaded out of its plane
//!   against the tip positions of Simo & Vu-Quoc (1986) (docs/references.md §11);
//! * the segment after a curved one starts on its end position and tangent (the arc's closed
//!   form), planar and spatial;
//! * every refusal of a bad `initial_curvature`.

mod common;
use common::*;
use hybeam::integrator::{EvalRequest, Integrable, StateRef};
use hybeam::model::{Model, Planar, Spatial};
use hybeam::scene::{rectangle_torsion_constant, Scene};
use hybeam::simulator::Simulator;
use std::f64::consts::PI;

/// Radius of the planar quarter circle [m] and the side of its square section [m].
const R: f64 = 1.0;
const B: f64 = 0.02;

fn ei() -> f64 {
    E_STEEL * B.powi(4) / 12.0
}
fn ea() -> f64 {
    E_STEEL * B * B
}

/// Castigliano's tip compliance of a planar clamped quarter circle (radius R, clamped at the
/// origin with tangent +x, curving counter-clockwise about the centre (0, R); the tip at
/// (R, R) with tangent +y) under a tip force F = (F_x, F_y) (F_x radial outward, F_y
/// tangential): with the section at angle φ ∈ [0, π/2] at P(φ) = R(sin φ, 1 − cos φ),
/// M(φ) = R(1 − sin φ)F_y − R cos φ F_x, N(φ) = F_x cos φ + F_y sin φ and
/// U = ∫₀^{π/2} [M²/(2EI) + N²/(2EA)] R dφ (the slender curved beam: bending and stretching,
/// no shear), δ = ∂U/∂F:
///   δ_x = (R³/EI)(π/4 F_x − ½F_y) + (R/EA)(π/4 F_x + ½F_y),
///   δ_y = (R³/EI)(−½F_x + (3π/4 − 2)F_y) + (R/EA)(½F_x + π/4 F_y).
fn castigliano_quarter(f: [f64; 2]) -> [f64; 2] {
    let (b, a) = (R.powi(3) / ei(), R / ea());
    [
        b * (PI / 4.0 * f[0] - 0.5 * f[1]) + a * (PI / 4.0 * f[0] + 0.5 * f[1]),
        b * (-0.5 * f[0] + (0.75 * PI - 2.0) * f[1]) + a * (0.5 * f[0] + PI / 4.0 * f[1]),
    ]
}

fn header_planar(force: [f64; 2]) -> String {
    format!("[tip]\nforce = [{:e}, {:e}]", force[0], force[1])
}

/// The static tip displacement of the quarter circle on `elements` ANCF elements.
fn quarter_tip(force: [f64; 2], elements: usize) -> [f64; 2] {
    let seg = ancf(
        "arc",
        0.5 * PI * R,
        &square(B),
        elements,
        &format!("initial_curvature = {:e}", 1.0 / R),
    );
    let mut sim = Simulator::<Planar>::new(scene(&header_planar(force), &[seg])).unwrap();
    sim.solve_static().unwrap();
    let p = sim.outputs().tip_position;
    [p[0] - R, p[1] - R]
}

/// Planar quarter-circle cantilever, 32 elements, tip force 2e-6·EI/R² (radial, then
/// tangential): relative error of the tip displacement vector against
/// [`castigliano_quarter`] ≤ 1e-4. Seen: `cargo test --release -p hybeam --test curved --
/// --nocapture quarter`.
#[test]
fn quarter_circle_matches_castigliano() {
    let f0 = 2e-6 * ei() / (R * R);
    for (label, f) in [("radial", [f0, 0.0]), ("tangential", [0.0, f0])] {
        let want = castigliano_quarter(f);
        for n in [8, 32] {
            let got = quarter_tip(f, n);
            let err = ((got[0] - want[0]).powi(2) + (got[1] - want[1]).powi(2)).sqrt()
                / (want[0].powi(2) + want[1].powi(2)).sqrt();
            eprintln!("quarter circle, {label} load, {n} elements: tip {got:?} Castigliano {want:?}, relative error {err:.2e}");
            if n == 32 {
                assert!(err <= 1e-4, "{label}: relative error {err:e}");
            }
        }
    }
}

/// The unloaded curved cantilever is its own stress-free reference: the residual at the initial
/// coordinates is zero to rounding (relative to EA), the static solution does not move the tip,
/// and a dynamic run stays at rest.
#[test]
fn unloaded_curved_cantilever_stays_at_rest() {
    for (k, n) in [(1.0 / R, 8), (-2.0 / R, 5)] {
        let seg = ancf(
            "arc",
            1.3 * R,
            &square(B),
            n,
            &format!("initial_curvature = {k:e}"),
        );
        let s = scene("", &[seg]);
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        let nq = model.coordinates();
        let m = model.constraints();
        let q = model.initial_coordinates().to_vec();
        let zeros = vec![0.0; nq];
        let lam = vec![0.0; m];
        let mut res = vec![0.0; nq + m];
        let req = EvalRequest {
            sd: 1.0,
            matrix: None,
            lambda_hessian: false,
        };
        model.eval(
            StateRef::new(&q, &zeros, &zeros, &lam).with_load(1.0),
            req,
            &mut res,
        );
        let worst = res.iter().fold(0.0f64, |a, r| a.max(r.abs()));
        eprintln!(
            "κ = {k}: largest residual {worst:.2e} N (EA = {:.2e} N)",
            ea()
        );
        assert!(worst <= 1e-13 * ea(), "κ = {k}: residual {worst:e}");
        // the arc's closed-form tip
        let a = k * 1.3 * R;
        let want = [a.sin() / k, (1.0 - a.cos()) / k];
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        let p0 = sim.outputs().tip_position;
        sim.solve_static().unwrap();
        let p1 = sim.outputs().tip_position;
        sim.advance(0.01).unwrap();
        let p2 = sim.outputs().tip_position;
        for p in [p0, p1, p2] {
            let d = ((p[0] - want[0]).powi(2) + (p[1] - want[1]).powi(2)).sqrt();
            assert!(d <= 1e-12 * R, "κ = {k}: tip {p:?}, arc end {want:?}");
        }
        let ang = sim.outputs().tip_angle;
        assert!((ang - a).abs() < 1e-12, "tip angle {ang} vs {a}");
    }
}

/// A curved ANCF segment followed by a straight modal segment (and, alike, a straight ANCF
/// one): the second starts on the arc's end position and tangent (positions and angle
/// continuous at the joint, the tip on the straight continuation from the arc's closed-form
/// end), and under a small tip load the tip moves as Castigliano's theorem says for the arc and
/// its straight tangent leg of length L₂ (U = ∫M²/2EI + N²/2EA over both: on the leg, at
/// distance u from its root, M = −(L₂ − u)F_x, N = F_y; on the arc
/// M = R(1 − sin φ)F_y − (L₂ + R cos φ)F_x, N = F_x cos φ + F_y sin φ; integrated by composite
/// Simpson). The modal leg is inextensible (its N²/2EA is left out for it).
#[test]
fn the_next_segment_starts_on_the_end_tangent_planar() {
    let l2 = 0.5 * R;
    let f0 = 2e-6 * ei() / (R * R);
    let arc = ancf(
        "arc",
        0.5 * PI * R,
        &square(B),
        32,
        &format!("initial_curvature = {:e}", 1.0 / R),
    );
    for (label, leg, axial_leg) in [
        ("modal", modal("leg", l2, &square(B), 2, true, ""), false),
        ("ancf", ancf("leg", l2, &square(B), 8, ""), true),
    ] {
        let s = scene("", &[arc.clone(), leg.clone()]);
        let sim = Simulator::<Planar>::new(s).unwrap();
        let o = sim.outputs();
        let want = [R, R + l2];
        let d =
            ((o.tip_position[0] - want[0]).powi(2) + (o.tip_position[1] - want[1]).powi(2)).sqrt();
        eprintln!(
            "{label} leg: initial tip {:?} (want {want:?}), angle {}",
            o.tip_position, o.tip_angle
        );
        assert!(d < 1e-12, "{label}: initial tip {:?}", o.tip_position);
        assert!(
            (o.tip_angle - 0.5 * PI).abs() < 1e-12,
            "{label}: tip angle {}",
            o.tip_angle
        );
        for f in [[f0, 0.0], [0.0, f0]] {
            let s = scene(&header_planar(f), &[arc.clone(), leg.clone()]);
            let mut sim = Simulator::<Planar>::new(s).unwrap();
            sim.solve_static().unwrap();
            let p = sim.outputs().tip_position;
            let got = [p[0] - want[0], p[1] - want[1]];
            let exp = castigliano_arc_leg(f, l2, axial_leg);
            let err = ((got[0] - exp[0]).powi(2) + (got[1] - exp[1]).powi(2)).sqrt()
                / (exp[0].powi(2) + exp[1].powi(2)).sqrt();
            eprintln!("{label} leg, force {f:?}: tip displacement {got:?}, Castigliano {exp:?}, relative error {err:.2e}");
            assert!(err <= 2e-4, "{label} leg {f:?}: relative error {err:e}");
        }
    }
}

/// The layout turns with `initial.angle`: a quarter circle (8 elements) and a straight modal leg
/// at root angle 0.4 rad have their tip at the rotated closed-form point R(0.4)(R, R + L₂) and tip
/// angle 0.4 + π/2, and the unloaded static solution keeps them.
#[test]
fn curved_layout_turns_with_the_root_angle() {
    let (a, l2) = (0.4f64, 0.5 * R);
    let arc = ancf(
        "arc",
        0.5 * PI * R,
        &square(B),
        8,
        &format!("initial_curvature = {:e}", 1.0 / R),
    );
    let leg = modal("leg", l2, &square(B), 2, true, "");
    let s = scene(&format!("[initial]\nangle = {a:e}"), &[arc, leg]);
    let (sa, ca) = a.sin_cos();
    let want = [ca * R - sa * (R + l2), sa * R + ca * (R + l2)];
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    for stage in ["initial", "static"] {
        if stage == "static" {
            sim.solve_static().unwrap();
        }
        let o = sim.outputs();
        let d =
            ((o.tip_position[0] - want[0]).powi(2) + (o.tip_position[1] - want[1]).powi(2)).sqrt();
        assert!(d < 1e-12, "{stage}: tip {:?} vs {want:?}", o.tip_position);
        assert!(
            (o.tip_angle - (a + 0.5 * PI)).abs() < 1e-12,
            "{stage}: tip angle {}",
            o.tip_angle
        );
    }
}

/// A tiny curvature loses no digits in the layout: κ = 1e-9 1/m over 2 m (planar) and
/// [κ_y, κ_z] = [0, 1e-9] (spatial): the tip at (L − κ²L³/6, κL²/2) within 1e-15 m, its lateral
/// offset to 1e-6 relative (a (sin φ₁ − sin φ₀)/κ form would lose ~7 digits here).
#[test]
fn tiny_curvature_keeps_its_digits() {
    let (k, l) = (1e-9f64, 2.0f64);
    let want = [l - k * k * l.powi(3) / 6.0, k * l * l / 2.0];
    for space in ["", "space = \"spatial\""] {
        let curv = if space.is_empty() {
            format!("{k:e}")
        } else {
            format!("[0.0, {k:e}]")
        };
        let seg = ancf(
            "arc",
            l,
            &round(0.02),
            4,
            &format!("initial_curvature = {curv}"),
        );
        let s = scene(space, &[seg]);
        let p = if space.is_empty() {
            let t = Simulator::<Planar>::new(s).unwrap().outputs().tip_position;
            [t[0], t[1]]
        } else {
            let t = Simulator::<Spatial>::new(s).unwrap().outputs().tip_position;
            assert!(t[2].abs() <= 1e-15, "z {}", t[2]);
            [t[0], t[1]]
        };
        eprintln!("κ = 1e-9 {space}: tip {p:?}, want {want:?}");
        assert!((p[0] - want[0]).abs() <= 1e-15, "{space}: {p:?}");
        assert!((p[1] - want[1]).abs() <= 1e-6 * want[1], "{space}: {p:?}");
    }
}

/// The composite Simpson rule of `f` on [a, b] with 2000 panels.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 2000;
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for k in 1..n {
        s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// Castigliano's tip displacement of the quarter circle with a straight tangent leg of length
/// `l2` ([`the_next_segment_starts_on_the_end_tangent_planar`]); `axial_leg`: count the leg's
/// stretching.
fn castigliano_arc_leg(f: [f64; 2], l2: f64, axial_leg: bool) -> [f64; 2] {
    // ∂M/∂F_i and ∂N/∂F_i are the unit-load fields; δ_i = Σ ∫ (M m_i/EI + N n_i/EA) ds
    let arc_m = |phi: f64, g: [f64; 2]| R * (1.0 - phi.sin()) * g[1] - (l2 + R * phi.cos()) * g[0];
    let arc_n = |phi: f64, g: [f64; 2]| g[0] * phi.cos() + g[1] * phi.sin();
    let leg_m = |u: f64, g: [f64; 2]| -(l2 - u) * g[0];
    let leg_n = |_: f64, g: [f64; 2]| g[1];
    let mut d = [0.0; 2];
    for (i, unit) in [[1.0, 0.0], [0.0, 1.0]].into_iter().enumerate() {
        d[i] = simpson(
            |phi| {
                (arc_m(phi, f) * arc_m(phi, unit) / ei() + arc_n(phi, f) * arc_n(phi, unit) / ea())
                    * R
            },
            0.0,
            0.5 * PI,
        ) + simpson(
            |u| {
                leg_m(u, f) * leg_m(u, unit) / ei()
                    + if axial_leg {
                        leg_n(u, f) * leg_n(u, unit) / ea()
                    } else {
                        0.0
                    }
            },
            0.0,
            l2,
        );
    }
    d
}

/// The Simpson integration of [`castigliano_arc_leg`] with no leg is the closed form
/// [`castigliano_quarter`] (the two references agree).
#[test]
fn castigliano_references_agree() {
    for f in [[1.0, 0.0], [0.0, 1.0], [0.3, -0.7]] {
        let a = castigliano_quarter(f);
        let b = castigliano_arc_leg(f, 0.0, true);
        for k in 0..2 {
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * a[0].abs().max(a[1].abs()),
                "{f:?}: {a:?} {b:?}"
            );
        }
    }
}

// ---- spatial ----

/// The 45° bend cantilever of Bathe & Bolourchi (1979): R = 100, square section A = 1,
/// I = 1/12, E = 1e7, G = E/2 (torsion J = 1/6 in the literature: here the Saint-Venant J of
/// the unit square, 0.1406, with the Poisson ratio set so that GJ = (E/2)(1/6)), in the x–y
/// plane from the origin along x, curving towards +y (κ_z = 1/R); the tip force P along +z.
fn bend_scene(p: f64, elements: usize, header_extra: &str) -> Scene {
    let e = 1e7;
    let j = rectangle_torsion_constant(1.0, 1.0);
    let g = 0.5 * e / 6.0 / j; // G·J = (E/2)(1/6)
    let nu = e / (2.0 * g) - 1.0;
    let seg = format!(
        "name = \"bend\"\nkind = \"ancf\"\nlength = {:e}\nsection = \"rectangle\"\nwidth = 1.0\nheight = 1.0\nyoungs_modulus = {e:e}\npoisson_ratio = {nu:e}\ndensity = 1.0\nelements = {elements}\ninitial_curvature = [0.0, 0.01]\n",
        0.25 * PI * 100.0
    );
    scene(
        &format!("space = \"spatial\"\n{header_extra}\n[tip]\nforce = [0.0, 0.0, {p:e}]"),
        &[seg],
    )
}

/// Tip positions of the 45° bend under the out-of-plane tip force P (docs/references.md §11):
/// Simo & Vu-Quoc (1986), P = 300: (58.84, 22.33, 40.08); P = 600: (47.23, 15.79, 53.37); and
/// at P = 600 the tip displacement of Bathe & Bolourchi (1979), (−23.5, −13.4, 53.4) in these
/// axes (along the root tangent, towards the centre side, along the load; quoted as
/// (−13.4, 53.4, −23.5) in the OpenFAST r-test `bd_curved_beam` README and the Kynema docs,
/// whose beam starts along z and curves towards +x under a load along y). Each within 1 % of
/// the radius (1.0), 16 director elements. Statics by the solver's load stepping. Seen:
/// `cargo test --release -p hybeam --test curved -- --nocapture bend`.
#[test]
fn bend_45_degree_matches_simo_vu_quoc() {
    for (p, want) in [
        (300.0, [58.84, 22.33, 40.08]),
        (600.0, [47.23, 15.79, 53.37]),
    ] {
        let mut sim = Simulator::<Spatial>::new(bend_scene(p, 16, "")).unwrap();
        let t0 = sim.outputs().tip_position;
        let r = 100.0 / 2f64.sqrt();
        assert!(
            (t0[0] - r).abs() < 1e-9 && (t0[1] - (100.0 - r)).abs() < 1e-9 && t0[2].abs() < 1e-12,
            "initial tip {t0:?}"
        );
        sim.solve_static().unwrap();
        let got = sim.outputs().tip_position;
        let d = (0..3)
            .map(|k| (got[k] - want[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        eprintln!("45° bend, P = {p}: tip {got:?}, Simo & Vu-Quoc {want:?}, distance {d:.3} (1 % of R = 1.0)");
        assert!(d <= 1.0, "P = {p}: tip {got:?} vs {want:?}");
        if p == 600.0 {
            let bb = [-23.5, -13.4, 53.4];
            let u = [0, 1, 2].map(|k| got[k] - t0[k]);
            let d = (0..3).map(|k| (u[k] - bb[k]).powi(2)).sum::<f64>().sqrt();
            eprintln!("45° bend, P = 600: tip displacement {u:?}, Bathe & Bolourchi {bb:?}, distance {d:.3}");
            assert!(d <= 1.0, "tip displacement {u:?} vs {bb:?}");
        }
    }
}

/// The spatial quarter circle (the planar one's geometry, R = 1 m, square 2 cm, x–y plane,
/// κ_z = 1/R, director elements) under a small tip force F_z out of its plane, against
/// Castigliano's theorem with bending and torsion: at the section φ the arm to the tip is
/// d = R(1 − sin φ, cos φ, 0), the moment d × F = R F_z(cos φ, −(1 − sin φ), 0); its torsion
/// T = R F_z(1 − sin φ) about the tangent (cos φ, sin φ, 0) and bending M = −R F_z cos φ about
/// the in-plane normal, so U = ∫₀^{π/2}[M²/(2EI) + T²/(2GJ)] R dφ and
///   δ_z = R³F_z [π/(4EI) + (3π/4 − 2)/(GJ)],
/// J the square's Saint-Venant constant, G = E/(2(1 + ν)), ν = 0.3. The element's error is
/// second order in the element length (the one twist rate per element): ≤ 1e-4 relative with
/// 128 elements, and the error ratio 64 → 128 elements ≈ 4. Seen (8, 16, 32, 64, 128
/// elements): 6.7e-3, 1.7e-3, 4.2e-4, 1.05e-4, 2.6e-5.
#[test]
fn spatial_quarter_circle_out_of_plane_matches_castigliano() {
    let gj = E_STEEL / 2.6 * rectangle_torsion_constant(B, B);
    let fz = 2e-6 * ei() / (R * R);
    let want = R.powi(3) * fz * (PI / (4.0 * ei()) + (0.75 * PI - 2.0) / gj);
    let errors = [64, 128].map(|ne| {
        let seg = ancf(
            "arc",
            0.5 * PI * R,
            &square(B),
            ne,
            &format!("initial_curvature = [0.0, {:e}]", 1.0 / R),
        );
        let s = scene(
            &format!("space = \"spatial\"\n[tip]\nforce = [0.0, 0.0, {fz:e}]"),
            &[seg],
        );
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        let p = sim.outputs().tip_position;
        let got = [p[0] - R, p[1] - R, p[2]];
        let err = (got[2] - want).abs() / want;
        eprintln!("spatial quarter circle, {ne} elements, out-of-plane load: tip displacement {got:?}, Castigliano δ_z = {want:e}, relative error {err:.2e}");
        assert!(got[0].abs().max(got[1].abs()) <= 1e-3 * want, "in-plane motion {got:?}");
        err
    });
    assert!(
        errors[1] <= 1e-4,
        "128 elements: relative error {:e}",
        errors[1]
    );
    let ratio = errors[0] / errors[1];
    assert!(
        (3.0..5.0).contains(&ratio),
        "error ratio 64 → 128 elements {ratio}"
    );
}

/// The unloaded spatial bend stays at rest: the residual at the initial coordinates is zero to
/// rounding (relative to EA), the static solution does not move the tip.
#[test]
fn unloaded_spatial_bend_stays_at_rest() {
    let s = bend_scene(0.0, 6, "");
    let mut model = Model::<Spatial>::from_scene(&s).unwrap();
    let nq = model.coordinates();
    let m = model.constraints();
    let q = model.initial_coordinates().to_vec();
    let zeros = vec![0.0; nq];
    let lam = vec![0.0; m];
    let mut res = vec![0.0; nq + m];
    let req = EvalRequest {
        sd: 1.0,
        matrix: None,
        lambda_hessian: false,
    };
    model.eval(
        StateRef::new(&q, &zeros, &zeros, &lam).with_load(1.0),
        req,
        &mut res,
    );
    let worst = res.iter().fold(0.0f64, |a, r| a.max(r.abs()));
    eprintln!("spatial bend: largest residual {worst:.2e} (EA = 1e7)");
    assert!(worst <= 1e-13 * 1e7, "residual {worst:e}");
}

/// Spatial: a curved director segment bent out of the root's x–y plane ([κ_y, κ_z] = [0.4, 0.3]
/// 1/m, 1 m) followed by a straight modal segment and by a straight ANCF segment: the tip is at
/// the arc's closed-form end plus the leg along the end tangent (the frame R(s) = exp(s[k]×),
/// k = (0, κ_y, κ_z), position e₁ sin(|k|s)/|k| + (n × e₁)(1 − cos(|k|s))/|k|, n = k/|k|), the
/// tip frame is the arc's end frame, both turned with the root frame (`initial.orientation`),
/// and the unloaded model stays there under the static solver.
#[test]
fn the_next_segment_starts_on_the_end_tangent_spatial() {
    let (ky, kz, l1, l2): (f64, f64, f64, f64) = (0.4, 0.3, 1.0, 0.5);
    let w = (ky * ky + kz * kz).sqrt();
    let n = [0.0, ky / w, kz / w];
    let (sn, cs) = (w * l1).sin_cos();
    // n × e₁ = (0, n_z, −n_y); tangent R e₁ = e₁ cos + (n × e₁) sin
    let end = [sn / w, n[2] * (1.0 - cs) / w, -n[1] * (1.0 - cs) / w];
    let t = [cs, n[2] * sn, -n[1] * sn];
    let want = [0, 1, 2].map(|k| end[k] + l2 * t[k]);
    let arc = ancf(
        "arc",
        l1,
        &round(0.02),
        8,
        &format!("initial_curvature = [{ky:e}, {kz:e}]"),
    );
    // the root frame: the identity, and turned by Q = 90° about z, (x, y, z) → (−y, x, z)
    let h = 0.5f64.sqrt();
    for (label, leg, turned) in [
        ("modal", modal("leg", l2, &round(0.02), 2, true, ""), false),
        ("ancf", ancf("leg", l2, &round(0.02), 4, ""), false),
        (
            "modal, turned root",
            modal("leg", l2, &round(0.02), 2, true, ""),
            true,
        ),
        (
            "ancf, turned root",
            ancf("leg", l2, &round(0.02), 4, ""),
            true,
        ),
    ] {
        let q = |v: [f64; 3]| if turned { [-v[1], v[0], v[2]] } else { v };
        let want = q(want);
        let header = if turned {
            format!("space = \"spatial\"\n[initial]\norientation = [{h:e}, 0.0, 0.0, {h:e}]")
        } else {
            "space = \"spatial\"".to_string()
        };
        let s = scene(&header, &[arc.clone(), leg]);
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        let p0 = sim.outputs().tip_position;
        sim.solve_static().unwrap();
        let p1 = sim.outputs().tip_position;
        eprintln!("spatial {label} leg: tip {p0:?}, after statics {p1:?}, want {want:?}");
        for p in [p0, p1] {
            let d = (0..3).map(|k| (p[k] - want[k]).powi(2)).sum::<f64>().sqrt();
            assert!(d < 1e-10, "{label}: tip {p:?} vs {want:?}");
        }
        // the tip's section frame is the arc's end frame R e_i = e_i cos + (n × e_i) sin +
        // n (n·e_i)(1 − cos)
        let frame = rotation_of(sim.outputs().tip_angle);
        for (i, e) in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            .iter()
            .enumerate()
        {
            let ne = [
                n[1] * e[2] - n[2] * e[1],
                n[2] * e[0] - n[0] * e[2],
                n[0] * e[1] - n[1] * e[0],
            ];
            let nd = n[0] * e[0] + n[1] * e[1] + n[2] * e[2];
            let col = q([0, 1, 2].map(|k| e[k] * cs + ne[k] * sn + n[k] * nd * (1.0 - cs)));
            for k in 0..3 {
                assert!(
                    (frame[k][i] - col[k]).abs() < 1e-10,
                    "{label}: tip frame column {i}: {:?} vs {col:?}",
                    frame.map(|r| r[i])
                );
            }
        }
    }
}

/// The rotation matrix (rows) of unit Euler parameters [e0, e1, e2, e3].
fn rotation_of(e: [f64; 4]) -> [[f64; 3]; 3] {
    let [w, x, y, z] = e;
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// Outputs that count strain count it from the arc: a coarse curved segment (half circles of
/// radius 1 m on 2 elements, planar cable and spatial director element), unloaded, under
/// `solver.max_axial_strain = 1e-6`, which the arc's own interpolated stretch ε₀ exceeds
/// (|ε₀| up to ~1e-2 on these elements, asserted): 10 ms of steps are not refused, and the
/// viewer's samples (`Simulator::shape`) show zero strain and curvature change (≤ 1e-9) while
/// the centreline lies on the circle (the nodes to 1e-12 m; between them ≤ 2e-2 m, the cubic
/// Hermite's own error on a quarter circle with unit slopes: 1.5e-2 m).
#[test]
fn strain_outputs_count_from_the_arc() {
    use hybeam::model::ancf::AncfReference;
    use hybeam::model::ancf3d::{Ancf3Props, Reference3};
    let le = 0.5 * PI;
    let e0_planar = AncfReference::arc(le, 1.0)
        .axial
        .iter()
        .fold(0.0f64, |a, e| a.max(e.abs()));
    let e0_spatial = {
        let mut s =
            hybeam::scene::Scene::from_toml(&one_segment("space = \"spatial\"", "ancf", ""))
                .unwrap();
        s.segments[0].length = PI;
        s.segments[0].elements = Some(2);
        let p = Ancf3Props::of_segment(&s.segments[0], true).unwrap();
        Reference3::arc(&p, [0.0, 1.0])
            .axial
            .iter()
            .fold(0.0f64, |a, e| a.max(e.abs()))
    };
    eprintln!("largest |ε₀| on a quarter-circle element: planar {e0_planar:.2e}, spatial {e0_spatial:.2e}");
    assert!(e0_planar > 1e-4 && e0_spatial > 1e-4);
    for (space, curv) in [("", "1.0"), ("space = \"spatial\"", "[0.0, 1.0]")] {
        let seg = ancf(
            "arc",
            PI,
            &round(0.02),
            2,
            &format!("initial_curvature = {curv}"),
        );
        let s = scene(
            &format!("{space}\n[solver]\nmax_axial_strain = 1e-6"),
            &[seg],
        );
        let spatial = !space.is_empty();
        let shape = if spatial {
            let mut sim = Simulator::<Spatial>::new(s).unwrap();
            sim.advance(0.01).unwrap_or_else(|e| panic!("spatial: {e}"));
            sim.shape(8)
        } else {
            let mut sim = Simulator::<Planar>::new(s).unwrap();
            sim.advance(0.01).unwrap_or_else(|e| panic!("planar: {e}"));
            sim.shape(8)
        };
        let mut worst = [0.0f64; 3];
        for (k, p) in shape.points.iter().enumerate() {
            worst[0] = worst[0].max(p.axial_strain.abs());
            worst[1] = worst[1].max(p.bending()).max(p.twist.abs());
            // distance from the circle of centre (0, 1)
            let r = (p.position[0].powi(2) + (p.position[1] - 1.0).powi(2) + p.position[2].powi(2))
                .sqrt();
            worst[2] = worst[2].max((r - 1.0).abs());
            if k % 8 == 0 {
                assert!((r - 1.0).abs() <= 1e-12, "node {}: {:?}", k / 8, p.position);
            }
        }
        eprintln!(
            "{}: samples' largest |ε| {:.1e}, |κ|, |τ| {:.1e}, off the circle {:.1e} m",
            if spatial { "spatial" } else { "planar" },
            worst[0],
            worst[1],
            worst[2]
        );
        assert!(worst[0] <= 1e-9 && worst[1] <= 1e-9, "{space}: {worst:?}");
        assert!(worst[2] <= 2e-2, "{space}: {worst:?}");
    }
}

/// The Newton matrix of curved segments (stiffness with the reference measures subtracted,
/// Kelvin–Voigt damping, the joint to a modal leg on the arc's end frame) against central
/// differences of the residual ([`check_newton_matrix`]: 1e-6·(1 + |entry|)), planar (cable,
/// exact strain) and spatial (director element).
#[test]
fn newton_matrix_of_curved_segments() {
    let planar = scene(
        "",
        &[
            ancf(
                "arc",
                1.0,
                &round(0.02),
                3,
                "initial_curvature = 1.2\ndamping_time = 1e-3",
            ),
            modal("leg", 0.4, &round(0.02), 2, true, ""),
        ],
    );
    let mut model = Model::<Planar>::from_scene(&planar).unwrap();
    model.set_tip_force([0.3, -0.7]);
    let worst = check_newton_matrix(&mut model);
    eprintln!("planar: worst error {worst:.2e} of the tolerance");
    let spatial = scene(
        "space = \"spatial\"",
        &[
            ancf(
                "arc",
                1.0,
                &round(0.02),
                3,
                "initial_curvature = [0.4, -0.9]\ndamping_time = 1e-3",
            ),
            modal("leg", 0.4, &round(0.02), 2, true, ""),
        ],
    );
    let mut model = Model::<Spatial>::from_scene(&spatial).unwrap();
    model.set_tip_force([0.3, -0.7, 0.2]);
    let worst = check_newton_matrix(&mut model);
    eprintln!("spatial: worst error {worst:.2e} of the tolerance");
}

// ---- refusals ----

fn refused(text: &str) -> String {
    match Scene::from_toml(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn one_segment(header: &str, kind: &str, extra: &str) -> String {
    let seg = match kind {
        "modal" => modal("s", 1.0, &square(0.02), 2, false, extra),
        _ => ancf("s", 1.0, &square(0.02), 4, extra),
    };
    format!("name = \"t\"\n{header}\n[[segments]]\n{seg}")
}

#[test]
fn bad_curvatures_are_refused() {
    let cases: [(&str, &str, &str, &[&str]); 8] = [
        (
            "",
            "modal",
            "initial_curvature = 1.0",
            &["initial_curvature = 1", "make the segment ANCF"],
        ),
        (
            "",
            "ancf",
            "initial_curvature = 60.0",
            &["initial_curvature = 60", "radius", "depth 0.02"],
        ),
        (
            "",
            "ancf",
            "initial_curvature = [0.0, 1.0]",
            &["initial_curvature = [0.0, 1.0]", "one number"],
        ),
        (
            "space = \"spatial\"",
            "ancf",
            "initial_curvature = 1.0",
            &["initial_curvature = 1", "[κ_y, κ_z]"],
        ),
        (
            "space = \"spatial\"",
            "ancf",
            "initial_curvature = [1.0]",
            &["initial_curvature = [1.0]", "[κ_y, κ_z]"],
        ),
        (
            "space = \"spatial\"",
            "ancf",
            "initial_curvature = [60.0, 0.0]",
            &["initial_curvature = [60.0, 0.0]", "radius"],
        ),
        (
            "",
            "ancf",
            "initial_curvature = 1.0\nstrain = \"paper\"",
            &["initial_curvature = 1", "strain = \"paper\""],
        ),
        (
            "space = \"spatial\"\ntorsion_element = \"angle\"",
            "ancf",
            "initial_curvature = [0.0, 1.0]",
            &["torsion_element = \"angle\"", "director"],
        ),
    ];
    for (header, kind, extra, needles) in cases {
        let e = refused(&one_segment(header, kind, extra));
        eprintln!("{e}");
        for n in needles {
            assert!(e.contains(n), "{e:?} lacks {n:?}");
        }
    }
    let e = refused(&one_segment(
        "space = \"spatial\"\ntorsion = false",
        "ancf",
        "initial_curvature = [0.0, 1.0]",
    ));
    assert!(e.contains("torsion = false"), "{e}");
    let e = refused(&one_segment("", "ancf", "initial_curvature = nan"));
    assert!(e.contains("finite"), "{e}");
    // a curved scene round-trips through its TOML text (the number and the list forms)
    for (header, curv) in [("", "1.5"), ("space = \"spatial\"", "[0.25, -1.5]")] {
        let text = one_segment(header, "ancf", &format!("initial_curvature = {curv}"));
        let s = Scene::from_toml(&text).unwrap();
        let back = Scene::from_toml(&s.to_toml()).unwrap();
        assert_eq!(back, s, "{}", s.to_toml());
        assert!(back.segments[0].curvature().is_some());
    }
    // a curvature just inside the depth limit is accepted, as is zero on a modal segment
    Scene::from_toml(&one_segment("", "ancf", "initial_curvature = 49.0")).unwrap();
    Scene::from_toml(&one_segment("", "modal", "initial_curvature = 0.0")).unwrap();
}
