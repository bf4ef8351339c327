//! The stability suite: extreme scenes and inputs, each run to its end or to a clean refusal.
//! Shared by the report binary (`report stability`) and by the crate's `tests/stability.rs` (the fast
//! subset), so both run exactly the same cases. Depends only on the hybeam library.

use hybeam::error::SimError;
use hybeam::model::Space;
use hybeam::model::{Planar, Spatial};
use hybeam::scene::{Scene, SpaceKind};
use hybeam::simulator::Simulator;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Tip input schedule (replaces the scene's tip force; the tip moment only where given).
#[derive(Debug, Clone)]
pub enum Input {
    /// No input.
    None,
    /// Constant force `f` [N] until `until` [s], zero after.
    Pulse {
        /// Force [N], global.
        f: [f64; 2],
        /// End of the pulse [s].
        until: f64,
    },
    /// Constant dead tip moment `m` [N m] (global x, y, z; the plane takes z) until `until`
    /// [s], zero after.
    MomentPulse {
        /// Moment [N m], global axes.
        m: [f64; 3],
        /// End of the pulse [s].
        until: f64,
    },
    /// Force of magnitude `mag` perpendicular to the root-to-tip line in the x–y plane
    /// (counter-clockwise about z), updated every communication step, until `until` [s].
    Perpendicular {
        /// Magnitude [N].
        mag: f64,
        /// End [s].
        until: f64,
    },
    /// Force ±`mag` along global axis `axis` (the vertical: 1 in the plane, 2 in space) with a
    /// random sign drawn every communication step.
    RandomSign {
        /// Magnitude [N].
        mag: f64,
        /// Index of the global axis.
        axis: usize,
        /// Seed of the xorshift generator.
        seed: u64,
    },
}

/// One case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Short name.
    pub name: String,
    /// What it does.
    pub what: String,
    /// Scene TOML text.
    pub scene: String,
    /// End time [s].
    pub t_end: f64,
    /// Communication step [s]: `advance` is called at its multiples.
    pub chunk: f64,
    /// Tip force input.
    pub input: Input,
    /// Part of the fast subset run by `tests/stability.rs`.
    pub fast: bool,
}

/// How a case ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Ran to the end.
    Completed,
    /// The scene, `Simulator::new` or `advance` returned an error (a clean refusal of its kind).
    Refused(SimError),
    /// Ok from `advance` but non-finite outputs.
    NonFinite(f64),
    /// The engine panicked.
    Panicked(String),
}

/// What a case measured.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// End state.
    pub status: Status,
    /// Time reached [s].
    pub t_reached: f64,
    /// max |E − E0 − W| over the run [J] (E = kinetic + strain + gravity potential, W = work of
    /// the tip force and of the tip moment).
    pub drift: f64,
    /// E − E0 − W at the sample where |E − E0 − W| is largest [J] (negative: energy lost).
    pub drift_signed: f64,
    /// Largest of kinetic energy, strain energy and |W| over the samples [J].
    pub energy_scale: f64,
    /// Largest strain energy [J].
    pub max_strain: f64,
    /// Work of the tip force (exact for a force held over each communication step) and of the
    /// tip moment (M·ω trapezoidal over each communication step) at the end [J].
    pub work: f64,
    /// Smallest internal step used [s].
    pub min_step: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts (each a Newton failure or singular matrix).
    pub rejected: u64,
    /// Newton iterations.
    pub iterations: u64,
    /// Largest distance of the tip from the root [m].
    pub max_tip_dist: f64,
    /// Total undeformed length [m].
    pub length: f64,
    /// Planar: range (max − min) of the unwrapped tip angle [rad]. Spatial: the accumulated
    /// rotation of the tip section, the sum of the rotation angles between consecutive samples
    /// [rad].
    pub rotation: f64,
    /// Tip speed at the end divided by its distance from the root [rad/s].
    pub final_omega: f64,
    /// Wall time [s].
    pub wall: f64,
    /// All outputs finite at every sample.
    pub finite: bool,
    /// Energies finite at every sample.
    pub energies_finite: bool,
}

impl Outcome {
    /// Drift relative to the largest strain energy.
    pub fn relative_drift(&self) -> f64 {
        self.drift / self.max_strain.max(1e-300)
    }

    /// Drift relative to the largest energy involved (kinetic, strain or work).
    pub fn scaled_drift(&self) -> f64 {
        self.drift / self.energy_scale.max(1e-300)
    }

    /// |tip| ≤ length × (1 + 2 %) relative to the root.
    pub fn bounded(&self) -> bool {
        self.max_tip_dist <= self.length * 1.02 + 1e-9
    }
}

const STEEL: &str = "youngs_modulus = 2.1e11\ndensity = 7850.0";
/// Steel with the Kelvin–Voigt damping of Case 2 (τ = 0.7 ms).
const STEEL_DAMPED: &str = "youngs_modulus = 2.1e11\ndensity = 7850.0\ndamping_time = 7e-4";

fn solver(h: f64, rho: f64) -> String {
    format!("[solver]\nrho_inf = {rho}\nmax_step = {h:e}\ntolerance = 1e-11\nmax_iterations = 12\n")
}

fn ancf(name: &str, l: f64, d: f64, n: usize, material: &str) -> String {
    format!(
        "[[segments]]\nname = \"{name}\"\nkind = \"ancf\"\nlength = {l:e}\nsection = \"round\"\n\
         diameter = {d:e}\n{material}\nelements = {n}\n"
    )
}

fn modal(name: &str, l: f64, d: f64, modes: usize, material: &str) -> String {
    format!(
        "[[segments]]\nname = \"{name}\"\nkind = \"modal\"\nlength = {l:e}\nsection = \"round\"\n\
         diameter = {d:e}\n{material}\nmodes = {modes}\ninterface_modes = true\n"
    )
}

fn scene_text(name: &str, gravity: f64, root: &str, solver: &str, segs: &[String]) -> String {
    let mut s =
        format!("name = \"{name}\"\ngravity = [0.0, {gravity:e}]\nroot = \"{root}\"\n{solver}\n");
    for g in segs {
        s.push_str(g);
    }
    s
}

/// A spatial scene, z up, gravity `gravity` [m/s²] along z.
fn scene3_text(name: &str, gravity: f64, root: &str, solver: &str, segs: &[String]) -> String {
    let mut s = format!(
        "name = \"{name}\"\nspace = \"spatial\"\ngravity = [0.0, 0.0, {gravity:e}]\n\
         root = \"{root}\"\n{solver}\n"
    );
    for g in segs {
        s.push_str(g);
    }
    s
}

/// The Case 1 rod in space (z up) as hybrid (4 modes + interface, 8 elements) of `material`.
fn case1_3d_hybrid_of(h: f64, gravity: f64, root: &str, material: &str) -> String {
    scene3_text(
        "case1_3d",
        gravity,
        root,
        &solver(h, 0.9),
        &[
            modal("modal", 0.2, 0.002, 4, material),
            ancf("ancf", 0.2, 0.002, 8, material),
        ],
    )
}

/// The Case 1 rod in space (z up) as hybrid, undamped steel.
fn case1_3d_hybrid(h: f64, gravity: f64, root: &str) -> String {
    case1_3d_hybrid_of(h, gravity, root, STEEL)
}

/// The Case 1 rod in space (z up) as all-ANCF with `n` elements of `material`.
fn case1_3d_ancf_of(n: usize, h: f64, gravity: f64, root: &str, material: &str) -> String {
    scene3_text(
        "case1_3d_ancf",
        gravity,
        root,
        &solver(h, 0.9),
        &[ancf("ancf", 0.4, 0.002, n, material)],
    )
}

/// The Case 1 rod in space (z up) as all-ANCF, undamped steel.
fn case1_3d_ancf(n: usize, h: f64, gravity: f64, root: &str) -> String {
    case1_3d_ancf_of(n, h, gravity, root, STEEL)
}

/// Torsional stiffness G·J/L of the Case 1 rod [N m/rad] (ν = 0.3, the scene default).
fn gj_over_l_case1() -> f64 {
    let g = 2.1e11 / (2.0 * 1.3);
    g * std::f64::consts::PI * 0.002f64.powi(4) / 32.0 / 0.4
}

/// Case 1 geometry as hybrid (4 modes + interface, 8 elements).
fn case1_hybrid(h: f64, rho: f64, gravity: f64, root: &str) -> String {
    scene_text(
        "case1",
        gravity,
        root,
        &solver(h, rho),
        &[
            modal("modal", 0.2, 0.002, 4, STEEL),
            ancf("ancf", 0.2, 0.002, 8, STEEL),
        ],
    )
}

/// Case 1 geometry as all-ANCF with `n` elements.
fn case1_ancf(n: usize, h: f64, gravity: f64, root: &str, material: &str) -> String {
    scene_text(
        "case1_ancf",
        gravity,
        root,
        &solver(h, 0.9),
        &[ancf("ancf", 0.4, 0.002, n, material)],
    )
}

/// EI of the Case 1 rod [N m²].
fn ei_case1() -> f64 {
    2.1e11 * std::f64::consts::PI * 0.002f64.powi(4) / 64.0
}

/// The stiff thin rod (steel, d = 0.5 mm, L = 0.4 m, 64 ANCF elements) under gravity at step
/// `h`, for min(2e4 h, 1) s, planar or spatial (named `3D …`, fast only for h ≥ 1e-3).
fn thin_rod(spatial: bool, h: f64) -> Case {
    let t_end = (2e4 * h).min(1.0);
    let (prefix, what) = if spatial {
        ("3D ", "spatial, with twist, gravity along −z")
    } else {
        ("", "gravity")
    };
    let solver = solver(h, 0.9);
    let rod = [ancf("rod", 0.4, 0.0005, 64, STEEL)];
    Case {
        name: format!("{prefix}stiff 0.5 mm rod, 64 el., h={h:e}"),
        what: format!("steel d = 0.5 mm, L = 0.4 m, 64 ANCF elements, {what}, {t_end} s"),
        scene: if spatial {
            scene3_text("thin", -9.81, "clamped", &solver, &rod)
        } else {
            scene_text("thin", -9.81, "clamped", &solver, &rod)
        },
        t_end,
        chunk: h.max(1e-3),
        input: Input::None,
        fast: !spatial || h >= 1e-3,
    }
}

/// The suite; `quick` leaves out the long variants.
pub fn cases(quick: bool) -> Vec<Case> {
    let mut v = Vec::new();
    let steps: [f64; 5] = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2];
    for h in steps {
        v.push(thin_rod(false, h));
    }
    for h in steps {
        let t_end = (2e4 * h).min(1.0);
        v.push(Case {
            name: format!("E = 1e13 Pa, h={h:e}"),
            what: format!("Case 1 rod all-ANCF (16 el.) with E = 1e13 Pa, gravity, {t_end} s"),
            scene: case1_ancf(
                16,
                h,
                -9.81,
                "clamped",
                "youngs_modulus = 1e13\ndensity = 7850.0",
            ),
            t_end,
            chunk: h.max(1e-3),
            input: Input::None,
            fast: true,
        });
    }
    let p50 = 50.0 * ei_case1() / 0.16;
    v.push(Case {
        name: "tip force step PL²/EI = 50".into(),
        what: format!(
            "Case 1 rod all-ANCF (16 el.), gravity, tip force (0, −{p50:.1} N) on for 0.5 s, then 0; 1 s"
        ),
        scene: case1_ancf(16, 1e-4, -9.81, "clamped", STEEL),
        t_end: 1.0,
        chunk: 1e-3,
        input: Input::Pulse {
            f: [0.0, -p50],
            until: 0.5,
        },
        fast: false,
    });
    v.push(Case {
        name: "whip impulse".into(),
        what: "Case 1 rod all-ANCF (16 el.), no gravity, tip force (0, 30 N) for 5 ms, then free; 0.5 s".into(),
        scene: case1_ancf(16, 1e-4, 0.0, "clamped", STEEL),
        t_end: 0.5,
        chunk: 1e-3,
        input: Input::Pulse {
            f: [0.0, 30.0],
            until: 5e-3,
        },
        fast: false,
    });
    for (label, text) in [
        ("hybrid", case1_hybrid(1e-4, 0.9, 0.0, "pinned")),
        ("all-ANCF", case1_ancf(16, 1e-4, 0.0, "pinned", STEEL)),
    ] {
        v.push(Case {
            name: format!("pinned spin-up, {label}"),
            what: format!(
                "Case 1 rod {label}, pinned, no gravity, 0.2 N tip force perpendicular to the beam for 1 s, then free; 1.5 s"
            ),
            scene: text,
            t_end: 1.5,
            chunk: 1e-3,
            input: Input::Perpendicular {
                mag: 0.2,
                until: 1.0,
            },
            fast: true,
        });
    }
    // soft rod (scenes/soft_rod.toml) with E lowered from γ = 17.3 to γ = 100
    let e100 = 5e7 * 17.27 / 100.0;
    v.push(Case {
        name: "soft rod γ = 100".into(),
        what: format!("soft_rod geometry (L = 0.5 m, d = 5 mm, ρ = 1100), E = {e100:.3e} Pa (γ = 100), 16 ANCF el., released under gravity; 2 s"),
        scene: scene_text(
            "soft100",
            -9.81,
            "clamped",
            &solver(1e-4, 0.9),
            &[ancf("rod", 0.5, 0.005, 16, &format!("youngs_modulus = {e100:e}\ndensity = 1100.0"))],
        ),
        t_end: 2.0,
        chunk: 1e-3,
        input: Input::None,
        fast: true,
    });
    for chunk in [0.1, 1.0] {
        v.push(Case {
            name: format!("output step {chunk} s"),
            what: format!("Case 1 hybrid, advanced in chunks of {chunk} s; 2 s"),
            scene: case1_hybrid(1e-4, 0.9, -9.81, "clamped"),
            t_end: 2.0,
            chunk,
            input: Input::None,
            fast: true,
        });
    }
    let rhos: &[f64] = if quick { &[0.9] } else { &[0.9, 0.99] };
    for &rho in rhos {
        v.push(Case {
            name: format!("60 s undamped, rho_inf = {rho}"),
            what: format!("Case 1 hybrid (no physical damping), h = 1e-4, rho_inf = {rho}; 60 s"),
            scene: case1_hybrid(1e-4, rho, -9.81, "clamped"),
            t_end: 60.0,
            chunk: 1e-3,
            input: Input::None,
            fast: false,
        });
    }
    v.push(Case {
        name: "random-sign force every step".into(),
        what:
            "Case 1 hybrid, gravity, vertical tip force ±0.05 N with a random sign every 1 ms; 2 s"
                .into(),
        scene: case1_hybrid(1e-4, 0.9, -9.81, "clamped"),
        t_end: 2.0,
        chunk: 1e-3,
        input: Input::RandomSign {
            mag: 0.05,
            axis: 1,
            seed: 0x9e37_79b9_7f4a_7c15,
        },
        fast: true,
    });
    v.push(Case {
        name: "single element".into(),
        what: "Case 1 rod as one ANCF element, gravity; 2 s".into(),
        scene: case1_ancf(1, 1e-4, -9.81, "clamped", STEEL),
        t_end: 2.0,
        chunk: 1e-3,
        input: Input::None,
        fast: true,
    });
    v.push(Case {
        name: "500 elements".into(),
        what: "Case 1 rod as 500 ANCF elements, gravity; 0.1 s".into(),
        scene: case1_ancf(500, 1e-4, -9.81, "clamped", STEEL),
        t_end: 0.1,
        chunk: 1e-3,
        input: Input::None,
        fast: true,
    });
    v.extend(spatial_cases(quick));
    v
}

/// The spatial cases (names start with `3D`): thin rod, fine mesh, large twist, fast spin,
/// long communication steps, no damping, random input.
fn spatial_cases(quick: bool) -> Vec<Case> {
    let mut v = Vec::new();
    for h in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        v.push(thin_rod(true, h));
    }
    v.push(Case {
        name: "3D 500 elements".into(),
        what: "spatial Case 1 rod as 500 ANCF elements (with twist), gravity; 0.05 s".into(),
        scene: case1_3d_ancf(500, 1e-4, -9.81, "clamped"),
        t_end: 0.05,
        chunk: 1e-3,
        input: Input::None,
        fast: false,
    });
    // dead moment about the rod's axis (global x), on for 0.5 s then off, on the damped Case 2
    // rod (undamped, the sudden load rings the first torsion mode, about 4 kHz, which h = 1e-4
    // does not resolve); the twist settles to M L/(G J) and back to zero
    let k = gj_over_l_case1();
    let ancf16 = || case1_3d_ancf_of(16, 1e-4, -9.81, "clamped", STEEL_DAMPED);
    let hybrid = || case1_3d_hybrid_of(1e-4, -9.81, "clamped", STEEL_DAMPED);
    for (label, text, twist_deg, fast) in [
        ("all-ANCF", ancf16(), 45.0, true),
        ("all-ANCF", ancf16(), 90.0, false),
        ("all-ANCF", ancf16(), 360.0, false),
        ("all-ANCF", ancf16(), 1080.0, false),
        ("hybrid", hybrid(), 10.0, true),
        ("hybrid", hybrid(), 45.0, true),
    ] {
        let m = k * f64::to_radians(twist_deg);
        v.push(Case {
            name: format!("3D twist {twist_deg}°, {label}"),
            what: format!(
                "spatial Case 2 rod (damped, τ = 0.7 ms) {label}, clamped, gravity, dead tip moment \
                 ({m:.4} N m, 0, 0) about the axis (static twist M L/(G J) = {twist_deg}°) for 0.5 s, \
                 then free; 1 s"
            ),
            scene: text,
            t_end: 1.0,
            chunk: 1e-3,
            input: Input::MomentPulse {
                m: [m, 0.0, 0.0],
                until: 0.5,
            },
            fast,
        });
    }
    for (label, text) in [
        ("hybrid", case1_3d_hybrid(1e-4, 0.0, "ball")),
        ("all-ANCF", case1_3d_ancf(16, 1e-4, 0.0, "ball")),
    ] {
        v.push(Case {
            name: format!("3D ball spin-up, {label}"),
            what: format!(
                "spatial Case 1 rod {label}, ball root, no gravity, dead tip moment (0, 0, 0.08 N m) about the \
                 vertical for 1 s, then free; 1.5 s"
            ),
            scene: text,
            t_end: 1.5,
            chunk: 1e-3,
            input: Input::MomentPulse {
                m: [0.0, 0.0, 0.08],
                until: 1.0,
            },
            fast: label == "hybrid",
        });
    }
    v.push(Case {
        name: "3D ball swing, hybrid".into(),
        what:
            "spatial Case 1 rod hybrid, ball root, released horizontal under gravity (an undamped \
               flexible pendulum); 2 s"
                .into(),
        scene: case1_3d_hybrid(1e-4, -9.81, "ball"),
        t_end: 2.0,
        chunk: 1e-3,
        input: Input::None,
        fast: true,
    });
    for chunk in [0.1, 1.0] {
        v.push(Case {
            name: format!("3D output step {chunk} s"),
            what: format!("spatial Case 1 hybrid, advanced in chunks of {chunk} s; 2 s"),
            scene: case1_3d_hybrid(1e-4, -9.81, "clamped"),
            t_end: 2.0,
            chunk,
            input: Input::None,
            fast: true,
        });
    }
    let t_long = if quick { 20.0 } else { 60.0 };
    v.push(Case {
        name: format!("3D {t_long} s undamped"),
        what: format!(
            "spatial Case 1 hybrid (no physical damping), h = 1e-4, rho_inf = 0.9; {t_long} s"
        ),
        scene: case1_3d_hybrid(1e-4, -9.81, "clamped"),
        t_end: t_long,
        chunk: 1e-3,
        input: Input::None,
        fast: false,
    });
    v.push(Case {
        name: "3D random-sign force every step".into(),
        what: "spatial Case 1 hybrid, gravity, vertical tip force ±0.05 N with a random sign every 1 ms; 2 s"
            .into(),
        scene: case1_3d_hybrid(1e-4, -9.81, "clamped"),
        t_end: 2.0,
        chunk: 1e-3,
        input: Input::RandomSign {
            mag: 0.05,
            axis: 2,
            seed: 0x9e37_79b9_7f4a_7c15,
        },
        fast: false,
    });
    v
}

fn xorshift(s: &mut u64) -> u64 {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    *s
}

/// The tip force at time `t` (global x, y, z; z = 0 in the plane), given the tip position.
fn force_at(input: &Input, t: f64, tip: [f64; 3], rng: &mut u64) -> [f64; 3] {
    match input {
        Input::None | Input::MomentPulse { .. } => [0.0; 3],
        Input::Pulse { f, until } => {
            if t < *until - 1e-12 {
                [f[0], f[1], 0.0]
            } else {
                [0.0; 3]
            }
        }
        Input::Perpendicular { mag, until } => {
            let r = (tip[0] * tip[0] + tip[1] * tip[1]).sqrt().max(1e-12);
            if t < *until - 1e-12 {
                [-mag * tip[1] / r, mag * tip[0] / r, 0.0]
            } else {
                [0.0; 3]
            }
        }
        Input::RandomSign { mag, axis, .. } => {
            let mut f = [0.0; 3];
            f[*axis] = if xorshift(rng) & 1 == 0 { *mag } else { -*mag };
            f
        }
    }
}

/// The tip moment at time `t` (global x, y, z), `None` for an input without one.
fn moment_at(input: &Input, t: f64) -> Option<[f64; 3]> {
    match input {
        Input::MomentPulse { m, until } => Some(if t < *until - 1e-12 { *m } else { [0.0; 3] }),
        _ => None,
    }
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic without message".into()
    }
}

/// Runs one case; never panics (an engine panic is caught and reported).
pub fn run(case: &Case) -> Outcome {
    let start = Instant::now();
    let mut o = Outcome {
        status: Status::Completed,
        t_reached: 0.0,
        drift: 0.0,
        drift_signed: 0.0,
        energy_scale: 0.0,
        max_strain: 0.0,
        work: 0.0,
        min_step: f64::INFINITY,
        steps: 0,
        rejected: 0,
        iterations: 0,
        max_tip_dist: 0.0,
        length: 0.0,
        rotation: 0.0,
        final_omega: f64::NAN,
        wall: 0.0,
        finite: true,
        energies_finite: true,
    };
    let result = catch_unwind(AssertUnwindSafe(|| drive(case, &mut o)));
    if let Err(p) = result {
        o.status = Status::Panicked(panic_text(p));
    }
    o.wall = start.elapsed().as_secs_f64();
    o
}

fn drive(case: &Case, o: &mut Outcome) {
    let scene = match Scene::from_toml(&case.scene) {
        Ok(s) => s,
        Err(e) => {
            o.status = Status::Refused(SimError::Scene(e));
            return;
        }
    };
    o.length = scene.total_length();
    match scene.space {
        SpaceKind::Planar => drive_in::<Planar>(case, scene, o),
        SpaceKind::Spatial => drive_in::<Spatial>(case, scene, o),
    }
}

/// `a` as three components (zero-padded).
fn three(a: &[f64]) -> [f64; 3] {
    [a[0], a[1], a.get(2).copied().unwrap_or(0.0)]
}

/// The moment components of space `S` from global (x, y, z): z alone in the plane.
fn set_moment<S: Space>(m: [f64; 3], out: &mut S::Moment) {
    let c = S::moment_components_mut(out);
    let n = c.len();
    c.copy_from_slice(&m[3 - n..]);
}

/// A moment or angular velocity of space `S` as global (x, y, z).
fn moment3<S: Space>(m: &S::Moment) -> [f64; 3] {
    match S::moment_components(m) {
        [z] => [0.0, 0.0, *z],
        c => three(c),
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Rotation angle [rad] between two unit quaternions (scalar first).
fn quat_angle(a: &[f64], b: &[f64]) -> f64 {
    let c: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    2.0 * c.abs().min(1.0).acos()
}

fn drive_in<S: Space>(case: &Case, scene: Scene, o: &mut Outcome) {
    let mut sim = match Simulator::<S>::start_at(scene, 0.0) {
        Ok(s) => s,
        Err(e) => {
            o.status = Status::Refused(e);
            return;
        }
    };
    let mut rng = match case.input {
        Input::RandomSign { seed, .. } => seed.max(1),
        _ => 1,
    };
    let out = sim.outputs();
    let e0 = out.kinetic + out.strain + out.potential;
    let mut tip = three(out.tip_position.as_ref());
    let mut omega = moment3::<S>(&out.tip_angular_velocity);
    // planar: the unwrapped tip angle and its range; spatial: the accumulated rotation
    let att0 = S::attitude_components(&out.tip_angle).to_vec();
    let planar = att0.len() == 1;
    let mut prev_att = att0.clone();
    let (mut ang, mut amin, mut amax) = (att0[0], att0[0], att0[0]);
    let mut path = 0.0;
    let n = (case.t_end / case.chunk).round().max(1.0) as usize;
    for k in 1..=n {
        let t0 = (k - 1) as f64 * case.chunk;
        let f_in = force_at(&case.input, t0, tip, &mut rng);
        let mut f = sim.tip_force();
        f.as_mut().copy_from_slice(&f_in[..S::DIM]);
        sim.set_tip_force(f);
        let f = three(sim.tip_force().as_ref());
        let m = moment_at(&case.input, t0).map(|m_in| {
            let mut m = sim.tip_moment();
            set_moment::<S>(m_in, &mut m);
            sim.set_tip_moment(m);
            moment3::<S>(&sim.tip_moment())
        });
        if let Err(e) = sim.advance(k as f64 * case.chunk) {
            o.status = Status::Refused(e);
            break;
        }
        let out = sim.outputs();
        let att = S::attitude_components(&out.tip_angle);
        let w = moment3::<S>(&out.tip_angular_velocity);
        let finite = out
            .tip_position
            .as_ref()
            .iter()
            .chain(out.tip_velocity.as_ref())
            .chain(att)
            .chain(&w)
            .chain(out.root_force.as_ref())
            .chain(S::moment_components(&out.root_moment))
            .chain(&[out.kinetic, out.strain, out.potential])
            .all(|x| x.is_finite());
        if !finite {
            o.finite = false;
            o.energies_finite = [out.kinetic, out.strain, out.potential]
                .iter()
                .all(|x| x.is_finite());
            o.status = Status::NonFinite(sim.time());
            break;
        }
        let p = three(out.tip_position.as_ref());
        o.work += f[0] * (p[0] - tip[0]) + f[1] * (p[1] - tip[1]) + f[2] * (p[2] - tip[2]);
        if let Some(m) = m {
            let w_mid = [
                0.5 * (w[0] + omega[0]),
                0.5 * (w[1] + omega[1]),
                0.5 * (w[2] + omega[2]),
            ];
            o.work += dot(m, w_mid) * case.chunk;
        }
        tip = p;
        omega = w;
        let e = out.kinetic + out.strain + out.potential;
        let de = e - e0 - o.work;
        if de.abs() > o.drift {
            o.drift = de.abs();
            o.drift_signed = de;
        }
        o.max_strain = o.max_strain.max(out.strain);
        o.energy_scale = o
            .energy_scale
            .max(out.kinetic)
            .max(out.strain)
            .max(o.work.abs());
        o.max_tip_dist = o.max_tip_dist.max(dot(tip, tip).sqrt());
        if planar {
            let mut d = att[0] - prev_att[0];
            d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            ang += d;
            amin = amin.min(ang);
            amax = amax.max(ang);
        } else {
            path += quat_angle(&prev_att, att);
        }
        prev_att.copy_from_slice(att);
        o.t_reached = sim.time();
        let v = three(out.tip_velocity.as_ref());
        o.final_omega = dot(v, v).sqrt() / dot(tip, tip).sqrt().max(1e-12);
    }
    o.rotation = if planar { amax - amin } else { path };
    let c = sim.counters();
    o.steps = c.steps;
    o.rejected = c.rejected;
    o.iterations = c.iterations;
    o.min_step = sim.min_step_used;
}
