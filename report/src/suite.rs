//! The stability suite: extreme scenes and inputs, each run to its end or to a clean refusal.
//! Shared by the report binary (`report stability`) and by the crate's `tests/stability.rs` (the fast
//! subset), so both run exactly the same cases. Depends only on the hybeam library.

use hybeam::error::SimError;
use hybeam::scene::Scene;
use hybeam::simulator::Simulator;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Tip force input schedule (on top of the scene's constant tip force).
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
    /// Force of magnitude `mag` perpendicular to the root-to-tip line (counter-clockwise),
    /// updated every communication step, until `until` [s].
    Perpendicular {
        /// Magnitude [N].
        mag: f64,
        /// End [s].
        until: f64,
    },
    /// Vertical force ±`mag` with a random sign drawn every communication step.
    RandomSign {
        /// Magnitude [N].
        mag: f64,
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
    /// tip forces).
    pub drift: f64,
    /// E − E0 − W at the sample where |E − E0 − W| is largest [J] (negative: energy lost).
    pub drift_signed: f64,
    /// Largest of kinetic energy, strain energy and |W| over the samples [J].
    pub energy_scale: f64,
    /// Largest strain energy [J].
    pub max_strain: f64,
    /// Work of the tip forces at the end [J].
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
    /// Range (max − min) of the unwrapped tip angle [rad].
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

/// The suite; `quick` leaves out the long variants.
pub fn cases(quick: bool) -> Vec<Case> {
    let mut v = Vec::new();
    let steps: [f64; 5] = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2];
    for h in steps {
        let t_end = (2e4 * h).min(1.0);
        v.push(Case {
            name: format!("stiff 0.5 mm rod, 64 el., h={h:e}"),
            what: format!("steel d = 0.5 mm, L = 0.4 m, 64 ANCF elements, gravity, {t_end} s"),
            scene: scene_text(
                "thin",
                -9.81,
                "clamped",
                &solver(h, 0.9),
                &[ancf("rod", 0.4, 0.0005, 64, STEEL)],
            ),
            t_end,
            chunk: h.max(1e-3),
            input: Input::None,
            fast: true,
        });
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
    v
}

fn xorshift(s: &mut u64) -> u64 {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    *s
}

fn input_at(input: &Input, t: f64, tip: [f64; 2], rng: &mut u64) -> [f64; 2] {
    match input {
        Input::None => [0.0, 0.0],
        Input::Pulse { f, until } => {
            if t < *until - 1e-12 {
                *f
            } else {
                [0.0, 0.0]
            }
        }
        Input::Perpendicular { mag, until } => {
            let r = (tip[0] * tip[0] + tip[1] * tip[1]).sqrt().max(1e-12);
            if t < *until - 1e-12 {
                [-mag * tip[1] / r, mag * tip[0] / r]
            } else {
                [0.0, 0.0]
            }
        }
        Input::RandomSign { mag, .. } => {
            if xorshift(rng) & 1 == 0 {
                [0.0, *mag]
            } else {
                [0.0, -*mag]
            }
        }
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
    let mut sim = match Simulator::new(scene) {
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
    let mut tip = out.tip_position;
    let (mut ang, mut prev_raw) = (out.tip_angle, out.tip_angle);
    let (mut amin, mut amax) = (ang, ang);
    let n = (case.t_end / case.chunk).round().max(1.0) as usize;
    for k in 1..=n {
        let t0 = (k - 1) as f64 * case.chunk;
        let f_in = input_at(&case.input, t0, tip, &mut rng);
        sim.set_tip_force(f_in);
        let f = sim.tip_force();
        if let Err(e) = sim.advance(k as f64 * case.chunk) {
            o.status = Status::Refused(e);
            break;
        }
        let out = sim.outputs();
        let vals = [
            out.tip_position[0],
            out.tip_position[1],
            out.tip_velocity[0],
            out.tip_velocity[1],
            out.tip_angle,
            out.kinetic,
            out.strain,
            out.potential,
            out.root_force[0],
            out.root_force[1],
            out.root_moment,
        ];
        if vals.iter().any(|x| !x.is_finite()) {
            o.finite = false;
            o.energies_finite = [out.kinetic, out.strain, out.potential]
                .iter()
                .all(|x| x.is_finite());
            o.status = Status::NonFinite(sim.time());
            break;
        }
        o.work += f[0] * (out.tip_position[0] - tip[0]) + f[1] * (out.tip_position[1] - tip[1]);
        tip = out.tip_position;
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
        o.max_tip_dist = o
            .max_tip_dist
            .max((tip[0] * tip[0] + tip[1] * tip[1]).sqrt());
        let mut d = out.tip_angle - prev_raw;
        d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
        prev_raw = out.tip_angle;
        ang += d;
        amin = amin.min(ang);
        amax = amax.max(ang);
        o.t_reached = sim.time();
        let v = out.tip_velocity;
        o.final_omega = (v[0] * v[0] + v[1] * v[1]).sqrt()
            / (tip[0] * tip[0] + tip[1] * tip[1]).sqrt().max(1e-12);
    }
    o.rotation = amax - amin;
    let c = sim.counters();
    o.steps = c.steps;
    o.rejected = c.rejected;
    o.iterations = c.iterations;
    o.min_step = sim.min_step_used;
}
