//! The limits beyond which the simulator refuses a state or an input rather than return a
//! number outside the model's validity (each refusal names its limit and what to change).

/// Largest elastic deflection of a modal segment accepted, as tip deflection over length or tip
/// slope [rad]: a linear floating frame is a small-deformation model.
pub const MAX_MODAL_DEFLECTION: f64 = 0.3;

/// Largest twist within one ANCF element accepted [rad] (45°): the twist energy takes the
/// element's twist from its nodal frames (exact for any angle below 180°, where its atan2 jumps),
/// but the section director r_y is interpolated linearly for the director inertia and the
/// sampled section frame, so at a twist φ per element the interpolated director's rate at the
/// element's middle is sin φ/((1 + cos φ)/2) instead of φ (+5.5 % at 45°, +27 % at 90°), and it
/// vanishes at 180°.
pub const MAX_TWIST_PER_ELEMENT: f64 = std::f64::consts::FRAC_PI_4;

/// Smallest chart margin 1 + t⁰·t accepted at a node of an element with twist angles
/// (`torsion_element = "angle"`): 1 − cos 150°, a tangent turned by at most 150° from the beam's
/// initial axis t⁰. The angles are measured from the smallest rotation of t⁰ onto the tangent,
/// which is undefined at 180° (its Jacobians grow as the margin's inverse).
pub const MIN_CHART_MARGIN: f64 = 0.133_974_596_215_561_35;

/// Smallest sine of the angle between an ANCF node's r_x and r_y accepted [-] (the nodal
/// penalty keeps them perpendicular, sine 1; at 0 the section frame is undefined).
pub const MIN_SECTION_SINE: f64 = 0.5;

/// Largest jump of the mount point from its predicted position in one communication step, as a
/// fraction of the beam's length: beyond it the host's pose is refused (a teleport or a unit
/// mistake), not re-anchored.
pub const MAX_MOUNT_JUMP_LENGTH: f64 = 0.1;

/// Largest rotation of the mount frame from its predicted orientation in one communication step
/// [rad] (30°).
pub const MAX_MOUNT_JUMP_ANGLE: f64 = std::f64::consts::FRAC_PI_6;

/// Iterations of the partner's deviation per internal step, at most; an internal step that
/// has not met the partner tolerance after them, nor the Newton tolerance in the last
/// ([`PARTNER_TOLERANCE`]), fails (and is halved, as a step whose Newton iteration fails).
pub const PARTNER_ITERATIONS: usize = 12;

/// Tolerance of the partner equation a₁ = G (R − R_ref) at an internal step's end, as a
/// multiple of the solver's Newton tolerance (`solver.tolerance`): per component i, relative
/// to the magnitude of its terms,
///
/// |a₁ᵢ − Σⱼ Gᵢⱼ (Rⱼ − R_ref,ⱼ)| ≤ this · solver.tolerance · (|a₁ᵢ| + Σⱼ |Gᵢⱼ| (|Rⱼ| + |R_ref,ⱼ|)),
///
/// a₁ the deviation's end acceleration (the mount's acceleration minus the host's): 1e-7 at
/// the default 1e-11. The reaction R is that of a step converged to the Newton tolerance, and
/// no better: its coordinates' remaining error, amplified by the stiffness at the mount and
/// by 1/h² in the accelerations, varies R between solves of the same step by about 1e-9–1e-8
/// of its size at the default and the boom's 0.2 ms steps (`scenes/boom.toml`), and by more
/// at smaller steps (it grows as 1/h²), which no iteration on a₁ resolves. So a step that has
/// not met this after [`PARTNER_ITERATIONS`] iterations is accepted at the Newton tolerance
/// itself, as the beam's coordinates are: if the correction of a₁ the iteration would still
/// make, δ, moves the mount over the step by less than it, h²/4 |δᵢ| ≤ solver.tolerance · ℓᵢ
/// (ℓ the Newton scale of the mount's coordinates: the beam's length for a translation, 1 rad
/// for a rotation).
pub const PARTNER_TOLERANCE: f64 = 1e4;
