//! Issue 39 item 2: linearly tapered sections (`diameter = [d0, d1]`, docs/scene-format.md),
//! on ANCF segments, planar and spatial (3D cable, director and angle elements), each against
//! an independent reference:
//!
//! * the static tip deflection of a tapered cantilever under a small tip force against the
//!   closed form of linear beam theory ([`tip_deflection`]);
//! * its first bending frequency against the Euler–Bernoulli equation (EI w″)″ = ρAω² w solved
//!   by shooting in this file ([`reference_lambda`]; RK4, checked on the uniform beam's
//!   λ₁ = 1.875104068711961);
//! * its weight under gravity and a line load against ρg∫A dx + qL (the line load stays a load
//!   per unit length);
//! * bad taper input against the validation's messages.
//!
//! `cargo test --release -p hybeam --test taper -- --nocapture` prints the measured figures
//! (docs/validation.md, "Tapered sections").

mod common;
use common::*;
use hybeam::model::{Model, Planar, Spatial};
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use std::f64::consts::PI;

/// Length [m] and end diameters [m] of the tapered steel rod (d halves root to tip).
const L: f64 = 0.5;
const D0: f64 = 0.004;
const D1: f64 = 0.002;

/// The tapered round section.
fn cone() -> String {
    format!("section = \"round\"\ndiameter = [{D0:e}, {D1:e}]")
}

/// Linear tip deflection [m] of a cantilever of length L, clamped at x = 0, whose round section
/// tapers linearly d(x) = d0 (1 + c x/L), c = d1/d0 − 1, under a tip force P [N].
///
/// Unit-load method: δ = P ∫₀ᴸ (L − x)² / (E I(x)) dx with I(x) = I0 (1 + cξ)⁴, I0 = π d0⁴/64,
/// ξ = x/L. With u = 1 + cξ and k = 1 + c = d1/d0:
/// ∫₀¹ (1 − ξ)²/(1 + cξ)⁴ dξ = c⁻³ ∫₁ᵏ (k − u)² u⁻⁴ du = c⁻³ [−k²/(3u³) + k/u² − 1/u]₁ᵏ
/// = c⁻³ (k − 1)³/(3k) = 1/(3k), so δ = P L³/(3 E I0) · d0/d1 = 64 P L³/(3π E d0³ d1)
/// (the uniform rod's P L³/(3EI) at d1 = d0).
fn tip_deflection(p: f64) -> f64 {
    64.0 * p * L.powi(3) / (3.0 * PI * E_STEEL * D0.powi(3) * D1)
}

/// First root λ of the clamped–free Euler–Bernoulli beam with EI(ξ) = EI0 f(ξ), ρA(ξ) = ρA0 g(ξ),
/// ξ = x/L, ω = λ² √(EI0/(ρA0 L⁴)): (f w″)″ = λ⁴ g w on [0, 1] as the first-order system
/// w′ = θ, θ′ = m/f, m′ = v, v′ = λ⁴ g w, shot from the clamp (w = θ = 0) with (m, v) = (1, 0)
/// and (0, 1), RK4 on `steps` steps; the free end asks m = v = 0, i.e. det[m, v] = 0 of the two
/// shots, bracketed on a scan of λ from 0.5 and bisected to machine precision.
fn reference_lambda(f: impl Fn(f64) -> f64, g: impl Fn(f64) -> f64, steps: usize) -> f64 {
    let rhs = |x: f64, y: [f64; 4], l4: f64| [y[1], y[2] / f(x), y[3], l4 * g(x) * y[0]];
    let shoot = |lam: f64| {
        let l4 = lam.powi(4);
        let h = 1.0 / steps as f64;
        let mut ends = [[0.0; 4]; 2];
        for (k, y0) in [[0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
            .iter()
            .enumerate()
        {
            let mut y = *y0;
            for i in 0..steps {
                let x = i as f64 * h;
                let add =
                    |y: [f64; 4], k: [f64; 4], s: f64| std::array::from_fn(|j| y[j] + s * k[j]);
                let k1 = rhs(x, y, l4);
                let k2 = rhs(x + 0.5 * h, add(y, k1, 0.5 * h), l4);
                let k3 = rhs(x + 0.5 * h, add(y, k2, 0.5 * h), l4);
                let k4 = rhs(x + h, add(y, k3, h), l4);
                y = std::array::from_fn(|j| {
                    y[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                });
            }
            ends[k] = y;
        }
        ends[0][2] * ends[1][3] - ends[0][3] * ends[1][2]
    };
    let (mut a, mut fa) = (0.5, shoot(0.5));
    loop {
        let b = a + 0.01;
        let fb = shoot(b);
        if fa * fb <= 0.0 {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if shoot(mid) * fa <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return 0.5 * (lo + hi);
        }
        (a, fa) = (b, fb);
        assert!(a < 20.0, "no root below 20");
    }
}

/// The tapered rod's first bending frequency [Hz] from [`reference_lambda`] (A ∝ d², I ∝ d⁴).
fn reference_f1() -> f64 {
    let c = D1 / D0 - 1.0;
    let lam = reference_lambda(|x| (1.0 + c * x).powi(4), |x| (1.0 + c * x).powi(2), 4000);
    let (a0, i0) = (PI * D0 * D0 / 4.0, PI * D0.powi(4) / 64.0);
    lam * lam * (E_STEEL * i0 / (RHO_STEEL * a0 * L.powi(4))).sqrt() / (2.0 * PI)
}

#[test]
fn the_shooting_reference_reproduces_the_uniform_beam() {
    let lam = reference_lambda(|_| 1.0, |_| 1.0, 4000);
    let err = lam / 1.875_104_068_711_961 - 1.0;
    eprintln!("shooting reference, uniform beam: lambda1 = {lam:.15}, error {err:+.2e}");
    assert!(err.abs() < 1e-10, "{err:e}");
}

/// Tip force [N] giving δ/L = 2e-4 (the geometric nonlinearity ~ (δ/L)² is far below 1e-4).
fn small_force() -> f64 {
    2e-4 * L / tip_deflection(1.0)
}

fn planar_static_tip(segs: &[String]) -> [f64; 2] {
    let p = small_force();
    let s = scene(&format!("[tip]\nforce = [0.0, {:e}]", -p), segs);
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    sim.outputs().tip_position
}

fn spatial_header(kind: &str) -> String {
    match kind {
        "cable" => "space = \"spatial\"\ntorsion = false".into(),
        "director" => "space = \"spatial\"\ntorsion = true".into(),
        _ => "space = \"spatial\"\ntorsion = true\ntorsion_element = \"angle\"".into(),
    }
}

const SPATIAL: [&str; 3] = ["cable", "director", "angle"];

#[test]
fn tapered_ancf_cantilever_tip_deflection_matches_the_closed_form() {
    let want = tip_deflection(small_force());
    let check = |label: &str, got: f64| {
        let rel = got / want - 1.0;
        eprintln!(
            "{label}: tip deflection {got:.6e} m, closed form {want:.6e} m, error {rel:+.2e}"
        );
        assert!(rel.abs() < 1e-4, "{label}: {rel:e}");
    };
    let tip = planar_static_tip(&[ancf("a", L, &cone(), 16, "")]);
    check("planar ANCF, 16 elements", -tip[1]);
    let p = small_force();
    for kind in SPATIAL {
        let header = format!(
            "{}\n[tip]\nforce = [0.0, 0.0, {:e}]",
            spatial_header(kind),
            -p
        );
        let s = scene(&header, &[ancf("a", L, &cone(), 16, "")]);
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        check(
            &format!("spatial ANCF {kind}, 16 elements"),
            -sim.outputs().tip_position[2],
        );
    }
}

#[test]
fn tapered_ancf_cantilever_first_frequency_matches_the_shooting_reference() {
    let want = reference_f1();
    let check = |label: &str, got: f64| {
        let rel = got / want - 1.0;
        eprintln!("{label}: f1 = {got:.6} Hz, reference {want:.6} Hz, error {rel:+.2e}");
        assert!(rel.abs() < 1e-4, "{label}: {rel:e}");
    };
    let segs = [ancf("a", L, &cone(), 16, "")];
    let s = scene("gravity = [0.0, 0.0]", &segs);
    let mut model = Model::<Planar>::from_scene(&s).unwrap();
    check(
        "planar ANCF, 16 elements",
        linearized_modes(&mut model)[0].0,
    );
    for kind in SPATIAL {
        let s = scene(&spatial_header(kind), &segs);
        let mut model = Model::<Spatial>::from_scene(&s).unwrap();
        check(
            &format!("spatial ANCF {kind}, 16 elements"),
            linearized_modes(&mut model)[0].0,
        );
    }
}

/// The root carries the weight ρ g ∫A dx, ∫A dx = (π/4) L (d0² + d0 d1 + d1²)/3 (a frustum),
/// and the line load q L whatever the section (q per unit length).
#[test]
fn tapered_segment_weight_and_line_load_reach_the_root() {
    let (g, q) = (9.81, 3.0);
    let volume = PI / 4.0 * L * (D0 * D0 + D0 * D1 + D1 * D1) / 3.0;
    let want = RHO_STEEL * g * volume + q * L;
    let line = format!("line_load = [0.0, {:e}]", -q);
    let s = scene(
        &format!("gravity = [0.0, {:e}]", -g),
        &[ancf("a", L, &cone(), 8, &line)],
    );
    let mut sim = Simulator::<Planar>::new(s).unwrap();
    sim.solve_static().unwrap();
    let got = sim.outputs().root_force[1];
    let rel = got / want - 1.0;
    eprintln!("planar root force {got:.9} N, rho g V + q L = {want:.9} N, error {rel:+.2e}");
    assert!(rel.abs() < 1e-9, "{rel:e}");
    for kind in SPATIAL {
        let header = format!("{}\ngravity = [0.0, 0.0, {:e}]", spatial_header(kind), -g);
        let line = format!("line_load = [0.0, 0.0, {:e}]", -q);
        let s = scene(&header, &[ancf("a", L, &cone(), 8, &line)]);
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        let got = sim.outputs().root_force[2];
        let rel = got / want - 1.0;
        eprintln!("spatial {kind} root force {got:.9} N, error {rel:+.2e}");
        assert!(rel.abs() < 1e-9, "{kind}: {rel:e}");
    }
}

fn error_of(section: &str, kind: &str) -> String {
    let seg = match kind {
        "modal" => modal("a", L, section, 4, false, ""),
        _ => ancf("a", L, section, 4, ""),
    };
    let text = format!("name = \"t\"\n[[segments]]\n{seg}");
    match Scene::from_toml(&text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_tapers_are_refused_with_the_field_value_and_fix() {
    let cases = [
        (
            "section = \"round\"\ndiameter = [0.004, 0.003, 0.002]",
            "ancf",
            "segments[0].diameter = [0.004, 0.003, 0.002]: a taper is a list of two numbers",
        ),
        (
            "section = \"round\"\ndiameter = [0.004]",
            "ancf",
            "segments[0].diameter = [0.004]: a taper is a list of two numbers",
        ),
        (
            "section = \"round\"\ndiameter = [0.004, 0.0]",
            "ancf",
            "segments[0].diameter = [0.004, 0.0]: both ends of a taper must be finite numbers > 0",
        ),
        (
            "section = \"rectangle\"\nwidth = 0.01\nheight = [-0.01, 0.01]",
            "ancf",
            "segments[0].height = [-0.01, 0.01]: both ends",
        ),
        (
            "section = \"tube\"\ndiameter = [0.004, 0.002]\ninner_diameter = 0.003",
            "ancf",
            "segments[0].inner_diameter = 0.003: at the segment's end it is 0.003, must be in [0, diameter = 0.002)",
        ),
        (
            "section = \"tube\"\ndiameter = 0.004\ninner_diameter = [0.002, 0.004]",
            "ancf",
            "segments[0].inner_diameter = [0.002, 0.004]: at the segment's end",
        ),
        (
            "section = \"round\"\ndiameter = \"thick\"",
            "ancf",
            "a number of metres or a taper [at_start, at_end]",
        ),
    ];
    for (section, kind, want) in cases {
        let e = error_of(section, kind);
        eprintln!("{e}");
        assert!(e.contains(want), "{section}: {e}\n  wanted: {want}");
    }
}

#[test]
fn uniform_dimensions_still_serialize_as_numbers_and_tapers_as_lists() {
    let s = scene(
        "",
        &[
            ancf("a", L, &cone(), 4, ""),
            ancf("b", L, &round(D1), 4, ""),
        ],
    );
    let text = toml::to_string(&s).unwrap();
    assert!(text.contains("diameter = [0.004, 0.002]"), "{text}");
    assert!(text.contains("diameter = 0.002\n"), "{text}");
    assert_eq!(Scene::from_toml(&text).unwrap(), s);
}

// ---- tapered MODAL segments (issue 39 item 2, second part) ----

/// The rod split at its middle: the root half tapers D0 → Dm, the tip half Dm → D1.
fn half_cones() -> (String, String) {
    let dm = 0.5 * (D0 + D1);
    (
        format!("section = \"round\"\ndiameter = [{D0:e}, {dm:e}]"),
        format!("section = \"round\"\ndiameter = [{dm:e}, {D1:e}]"),
    )
}

/// The tapered rod as all-modal, modal root + ANCF tip and ANCF root + modal tip (`modes`
/// bending modes with the interface shapes on every modal segment, 8 ANCF elements per half).
fn modal_layouts(modes: usize, extra: &str) -> Vec<(&'static str, Vec<String>)> {
    let (a, b) = half_cones();
    vec![
        (
            "all-modal",
            vec![modal("a", L, &cone(), modes, true, extra)],
        ),
        (
            "modal root + ANCF tip",
            vec![
                modal("a", 0.5 * L, &a, modes, true, extra),
                ancf("b", 0.5 * L, &b, 8, extra),
            ],
        ),
        (
            "ANCF root + modal tip",
            vec![
                ancf("a", 0.5 * L, &a, 8, extra),
                modal("b", 0.5 * L, &b, modes, true, extra),
            ],
        ),
    ]
}

/// Bending modes per modal segment of the modal tests.
const MODAL_MODES: usize = 12;

#[test]
fn tapered_modal_cantilever_tip_deflection_matches_the_closed_form() {
    let want = tip_deflection(small_force());
    let p = small_force();
    for (label, segs) in modal_layouts(MODAL_MODES, "") {
        let got = -planar_static_tip(&segs)[1];
        let rel = got / want - 1.0;
        eprintln!("planar {label}, {MODAL_MODES} modes + 2 interface: tip deflection {got:.6e} m, closed form {want:.6e} m, error {rel:+.2e}");
        assert!(rel.abs() < 1e-4, "planar {label}: {rel:e}");
        let header = format!(
            "{}\n[tip]\nforce = [0.0, 0.0, {:e}]",
            spatial_header("director"),
            -p
        );
        let mut sim = Simulator::<Spatial>::new(scene(&header, &segs)).unwrap();
        sim.solve_static().unwrap();
        let got = -sim.outputs().tip_position[2];
        let rel = got / want - 1.0;
        eprintln!("spatial {label}: tip deflection {got:.6e} m, error {rel:+.2e}");
        assert!(rel.abs() < 1e-4, "spatial {label}: {rel:e}");
    }
}

#[test]
fn tapered_modal_cantilever_first_frequency_matches_the_shooting_reference() {
    let want = reference_f1();
    for (label, segs) in modal_layouts(MODAL_MODES, "") {
        let s = scene("gravity = [0.0, 0.0]", &segs);
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        let got = linearized_modes(&mut model)[0].0;
        let rel = got / want - 1.0;
        eprintln!("planar {label}: f1 = {got:.6} Hz, reference {want:.6} Hz, error {rel:+.2e}");
        assert!(rel.abs() < 1e-4, "planar {label}: {rel:e}");
        let s = scene(&spatial_header("director"), &segs);
        let mut model = Model::<Spatial>::from_scene(&s).unwrap();
        let got = linearized_modes(&mut model)[0].0;
        let rel = got / want - 1.0;
        eprintln!("spatial {label}: f1 = {got:.6} Hz, error {rel:+.2e}");
        assert!(rel.abs() < 1e-4, "spatial {label}: {rel:e}");
    }
}

/// Convergence of the all-modal segment with the number of modes (printed; the bounds are
/// asserted above).
#[test]
fn tapered_modal_convergence_with_the_number_of_modes() {
    let (f1, d) = (reference_f1(), tip_deflection(small_force()));
    for interface in [false, true] {
        for modes in [2, 4, 6, 8, 12] {
            let segs = [modal("a", L, &cone(), modes, interface, "")];
            let s = scene("gravity = [0.0, 0.0]", &segs);
            let mut model = Model::<Planar>::from_scene(&s).unwrap();
            let ef = linearized_modes(&mut model)[0].0 / f1 - 1.0;
            let ed = -planar_static_tip(&segs)[1] / d - 1.0;
            eprintln!(
                "all-modal, {modes} modes, interface {interface}: f1 error {ef:+.2e}, static error {ed:+.2e}"
            );
        }
    }
}

/// The tapered modal segment's root carries ρ g ∫A dx + q L (the line load per unit length,
/// not per unit mass), planar and spatial, the nonlinear and the linear body.
#[test]
fn tapered_modal_segment_weight_and_line_load_reach_the_root() {
    let (g, q) = (9.81, 3.0);
    let volume = PI / 4.0 * L * (D0 * D0 + D0 * D1 + D1 * D1) / 3.0;
    let want = RHO_STEEL * g * volume + q * L;
    for lin in ["", "linear = true"] {
        let line = format!("line_load = [0.0, {:e}]\n{lin}", -q);
        let s = scene(
            &format!("gravity = [0.0, {:e}]", -g),
            &[modal("a", L, &cone(), 6, true, &line)],
        );
        let mut sim = Simulator::<Planar>::new(s).unwrap();
        sim.solve_static().unwrap();
        let got = sim.outputs().root_force[1];
        let rel = got / want - 1.0;
        eprintln!("planar modal {lin:?}: root force {got:.9} N, rho g V + q L = {want:.9} N, error {rel:+.2e}");
        assert!(rel.abs() < 1e-9, "{lin}: {rel:e}");
        let header = format!(
            "{}\ngravity = [0.0, 0.0, {:e}]",
            spatial_header("director"),
            -g
        );
        let line = format!("line_load = [0.0, 0.0, {:e}]\n{lin}", -q);
        let s = scene(&header, &[modal("a", L, &cone(), 6, true, &line)]);
        let mut sim = Simulator::<Spatial>::new(s).unwrap();
        sim.solve_static().unwrap();
        let got = sim.outputs().root_force[2];
        let rel = got / want - 1.0;
        eprintln!("spatial modal {lin:?}: root force {got:.9} N, error {rel:+.2e}");
        assert!(rel.abs() < 1e-9, "spatial {lin}: {rel:e}");
    }
}

/// The Newton matrix of tapered modal bodies (a held root segment and a free one behind an ANCF
/// segment; gravity with an axial part, a line load, modal and Kelvin–Voigt damping) against
/// central differences of the residual, planar and spatial, nonlinear and linear bodies.
#[test]
fn tapered_modal_newton_matrix_matches_central_differences() {
    let (a, b) = half_cones();
    let extra = "damping_ratio = 0.03\ndamping_time = 1e-4";
    let segs = |lin: &str, q1: &str, q2: &str| {
        let m1 = format!("{extra}\n{lin}\nline_load = [{q1}]");
        let m2 = format!("{extra}\n{lin}\nline_load = [{q2}]");
        [
            modal("m1", 0.5 * L, &a, 3, true, &m1),
            ancf("e", 0.1, &b, 1, ""),
            modal("m2", 0.5 * L, &b, 3, false, &m2),
        ]
    };
    for lin in ["", "linear = true"] {
        let s = scene(
            "gravity = [-3.0, -9.81]",
            &segs(lin, "150.0, -200.0", "-50.0, 100.0"),
        );
        let mut model = Model::<Planar>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7]);
        let worst = check_newton_matrix(&mut model);
        eprintln!("planar {lin:?}: worst error / tolerance {worst:.2e}");
        let header = format!(
            "{}\ngravity = [-3.0, 1.0, -9.81]",
            spatial_header("director")
        );
        let s = scene(
            &header,
            &segs(lin, "150.0, -200.0, 70.0", "-50.0, 100.0, 30.0"),
        );
        let mut model = Model::<Spatial>::from_scene(&s).unwrap();
        model.set_tip_force([0.3, -0.7, 0.2]);
        let worst = check_newton_matrix(&mut model);
        eprintln!("spatial {lin:?}: worst error / tolerance {worst:.2e}");
    }
}
