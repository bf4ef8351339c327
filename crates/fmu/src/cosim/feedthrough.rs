//! A mounted beam's direct feedthrough and the outputs' first derivatives: the apparent mass
//! (the reaction's partials by the mount accelerations), the rigid inertia's mass matrix (the
//! elastic outputs' feedthrough is the apparent mass minus it), and the backward differences
//! of the outputs without an exact derivative. One reaction row per output
//! ([`reaction_row`]).

use hybeam::simulator::{
    AnyOutputs, AnySimulator, InputId, InputKind, MountMatrix, OutputId, Quantity,
    PARTNER_COMPONENTS,
};

use super::variables::{Access, Table};

/// The reaction component of an output: its row (force components, then moment components)
/// and whether it is the elastic part (beyond the rigid inertia's); `None` for any other
/// output. `dim`: the space's number of force components.
pub fn reaction_row(id: OutputId, dim: usize) -> Option<(usize, bool)> {
    match id.quantity {
        Quantity::RootForce => Some((id.component, false)),
        Quantity::RootMoment => Some((dim + id.component, false)),
        Quantity::ElasticForce => Some((id.component, true)),
        Quantity::ElasticMoment => Some((dim + id.component, true)),
        _ => None,
    }
}

/// The column of a mount input in the apparent mass and the factor on it: accelerations
/// directly, velocities (with `motion_input = "pose_velocity"`) through the backward-difference
/// estimate of the acceleration, divided by the last communication step `h`. `None` for other
/// inputs.
fn mount_column(id: InputId, dim: usize, h: f64) -> Option<(usize, f64)> {
    match id.kind {
        InputKind::MountAcceleration => Some((id.component, 1.0)),
        InputKind::MountAngularAcceleration => Some((dim + id.component, 1.0)),
        InputKind::MountVelocity => Some((id.component, 1.0 / h)),
        InputKind::MountAngularVelocity => Some((dim + id.component, 1.0 / h)),
        _ => None,
    }
}

/// The outputs of a state with its apparent mass and rigid inertia's mass matrix at the mount
/// (`None` for a fixed root).
#[derive(Debug, Clone)]
pub struct Evaluated {
    /// The outputs.
    pub outputs: AnyOutputs,
    apparent: Option<(MountMatrix, usize)>,
    rigid: Option<(MountMatrix, usize)>,
}

impl Evaluated {
    /// Evaluates `sim`'s current state without its apparent mass (computed on demand:
    /// [`Feedthrough::ensure_apparent`]).
    pub fn outputs_of(sim: &mut AnySimulator) -> Self {
        let outputs = sim.outputs();
        let rigid = sim.rigid_mass_array(&outputs);
        Self {
            outputs,
            apparent: None,
            rigid,
        }
    }

    /// Evaluates `sim`'s current state with its apparent mass.
    pub fn of(sim: &mut AnySimulator) -> Self {
        let outputs = sim.outputs();
        let apparent = sim.apparent_mass_array();
        let rigid = sim.rigid_mass_array(&outputs);
        Self {
            outputs,
            apparent,
            rigid,
        }
    }

    /// Whether the apparent mass is finite (or absent).
    pub fn apparent_is_finite(&self) -> bool {
        self.apparent.as_ref().is_none_or(|(j, n)| {
            j[..*n]
                .iter()
                .all(|r| r[..*n].iter().all(|x| x.is_finite()))
        })
    }
}

/// The current state's feedthrough and the outputs' backward differences.
#[derive(Debug, Clone)]
pub struct Feedthrough {
    apparent: Option<(MountMatrix, usize)>,
    /// The apparent mass is not yet computed for the current state (it takes one solve per
    /// mount acceleration component and a rebuilt Newton matrix: about three quarters of a
    /// mounted boom's step, so it is computed when a host needs it, not after every step).
    stale: bool,
    rigid: Option<(MountMatrix, usize)>,
    /// The last communication step [s] (the velocity-input mode's partials divide by it).
    last_step: f64,
    /// Per variable (table order): the change of an output over the last communication step
    /// divided by it, the first-order derivative of the outputs without an exact one
    /// (reactions, energies, inertia); 0 before the first step.
    backward: Vec<f64>,
}

impl Feedthrough {
    /// None yet, for `variables` variables, a first step of `step` [s].
    pub fn new(variables: usize, step: f64) -> Self {
        Self {
            apparent: None,
            stale: true,
            rigid: None,
            last_step: step,
            backward: vec![0.0; variables],
        }
    }

    /// Takes the evaluated state's matrices; returns its outputs.
    pub fn take(&mut self, e: Evaluated) -> AnyOutputs {
        self.stale = e.apparent.is_none();
        self.apparent = e.apparent;
        self.rigid = e.rigid;
        e.outputs
    }

    /// Computes the apparent mass of `sim`'s current state if it is not yet (a mounted beam;
    /// the run continues bit for bit: [`AnySimulator::apparent_mass`]).
    pub fn ensure_apparent(&mut self, sim: &mut AnySimulator) {
        if self.stale {
            self.apparent = sim.apparent_mass_array();
            self.stale = false;
        }
    }

    /// A new run: no step taken yet.
    pub fn restart(&mut self) {
        self.backward.fill(0.0);
    }

    /// A communication step of `h` [s] from outputs `before` to `after`.
    pub fn stepped(&mut self, h: f64, before: &AnyOutputs, after: &AnyOutputs, table: &Table) {
        self.last_step = h;
        for (index, rate) in self.backward.iter_mut().enumerate() {
            if let Access::Output(id) = table.access(index) {
                if let (Some(a), Some(b)) = (before.value(id), after.value(id)) {
                    *rate = (b - a) / h;
                }
            }
        }
    }

    /// The backward differences (table order), as a snapshot holds them.
    pub fn backward(&self) -> &[f64] {
        &self.backward
    }

    /// Restores the backward differences of a snapshot.
    pub fn set_backward(&mut self, backward: Vec<f64>) {
        self.backward = backward;
    }

    /// The first derivative of variable `index`: `exact` if the state has one, else the
    /// backward difference.
    pub fn derivative(&self, index: usize, exact: Option<f64>) -> f64 {
        exact.unwrap_or(self.backward[index])
    }

    /// The partials of reaction `row` by the mount accelerations (columns): the apparent mass,
    /// minus the rigid inertia's mass matrix for the elastic part. `None` when not available.
    fn row(&self, (row, elastic): (usize, bool)) -> Option<[f64; PARTNER_COMPONENTS]> {
        let (j, _) = self.apparent.as_ref()?;
        if !elastic {
            return Some(j[row]);
        }
        let (r, _) = self.rigid.as_ref()?;
        Some(std::array::from_fn(|c| j[row][c] - r[row][c]))
    }

    /// Output `id`'s value `cached` with the direct feedthrough of the mount accelerations set
    /// for the next step (exact: both are linear in them); other outputs as they are.
    pub fn value(&self, id: OutputId, cached: f64, sim: &AnySimulator) -> f64 {
        let dim = sim.scene().space.dim();
        let j = reaction_row(id, dim).and_then(|r| self.row(r));
        match (j, sim.mount_acceleration_change()) {
            (Some(j), Some(d)) => cached + j.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>(),
            _ => cached,
        }
    }

    /// ∂output/∂input: the apparent mass for a reaction output and a mount input, 0 for any
    /// other pair; `None` when the apparent mass is not available.
    pub fn partial(&self, output: OutputId, input: InputId, dim: usize) -> Option<f64> {
        let (Some(row), Some((col, scale))) = (
            reaction_row(output, dim),
            mount_column(input, dim, self.last_step),
        ) else {
            return Some(0.0);
        };
        self.row(row).map(|j| j[col] * scale)
    }
}
