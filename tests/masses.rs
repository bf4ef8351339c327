//! Attached point masses (`[[masses]]`, issue 39 item 1) against independent references:
//! - the Newton matrices with masses on ANCF and modal segments against central differences;
//! - a cantilever with a tip mass M: its first two bending frequencies against the roots of the
//!   exact frequency equation 1 + cos β cosh β + μβ (cos β sinh β − sin β cosh β) = 0,
//!   ω = β²√(EI/(ρA L⁴)), μ = M/(ρAL) (Blevins, Formulas for Natural Frequency and Mode Shape,
//!   Table 8-1 case 4; docs/references.md §10), solved here by bisection;
//! - a point mass's weight: the static tip deflection P a²(3L − a)/(6EI) of a load P at a
//!   (Roark's Formulas for Stress and Strain, Table 8.1 case 1a) plus the beam's own qL⁴/(8EI);
//! - the support reaction and the mount's rigid inertia against the rigid sums;
//! - an undamped swinging beam with a mass: kinetic + strain + gravity energy constant, the
//!   gravity potential at the start against −gᵀ(∫ρA r dx + m r_m).

mod common;
use common::*;
use hybeam::model::{Model, Planar, Space, Spatial};
use hybeam::simulator::Simulator;

/// Rod: L = 0.4 m, steel, round d = 2 mm.
const L: f64 = 0.4;
const D: f64 = 0.002;

fn rho_a() -> f64 {
    RHO_STEEL * std::f64::consts::PI * D * D / 4.0
}

fn ei() -> f64 {
    E_STEEL * std::f64::consts::PI * D.powi(4) / 64.0
}

/// A `[[masses]]` table.
fn mass_table(name: &str, segment: &str, at: f64, mass: f64) -> String {
    format!(
        "[[masses]]\nname = \"{name}\"\nsegment = \"{segment}\"\nat = {at:e}\nmass = {mass:e}\n"
    )
}

/// A scene from a header, segments and trailing tables (masses).
fn scene_with(header: &str, segments: &[String], tail: &str) -> hybeam::scene::Scene {
    let mut text = format!("name = \"test\"\n{header}\n");
    for s in segments {
        text.push_str("[[segments]]\n");
        text.push_str(s);
        text.push('\n');
    }
    text.push_str(tail);
    hybeam::scene::Scene::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The lowest two roots β > 0.05 of `f` (a scan for sign changes in steps of 1e-3, then
/// bisection to rounding).
fn lowest_two_roots(f: impl Fn(f64) -> f64) -> [f64; 2] {
    let mut roots = Vec::new();
    let mut b0 = 0.05;
    while roots.len() < 2 {
        let b1 = b0 + 1e-3;
        if f(b0).signum() != f(b1).signum() {
            let (mut lo, mut hi) = (b0, b1);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if f(lo).signum() == f(mid).signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            roots.push(0.5 * (lo + hi));
        }
        b0 = b1;
    }
    [roots[0], roots[1]]
}
/// The lowest two roots β of 1 + cos β cosh β + μβ(cos β sinh β − sin β cosh β) = 0.
fn tip_mass_roots(mu: f64) -> [f64; 2] {
    let f = |b: f64| 1.0 + b.cos() * b.cosh() + mu * b * (b.cos() * b.sinh() - b.sin() * b.cosh());
    lowest_two_roots(f)
}

/// The exact first two bending frequencies [Hz] of the rod with tip mass ratio μ.
fn tip_mass_frequencies(mu: f64) -> [f64; 2] {
    let w = (ei() / (rho_a() * L.powi(4))).sqrt();
    tip_mass_roots(mu).map(|b| b * b * w / std::f64::consts::TAU)
}

fn check_frequencies(name: &str, got: [f64; 2], want: [f64; 2], tol: f64) -> f64 {
    let mut worst = 0.0f64;
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        let rel = g / w - 1.0;
        eprintln!(
            "{name}: f{} = {g:.6} Hz, exact {w:.6} Hz, error {rel:+.2e}",
            i + 1
        );
        worst = worst.max(rel.abs());
        assert!(rel.abs() < tol, "{name}: f{} error {rel:e}", i + 1);
    }
    worst
}

/// The lowest two bending frequencies [Hz] of the linearized model (planar: the lowest two;
/// spatial, round section: the lowest two pairs, each pair equal).
fn bending_frequencies<S: Space>(model: &mut Model<S>, spatial: bool) -> [f64; 2] {
    let f: Vec<f64> = linearized_modes(model).iter().map(|m| m.0).collect();
    if spatial {
        for k in [0, 2] {
            assert!((f[k + 1] / f[k] - 1.0).abs() < 1e-8, "pair {k}: {f:?}");
        }
        [f[0], f[2]]
    } else {
        [f[0], f[1]]
    }
}

/// The test rods, each with the tip mass on its last segment: (label, segments, the segment
/// carrying the mass).
fn rods() -> Vec<(&'static str, Vec<String>, &'static str)> {
    let r = round(D);
    vec![
        ("all-ANCF", vec![ancf("a", L, &r, 16, "")], "a"),
        ("all-modal", vec![modal("m", L, &r, 8, true, "")], "m"),
        (
            "hybrid modal+ANCF",
            vec![
                modal("m", 0.5 * L, &r, 6, true, ""),
                ancf("a", 0.5 * L, &r, 12, ""),
            ],
            "a",
        ),
        (
            "hybrid ANCF+modal",
            vec![
                ancf("a", 0.5 * L, &r, 12, ""),
                modal("m", 0.5 * L, &r, 6, true, ""),
            ],
            "m",
        ),
    ]
}

#[test]
fn tip_mass_frequencies_match_the_exact_frequency_equation() {
    // the equation's limits: μ = 0 gives the clamped–free roots 1.8751, 4.6941
    let b0 = tip_mass_roots(0.0);
    assert!((b0[0] - 1.875_104_068_711_961).abs() < 1e-12);
    assert!((b0[1] - 4.694_091_132_974_175).abs() < 1e-12);
    let mu = 0.5;
    let m = mu * rho_a() * L;
    let want = tip_mass_frequencies(mu);
    let mut worst = 0.0f64;
    for (label, segs, on) in rods() {
        let len: f64 = if segs.len() == 1 { L } else { 0.5 * L };
        let tail = mass_table("tip", on, len, m);
        for spatial in [false, true] {
            // a cable (torsion = false) passes no torque to a modal segment after it: the
            // director element there
            let torsion = label == "hybrid ANCF+modal";
            let header = if spatial {
                format!("space = \"spatial\"\ntorsion = {torsion}\ngravity = [0.0, 0.0, 0.0]")
            } else {
                "gravity = [0.0, 0.0]".to_string()
            };
            let s = scene_with(&header, &segs, &tail);
            let got = if spatial {
                bending_frequencies(&mut Model::<Spatial>::from_scene(&s).unwrap(), true)
            } else {
                bending_frequencies(&mut Model::<Planar>::from_scene(&s).unwrap(), false)
            };
            let space = if spatial { "spatial" } else { "planar" };
            worst = worst.max(check_frequencies(
                &format!("{space} {label}, mu = {mu}"),
                got,
                want,
                1e-4,
            ));
        }
    }
    eprintln!("worst relative frequency error {worst:.2e}");
}

#[test]
fn newton_matrices_with_masses_match_central_differences() {
    let r = round(0.004);
    let segs = [
        modal("m1", 0.2, &r, 3, true, "damping_ratio = 0.05"),
        ancf("a", 0.2, &r, 2, "damping_time = 1e-3"),
        modal("m2", 0.2, &r, 2, false, ""),
    ];
    let tail = [
        mass_table("p1", "m1", 0.07, 0.01),
        mass_table("p2", "a", 0.1, 0.02),
        mass_table("p3", "a", 0.13, 0.005),
        mass_table("p4", "m2", 0.2, 0.03),
    ]
    .concat();
    for lin in [false, true] {
        let segs: Vec<String> = segs
            .iter()
            .map(|s| {
                if lin && s.contains("modal") {
                    format!("{s}linear = true\n")
                } else {
                    s.clone()
                }
            })
            .collect();
        let s = scene_with("root = \"pinned\"\ngravity = [1.0, -9.81]", &segs, &tail);
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7]);
        let w = check_newton_matrix(&mut model);
        eprintln!("planar, linear = {lin}: worst error {w:.2e} of the tolerance");
        for torsion in [
            "torsion = true",
            "torsion_element = \"angle\"",
            "torsion = false",
        ] {
            // a cable passes no torque to a modal segment after it: the cable without m2
            let segs = if torsion == "torsion = false" {
                &segs[..2]
            } else {
                &segs[..]
            };
            let tail = if torsion == "torsion = false" {
                &tail[..tail.rfind("[[masses]]").unwrap()]
            } else {
                &tail[..]
            };
            let s = scene_with(
                &format!(
                    "space = \"spatial\"\n{torsion}\nroot = \"ball\"\ngravity = [0.0, 1.0, -9.81]"
                ),
                segs,
                tail,
            );
            let mut model = Model::<Spatial>::from_scene(&s).unwrap();
            model.set_tip_force([0.3, -0.7, 0.2]);
            let w = check_newton_matrix(&mut model);
            eprintln!("spatial {torsion}, linear = {lin}: worst error {w:.2e} of the tolerance");
        }
    }
}

#[test]
fn point_mass_weight_deflects_the_tip_as_roark() {
    // square b = 1 cm, L = 1 m, light material (ρ = 1 kg/m³) so that the tip deflection stays
    // near 1e-4 L (linear range); P = m g at a = 0.6 L on a node of the mesh
    let (l, b, g): (f64, f64, f64) = (1.0, 0.01, 9.81);
    let ei = E_STEEL * b.powi(4) / 12.0;
    let rho = 1.0;
    let q = rho * b * b * g;
    let (a, m) = (0.6 * l, 0.0124);
    let p = m * g;
    let want = p * a * a * (3.0 * l - a) / (6.0 * ei) + q * l.powi(4) / (8.0 * ei);
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = {l:e}\n{}\nyoungs_modulus = {E_STEEL:e}\ndensity = {rho:e}\nelements = 10\n",
        square(b)
    );
    let tail = mass_table("load", "rod", a, m);
    let planar = scene_with(
        &format!("gravity = [0.0, {:e}]", -g),
        std::slice::from_ref(&seg),
        &tail,
    );
    let mut sim = Simulator::<Planar>::new(planar).unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    let got = -o.tip_position[1];
    let rel = got / want - 1.0;
    eprintln!("planar: tip deflection {got:.9e} m, Roark {want:.9e} m, error {rel:+.2e}");
    assert!(rel.abs() < 1e-6, "{rel:e}");
    // the support carries the beam's and the mass's weight, and their moment
    let weight = (rho * b * b * l + m) * g;
    assert!(
        (o.root_force[1] / weight - 1.0).abs() < 1e-10,
        "{:?}",
        o.root_force
    );
    let moment = (rho * b * b * l * l / 2.0 + m * a) * g;
    let rm = hybeam::model::Planar::moment_components(&o.root_moment)[0];
    assert!((rm / moment - 1.0).abs() < 1e-3, "{rm} vs {moment}");
    for torsion in ["torsion = false", "torsion = true"] {
        let spatial = scene_with(
            &format!(
                "space = \"spatial\"\n{torsion}\ngravity = [0.0, 0.0, {:e}]",
                -g
            ),
            std::slice::from_ref(&seg),
            &tail,
        );
        let mut sim = Simulator::<Spatial>::new(spatial).unwrap();
        sim.solve_static().unwrap();
        let got = -sim.outputs().tip_position[2];
        let rel = got / want - 1.0;
        eprintln!(
            "spatial {torsion}: tip deflection {got:.9e} m, Roark {want:.9e} m, error {rel:+.2e}"
        );
        assert!(rel.abs() < 1e-6, "{rel:e}");
    }
}

#[test]
fn mount_rigid_inertia_includes_the_masses() {
    // a mounted rod (modal then ANCF) with a mass on each segment: mass, centre of mass and
    // inertia about the mount point against the rigid sums of the straight rod and the points
    let r = round(D);
    let segs = [
        modal("m", 0.5 * L, &r, 3, true, ""),
        ancf("a", 0.5 * L, &r, 4, ""),
    ];
    let (m1, x1, m2, x2) = (0.01, 0.13, 0.02, 0.1);
    let tail = [mass_table("p1", "m", x1, m1), mass_table("p2", "a", x2, m2)].concat();
    let (x1, x2) = (x1, 0.5 * L + x2);
    let mb = rho_a() * L;
    let mass = mb + m1 + m2;
    let com = (mb * L / 2.0 + m1 * x1 + m2 * x2) / mass;
    let izz = mb * L * L / 3.0 + m1 * x1 * x1 + m2 * x2 * x2;
    for spatial in [false, true] {
        let header = if spatial {
            "space = \"spatial\"\ntorsion = false\nroot = \"mounted\"\ngravity = [0.0, 0.0, -9.81]"
        } else {
            "root = \"mounted\"\ngravity = [0.0, -9.81]"
        };
        let s = scene_with(header, &segs, &tail);
        let (m, c, i) = if spatial {
            let sim = Simulator::<Spatial>::new(s).unwrap();
            let mi = sim.outputs().mount.unwrap();
            (mi.mass, mi.center_of_mass[0], mi.inertia[8])
        } else {
            let sim = Simulator::<Planar>::new(s).unwrap();
            let mi = sim.outputs().mount.unwrap();
            (mi.mass, mi.center_of_mass[0], mi.inertia[0])
        };
        eprintln!("spatial {spatial}: mass {m:.9e} ({mass:.9e}), com {c:.9e} ({com:.9e}), Izz {i:.9e} ({izz:.9e})");
        assert!((m / mass - 1.0).abs() < 1e-12);
        assert!((c / com - 1.0).abs() < 1e-12);
        assert!((i / izz - 1.0).abs() < 1e-9);
    }
}

#[test]
fn swinging_beam_with_masses_keeps_its_energy() {
    // a pinned (planar) or ball-rooted (spatial) hybrid rod with a mass on each segment,
    // released horizontal under gravity, undamped: total energy constant over 0.5 s; the start's
    // gravity potential with gravity (g_x, g_y) against −g_x(ρA L²/2 + Σ m x_m)
    let r = round(0.004);
    let rho_a = RHO_STEEL * std::f64::consts::PI * 0.004f64.powi(2) / 4.0;
    let segs = [
        modal("m", 0.5 * L, &r, 4, true, ""),
        ancf("a", 0.5 * L, &r, 6, ""),
    ];
    let (m1, x1, m2, x2) = (0.02, 0.1, 0.03, 0.2);
    let tail = [mass_table("p1", "m", x1, m1), mass_table("p2", "a", x2, m2)].concat();
    let (x1, x2) = (x1, 0.5 * L + x2);
    let (gx, g) = (0.5, 9.81);
    let scale = (rho_a * L + m1 + m2) * g * L / 2.0;
    let want_u0 = -gx * (rho_a * L * L / 2.0 + m1 * x1 + m2 * x2);
    let solver =
        "[solver]\nrho_inf = 0.99\nmax_step = 2.5e-4\ntolerance = 1e-11\nmax_iterations = 20\n";
    for spatial in [false, true] {
        let header = if spatial {
            format!("space = \"spatial\"\ntorsion = false\nroot = \"ball\"\ngravity = [{gx:e}, 0.0, {:e}]\n{solver}", -g)
        } else {
            format!("root = \"pinned\"\ngravity = [{gx:e}, {:e}]\n{solver}", -g)
        };
        let s = scene_with(&header, &segs, &tail);
        let energy = |k: f64, u: f64, p: f64| k + u + p;
        let (u0, mut drift, mut kmax) = if spatial {
            let mut sim = Simulator::<Spatial>::new(s).unwrap();
            let o = sim.outputs();
            let (u0, e0) = (o.potential, energy(o.kinetic, o.strain, o.potential));
            let (mut d, mut km) = (0.0f64, 0.0f64);
            for k in 1..=500 {
                sim.advance(k as f64 * 1e-3).unwrap();
                let o = sim.outputs();
                d = d.max((energy(o.kinetic, o.strain, o.potential) - e0).abs());
                km = km.max(o.kinetic);
            }
            (u0, d, km)
        } else {
            let mut sim = Simulator::<Planar>::new(s).unwrap();
            let o = sim.outputs();
            let (u0, e0) = (o.potential, energy(o.kinetic, o.strain, o.potential));
            let (mut d, mut km) = (0.0f64, 0.0f64);
            for k in 1..=500 {
                sim.advance(k as f64 * 1e-3).unwrap();
                let o = sim.outputs();
                d = d.max((energy(o.kinetic, o.strain, o.potential) - e0).abs());
                km = km.max(o.kinetic);
            }
            (u0, d, km)
        };
        drift /= scale;
        kmax /= scale;
        eprintln!(
            "spatial {spatial}: start potential {u0:.12e} J (closed form {want_u0:.12e}), energy drift {drift:.2e} of m g L/2, peak kinetic {kmax:.3} of it"
        );
        assert!((u0 / want_u0 - 1.0).abs() < 1e-12);
        assert!(kmax > 0.5, "it swings: {kmax}");
        assert!(drift < 1e-3, "{drift:e}");
    }
}

#[test]
fn offset_and_rotary_inertia_are_refused_on_spatial_cables_only() {
    // modelled in planar scenes and on spatial sections (director, angle, modal); refused on
    // the 3D cable (torsion = false), which has no section frame about its axis
    let segs = [
        ancf("a", 0.5 * L, &round(D), 2, ""),
        modal("m", 0.5 * L, &round(D), 2, true, ""),
    ];
    for (on, extra, spatial_extra) in [
        ("m", "inertia = [1e-4]", "inertia = [1e-4, 0.0, 0.0]"),
        ("a", "offset = [0.0, 0.01]", "offset = [0.0, 0.01, 0.0]"),
        ("a", "inertia = [1e-4]", "inertia = [0.0, 2e-4, 2e-4]"),
    ] {
        let tail = format!("{}{extra}\n", mass_table("p", on, 0.1, 0.01));
        let s = scene_with("gravity = [0.0, -9.81]", &segs, &tail);
        assert!(Model::<Planar>::from_scene(&s).is_ok());
        let tail = format!("{}{spatial_extra}\n", mass_table("p", on, 0.1, 0.01));
        for torsion in ["torsion = true", "torsion_element = \"angle\""] {
            let s = scene_with(
                &format!("space = \"spatial\"\n{torsion}\ngravity = [0.0, 0.0, -9.81]"),
                &segs,
                &tail,
            );
            assert!(Model::<Spatial>::from_scene(&s).is_ok(), "{torsion} {tail}");
        }
        // the cable: only the cable scene without the modal segment after it (no torque)
        let s = scene_with(
            "space = \"spatial\"\ntorsion = false\ngravity = [0.0, 0.0, -9.81]",
            &segs[..1],
            &tail.replace("segment = \"m\"", "segment = \"a\""),
        );
        let err = Model::<Spatial>::from_scene(&s).unwrap_err().0;
        let field = if spatial_extra.starts_with("offset") {
            "masses[0].offset = [0.0, 0.01, 0.0]"
        } else if spatial_extra.contains("1e-4") {
            "masses[0].inertia = [0.0001, 0.0, 0.0]"
        } else {
            "masses[0].inertia = [0.0, 0.0002, 0.0002]"
        };
        eprintln!("{err}");
        assert!(err.contains(field), "{err}");
        assert!(err.contains("torsion = true"), "{err}");
        assert!(err.contains("3D cable"), "{err}");
    }
    // zeros are a point mass, on the cable too
    let tail = format!(
        "{}inertia = [0.0, 0.0, 0.0]\noffset = [0.0, 0.0, 0.0]\n",
        mass_table("p", "a", 0.2, 0.01)
    );
    let s = scene_with(
        "space = \"spatial\"\ntorsion = false\ngravity = [0.0, 0.0, -9.81]",
        &segs[..1],
        &tail,
    );
    assert!(Model::<Spatial>::from_scene(&s).is_ok());
    // a modal segment of a cable scene carries a section body
    let tail = format!(
        "{}inertia = [1e-4, 2e-4, 3e-4]\noffset = [0.01, 0.0, 0.0]\n",
        mass_table("p", "m", 0.2, 0.01)
    );
    let s = scene_with(
        "space = \"spatial\"\ntorsion = false\ngravity = [0.0, 0.0, -9.81]",
        &[segs[1].clone()],
        &tail,
    );
    assert!(Model::<Spatial>::from_scene(&s).is_ok());
}

/// The lowest two roots β of the cantilever with an end body: mass ratio μ = M/(ρAL), rotary
/// inertia about its centre j = J/(ρAL³), centre at ε = e/L beyond the tip on the axis. From
/// the end conditions (the mass's centre moves by y_c = w + e w′, turns by w′):
/// EI w‴ = −Mω² y_c, EI w″ = Jω² w′ + e Mω² y_c at x = L, with the clamped–free solution
/// w = A(cosh βξ − cos βξ) + B(sinh βξ − sin βξ): the 2 × 2 determinant's zeros (at j = ε = 0
/// it is −2β⁵ times Blevins' equation).
fn end_body_roots(mu: f64, j: f64, eps: f64) -> [f64; 2] {
    let det = |b: f64| {
        let (c, cc, s, ss) = (b.cosh(), b.cos(), b.sinh(), b.sin());
        let b4 = b.powi(4);
        // (F, F′, F″, F‴) of the two functions at ξ = 1
        let f1 = [c - cc, b * (s + ss), b * b * (c + cc), b.powi(3) * (s - ss)];
        let f2 = [s - ss, b * (c - cc), b * b * (s + ss), b.powi(3) * (c + cc)];
        let rows = |f: [f64; 4]| {
            let yc = f[0] + eps * f[1];
            (
                f[3] + mu * b4 * yc,
                f[2] - j * b4 * f[1] - eps * mu * b4 * yc,
            )
        };
        let ((a1, a2), (b1, b2)) = (rows(f1), rows(f2));
        (a1 * b2 - b1 * a2) / b.powi(5)
    };
    lowest_two_roots(det)
}

#[test]
fn end_body_frequencies_match_the_frequency_equation_with_rotary_inertia_and_offset() {
    // the equation's limits: J → 0 (and no offset) is Blevins' tip-mass equation; μ → 0 and
    // J → 0 the clamped–free beam
    for mu in [0.0, 0.5, 2.0] {
        let (a, b) = (end_body_roots(mu, 1e-15, 0.0), tip_mass_roots(mu));
        assert!(
            (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9,
            "{a:?} {b:?}"
        );
    }
    let b = end_body_roots(0.0, 0.0, 0.3);
    assert!((b[0] - 1.875_104_068_711_961).abs() < 1e-9);
    // rotary inertia lowers the frequencies
    let (r0, r1) = (
        end_body_roots(0.5, 0.0, 0.0),
        end_body_roots(0.5, 0.01, 0.0),
    );
    assert!(r1[0] < r0[0] && r1[1] < r0[1]);
    let w = (ei() / (rho_a() * L.powi(4))).sqrt();
    let mu = 0.5;
    let m = mu * rho_a() * L;
    for (j, eps) in [(0.01, 0.0), (0.0, 0.05), (0.01, 0.05), (0.02, -0.03)] {
        let want = end_body_roots(mu, j, eps).map(|b| b * b * w / std::f64::consts::TAU);
        for (label, segs, on) in rods() {
            let len: f64 = if segs.len() == 1 { L } else { 0.5 * L };
            let tail = format!(
                "{}inertia = [{:e}]\noffset = [{:e}, 0.0]\n",
                mass_table("tip", on, len, m),
                j * rho_a() * L.powi(3),
                eps * L
            );
            let s = scene_with("gravity = [0.0, 0.0]", &segs, &tail);
            let got = bending_frequencies(&mut Model::<Planar>::from_scene(&s).unwrap(), false);
            check_frequencies(
                &format!("planar {label}, mu = {mu}, J/(rho A L^3) = {j}, e/L = {eps}"),
                got,
                want,
                1e-4,
            );
        }
    }
}

#[test]
fn section_bodies_newton_matrix_energy_and_statics() {
    // Newton matrix with bodies (offset, rotary inertia) on ANCF elements of a pinned hybrid
    let r = round(0.004);
    let segs = [
        modal("m", 0.2, &r, 3, true, ""),
        ancf("a", 0.2, &r, 3, "damping_time = 1e-3"),
    ];
    let body = |name: &str, at: f64, o: [f64; 2], j: f64| {
        format!(
            "{}inertia = [{j:e}]\noffset = [{:e}, {:e}]\n",
            mass_table(name, "a", at, 0.02),
            o[0],
            o[1]
        )
    };
    let on_modal = |name: &str, at: f64, o: [f64; 2], j: f64| {
        body(name, at, o, j).replace("segment = \"a\"", "segment = \"m\"")
    };
    let tail = [
        body("b1", 0.05, [0.01, 0.02], 1e-5),
        body("b2", 0.2, [0.0, -0.03], 0.0),
        mass_table("p", "m", 0.1, 0.01),
        on_modal("b3", 0.13, [-0.02, 0.01], 2e-5),
    ]
    .concat();
    for lin in ["", "linear = true\n"] {
        let segs = [format!("{}{lin}", segs[0]), segs[1].clone()];
        let s = scene_with("root = \"pinned\"\ngravity = [1.0, -9.81]", &segs, &tail);
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7]);
        let w = check_newton_matrix(&mut model);
        eprintln!("section bodies {lin:?}: Newton matrix worst error {w:.2e} of the tolerance");
    }
    // energy of the undamped swing; the start potential against the closed form
    let segs = [segs[0].clone(), ancf("a", 0.2, &r, 3, "")];
    let (gx, g) = (0.5, 9.81);
    let header = format!(
        "root = \"pinned\"\ngravity = [{gx:e}, {:e}]\n[solver]\nrho_inf = 0.99\nmax_step = 2.5e-4\ntolerance = 1e-11\nmax_iterations = 20\n",
        -g
    );
    let mut sim = Simulator::<Planar>::new(scene_with(&header, &segs, &tail)).unwrap();
    let rho_a4 = RHO_STEEL * std::f64::consts::PI * 0.004f64.powi(2) / 4.0;
    // centres: b1 at (0.25 + 0.01, 0.02), b2 at (0.4, −0.03), p at 0.1, b3 at (0.11, 0.01)
    let u_want = -gx
        * (rho_a4 * 0.4 * 0.4 / 2.0 + 0.02 * 0.26 + 0.02 * 0.4 + 0.01 * 0.1 + 0.02 * 0.11)
        + g * (0.02 * 0.02 - 0.02 * 0.03 + 0.02 * 0.01);
    let o = sim.outputs();
    let e0 = o.kinetic + o.strain + o.potential;
    assert!(
        (o.potential / u_want - 1.0).abs() < 1e-12,
        "{} {u_want}",
        o.potential
    );
    let scale = (rho_a4 * 0.4 + 0.07) * g * 0.2;
    let (mut drift, mut kmax) = (0.0f64, 0.0f64);
    for k in 1..=500 {
        sim.advance(k as f64 * 1e-3).unwrap();
        let o = sim.outputs();
        drift = drift.max((o.kinetic + o.strain + o.potential - e0).abs() / scale);
        kmax = kmax.max(o.kinetic / scale);
    }
    eprintln!("section bodies: energy drift {drift:.2e} of m g L/2 over 0.5 s, peak kinetic {kmax:.3} of it");
    assert!(kmax > 0.5 && drift < 1e-3, "{kmax} {drift:e}");
    // statics: a mass on a 1 m arm along the section normal at a = 0.6 L, gravity along the
    // axis: a moment M0 = m g o at a, tip deflection M0 a(2L − a)/(2EI) (Roark Table 8.1 case
    // 3a); the axial pull m g changes it by up to m g a²/EI = 9e-6 (second order, not in the closed
    // form)
    let (l, b, gg): (f64, f64, f64) = (1.0, 0.01, 9.81);
    let ei = E_STEEL * b.powi(4) / 12.0;
    let (a, m, arm) = (0.6 * l, 4.3e-4, 1.0);
    let want = m * gg * arm * a * (2.0 * l - a) / (2.0 * ei);
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = {l:e}\n{}\nyoungs_modulus = {E_STEEL:e}\ndensity = 1e-9\nelements = 10\n",
        square(b)
    );
    let tail = format!(
        "{}offset = [0.0, {arm:e}]\n",
        mass_table("arm", "rod", a, m)
    );
    let s = scene_with(&format!("gravity = [{gg:e}, 0.0]"), &[seg], &tail);
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    let got = -sim.outputs().tip_position[1];
    let rel = got / want - 1.0;
    eprintln!("offset arm: tip deflection {got:.9e} m, Roark {want:.9e} m, error {rel:+.2e}");
    assert!(rel.abs() < 1e-5, "{rel:e}");
}

/// The lowest two roots β of a clamped–free beam with a point mass μ ρAL at α L: the two-field
/// problem (w₁ on [0, αL], w₂ on [αL, L], each a combination of cosh, sinh, cos, sin of βx/L)
/// with w₁ = w₁′ = 0 at the clamp, w, w′, w″ continuous at the mass, the shear jump
/// w₁‴ − w₂‴ + μβ⁴w = 0 (the mass's inertia), w₂″ = w₂‴ = 0 at the free end: the zeros of the
/// 8 × 8 determinant (at α = 1 the tip-mass equation, at μ = 0 the clamped–free beam: both
/// checked in the test).
fn mid_mass_roots(mu: f64, alpha: f64) -> [f64; 2] {
    // (f, f′, f″, f‴) of cosh, sinh, cos, sin of βx at x
    let funcs = |b: f64, x: f64| {
        let (ch, sh, c, s) = ((b * x).cosh(), (b * x).sinh(), (b * x).cos(), (b * x).sin());
        let (b2, b3) = (b * b, b * b * b);
        [
            [ch, b * sh, b2 * ch, b3 * sh],
            [sh, b * ch, b2 * sh, b3 * ch],
            [c, -b * s, -b2 * c, b3 * s],
            [s, b * c, -b2 * s, -b3 * c],
        ]
    };
    let det = |b: f64| {
        let mut m = nalgebra::SMatrix::<f64, 8, 8>::zeros();
        let (f0, fa, fe) = (funcs(b, 0.0), funcs(b, alpha), funcs(b, 1.0 - alpha));
        for k in 0..4 {
            m[(0, k)] = f0[k][0];
            m[(1, k)] = f0[k][1];
            for d in 0..3 {
                m[(2 + d, k)] = fa[k][d];
                m[(2 + d, 4 + k)] = -f0[k][d];
            }
            m[(5, k)] = fa[k][3] + mu * b.powi(4) * fa[k][0];
            m[(5, 4 + k)] = -f0[k][3];
            m[(6, 4 + k)] = fe[k][2];
            m[(7, 4 + k)] = fe[k][3];
        }
        m.determinant()
    };
    lowest_two_roots(det)
}

#[test]
fn mid_span_mass_frequencies_match_the_two_field_equation() {
    for mu in [0.5, 2.0] {
        let (a, b) = (mid_mass_roots(mu, 1.0), tip_mass_roots(mu));
        assert!(
            (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9,
            "{a:?} {b:?}"
        );
    }
    let c = mid_mass_roots(0.0, 0.4);
    assert!((c[0] - 1.875_104_068_711_961).abs() < 1e-9);
    assert!((c[1] - 4.694_091_132_974_175).abs() < 1e-9);
    let (mu, alpha) = (1.0, 0.5);
    let w = (ei() / (rho_a() * L.powi(4))).sqrt();
    let want = mid_mass_roots(mu, alpha).map(|b| b * b * w / std::f64::consts::TAU);
    let m = mu * rho_a() * L;
    let r = round(D);
    // (label, segments, segment carrying the mass, its arc length there, tolerance)
    let cases = [
        (
            "all-ANCF",
            vec![ancf("a", L, &r, 16, "")],
            "a",
            0.5 * L,
            1e-4,
        ),
        (
            "hybrid modal+ANCF, mass at the joint",
            vec![
                modal("m", 0.5 * L, &r, 6, true, ""),
                ancf("a", 0.5 * L, &r, 12, ""),
            ],
            "m",
            0.5 * L,
            1e-4,
        ),
        (
            "hybrid ANCF+modal, mass at the joint",
            vec![
                ancf("a", 0.5 * L, &r, 12, ""),
                modal("m", 0.5 * L, &r, 6, true, ""),
            ],
            "m",
            0.0,
            1e-4,
        ),
        (
            // the modes stay Ritz functions: the shear jump inside the body converges slowly
            // from above (12 modes + interface: +6.6e-5 on f2)
            "all-modal 12 modes, mass inside the body",
            vec![modal("m", L, &r, 12, true, "")],
            "m",
            0.5 * L,
            1e-4,
        ),
    ];
    for (label, segs, on, at, tol) in cases {
        let tail = mass_table("mid", on, at, m);
        for spatial in [false, true] {
            let torsion = label.starts_with("hybrid ANCF+modal");
            let s = if spatial {
                scene_with(
                    &format!("space = \"spatial\"\ntorsion = {torsion}\ngravity = [0.0, 0.0, 0.0]"),
                    &segs,
                    &tail,
                )
            } else {
                scene_with("gravity = [0.0, 0.0]", &segs, &tail)
            };
            let got = if spatial {
                bending_frequencies(&mut Model::<Spatial>::from_scene(&s).unwrap(), true)
            } else {
                bending_frequencies(&mut Model::<Planar>::from_scene(&s).unwrap(), false)
            };
            let space = if spatial { "spatial" } else { "planar" };
            check_frequencies(
                &format!("{space} {label}, mu = {mu} at {alpha} L"),
                got,
                want,
                tol,
            );
        }
    }
}

#[test]
fn apparent_mass_along_the_axis_includes_the_masses() {
    // a mounted all-modal rod along x: an axial acceleration moves the straight, inextensible
    // body rigidly, so ∂F_x/∂a_x of the reaction is its whole mass, ρAL + Σm
    let r = round(D);
    let tail = [
        mass_table("p1", "m", 0.1, 0.01),
        mass_table("p2", "m", L, 0.02),
    ]
    .concat();
    let want = rho_a() * L + 0.03;
    for spatial in [false, true] {
        let segs = [modal("m", L, &r, 4, true, "")];
        let got = if spatial {
            let s = scene_with(
                "space = \"spatial\"\nroot = \"mounted\"\ngravity = [0.0, 0.0, -9.81]",
                &segs,
                &tail,
            );
            Simulator::<Spatial>::new(s)
                .unwrap()
                .apparent_mass()
                .unwrap()[0][0]
        } else {
            let s = scene_with("root = \"mounted\"\ngravity = [0.0, -9.81]", &segs, &tail);
            Simulator::<Planar>::new(s)
                .unwrap()
                .apparent_mass()
                .unwrap()[0][0]
        };
        eprintln!("spatial {spatial}: dF_x/da_x = {got:.12e} kg, rho A L + m = {want:.12e} kg");
        assert!((got / want - 1.0).abs() < 1e-9, "{got} vs {want}");
    }
}

/// The spatial twisting elements: (label, scene header line).
const SPATIAL_TORSION: [(&str, &str); 2] = [
    ("director", "torsion = true"),
    ("angle", "torsion_element = \"angle\""),
];

#[test]
fn spatial_end_body_frequencies_match_the_frequency_equation() {
    // a spatial cantilever with a tip body of mass μρAL, rotary inertia J = jρAL³ about both
    // bending axes (I_yy = I_zz, so each pair of planes is equal) and a polar I_xx, centre at
    // e = εL beyond the tip on the axis: the planar end-body equation in each plane
    let w = (ei() / (rho_a() * L.powi(4))).sqrt();
    let mu = 0.5;
    let m = mu * rho_a() * L;
    let mut worst = 0.0f64;
    for (j, eps) in [(0.01, 0.0), (0.0, 0.05), (0.01, 0.05), (0.02, -0.03)] {
        let want = end_body_roots(mu, j, eps).map(|b| b * b * w / std::f64::consts::TAU);
        let jj = j * rho_a() * L.powi(3);
        for (label, segs, on) in rods() {
            let len: f64 = if segs.len() == 1 { L } else { 0.5 * L };
            let tail = format!(
                "{}inertia = [{:e}, {jj:e}, {jj:e}]\noffset = [{:e}, 0.0, 0.0]\n",
                mass_table("tip", on, len, m),
                0.3 * jj,
                eps * L
            );
            for (element, line) in SPATIAL_TORSION {
                if element == "angle" && !segs.iter().any(|s| s.contains("ancf")) {
                    continue; // an all-modal rod has no ANCF element
                }
                let s = scene_with(
                    &format!("space = \"spatial\"\n{line}\ngravity = [0.0, 0.0, 0.0]"),
                    &segs,
                    &tail,
                );
                let got = bending_frequencies(&mut Model::<Spatial>::from_scene(&s).unwrap(), true);
                worst = worst.max(check_frequencies(
                    &format!(
                        "spatial {element} {label}, mu = {mu}, J/(rho A L^3) = {j}, e/L = {eps}"
                    ),
                    got,
                    want,
                    1e-4,
                ));
            }
        }
    }
    eprintln!("worst relative frequency error {worst:.2e}");
}

#[test]
fn tip_disk_torsion_frequency_matches_the_closed_form() {
    // a shaft (round d = 2 mm, L = 0.4 m, steel) clamped at the root with a tip disk of polar
    // inertia J_d = 5 ρI_pL (mass 1e-6 kg, no bending inertia): the first torsion frequency
    // ω = βc/L, β tan β = ρI_pL/J_d, c = √(G/ρ) (Blevins Table 8-19 / Timoshenko): the model's
    // frequency nearest to it within 1e-4 (director: 16 elements; angle: 16; modal: 2 torsion
    // shapes)
    let nu = 0.3;
    let g_mod = E_STEEL / (2.0 * (1.0 + nu));
    let ip = std::f64::consts::PI * D.powi(4) / 32.0;
    let jd = 5.0 * RHO_STEEL * ip * L;
    let ratio = RHO_STEEL * ip * L / jd;
    let (mut lo, mut hi) = (1e-6, std::f64::consts::FRAC_PI_2 - 1e-9);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid * mid.tan() < ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let beta = 0.5 * (lo + hi);
    let want = beta * (g_mod / RHO_STEEL).sqrt() / L / std::f64::consts::TAU;
    let r = round(D);
    let tail = format!(
        "{}inertia = [{jd:e}, 0.0, 0.0]\n",
        mass_table("disk", "s", L, 1e-6)
    );
    let mut worst = 0.0f64;
    for (label, seg, line) in [
        ("director", ancf("s", L, &r, 16, ""), "torsion = true"),
        (
            "angle",
            ancf("s", L, &r, 16, ""),
            "torsion_element = \"angle\"",
        ),
        ("modal", modal("s", L, &r, 4, true, ""), "torsion = true"),
    ] {
        let s = scene_with(
            &format!("space = \"spatial\"\n{line}\ngravity = [0.0, 0.0, 0.0]"),
            &[seg],
            &tail,
        );
        let f: Vec<f64> = linearized_modes(&mut Model::<Spatial>::from_scene(&s).unwrap())
            .iter()
            .map(|m| m.0)
            .collect();
        let got = f
            .iter()
            .copied()
            .min_by(|a, b| (a - want).abs().total_cmp(&(b - want).abs()))
            .unwrap();
        let rel = got / want - 1.0;
        eprintln!("{label}: torsion f1 = {got:.6} Hz, closed form {want:.6} Hz (beta = {beta:.9}), error {rel:+.2e}");
        worst = worst.max(rel.abs());
        assert!(rel.abs() < 1e-4, "{label}: {rel:e}");
    }
    eprintln!("worst relative torsion frequency error {worst:.2e}");
}

#[test]
fn axial_offset_weight_adds_its_moment_to_the_tip_deflection() {
    // a weightless cantilever (ρ = 1e-9) with a tip mass whose centre is e beyond the tip on
    // the axis: gravity along −z pulls P = m g at the tip and turns it by M = P e: tip
    // deflection P L³/(3EI) + M L²/(2EI) (Roark Table 8.1 cases 1a and 3a)
    let (l, b, g): (f64, f64, f64) = (1.0, 0.01, 9.81);
    let ei = E_STEEL * b.powi(4) / 12.0;
    // m: a tip deflection near 1.4e-4 L (the linear range: the arm's turn by the tip slope is
    // of second order, ~1e-8)
    let (m, e) = (0.005, 0.3);
    let p = m * g;
    let want = p * l.powi(3) / (3.0 * ei) + p * e * l * l / (2.0 * ei);
    let sec = square(b);
    let body = format!(
        "{}offset = [{e:e}, 0.0, 0.0]\ninertia = [1e-5, 2e-5, 3e-5]\n",
        mass_table("tip", "rod", l, m)
    );
    let light = |s: String| s.replace(&format!("density = {RHO_STEEL:e}"), "density = 1e-9");
    let mut worst = 0.0f64;
    for (label, seg, line) in [
        (
            "director",
            light(ancf("rod", l, &sec, 10, "")),
            "torsion = true",
        ),
        (
            "angle",
            light(ancf("rod", l, &sec, 10, "")),
            "torsion_element = \"angle\"",
        ),
        (
            "modal",
            light(modal("rod", l, &sec, 4, true, "")),
            "torsion = true",
        ),
        (
            "modal linear",
            light(modal("rod", l, &sec, 4, true, "linear = true")),
            "torsion = true",
        ),
    ] {
        let s = scene_with(
            &format!(
                "space = \"spatial\"\n{line}\ngravity = [0.0, 0.0, {:e}]",
                -g
            ),
            &[seg],
            &body,
        );
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        let o = sim.outputs();
        let got = -o.tip_position[2];
        let rel = got / want - 1.0;
        eprintln!(
            "{label}: tip deflection {got:.9e} m, closed form {want:.9e} m, error {rel:+.2e}"
        );
        worst = worst.max(rel.abs());
        assert!(rel.abs() < 1e-6, "{label}: {rel:e}");
        // the support carries the weight and its moment about y, m g (L + e)
        assert!(
            (o.root_force[2] / (m * g) - 1.0).abs() < 1e-9,
            "{:?}",
            o.root_force
        );
        let my = Spatial::moment_components(&o.root_moment)[1].abs();
        assert!(
            (my / (m * g * (l + e)) - 1.0).abs() < 1e-6,
            "{my} {:?}",
            o.root_moment
        );
    }
    eprintln!("worst relative deflection error {worst:.2e}");
}

#[test]
fn newton_matrices_with_spatial_section_bodies_match_central_differences() {
    let r = round(0.004);
    let body = |name: &str, seg: &str, at: f64, i: [f64; 3], o: [f64; 3]| {
        format!(
            "{}inertia = [{:e}, {:e}, {:e}]\noffset = [{:e}, {:e}, {:e}]\n",
            mass_table(name, seg, at, 0.02),
            i[0],
            i[1],
            i[2],
            o[0],
            o[1],
            o[2]
        )
    };
    let tail = [
        body("b1", "m1", 0.07, [1e-5, 2e-5, 3e-5], [0.01, -0.02, 0.03]),
        body("b2", "a", 0.1, [2e-5, 1e-5, 1e-5], [0.0, 0.02, -0.01]),
        mass_table("p", "a", 0.13, 0.005),
        body("b3", "a", 0.2, [0.0, 3e-5, 1e-5], [-0.02, 0.0, 0.01]),
        body("b4", "m2", 0.2, [1e-5, 1e-5, 2e-5], [0.02, 0.01, 0.0]),
    ]
    .concat();
    for lin in ["", "linear = true"] {
        let segs = [
            modal(
                "m1",
                0.2,
                &r,
                3,
                true,
                &format!("damping_ratio = 0.05\n{lin}"),
            ),
            ancf("a", 0.2, &r, 2, "damping_time = 1e-3"),
            modal("m2", 0.2, &r, 2, false, lin),
        ];
        for (element, line) in SPATIAL_TORSION {
            let s = scene_with(
                &format!(
                    "space = \"spatial\"\n{line}\nroot = \"ball\"\ngravity = [0.0, 1.0, -9.81]"
                ),
                &segs,
                &tail,
            );
            let mut model = Model::<Spatial>::from_scene(&s).unwrap();
            model.set_tip_force([0.3, -0.7, 0.2]);
            let w = check_newton_matrix(&mut model);
            eprintln!("spatial {element}, {lin:?}: worst error {w:.2e} of the tolerance");
        }
    }
}

#[test]
fn mounted_spatial_rigid_inertia_includes_the_section_bodies() {
    // a mounted rod along x (modal then director ANCF) with an offset body on each segment:
    // mass, centre of mass and the inertia tensor about the mount point against the hand sum:
    // the rod (ρAL, centre L/2, I_xx = ρI_pL, I_yy = I_zz = ρAL³/3) plus each body's
    // I_c + m(|c|²1 − c cᵀ) (parallel axes), section axes = mount axes at rest
    let r = round(D);
    let segs = [
        modal("m", 0.5 * L, &r, 3, true, ""),
        ancf("a", 0.5 * L, &r, 4, ""),
    ];
    let bodies = [
        ("m", 0.13, 0.01, [1e-6, 2e-6, 3e-6], [0.01, -0.02, 0.03]),
        ("a", 0.1, 0.02, [4e-6, 1e-6, 2e-6], [-0.015, 0.025, -0.01]),
    ];
    let mut tail = String::new();
    let mb = rho_a() * L;
    let ip = std::f64::consts::PI * D.powi(4) / 32.0;
    let mut mass = mb;
    let mut first = [mb * L / 2.0, 0.0, 0.0];
    let mut inertia = [[0.0; 3]; 3];
    inertia[0][0] = RHO_STEEL * ip * L;
    inertia[1][1] = mb * L * L / 3.0;
    inertia[2][2] = mb * L * L / 3.0;
    for (k, (seg, at, m, i, o)) in bodies.iter().enumerate() {
        tail.push_str(&format!(
            "{}inertia = [{:e}, {:e}, {:e}]\noffset = [{:e}, {:e}, {:e}]\n",
            mass_table(&format!("b{k}"), seg, *at, *m),
            i[0],
            i[1],
            i[2],
            o[0],
            o[1],
            o[2]
        ));
        let x0 = if *seg == "a" { 0.5 * L } else { 0.0 };
        let c = [x0 + at + o[0], o[1], o[2]];
        mass += m;
        let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        for a in 0..3 {
            first[a] += m * c[a];
            for b in 0..3 {
                let delta = if a == b { 1.0 } else { 0.0 };
                inertia[a][b] += m * (c2 * delta - c[a] * c[b]) + delta * i[a];
            }
        }
    }
    let com = first.map(|x| x / mass);
    let s = scene_with(
        "space = \"spatial\"\ntorsion = true\nroot = \"mounted\"\ngravity = [0.0, 0.0, 0.0]",
        &segs,
        &tail,
    );
    let sim = Simulator::<Spatial>::new(s).unwrap();
    let mi = sim.outputs().mount.unwrap();
    eprintln!("mass {:.12e} kg (hand sum {mass:.12e})", mi.mass);
    assert!((mi.mass / mass - 1.0).abs() < 1e-12);
    for a in 0..3 {
        eprintln!(
            "com[{a}] {:.12e} m (hand sum {:.12e})",
            mi.center_of_mass[a], com[a]
        );
        assert!((mi.center_of_mass[a] - com[a]).abs() < 1e-12 * L, "com {a}");
        for b in 0..3 {
            let (got, want) = (mi.inertia[3 * a + b], inertia[a][b]);
            eprintln!("I[{a}{b}] {got:.12e} kg m2 (hand sum {want:.12e})");
            assert!(
                (got - want).abs() < 1e-9 * inertia[1][1],
                "I[{a}{b}] {got:e} vs {want:e}"
            );
        }
    }
}
