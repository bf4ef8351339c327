//! The inputs a host changes between communication steps: the tip loads and gravity
//! ([`Inputs`]), their derivatives over the next step ([`LoadRates`]), and the simulator's
//! setters and getters of them. The simulator owns the inputs: those set for the next step
//! (pending) and those the state is consistent with (applied); the model holds the applied
//! ones, and the step (`step.rs`) is the one place that moves the pending ones into it.

use super::*;
use crate::scene::MAX_LINE_LOADS;

/// The inputs of the equations a host may change between communication steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct Inputs<S: Space> {
    /// Total tip force [N], global axes.
    pub tip_force: S::Vec,
    /// Total dead tip moment [N m], global axes (in the plane: about z, counter-clockwise).
    pub tip_moment: S::Moment,
    /// Gravity [m/s²], global axes.
    pub gravity: S::Vec,
    /// The line load of each slot [N/m], global axes: slot k belongs to the k-th segment that
    /// declares `line_load` ([`crate::scene::Scene::line_load_segments`]; zero beyond them).
    pub line_loads: [S::Vec; MAX_LINE_LOADS],
}

impl<S: Space> Inputs<S> {
    /// The loads a model holds.
    pub(super) fn of(model: &Model<S>) -> Self {
        Self {
            tip_force: model.tip_force(),
            tip_moment: model.tip_moment(),
            gravity: model.gravity(),
            line_loads: model.line_loads(),
        }
    }

    pub(super) fn apply(&self, model: &mut Model<S>) {
        model.set_tip_force(self.tip_force);
        model.set_tip_moment(self.tip_moment);
        if model.gravity() != self.gravity {
            model.set_gravity(self.gravity);
        }
        let held = model.line_loads();
        for (slot, q) in self.line_loads.iter().enumerate() {
            if held[slot] != *q {
                model.set_line_load(slot, *q);
            }
        }
    }
}

/// First and second time derivatives of the tip loads over the coming communication step (FMI
/// input derivatives; zero: the loads are held): the step integrates
/// F(t₀ + τ) = F + Ḟτ + ½F̈τ² (and the moment likewise) at every internal step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct LoadRates<S: Space> {
    /// Ḟ [N/s], F̈ [N/s²], global axes.
    pub force: [S::Vec; 2],
    /// Ṁ [N m/s], M̈ [N m/s²].
    pub moment: [S::Moment; 2],
    /// q̇ [N/(m s)], q̈ [N/(m s²)] of each line-load slot, global axes.
    pub line: [[S::Vec; 2]; MAX_LINE_LOADS],
}

impl<S: Space> LoadRates<S> {
    /// Whether any rate is nonzero.
    pub(super) fn any(&self) -> bool {
        self.force
            .iter()
            .any(|f| f.as_ref().iter().any(|x| *x != 0.0))
            || self
                .moment
                .iter()
                .any(|m| S::moment_components(m).iter().any(|x| *x != 0.0))
            || self
                .line
                .iter()
                .flatten()
                .any(|q| q.as_ref().iter().any(|x| *x != 0.0))
    }

    /// The loads `tau` [s] after `at`, whose loads are the values at the start.
    pub(super) fn advanced(&self, at: &Inputs<S>, tau: f64) -> Inputs<S> {
        let mut out = *at;
        let (c1, c2) = (tau, 0.5 * tau * tau);
        for k in 0..S::DIM {
            out.tip_force[k] += c1 * self.force[0][k] + c2 * self.force[1][k];
        }
        for (q, [d1, d2]) in out.line_loads.iter_mut().zip(&self.line) {
            for k in 0..S::DIM {
                q[k] += c1 * d1[k] + c2 * d2[k];
            }
        }
        let (d1, d2) = (
            S::moment_components(&self.moment[0]),
            S::moment_components(&self.moment[1]),
        );
        for ((m, a), b) in S::moment_components_mut(&mut out.tip_moment)
            .iter_mut()
            .zip(d1)
            .zip(d2)
        {
            *m += c1 * a + c2 * b;
        }
        out
    }
}

impl<S: Space> Simulator<S> {
    /// Sets gravity [m/s²] (takes effect at the next step, as a jump of the inputs; the model
    /// and the outputs keep the applied gravity until then).
    pub fn set_gravity(&mut self, g: S::Vec) {
        self.pending.gravity = g;
    }

    /// Work counters.
    pub fn counters(&self) -> Counters {
        *self.integ.counters()
    }

    /// Sets the total tip force [N], global axes (replaces the scene's; takes effect at the
    /// next step, as a jump of the inputs at the current time: see [`Simulator::advance`]).
    pub fn set_tip_force(&mut self, f: S::Vec) {
        self.pending.tip_force = f;
    }

    /// The total tip force set for the next step [N], global axes.
    pub fn tip_force(&self) -> S::Vec {
        self.pending.tip_force
    }

    /// Sets the total dead tip moment [N m], global axes (in the plane: about z,
    /// counter-clockwise; replaces the scene's; takes effect at the next step, as a jump of the
    /// inputs like the tip force).
    pub fn set_tip_moment(&mut self, m: S::Moment) {
        self.pending.tip_moment = m;
    }

    /// The total tip moment set for the next step [N m], global axes.
    pub fn tip_moment(&self) -> S::Moment {
        self.pending.tip_moment
    }

    /// Gravity set for the next step [m/s²], global axes.
    pub fn gravity(&self) -> S::Vec {
        self.pending.gravity
    }

    /// The inputs set for the next step (tip force, tip moment, gravity).
    pub fn inputs(&self) -> Inputs<S> {
        self.pending
    }

    /// Sets all inputs (each takes effect at the next step, as a jump of the inputs).
    pub fn set_inputs(&mut self, inputs: &Inputs<S>) {
        self.pending = *inputs;
    }

    /// The tip loads' derivatives for the next step ([`LoadRates`]); they hold for that step
    /// only (zero after it).
    pub fn set_load_rates(&mut self, rates: LoadRates<S>) {
        self.load_rates = rates;
    }

    /// The tip loads' derivatives set for the next step.
    pub fn load_rates(&self) -> LoadRates<S> {
        self.load_rates
    }
}

impl<S: Space> Inputs<S> {
    /// The value of one input; `None` for a component this space does not have (and for the
    /// mount's inputs, which are not part of these).
    pub fn get(&self, id: InputId) -> Option<f64> {
        let k = id.component;
        match id.kind {
            InputKind::TipForce => self.tip_force.as_ref().get(k).copied(),
            InputKind::TipMoment => S::moment_components(&self.tip_moment).get(k).copied(),
            InputKind::Gravity => self.gravity.as_ref().get(k).copied(),
            InputKind::LineLoad => {
                let (slot, axis) = InputId::line_load_slot(k);
                self.line_loads.get(slot)?.as_ref().get(axis).copied()
            }
            _ => None,
        }
    }

    /// Sets one input; `false` (and no change) for a component this space does not have.
    pub fn set(&mut self, id: InputId, x: f64) -> bool {
        let k = id.component;
        let slot = match id.kind {
            InputKind::TipForce => self.tip_force.as_mut().get_mut(k),
            InputKind::TipMoment => S::moment_components_mut(&mut self.tip_moment).get_mut(k),
            InputKind::Gravity => self.gravity.as_mut().get_mut(k),
            InputKind::LineLoad => {
                let (slot, axis) = InputId::line_load_slot(k);
                self.line_loads
                    .get_mut(slot)
                    .and_then(|q| q.as_mut().get_mut(axis))
            }
            _ => None,
        };
        slot.map(|s| *s = x).is_some()
    }
}

impl<S: Space> LoadRates<S> {
    /// The slot of the `order`-th derivative (1 or 2) of a tip load component; `None` for
    /// other inputs (gravity takes no derivatives) or components.
    fn slot(&mut self, id: InputId, order: u32) -> Option<&mut f64> {
        let rates = self;
        let o = (order as usize).checked_sub(1).filter(|o| *o < 2)?;
        match id.kind {
            InputKind::TipForce => rates.force[o].as_mut().get_mut(id.component),
            InputKind::TipMoment => {
                S::moment_components_mut(&mut rates.moment[o]).get_mut(id.component)
            }
            InputKind::LineLoad => {
                let (slot, axis) = InputId::line_load_slot(id.component);
                rates.line.get_mut(slot)?[o].as_mut().get_mut(axis)
            }
            _ => None,
        }
    }
}

impl<S: Space> Simulator<S> {
    /// Whether the model has the slot of a line-load input (every other input: true).
    fn has_slot(&self, id: InputId) -> bool {
        id.kind != InputKind::LineLoad
            || InputId::line_load_slot(id.component).0 < self.model.line_load_slots()
    }

    /// The value of an input set for the next step; `None` for a component this space (or a
    /// fixed root) does not have.
    pub fn input(&self, id: InputId) -> Option<f64> {
        if !self.has_slot(id) {
            return None;
        }
        if id.kind.is_partner() {
            let mounted = self.mount_accelerations_given().is_some();
            let mut p = self.partner();
            return p.slot(id).filter(|_| mounted).map(|x| *x);
        }
        if id.kind.is_mount() {
            return self.mount_input().and_then(|mut m| m.slot(id).map(|x| *x));
        }
        self.pending.get(id)
    }

    /// Sets one input for the next step (a jump of the inputs: see [`Simulator::advance`]; a
    /// mount input is checked there), leaving every other input as it is; an input set again
    /// forgets its derivatives (they held for one step). `false` (and no change) for a
    /// component this space (or a fixed root) does not have.
    pub fn set_input(&mut self, id: InputId, x: f64) -> bool {
        if !self.has_slot(id) {
            return false;
        }
        if id.kind.is_partner() {
            let mut p = self.partner();
            return p.slot(id).map(|slot| *slot = x).is_some() && self.set_partner(p);
        }
        if id.kind.is_mount() {
            let Some(mut m) = self.mount_input() else {
                return false;
            };
            let known = m.slot(id).map(|slot| *slot = x).is_some();
            let velocity_mode = self.mount_accelerations_given() == Some(false);
            for order in [1, 2] {
                if let Some(d) = m.derivative_slot(id, order, velocity_mode) {
                    if !(velocity_mode && order == 1) {
                        *d = 0.0;
                    }
                }
            }
            if velocity_mode
                && matches!(
                    id.kind,
                    InputKind::MountVelocity | InputKind::MountAngularVelocity
                )
            {
                m.accelerations = false;
            }
            return known && self.set_mount_unchecked(m);
        }
        let known = self.pending.set(id, x);
        if known {
            for order in [1, 2] {
                if let Some(d) = self.load_rates.slot(id, order) {
                    *d = 0.0;
                }
            }
        }
        known
    }

    /// Sets the derivative of order 1 or 2 of an input over the coming communication step
    /// (FMI input derivatives; they hold for the next step only). Mount inputs: the
    /// accelerations' derivatives (or, with `motion_input = "pose_velocity"`, the velocities')
    /// shape the base motion; derivatives of the pose, implied by the velocities, are accepted
    /// and not used. Tip loads: [`LoadRates`]. `false` for gravity.
    pub fn set_input_derivative(&mut self, id: InputId, order: u32, x: f64) -> bool {
        if !(1..=2).contains(&order) || !self.has_slot(id) {
            return false;
        }
        if id.kind.is_partner() {
            // the partner model is held over a step: a derivative is accepted, not used
            return self.input(id).is_some();
        }
        if !id.kind.is_mount() {
            return self.load_rates.slot(id, order).map(|d| *d = x).is_some();
        }
        let (Some(mut m), Some(given)) = (self.mount_input(), self.mount_accelerations_given())
        else {
            return false;
        };
        if m.slot(id).is_none() {
            return false;
        }
        let Some(slot) = m.derivative_slot(id, order, !given) else {
            // a derivative implied by other inputs (the pose's, or the velocities' when
            // accelerations are inputs): accepted, not used
            return true;
        };
        *slot = x;
        if !given && order == 1 {
            // the velocity's derivative given: no backward-difference estimate
            m.accelerations = true;
        }
        self.set_mount_unchecked(m)
    }
}

/// The time `dt` into a step of size `h` from `t_start` to `t_next`, at which a stage takes its
/// inputs (load rates, the mount's path): `t_next` itself at the step's end (its rounding is
/// the communication grid's), `t_start + dt` at a stage inside.
pub(super) fn stage_time(t_start: f64, t_next: f64, h: f64, dt: f64) -> f64 {
    if dt == h {
        t_next
    } else {
        t_start + dt
    }
}
