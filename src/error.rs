//! Why a [`Simulator`](crate::simulator::Simulator) call failed, by kind, so that a caller
//! chooses what to do from the kind (the FMU adapter: fmi2Discard for a step it may retry,
//! fmi2Error for a snapshot of another model) and shows the message, which says what to change.

use crate::integrator::{StaticFailure, StepFailure};
use crate::scene::{SceneError, MIN_STEP};
use crate::simulator::limits::{
    MAX_MODAL_DEFLECTION, MAX_TWIST_PER_ELEMENT, MIN_CHART_MARGIN, MIN_SECTION_SINE,
};
use thiserror::Error;

/// A failure of the simulator. On every step failure, refusal or non-finite result the
/// simulator keeps its state from before the call.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SimError {
    /// The scene (or the model built from it) is invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// `initial.state = "static"`: the static equilibrium was not found.
    #[error("initial.state = \"static\": {0}; try initial.state = \"straight\" or smaller loads")]
    InitialStatic(#[source] StaticFailure),
    /// The consistent initial accelerations could not be computed.
    #[error("initial accelerations: {0}")]
    InitialAccelerations(#[source] StepFailure),
    /// [`Simulator::solve_static`](crate::simulator::Simulator::solve_static) found no
    /// equilibrium.
    #[error(transparent)]
    Static(#[from] StaticFailure),
    /// `advance` was asked to go to a time not after the current one (or not finite).
    #[error("cannot advance from t = {t0} to t = {t_end}")]
    BadTime {
        /// Current time [s].
        t0: f64,
        /// Requested end time [s].
        t_end: f64,
    },
    /// The communication step needs more internal steps of `solver.max_step` than
    /// `solver.max_internal_steps`; refused before any work.
    #[error(
        "step from t = {t0:.6} s to {t_end:.6} s refused: it needs {needed:.0} internal steps of solver.max_step = {h_max:e} s, more than the cap solver.max_internal_steps = {cap}; split it into communication steps of at most {:e} s, or raise solver.max_step (or solver.max_internal_steps in the scene)",
        *.cap as f64 * .h_max
    )]
    WorkCap {
        /// Start of the communication step [s].
        t0: f64,
        /// Requested end [s].
        t_end: f64,
        /// Internal steps of `h_max` the span needs.
        needed: f64,
        /// `solver.max_step` [s].
        h_max: f64,
        /// `solver.max_internal_steps`.
        cap: u64,
    },
    /// The accelerations consistent with inputs changed at a communication point could not be
    /// computed.
    #[error("step from t = {t:.6} s: accelerations consistent with the new inputs: {source}; reduce the loads")]
    InputJump {
        /// Time of the input change [s].
        t: f64,
        /// The integrator's failure.
        source: StepFailure,
    },
    /// An internal step failed (no convergence or singular) and could not be halved further.
    #[error(
        "step from t = {t:.6} s failed {limit}: {source}. Reduce the communication step or solver.max_step, add damping, lower solver.rho_inf, or reduce the loads"
    )]
    Step {
        /// Start of the communication step [s].
        t: f64,
        /// Halvings of the internal step done before giving up.
        halvings: u32,
        /// Which limit stopped the halving.
        limit: StepLimit,
        /// The integrator's last failure.
        source: StepFailure,
    },
    /// An internal step with the partner model (`root.mobility`) did not meet the partner
    /// equation a = a_host + G (R − R_ref) within
    /// [`PARTNER_ITERATIONS`](crate::simulator::limits::PARTNER_ITERATIONS) iterations, to neither of
    /// its tolerances ([`PARTNER_TOLERANCE`](crate::simulator::limits::PARTNER_TOLERANCE)), and could
    /// not be halved further.
    #[error(
        "step from t = {t:.6} s failed {limit}: the partner model's equation a = a_host + G (R - R_ref) (root.mobility, root.reaction_reference) was not met at an internal step of {h:.3e} s after {} iterations: residual {residual:.2e} of the magnitude of its terms (tolerance {tolerance:.1e}, {:.0e} x solver.tolerance), and the correction of the mount's acceleration still to make {correction:.2e} x what moves the mount by solver.tolerance over the step. Check that root.mobility is the host's own mobility at the mount (without the beam's inertia) and finite in size, or reduce the communication step",
        crate::simulator::limits::PARTNER_ITERATIONS,
        crate::simulator::limits::PARTNER_TOLERANCE
    )]
    Partner {
        /// Start of the communication step [s].
        t: f64,
        /// Halvings of the internal step done before giving up.
        halvings: u32,
        /// Which limit stopped the halving.
        limit: StepLimit,
        /// The last internal step tried [s].
        h: f64,
        /// Its last residual, the largest component relative to the magnitude of the
        /// equation's terms.
        residual: f64,
        /// The tolerance it missed, relative as `residual`.
        tolerance: f64,
        /// The correction of the deviation's acceleration the iteration would still make,
        /// relative to the one that moves the mount by the Newton tolerance over the step.
        correction: f64,
    },
    /// The step converged to a state outside the model's validity.
    #[error("step to t = {t:.6} s refused: {refusal}")]
    Refused {
        /// End of the refused communication step [s].
        t: f64,
        /// What was out of range.
        refusal: Refusal,
    },
    /// The step produced non-finite coordinates or velocities.
    #[error("step to t = {t:.6} s produced non-finite coordinates; reduce the communication step or solver.max_step")]
    NonFinite {
        /// End of the communication step [s].
        t: f64,
    },
    /// A snapshot does not fit this simulator.
    #[error(transparent)]
    Snapshot(#[from] SnapshotError),
}

/// The limit that ended the halving of a failing internal step.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum StepLimit {
    /// [`MAX_HALVINGS`](crate::integrator::MAX_HALVINGS) reached.
    #[error(
        "after {} halvings of the internal step",
        crate::integrator::MAX_HALVINGS
    )]
    MaxHalvings,
    /// Halving (or the error control's reduction) would go below [`MIN_STEP`].
    #[error("at an internal step of {h:e} s (a smaller one would go below the smallest internal step {MIN_STEP:e} s)")]
    MinStep {
        /// The internal step that failed [s].
        h: f64,
    },
    /// The real-time mode (`solver.mode = "realtime"`) does not halve a step.
    #[error("in the real-time mode, which never halves an internal step")]
    Realtime,
    /// Another halving would exceed `solver.max_internal_steps`.
    #[error("after {halvings} halvings of the internal step (another would exceed solver.max_internal_steps = {cap} internal steps in one communication step)")]
    WorkCap {
        /// Halvings done.
        halvings: u32,
        /// `solver.max_internal_steps`.
        cap: u64,
    },
}

/// A converged state the model refuses as outside its validity.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Refusal {
    /// A modal segment deflects beyond [`MAX_MODAL_DEFLECTION`].
    #[error(
        "modal segment '{segment}' deflects {:.1} % of its length (or 1/100 rad of tip slope), beyond the {:.0} % validity of a linear floating frame; make it kind = \"ancf\", shorten it, or reduce the loads",
        100.0 * .value,
        100.0 * MAX_MODAL_DEFLECTION
    )]
    ModalDeflection {
        /// Scene name of the segment.
        segment: String,
        /// Tip deflection over length, or tip slope [rad].
        value: f64,
    },
    /// The largest axial strain exceeds the scene's `solver.max_axial_strain`.
    #[error(
        "axial strain {:.1} % exceeds solver.max_axial_strain = {limit}, the validity limit of the linear elastic rod; the loads (tip force or gravity) are too large for this beam, or, for a material that stays elastic further (a rubber hose, a soft polymer rod), raise solver.max_axial_strain",
        100.0 * .value
    )]
    AxialStrain {
        /// Largest axial strain [-].
        value: f64,
        /// The limit it exceeds (`solver.max_axial_strain`) [-].
        limit: f64,
    },
    /// An ANCF element twists more than [`MAX_TWIST_PER_ELEMENT`].
    #[error(
        "ANCF segment '{segment}' twists {:.0}° within one element, beyond the {:.0}° its elements resolve (the section director r_y is interpolated linearly, so the twist rate within an element grows uneven and the director vanishes at 180°); give the segment more elements, or reduce the tip moment about the beam axis",
        .value.to_degrees(),
        MAX_TWIST_PER_ELEMENT.to_degrees()
    )]
    Twist {
        /// Scene name of the segment.
        segment: String,
        /// Largest twist within one element [rad].
        value: f64,
    },
    /// A node of an element with twist angles turned (nearly) back onto the beam's initial
    /// axis, where its angle has no reference.
    #[error(
        "ANCF segment '{segment}': a node's tangent turned {:.1}° from the beam's initial axis (beyond {:.0}°); torsion_element = \"angle\" measures the twist from the smallest rotation of that axis onto the tangent, which has no meaning near 180°; use torsion_element = \"director\" for a beam that turns this far",
        crate::math::acos((.value - 1.0).clamp(-1.0, 1.0)).to_degrees(),
        crate::math::acos(MIN_CHART_MARGIN - 1.0).to_degrees()
    )]
    TwistChart {
        /// Scene name of the segment.
        segment: String,
        /// Smallest 1 + t⁰·t of a node [-].
        value: f64,
    },
    /// A node's section director r_y is (nearly) parallel to its slope r_x: no section frame.
    #[error(
        "ANCF segment '{segment}': a node's section director r_y is within {:.1}° of its slope r_x (sine {value:.2e}, at least {MIN_SECTION_SINE} needed), so it defines no section frame; r_y must stay a unit vector across the section, perpendicular to r_x",
        crate::math::asin(value.clamp(-1.0, 1.0)).to_degrees()
    )]
    SectionDirector {
        /// Scene name of the segment.
        segment: String,
        /// Smallest sine of the angle between r_x and r_y [-].
        value: f64,
    },
    /// The mount moved further in one communication step than the bound (a host's pose that
    /// jumps, e.g. a teleport or a unit mistake).
    #[error(
        "mount pose jumps by {distance:.3e} m and {:.1}° from the predicted pose in one communication step, beyond the bound of {:.0} % of the beam length and {:.0}°; move the mount continuously (a pose with consistent velocity and acceleration inputs), or shorten the communication step",
        .angle.to_degrees(),
        100.0 * crate::simulator::limits::MAX_MOUNT_JUMP_LENGTH,
        crate::simulator::limits::MAX_MOUNT_JUMP_ANGLE.to_degrees()
    )]
    MountJump {
        /// Distance of the host's mount point from the predicted one [m].
        distance: f64,
        /// Angle of the rotation between the host's and the predicted orientation [rad].
        angle: f64,
    },
    /// A mount input that defines no motion.
    #[error("mount input refused: {0}")]
    MountInput(String),
}

/// A snapshot that does not fit this simulator.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SnapshotError {
    /// The bytes are not a simulator snapshot (truncated, trailing bytes or malformed).
    #[error("not a hybeam simulator snapshot: {0}")]
    Malformed(String),
    /// The snapshot was written in another format version.
    #[error("snapshot format version {found} is not this simulator's version {expected}")]
    Version {
        /// Version in the bytes.
        found: u32,
        /// [`SNAPSHOT_VERSION`](crate::simulator::SNAPSHOT_VERSION).
        expected: u32,
    },
    /// The snapshot was taken from a simulator of another scene (or other parameters).
    #[error("snapshot belongs to another model: its scene (apart from the tip force and gravity it carries) differs from this simulator's; restore it into an instance of the same scene and parameters")]
    OtherModel,
    /// Vector lengths differ from this model's.
    #[error("state dimensions do not match this model")]
    Dimensions,
    /// The step control's step is outside [`MIN_STEP`, `solver.max_step`].
    #[error("snapshot step size {h:e} s is not in [{MIN_STEP:e}, solver.max_step = {h_max:e}] s (the smallest internal step is {MIN_STEP:e} s)")]
    StepSize {
        /// Snapshot step [s].
        h: f64,
        /// `solver.max_step` [s].
        h_max: f64,
    },
    /// The held Newton matrix's step is outside (0, `solver.max_step`].
    #[error(
        "snapshot Newton-matrix step size {h:e} s is not in (0, solver.max_step = {h_max:e}] s"
    )]
    JacobianStep {
        /// Snapshot Newton-matrix step [s].
        h: f64,
        /// `solver.max_step` [s].
        h_max: f64,
    },
    /// A value of the snapshot (state, inputs, integrator memory, mount path, load rates) is
    /// NaN or infinite.
    #[error("snapshot field {field} = {value} is not finite: the state cannot be continued from")]
    NonFiniteField {
        /// Path of the value in the snapshot (e.g. `memory.mount.base.acceleration[0]`).
        field: String,
        /// The value.
        value: f64,
    },
    /// A value of the snapshot is finite but outside what it can be.
    #[error("snapshot field {field} = {value} is not {expected}")]
    Field {
        /// Path of the value in the snapshot.
        field: &'static str,
        /// The value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// An orientation of the mount's path is not unit Euler parameters (or not normalizable,
    /// for the pending input).
    #[error("snapshot field {field}.attitude = {components:?} is not a usable orientation (unit Euler parameters; nonzero ones for a pending input)")]
    Attitude {
        /// Path of the motion in the snapshot.
        field: &'static str,
        /// Its orientation components.
        components: Vec<f64>,
    },
    /// The snapshot's state is one the model cannot continue from.
    #[error("snapshot state refused: {0}")]
    Refused(Refusal),
    /// The held Newton matrix could not be rebuilt.
    #[error("cannot rebuild the Newton matrix of the snapshot: {0}")]
    NewtonMatrix(#[source] StepFailure),
}

impl SimError {
    /// A short name of the kind, for tables and logs (e.g. `"refusal"`).
    pub fn kind(&self) -> &'static str {
        match self {
            SimError::Scene(_) => "scene",
            SimError::InitialStatic(_) | SimError::InitialAccelerations(_) => "initial state",
            SimError::Static(_) => "statics",
            SimError::BadTime { .. } => "bad time",
            SimError::WorkCap { .. } => "work cap",
            SimError::InputJump { .. } | SimError::Step { .. } | SimError::Partner { .. } => {
                "step failure"
            }
            SimError::Refused { .. } => "refusal",
            SimError::NonFinite { .. } => "non-finite",
            SimError::Snapshot(_) => "snapshot",
        }
    }
}
