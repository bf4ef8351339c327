//! Every setting of the time integration and the statics, in one place: the fields of
//! [`IntegrationParameters`] (the scene's `[solver]` table deserialises into it, the FMU exposes
//! some as parameters), and the fixed constants of the step policy beside it.
//!
//! The constants stay constants, not fields: none changes a result a user could want changed
//! (they decide how hard the engine tries before refusing, never what a converged step is), the
//! golden histories are recorded with them, and as fields they would add keys to the scene
//! format (`docs/scene-format.md`), FMU parameters and validation without a use asking for it.

use serde::{Deserialize, Serialize};

/// Settings of the generalized-α integrator, its step control and the statics: the `[solver]`
/// table of a scene. Validated by `Scene::validate` (which names the TOML field).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IntegrationParameters {
    /// Time integration method (default: generalized-α).
    pub method: Method,
    /// Spectral radius at infinite frequency of generalized-α, in [0, 1): the numerical damping
    /// of the highest frequencies, needed by index-3 constraints (default: 0.9).
    pub rho_inf: f64,
    /// Largest internal step [s], at least [`MIN_STEP`] (default: 1e-3); with
    /// `error_tolerance`, the upper bound of the step the error control chooses, and its first
    /// step.
    pub max_step: f64,
    /// Newton tolerance on scaled increments, relative to the beam length for positions and
    /// modal amplitudes, to 1 for slopes and angles; in [[`MIN_TOLERANCE`], 0.01). `None`
    /// (not given): [`DEFAULT_TOLERANCE`], or with `error_tolerance`
    /// [`NEWTON_FRACTION_OF_ERROR`] times it (not below [`MIN_TOLERANCE`]): the value in use is
    /// [`IntegrationParameters::newton_tolerance`]. The statics use
    /// [`STATIC_TOLERANCE_FACTOR`] times that.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// The ESDIRK4's local error per internal step, relative to each coordinate's scale
    /// (positions to the beam length, slopes and angles to 1; a velocity's error times the step
    /// counts as a position's): with it the internal step is chosen by the error estimate of
    /// the embedded order-3 solution ([`super::control`], docs/scene-format.md), up to
    /// `max_step`, instead of equal steps of `max_step`. In [[`MIN_ERROR_TOLERANCE`], 1);
    /// `method = "esdirk4"` only (default: none, the fixed step).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_tolerance: Option<f64>,
    /// Newton iteration limit per step, in 1..=100 (default: 12).
    pub max_iterations: usize,
    /// Work cap: the largest number of internal steps, accepted or rejected (a halving doubles
    /// the steps still to go), in one communication step. A longer communication step is
    /// refused before any work is done (the FMU returns fmi2Discard and keeps its state).
    /// Default: 20 000 (one Case 1–3 step takes 6–18 µs here, so a call stays below about
    /// 0.4 s; it allows communication steps up to 2 s at `max_step` = 1e-4 s).
    pub max_internal_steps: u64,
    /// Largest axial strain [-] a state may reach: a step beyond it is refused (the FMU returns
    /// fmi2Discard and keeps its state) rather than giving a number outside the linear elastic
    /// law's meaning. In (0, 1]; default [`DEFAULT_MAX_AXIAL_STRAIN`] (a metal rod); a rubber
    /// hose or a soft polymer rod may raise it.
    pub max_axial_strain: f64,
    /// The work per communication step: [`Mode::Normal`] (default) or [`Mode::Realtime`], a
    /// cost fixed before the step starts (docs/realtime.md).
    #[serde(skip_serializing_if = "Mode::is_normal")]
    pub mode: Mode,
    /// Real-time mode: Newton iterations per implicit solve, always all of them, in 1..=20
    /// (default 3).
    #[serde(skip_serializing_if = "is_default_iterations")]
    pub realtime_iterations: usize,
    /// Real-time mode: the Newton matrix is evaluated and factorized at the first iteration of
    /// every k-th implicit solve (and of the first after a change of inputs or step size), in
    /// 1..=1000 (default 1: every solve).
    #[serde(skip_serializing_if = "is_default_refresh")]
    pub realtime_refresh: u32,
    /// Real-time mode: the largest scaled Newton increment of a solve's last iteration, in
    /// units of `tolerance`, that a step is accepted with; beyond it the step fails (the FMU
    /// returns fmi2Discard naming the value and keeps its state). In [1, 1e12] (default 1e3).
    #[serde(skip_serializing_if = "is_default_bound")]
    pub realtime_bound: f64,
}

/// The work per communication step (`solver.mode`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    /// Newton iterates to `tolerance`, the held matrix refreshed when it contracts poorly, a
    /// failing internal step halved: accurate, its cost varying from step to step.
    #[default]
    Normal,
    /// A fixed work per communication step for hard real-time hosts: the internal steps of
    /// `max_step`, never halved; `realtime_iterations` Newton iterations per implicit solve;
    /// the matrix refreshed every `realtime_refresh` solves; a step whose last increment exceeds
    /// `realtime_bound` × `tolerance` fails with the value in the message.
    Realtime,
}

impl Mode {
    fn is_normal(&self) -> bool {
        *self == Mode::Normal
    }
}

/// Default of `solver.realtime_iterations`.
pub const DEFAULT_REALTIME_ITERATIONS: usize = 3;
/// Default of `solver.realtime_refresh`.
pub const DEFAULT_REALTIME_REFRESH: u32 = 1;
/// Default of `solver.realtime_bound`.
pub const DEFAULT_REALTIME_BOUND: f64 = 1e3;

fn is_default_iterations(x: &usize) -> bool {
    *x == DEFAULT_REALTIME_ITERATIONS
}
fn is_default_refresh(x: &u32) -> bool {
    *x == DEFAULT_REALTIME_REFRESH
}
fn is_default_bound(x: &f64) -> bool {
    *x == DEFAULT_REALTIME_BOUND
}

/// The fixed work of a real-time implicit solve ([`Mode::Realtime`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedWork {
    /// Newton iterations per solve.
    pub iterations: usize,
    /// The matrix refreshed every this many solves.
    pub refresh: u32,
    /// The accepted last increment, in units of the tolerance.
    pub bound: f64,
}

impl IntegrationParameters {
    /// The fixed work of the real-time mode (`None` in the normal mode).
    pub fn fixed_work(&self) -> Option<FixedWork> {
        (self.mode == Mode::Realtime).then_some(FixedWork {
            iterations: self.realtime_iterations,
            refresh: self.realtime_refresh,
            bound: self.realtime_bound,
        })
    }
}

/// The time integration method: the scene's `solver.method`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Generalized-α (Chung & Hulbert; Arnold & Brüls for the index-3 constraints): one
    /// implicit solve per step, second order, numerical damping set by `rho_inf`.
    #[default]
    GeneralizedAlpha,
    /// Kennedy & Carpenter's L-stable six-stage ESDIRK of order 4 and stage order 2
    /// (γ = 1/4, the first stage explicit): five solves with one matrix per step, a phase error
    /// of order (ωh)⁴ instead of (ωh)²; `rho_inf` unused.
    Esdirk4,
}

impl IntegrationParameters {
    /// The Newton tolerance in use: `tolerance` if given; else with `error_tolerance`
    /// [`NEWTON_FRACTION_OF_ERROR`] × `error_tolerance` (not below [`MIN_TOLERANCE`]), else
    /// [`DEFAULT_TOLERANCE`].
    pub fn newton_tolerance(&self) -> f64 {
        match (self.tolerance, self.error_tolerance) {
            (Some(t), _) => t,
            (None, Some(e)) => (NEWTON_FRACTION_OF_ERROR * e).max(MIN_TOLERANCE),
            (None, None) => DEFAULT_TOLERANCE,
        }
    }

    /// Newton tolerance of the statics: [`Self::newton_tolerance`] ×
    /// [`STATIC_TOLERANCE_FACTOR`].
    pub fn static_tolerance(&self) -> f64 {
        self.newton_tolerance() * STATIC_TOLERANCE_FACTOR
    }
}

impl Default for IntegrationParameters {
    /// The defaults documented on the fields (those of a `[solver]` table left empty).
    fn default() -> Self {
        Self {
            method: Method::GeneralizedAlpha,
            rho_inf: 0.9,
            max_step: 1e-3,
            tolerance: None,
            error_tolerance: None,
            max_iterations: 12,
            max_internal_steps: 20_000,
            max_axial_strain: DEFAULT_MAX_AXIAL_STRAIN,
            mode: Mode::Normal,
            realtime_iterations: DEFAULT_REALTIME_ITERATIONS,
            realtime_refresh: DEFAULT_REALTIME_REFRESH,
            realtime_bound: DEFAULT_REALTIME_BOUND,
        }
    }
}

/// The default of `solver.max_axial_strain`: 5 %, beyond which the linear elastic law has no
/// meaning for a metal rod.
pub const DEFAULT_MAX_AXIAL_STRAIN: f64 = 0.05;

/// Smallest internal step [s]: the lower bound of `solver.max_step`, of the step size a
/// snapshot holds, and of a halved internal step.
///
/// The fastest mode of every shipped scene (the axial mode of a 25 mm steel ANCF element) has
/// ω_max ≈ 2.0e6 rad/s, a period of 3.2 µs: at 1e-8 s a step resolves it with ω_max·h ≈ 0.02,
/// about 300 steps per period. Generalized-α is unconditionally stable, so a smaller step buys
/// neither stability nor resolved physics (elements 100 times shorter, thinner than the rod
/// they model, would still give ω_max·h ≈ 2); it only multiplies the work: 1e-12 s would take
/// about 1.4 hours of stepping per millisecond. A communication step shorter than this is
/// taken as one internal step of its own length and never halved.
pub const MIN_STEP: f64 = 1e-8;

/// The Newton tolerance when `solver.tolerance` is not given (and no `error_tolerance`).
pub const DEFAULT_TOLERANCE: f64 = 1e-11;

/// With `solver.error_tolerance` and no `solver.tolerance`, the Newton tolerance is this
/// fraction of the error tolerance. A stage's unconverged coordinates ε become a velocity
/// error of about 20 ε/h (docs/references.md §5), which moves the position by 20 ε within the
/// step: 2 % of the local error the step may make. Measured on the Case 1 all-ANCF rod
/// (16 elements, 2 s, docs/accuracy.md): at error tolerance 1e-7 the tip error is 5.1e-6 m
/// with Newton 1e-10 (34 077 iterations), 4.7e-6 m with 1e-11 (40 960), 8.8e-6 m with 1e-9
/// (24 837, the fraction 1e-2).
pub const NEWTON_FRACTION_OF_ERROR: f64 = 1e-3;

/// Smallest `solver.error_tolerance`: below it the error estimate, a difference of two
/// solutions built from the same stage accelerations, is round-off and Newton residue (the
/// stages' Newton tolerance is then [`MIN_TOLERANCE`]).
pub const MIN_ERROR_TOLERANCE: f64 = 1e-12;

/// Smallest Newton tolerance: about 4.5 machine epsilons, below which round-off in the
/// coordinates (relative 2.2e-16) keeps Newton from ever converging.
pub const MIN_TOLERANCE: f64 = 1e-15;

/// Largest number of halvings of the internal step before a communication step fails.
pub const MAX_HALVINGS: u32 = 12;

/// Communication steps completed at a reduced internal step before it is doubled again.
pub const CALM_BEFORE_GROWTH: u32 = 4;

/// Error control (`solver.error_tolerance`, [`super::control`]): the step proposed after an
/// accepted step of error `err` (in units of the tolerance) is h · [`STEP_SAFETY`] · err^(−1/4)
/// (the embedded solution is of order 3: its local error goes as h⁴), at least
/// [`STEP_SHRINK_MIN`] · h. Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4, eq. (4.13), with
/// their recommended safety factor 0.9.
pub const STEP_SAFETY: f64 = 0.9;

/// Error control: the most a step shrinks after one attempt (Hairer, Nørsett & Wanner's
/// facmin, §II.4).
pub const STEP_SHRINK_MIN: f64 = 0.2;

/// Error control: the most the proposed step grows after an accepted step (facmax, §II.4,
/// where 1.5 to 5 is recommended); none right after a rejection.
pub const STEP_GROWTH_MAX: f64 = 2.0;

/// Error control: a proposal up to this factor above the current one keeps the current one
/// (and its factorized Newton matrix, which depends on the step): RADAU5's `quot2` (Hairer &
/// Wanner, *Solving ODEs II*, §IV.8; its code's default 1.2).
pub const STEP_KEEP_BAND: f64 = 1.2;

/// Newton contraction rate above which a stale (held) Newton matrix is refreshed.
pub const REFRESH_RATE: f64 = 0.25;

/// Newton tolerance of the statics relative to `tolerance` (the statics solve 100 times
/// tighter than a step).
pub const STATIC_TOLERANCE_FACTOR: f64 = 1e-2;

/// Newton iteration limit per load step of the statics.
pub const STATIC_MAX_ITER: usize = 40;

/// Largest n + m of [`super::solve_relative_static`] (its dense Jacobian).
pub const RELATIVE_STATIC_MAX: usize = 3000;

/// Smallest load increment of the statics' load stepping before giving up.
pub const STATIC_MIN_INCREMENT: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;

    /// The defaults of an empty `[solver]` table are those `docs/scene-format.md` documents.
    #[test]
    fn defaults_match_the_scene_format_page() {
        let page = include_str!("../../docs/scene-format.md");
        let documented = |field: &str| -> f64 {
            let key = format!("| `solver.{field}` | ");
            let line = page
                .lines()
                .find(|l| l.starts_with(&key))
                .unwrap_or_else(|| panic!("solver.{field} not documented"));
            line[key.len()..]
                .split(" |")
                .next()
                .unwrap()
                .parse()
                .unwrap()
        };
        let p: IntegrationParameters = toml::from_str("").unwrap();
        assert_eq!(p, IntegrationParameters::default());
        assert_eq!(p.rho_inf, documented("rho_inf"));
        assert_eq!(p.max_step, documented("max_step"));
        assert_eq!(p.tolerance, None);
        assert_eq!(p.newton_tolerance(), documented("tolerance"));
        assert_eq!(p.max_iterations as f64, documented("max_iterations"));
        assert_eq!(
            p.max_internal_steps as f64,
            documented("max_internal_steps")
        );
        assert_eq!(p.max_axial_strain, documented("max_axial_strain"));
        assert_eq!(p.error_tolerance, None);
    }

    /// The Newton tolerance in use: a given `tolerance` wins; without it, 1e-3 ×
    /// `error_tolerance` (not below the floor) or the default; a scene written back out keeps
    /// a tolerance it did not give as not given.
    #[test]
    fn the_newton_tolerance_follows_the_error_tolerance_unless_given() {
        let p = |text: &str| toml::from_str::<IntegrationParameters>(text).unwrap();
        assert_eq!(p("").newton_tolerance(), 1e-11);
        assert_eq!(p("error_tolerance = 1e-6").newton_tolerance(), 1e-9);
        assert_eq!(
            p("error_tolerance = 1e-12").newton_tolerance(),
            MIN_TOLERANCE
        );
        let given = p("tolerance = 1e-11
error_tolerance = 1e-6");
        assert_eq!(given.newton_tolerance(), 1e-11);
        assert_eq!(given.static_tolerance(), 1e-11 * STATIC_TOLERANCE_FACTOR);
        let tied = p("error_tolerance = 1e-6");
        let text = toml::to_string(&tied).unwrap();
        assert!(!text.contains("tolerance = 1e-9"), "{text}");
        assert_eq!(p(&text), tied);
        assert_eq!(
            toml::from_str::<IntegrationParameters>(&toml::to_string(&given).unwrap()).unwrap(),
            given
        );
    }
}
