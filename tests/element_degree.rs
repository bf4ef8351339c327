//! ANCF cable elements of degree p > 3 (a segment's `degree`: the cubic element plus
//! hierarchic bubbles, docs/elements.md) against independent references: statics against the
//! closed-form circle of a tip moment (planar, and tilted in space for the 3D cable; up to the
//! closed ring) and the
//! extensible elastica of docs/references.md §4a,
//! with the measured convergence orders; the soft rod's dynamics against the converged cubic
//! element; energy conservation of an undamped swing; the refusals.

mod common;
use common::*;
use hybeam::model::{Model, Planar};
use hybeam::simulator::Simulator;

/// Slender square steel cantilever, L = 1 m, b = 1 cm (as tests/statics.rs).
const L: f64 = 1.0;
const B: f64 = 0.01;

fn ei() -> f64 {
    E_STEEL * B.powi(4) / 12.0
}

/// The static tip position of a cantilever of `elements` elements of degree `degree` under
/// `header`'s loads.
fn static_tip(
    header: &str,
    length: f64,
    section: &str,
    elements: usize,
    degree: usize,
) -> [f64; 2] {
    let s = scene(
        header,
        &[ancf(
            "rod",
            length,
            section,
            elements,
            &format!("degree = {degree}"),
        )],
    );
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    sim.outputs().tip_position
}

/// log2 of the ratios of successive errors (mesh halved each time).
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The tip errors [m] of `degree` on the meshes `meshes` against `want`, with their orders.
fn convergence(
    label: &str,
    degree: usize,
    meshes: &[usize],
    want: [f64; 2],
    tip: impl Fn(usize, usize) -> [f64; 2],
) -> (Vec<f64>, Vec<f64>) {
    let errors: Vec<f64> = (meshes.iter())
        .map(|&n| {
            let t = tip(n, degree);
            ((t[0] - want[0]).powi(2) + (t[1] - want[1]).powi(2)).sqrt()
        })
        .collect();
    let o = orders(&errors);
    eprintln!(
        "{label}, degree {degree}, elements {meshes:?}: errors {:?}, orders {:?}",
        errors
            .iter()
            .map(|e| format!("{e:.3e}"))
            .collect::<Vec<_>>(),
        o.iter().map(|x| format!("{x:.2}")).collect::<Vec<_>>()
    );
    (errors, o)
}

/// A tip moment M bends the cantilever into a circle of radius R = EI/M (no axial force, so no
/// stretch: the exact solution of the element's own measures): tip (R sin(L/R), R(1 − cos(L/R))),
/// here L/R = 1.5 rad. Seen: the cubic converges at order 4.0 = 2(p − 1) (8.8e-5 … 1.7e-8 m on
/// 4 … 32 elements), degree 5 at order 8.0 (1.1e-5 m on one element, 1.8e-10 m on 4).
#[test]
fn tip_moment_rolls_the_cantilever_into_a_circle() {
    let phi: f64 = 1.5; // the tip angle L/R [rad]
    let m = phi * ei() / L;
    let r = L / phi;
    let want = [r * phi.sin(), r * (1.0 - phi.cos())];
    let header = format!("[tip]\nmoment = [{m:e}]");
    let tip = |n, degree| static_tip(&header, L, &square(B), n, degree);
    let (e3, o3) = convergence("moment", 3, &[4, 8, 16, 32], want, tip);
    let (e5, o5) = convergence("moment", 5, &[1, 2, 4], want, tip);
    for (degree, meshes) in [(4, [1, 2, 4, 8]), (6, [1, 2, 4, 8]), (7, [1, 2, 4, 8])] {
        convergence("moment", degree, &meshes, want, tip);
    }
    assert!(o3.iter().all(|o| (3.0..6.5).contains(o)), "{o3:?}");
    assert!(o5.iter().all(|o| (7.0..9.0).contains(o)), "{o5:?}");
    // 4 elements of degree 5 (34 free coordinates) beat 32 cubic ones (130) by far (seen: 96×)
    assert!(e5[2] < e3[3] / 20.0, "{e5:?} vs {e3:?}");
}

/// Exudyn's ANCF cantilever (docs/references.md §4a: L = 2 m, E = 2.07e11 Pa, 0.1 × 0.1 m,
/// P = 3EI/L²) against the extensible elastica, u = 0.5085373043, v = 1.2072398545 m (10
/// digits: errors below 1e-10 m are the reference's). Seen: the cubic at order 5.0–5.4 (1.2e-6 m
/// on 16 elements), degree 5 at 5.8 then 7.9 (4.8e-8 m on 4 elements).
#[test]
fn tip_force_matches_the_extensible_elastica() {
    let (l, b, e): (f64, f64, f64) = (2.0, 0.1, 2.07e11);
    let ei = e * b.powi(4) / 12.0;
    let p = 3.0 * ei / (l * l);
    let want = [l - 0.508_537_304_3, -1.207_239_854_5];
    let header = format!("[tip]\nforce = [0.0, {:e}]", -p);
    let tip = |n: usize, degree: usize| {
        let seg = format!(
            "name = \"rod\"\nkind = \"ancf\"\nlength = {l:e}\n{}\nyoungs_modulus = {e:e}\ndensity = 7850.0\nelements = {n}\ndegree = {degree}\n",
            square(b)
        );
        let mut sim = Simulator::<Planar>::new(scene(&header, &[seg])).unwrap();
        sim.solve_static().unwrap();
        sim.outputs().tip_position
    };
    let (e3, o3) = convergence("elastica", 3, &[4, 8, 16, 32], want, tip);
    let (e5, o5) = convergence("elastica", 5, &[1, 2, 4], want, tip);
    for degree in [4, 6, 7] {
        convergence("elastica", degree, &[1, 2, 4], want, tip);
    }
    assert!(o3.iter().all(|o| (3.0..6.5).contains(o)), "{o3:?}");
    assert!(o5.iter().all(|o| *o > 5.0), "{o5:?}");
    assert!(o5[1] > o3[2] + 2.0, "{o5:?} vs {o3:?}");
    // 4 elements of degree 5 (34 free coordinates) against 16 cubic ones (66): seen 25× closer
    assert!(e5[2] < e3[2] / 10.0, "{e5:?} vs {e3:?}");
}

/// The soft rod (scenes/soft_rod.toml, γ = 17, released straight under gravity) for 0.3 s: the
/// tip history with `n` elements of degree `degree`, every 1 ms.
fn soft_rod(degree: usize, n: usize) -> Vec<[f64; 2]> {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/soft_rod.toml"))
            .unwrap();
    let set = |k: &str, v: String| (k.to_string(), v);
    let s = hybeam::scene::Scene::from_toml_with_overrides(
        &text,
        &[
            set("segments.0.elements", n.to_string()),
            set("segments.0.degree", degree.to_string()),
        ],
    )
    .unwrap();
    tip_history(s, 0.3, 1e-3)
}

/// The soft rod's large motion (the tip falls 0.43 m in 0.3 s) with 8 elements of degree 5
/// against the converged cubic element (64 elements, whose own error at the same step is
/// 1.5e-7 m against 64 elements of degree 5): within 5e-6 m (seen 2.3e-6 m), where 8 cubic
/// elements are 8.5e-4 m off, at the same step (the time error cancels).
#[test]
fn soft_rod_of_degree_five_matches_the_converged_cubic_rod() {
    let reference = soft_rod(3, 64);
    let p5 = max_distance(&soft_rod(5, 8), &reference);
    let cubic = max_distance(&soft_rod(3, 8), &reference);
    eprintln!(
        "soft rod 0.3 s vs 64 cubic elements: 8 of degree 5 {p5:.3e} m, 8 cubic {cubic:.3e} m"
    );
    assert!(p5 < 5e-6, "{p5:e}");
    assert!(p5 < 1e-2 * cubic, "{p5:e} vs {cubic:e}");
}

/// The largest |E(t) − E(0)| of the total energy over a run, as a fraction of the largest
/// kinetic energy: a soft rod pinned at its root swings down from horizontal under gravity
/// (undamped), `n` elements of degree `degree`, step `h` [s].
fn energy_drift(degree: usize, n: usize, h: f64) -> f64 {
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = 0.5\n{}\nyoungs_modulus = 5e7\ndensity = 1100.0\nelements = {n}\ndegree = {degree}\n",
        round(0.005)
    );
    let header = format!("root = \"pinned\"\ngravity = [0.0, -9.81]\n[solver]\nmax_step = {h:e}");
    let mut sim = Simulator::<Planar>::new(scene(&header, &[seg])).unwrap();
    let energy = |o: &hybeam::model::Outputs<Planar>| o.kinetic + o.strain + o.potential;
    let e0 = energy(&sim.outputs());
    let (mut drift, mut kinetic) = (0.0f64, 0.0f64);
    for k in 1..=400 {
        sim.advance(k as f64 * 1e-3).unwrap();
        let o = sim.outputs();
        drift = drift.max((energy(&o) - e0).abs());
        kinetic = kinetic.max(o.kinetic);
    }
    drift / kinetic
}

/// An undamped free swing keeps its energy to the integrator's drift (generalized-α with
/// ρ∞ = 0.9 dissipates the highest modes a little): with elements of degree 5 as with the
/// cubic element at the same step and mesh.
#[test]
fn undamped_swing_keeps_its_energy() {
    let mut drifts = Vec::new();
    for h in [1e-4, 2.5e-5] {
        let cubic = energy_drift(3, 4, h);
        let p5 = energy_drift(5, 4, h);
        eprintln!("swing 0.4 s, h = {h:e}: energy drift / max kinetic: 4 cubic {cubic:.3e}, 4 of degree 5 {p5:.3e}");
        drifts.push(p5);
        // seen: 2.9e-7 for both at h = 1e-4, 1.2e-8 and 1.8e-8 at h = 2.5e-5
        assert!(p5 < 2.0 * cubic + 1e-9, "h = {h:e}: {p5:e} vs {cubic:e}");
    }
    // the drift is the integrator's: it falls with the step (seen: by 16)
    assert!(drifts[1] < drifts[0] / 8.0, "{drifts:?}");
}

/// The assembled Newton matrix of models with elements of degree 4 and 5 (mass, damping,
/// stiffness; point masses, line load, gravity, the paper's strain measures; joints to a modal
/// and a cubic segment; tip force and moment) against central differences of the residual.
#[test]
fn newton_matrix_of_higher_degrees_matches_differences() {
    let d = 0.004;
    let mass = "[[masses]]\nname = \"lamp\"\nsegment = \"a\"\nat = 0.13\nmass = 0.05\n";
    for (header, segs) in [
        (
            "gravity = [1.0, -9.81]",
            vec![
                ancf(
                    "a",
                    0.3,
                    &round(d),
                    2,
                    "degree = 5\ndamping_time = 1e-3\nline_load = [0.5, -2.0]",
                ),
                modal("m", 0.2, &round(d), 2, true, ""),
                ancf("b", 0.2, &round(d), 2, "degree = 4\nstrain = \"paper\""),
                ancf("c", 0.2, &round(d), 1, ""),
            ],
        ),
        (
            "root = \"pinned\"\ngravity = [0.0, -9.81]",
            vec![ancf("a", 0.3, &round(d), 3, "degree = 6")],
        ),
    ] {
        let mut text = format!("name = \"test\"\n{header}\n");
        for s in &segs {
            text += &format!("[[segments]]\n{s}\n");
        }
        text += mass;
        let s = hybeam::scene::Scene::from_toml(&text).unwrap();
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7]);
        model.set_tip_moment(0.2);
        let worst = check_newton_matrix(&mut model);
        eprintln!("{header:?}: worst error {worst:.2e} of the tolerance");
    }
}

/// A station inside an element of degree 5 (the element's partial load over [0, ξ]) and one at
/// a node, in a static cantilever under a tip force P: the section loads are P and the moment
/// of P about the cut, (r_tip − r_cut) × P, with r_cut the centreline there.
#[test]
fn stations_inside_an_element_of_degree_five_balance_the_tip_load() {
    let p = [0.0, -40.0];
    let mut text = format!(
        "name = \"test\"\n[tip]\nforce = [{:e}, {:e}]\n[[segments]]\n{}",
        p[0],
        p[1],
        ancf("a", 1.0, &square(B), 4, "degree = 5")
    );
    for (k, at) in [0.3, 0.5, 0.0].iter().enumerate() {
        text += &format!("[[stations]]\nname = \"s{k}\"\nsegment = \"a\"\nat = {at:e}\n");
    }
    let mut sim =
        Simulator::<Planar>::new(hybeam::scene::Scene::from_toml(&text).unwrap()).unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    let shape = sim.shape(10);
    let tip = o.tip_position;
    for (k, at) in [0.3, 0.5, 0.0].iter().enumerate() {
        let pt = shape
            .points
            .iter()
            .find(|q| (q.arc - at).abs() < 1e-12)
            .unwrap();
        let r = pt.position;
        let want = (tip[0] - r[0]) * p[1] - (tip[1] - r[1]) * p[0];
        let st = o.stations[k];
        let f = (st.force[0].powi(2) + st.force[1].powi(2)).sqrt();
        eprintln!(
            "station at {at}: |F| {f:.9e} (P = 40), M {:.9e} vs {want:.9e}",
            st.moment[2]
        );
        assert!((f - 40.0).abs() < 1e-8 * 40.0, "{f}");
        assert!(
            (st.moment[2].abs() - want.abs()).abs() < 1e-8 * want.abs(),
            "{:?} vs {want}",
            st.moment
        );
    }
}

/// A mounted rod of degree 5 bent by gravity: its rigid inertia at the mount (from the mass
/// matrix and the coordinates' rigid motions, the bubbles turning as directions) is the
/// quadrature of ρA over its sampled centreline: mass ρAL, centre ∫ρA r dx / m, I_zz =
/// ∫ρA |r|² dx.
#[test]
fn mount_inertia_of_a_bent_rod_of_degree_five_is_its_centreline_integral() {
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = 0.5\n{}\nyoungs_modulus = 5e7\ndensity = 1100.0\nelements = 2\ndegree = 5\n",
        round(0.005)
    );
    let header = "root = \"mounted\"\ngravity = [0.0, -9.81]\n[mount]\nposition = [0.2, 1.0]\nangle = 0.4\n[initial]\nstate = \"static\"";
    let sim = Simulator::<Planar>::new(scene(header, &[seg])).unwrap();
    let mi = sim.outputs().mount.unwrap();
    let rho_a = 1100.0 * std::f64::consts::PI * 0.005f64.powi(2) / 4.0;
    // Simpson on 2 × 200 intervals of the arc (the reference length), mount frame
    let shape = sim.shape(200);
    let (s, c) = (0.4f64).sin_cos();
    let local = |q: &hybeam::model::ShapePoint| {
        let (x, y) = (q.position[0] - 0.2, q.position[1] - 1.0);
        [c * x + s * y, -s * x + c * y]
    };
    let npts = shape.points.len();
    let (mut m, mut cm, mut izz) = (0.0, [0.0; 2], 0.0);
    for (i, q) in shape.points.iter().enumerate() {
        let w = if i == 0 || i == npts - 1 {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let w = w * 0.5 / (npts - 1) as f64 / 3.0 * rho_a;
        let r = local(q);
        m += w;
        cm[0] += w * r[0];
        cm[1] += w * r[1];
        izz += w * (r[0] * r[0] + r[1] * r[1]);
    }
    eprintln!(
        "mount inertia: mass {:.9e} vs {m:.9e}, centre {:?} vs {:?}, Izz {:.9e} vs {izz:.9e}",
        mi.mass,
        mi.center_of_mass,
        [cm[0] / m, cm[1] / m],
        mi.inertia[0]
    );
    assert!((mi.mass / m - 1.0).abs() < 1e-10);
    assert!(cm[1] / m < -0.05, "bent: {cm:?}");
    for k in 0..2 {
        assert!((mi.center_of_mass[k] - cm[k] / m).abs() < 1e-9, "{k}");
    }
    assert!((mi.inertia[0] / izz - 1.0).abs() < 1e-9);
}

/// Degree 3 is the default and the cubic element itself: bit-identical histories, and a scene
/// dump leaves the key out.
#[test]
fn degree_three_is_the_default_cubic_element() {
    let run = |extra: &str| {
        let seg = ancf("a", 0.4, &round(0.002), 4, extra);
        tip_history(scene("gravity = [0.0, -9.81]", &[seg]), 0.05, 1e-3)
    };
    assert_eq!(run(""), run("degree = 3"));
    let s = scene("", &[ancf("a", 0.4, &round(0.002), 4, "degree = 3")]);
    assert!(!s.to_toml().contains("degree"));
    let s = scene("", &[ancf("a", 0.4, &round(0.002), 4, "degree = 5")]);
    assert!(s.to_toml().contains("degree = 5"));
}

/// What elements of degree > 3 do not support is refused, naming the field, the value and the
/// fix.
#[test]
fn unsupported_degrees_are_refused_naming_the_field() {
    let err = |header: &str, seg: String, extra: &str| {
        let text = format!("name = \"t\"\n{header}\n[[segments]]\n{seg}\n{extra}");
        hybeam::scene::Scene::from_toml(&text).unwrap_err().0
    };
    let a = |extra: &str| ancf("a", 0.4, &round(0.002), 4, extra);
    for (e, want) in [
        (
            err("", a("degree = 8"), ""),
            "segments[0].degree = 8: must be in 3..=7",
        ),
        (
            err("", a("degree = 2"), ""),
            "segments[0].degree = 2: must be in 3..=7",
        ),
        (
            err(
                "",
                modal("m", 0.4, &round(0.002), 2, false, "degree = 5"),
                "",
            ),
            "segments[0].degree = 5: a modal segment",
        ),
        (
            err(
                "",
                ancf(
                    "a",
                    0.4,
                    "section = \"round\"\ndiameter = [0.002, 0.001]",
                    4,
                    "degree = 5",
                ),
                "",
            ),
            "segments[0].degree = 5: a tapered segment",
        ),
        (
            err("", a("degree = 5\ninitial_curvature = 1.0"), ""),
            "segments[0].degree = 5: an initially curved",
        ),
        (
            err("space = \"spatial\"", a("degree = 5"), ""),
            "segments[0].degree = 5: with torsion = true",
        ),
        (
            err(
                "",
                a("degree = 4"),
                "[[masses]]\nname = \"m\"\nsegment = \"a\"\nat = 0.2\nmass = 0.1\ninertia = [1e-4]",
            ),
            "masses[0].inertia: segment \"a\" has elements of degree 4",
        ),
    ] {
        assert!(e.contains(want), "{e}\n  wanted: {want}");
        assert!(
            e.contains("degree = 3") || e.contains("3..=7") || e.contains("remove degree"),
            "{e}"
        );
    }
}

/// The soft rod as a 3D cable (`torsion = false`), released under gravity with an out-of-plane
/// component, 0.3 s: the tip history every 1 ms with `n` elements of degree `degree`.
fn soft_rod_3d(degree: usize, n: usize, gravity: &str) -> Vec<[f64; 3]> {
    use hybeam::model::Spatial;
    let seg = format!(
        "name = \"rod\"\nkind = \"ancf\"\nlength = 0.5\n{}\nyoungs_modulus = 5e7\ndensity = 1100.0\nelements = {n}\ndegree = {degree}\n",
        round(0.005)
    );
    let header = format!(
        "space = \"spatial\"\ntorsion = false\ngravity = {gravity}\n[solver]\nmax_step = 1e-4"
    );
    let mut sim = Simulator::<Spatial>::new(scene(&header, &[seg])).unwrap();
    let mut out = vec![sim.outputs().tip_position];
    for k in 1..=300 {
        sim.advance(k as f64 * 1e-3).unwrap();
        out.push(sim.outputs().tip_position);
    }
    out
}

fn max_distance3(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    (a.iter().zip(b))
        .map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}

/// The 3D cable of degree 5: in the x–z plane it is the planar element of degree 5 (the same
/// energy; the tip histories agree to round-off), and out of the plane (gravity with a
/// sideways component, the rod swinging in space) 8 elements of degree 5 match 64 cubic ones
/// within 5e-6 m (seen 2.1e-6 m), where 8 cubic elements are 1.1e-3 m off.
#[test]
fn cable_3d_of_degree_five_matches_the_plane_and_the_converged_cubic_cable() {
    let planar = soft_rod(5, 8);
    let spatial = soft_rod_3d(5, 8, "[0.0, 0.0, -9.81]");
    let plane = planar
        .iter()
        .zip(&spatial)
        .map(|(p, s)| (p[0] - s[0]).abs() + (p[1] - s[2]).abs() + s[1].abs())
        .fold(0.0, f64::max);
    eprintln!("3D cable of degree 5 in the x-z plane vs the planar element: {plane:.3e} m");
    assert!(plane < 1e-10, "{plane:e}");
    let g = "[0.0, 4.0, -9.81]";
    let reference = soft_rod_3d(3, 64, g);
    let p5 = max_distance3(&soft_rod_3d(5, 8, g), &reference);
    let cubic = max_distance3(&soft_rod_3d(3, 8, g), &reference);
    eprintln!(
        "3D soft rod 0.3 s vs 64 cubic elements: 8 of degree 5 {p5:.3e} m, 8 cubic {cubic:.3e} m"
    );
    assert!(p5 < 5e-6, "{p5:e}");
    assert!(p5 < 1e-2 * cubic, "{p5:e} vs {cubic:e}");
}

/// The spatial Newton matrix with 3D cables of degree 5 and 4 (damped; a point mass, a line
/// load; joined to a modal root segment by the spherical + DOT1 rows) against central
/// differences.
#[test]
fn spatial_newton_matrix_of_higher_degrees_matches_differences() {
    use hybeam::model::Spatial;
    let d = 0.004;
    let mut text =
        "name = \"t\"\nspace = \"spatial\"\ntorsion = false\ngravity = [0.0, 1.0, -9.81]\n"
            .to_string();
    for s in [
        modal("m", 0.2, &round(d), 2, true, ""),
        ancf(
            "a",
            0.3,
            &round(d),
            2,
            "degree = 5\ndamping_time = 1e-3\nline_load = [0.5, 0.3, -2.0]",
        ),
        ancf("b", 0.2, &round(d), 2, "degree = 4"),
    ] {
        text += &format!("[[segments]]\n{s}\n");
    }
    text += "[[masses]]\nname = \"lamp\"\nsegment = \"a\"\nat = 0.13\nmass = 0.05\n";
    let s = hybeam::scene::Scene::from_toml(&text).unwrap();
    let mut model = Model::<Spatial>::from_scene(&s).unwrap();
    model.set_tip_force([0.3, -0.7, 0.2]);
    let worst = check_newton_matrix(&mut model);
    eprintln!("spatial degree 5/4: worst error {worst:.2e} of the tolerance");
}

/// A station inside a 3D cable element of degree 5 in a static cantilever under a tip force P
/// out of every axis: the section force is P and the moment (r_tip − r_cut) × P.
#[test]
fn spatial_station_inside_an_element_of_degree_five_balances_the_tip_load() {
    use hybeam::model::Spatial;
    let p = [5.0, -20.0, 30.0];
    let mut text = format!(
        "name = \"t\"\nspace = \"spatial\"\ntorsion = false\n[tip]\nforce = [{:e}, {:e}, {:e}]\n[[segments]]\n{}",
        p[0],
        p[1],
        p[2],
        ancf("a", 1.0, &round(0.006), 4, "degree = 5")
    );
    text += "[[stations]]\nname = \"s\"\nsegment = \"a\"\nat = 0.3\n";
    let s = hybeam::scene::Scene::from_toml(&text).unwrap();
    let mut sim = Simulator::<Spatial>::new(s).unwrap();
    sim.solve_static().unwrap();
    let o = sim.outputs();
    let shape = sim.shape(10);
    let r = shape
        .points
        .iter()
        .find(|q| (q.arc - 0.3).abs() < 1e-12)
        .unwrap()
        .position;
    let tip = o.tip_position;
    let arm = [tip[0] - r[0], tip[1] - r[1], tip[2] - r[2]];
    let want = [
        arm[1] * p[2] - arm[2] * p[1],
        arm[2] * p[0] - arm[0] * p[2],
        arm[0] * p[1] - arm[1] * p[0],
    ];
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let st = o.stations[0];
    let pn = norm(p);
    eprintln!(
        "spatial station: |F| {:.9e} vs {pn:.9e}, |M| {:.9e} vs {:.9e}, tip {tip:?}",
        norm(st.force),
        norm(st.moment),
        norm(want)
    );
    assert!((norm(st.force) - pn).abs() < 1e-8 * pn);
    assert!((norm(st.moment) - norm(want)).abs() < 1e-8 * norm(want));
    assert!(
        tip[1] < -0.1 && tip[2] > 0.1,
        "bent out of every plane: {tip:?}"
    );
}

/// The static tip of a 3D cable cantilever along x (`torsion = false`) of `elements` elements
/// of degree `degree` under the tip moment `moment` [N m].
fn static_tip_3d(moment: [f64; 3], elements: usize, degree: usize) -> [f64; 3] {
    use hybeam::model::Spatial;
    let header = format!(
        "space = \"spatial\"\ntorsion = false\n[tip]\nmoment = [{:e}, {:e}, {:e}]",
        moment[0], moment[1], moment[2]
    );
    let seg = ancf(
        "rod",
        L,
        &square(B),
        elements,
        &format!("degree = {degree}"),
    );
    let mut sim = Simulator::<Spatial>::new(scene(&header, &[seg])).unwrap();
    sim.solve_static().unwrap();
    sim.outputs().tip_position
}

/// A tip moment M about an axis m̂ across the 3D cable (here m̂ = (0, cos 30°, sin 30°), out of
/// every coordinate plane) bends it into a circle of radius R = EI/M in the plane normal to m̂:
/// tip R sin φ x̂ + R (1 − cos φ) (m̂ × x̂), φ = L/R = 1.5 rad (the moment stays normal to the
/// tangent, so the cable without torsion carries it exactly). The 3D cable of degree p
/// converges at the planar element's orders 2(p − 1): seen 4.3, 4.0, 4.0 for the cubic
/// (8.8e-5 … 1.7e-8 m on 4 … 32 elements) and 8.0 for degree 5 (1.1e-5 m on one element,
/// 1.8e-10 m on 4), the planar figures to their digits.
#[test]
fn tip_moment_rolls_the_3d_cable_into_a_tilted_circle() {
    let phi: f64 = 1.5;
    let m = phi * ei() / L;
    let r = L / phi;
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let axis = [0.0, c, s];
    // m̂ × x̂ = (0, m_z, −m_y)
    let normal = [0.0, axis[2], -axis[1]];
    let want = [
        r * phi.sin(),
        r * (1.0 - phi.cos()) * normal[1],
        r * (1.0 - phi.cos()) * normal[2],
    ];
    let moment = axis.map(|a| a * m);
    let conv = |degree: usize, meshes: &[usize]| {
        let errors: Vec<f64> = (meshes.iter())
            .map(|&n| {
                let t = static_tip_3d(moment, n, degree);
                (0..3).map(|k| (t[k] - want[k]).powi(2)).sum::<f64>().sqrt()
            })
            .collect();
        let o = orders(&errors);
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
        eprintln!(
            "3D moment, degree {degree}, elements {meshes:?}: errors {shown:?}, orders {o:.2?}"
        );
        (errors, o)
    };
    let (e3, o3) = conv(3, &[4, 8, 16, 32]);
    let (e5, o5) = conv(5, &[1, 2, 4]);
    assert!(o3.iter().all(|o| (3.0..6.5).contains(o)), "{o3:?}");
    assert!(o5.iter().all(|o| (7.0..9.0).contains(o)), "{o5:?}");
    assert!(e5[2] < e3[3] / 20.0, "{e5:?} vs {e3:?}");
}

/// The closed ring: the tip moment M = 2π EI/L rolls the cantilever into a full circle of radius
/// L/2π, its tip back at the root (the closed form of the element's own measures, as above, at
/// φ = 2π), planar and as the 3D cable about the tilted axis. Seen, planar and 3D alike: the
/// cubic at orders 4.4, 4.0, 4.0 (2.1e-3 … 3.9e-7 m on 8 … 64 elements), degree 5 at 7.6, 7.9
/// (1.3e-3 … 2.8e-8 m on 2 … 8): 8 elements of degree 5 close the ring 14× better than 64 cubic.
#[test]
fn tip_moment_closes_the_cantilever_into_a_ring() {
    let phi = 2.0 * std::f64::consts::PI;
    let m = phi * ei() / L;
    let header = format!("[tip]\nmoment = [{m:e}]");
    let planar = |n, degree| static_tip(&header, L, &square(B), n, degree);
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let spatial = |n, degree| {
        let t = static_tip_3d([0.0, c * m, s * m], n, degree);
        // the distance from the root, in the ring's plane's (x, ·) coordinates
        [t[0], (t[1] * t[1] + t[2] * t[2]).sqrt()]
    };
    for (label, tip) in [
        ("ring", &planar as &dyn Fn(usize, usize) -> [f64; 2]),
        ("3D ring", &spatial),
    ] {
        let (e3, o3) = convergence(label, 3, &[8, 16, 32, 64], [0.0, 0.0], tip);
        let (e5, o5) = convergence(label, 5, &[2, 4, 8], [0.0, 0.0], tip);
        assert!(o3.iter().all(|o| (3.5..5.0).contains(o)), "{label}: {o3:?}");
        assert!(o5.iter().all(|o| (7.0..9.0).contains(o)), "{label}: {o5:?}");
        assert!(e5[2] < e3[3] / 5.0, "{label}: {e5:?} vs {e3:?}");
    }
}
