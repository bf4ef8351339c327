//! The FMU's state: its own part (the parameter values in table order, the outputs' backward
//! differences) around the simulator's snapshot (state, memory, inputs; versioned and bound to
//! the scene), encoded with `postcard`; restoring checks every value before it changes
//! anything.

use hybeam::scene::Scene;
use hybeam::simulator::AnySimulator;

use super::feedthrough::Evaluated;
use super::variables::{Access, Table};
use super::BeamFmu;

impl BeamFmu {
    /// The FMU's part (the parameter values, in table order) around the simulator's snapshot
    /// (state, memory, inputs; versioned and bound to the scene), encoded with `postcard`.
    pub(super) fn state_bytes(&self) -> Vec<u8> {
        let snapshot: FmuSnapshot = (
            self.parameters(),
            self.sim.snapshot(),
            self.feed.backward().to_vec(),
        );
        postcard::to_allocvec(&snapshot).unwrap_or_default()
    }

    /// Restores bytes of [`BeamFmu::state_bytes`]: every value checked (the parameters as
    /// fmi2SetReal checks them, the simulator's snapshot, the backward differences, the outputs
    /// and apparent mass of the restored state); on `Err` the instance keeps its state.
    pub(super) fn restore_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let (snapshot, rest) = postcard::take_from_bytes::<FmuSnapshot>(bytes)
            .map_err(|e| format!("not a hybeam FMU snapshot: {e}"))?;
        if !rest.is_empty() {
            return Err(format!(
                "not a hybeam FMU snapshot: {} trailing bytes",
                rest.len()
            ));
        }
        let (params, sim_bytes, backward) = snapshot;
        if backward.len() != self.feed.backward().len() {
            return Err("snapshot output count does not match this model".into());
        }
        let variables = self.table.variables();
        if let Some((k, x)) = backward.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(format!(
                "snapshot backward difference of {} = {x} is not finite",
                variables[k].name
            ));
        }
        let scene = self.build_scene_with_parameters(&params)?;
        // a rollback (the running simulator's parameters) restores into it, keeping its own
        // state to return to if the snapshot is refused; other parameters build a model anew
        let rollback = self.start.started && params == self.parameters();
        let (mut fresh, backup) = if rollback {
            (None, Some(self.sim.snapshot()))
        } else {
            let sim = AnySimulator::restorable(scene.clone()).map_err(|e| e.to_string())?;
            (Some(sim), None)
        };
        let sim = fresh.as_mut().unwrap_or(&mut self.sim);
        let checked = checked_restore(sim, &sim_bytes, &self.table);
        let evaluated = match checked {
            Ok(evaluated) => evaluated,
            Err(e) => {
                if let Some(b) = backup {
                    // its own snapshot of a moment ago: restores
                    let _ = self.sim.restore_snapshot(&b);
                }
                return Err(e);
            }
        };
        if let Some(sim) = fresh {
            self.sim = sim;
        }
        self.scene = scene;
        self.feed.set_backward(backward);
        self.outputs = self.feed.take(evaluated);
        self.start.started();
        Ok(())
    }

    /// The parameter values, in table order.
    pub(super) fn parameters(&self) -> Vec<f64> {
        self.table
            .parameters()
            .filter_map(|a| a.parameter(&self.scene))
            .collect()
    }

    fn build_scene_with_parameters(&self, params: &[f64]) -> Result<Scene, String> {
        let mut scene = self.base.clone();
        if self.table.parameters().count() != params.len() {
            return Err("snapshot parameter count does not match this model".into());
        }
        for (a, x) in self.table.parameters().zip(params) {
            a.set_parameter(&mut scene, *x);
        }
        scene.validate().map_err(|e| e.0)?;
        Ok(scene)
    }
}

/// Restores `bytes` of [`AnySimulator::snapshot`] into `sim` and evaluates the state: a
/// snapshot that does not fit is an error of the call (fmi2Error), not of a step, and so is
/// a state whose values are finite but whose outputs overflow (coordinates of 1e300: infinite
/// energies) or whose apparent mass is not finite.
fn checked_restore(
    sim: &mut AnySimulator,
    bytes: &[u8],
    table: &Table,
) -> Result<Evaluated, String> {
    sim.restore_snapshot(bytes).map_err(|e| e.to_string())?;
    let evaluated = Evaluated::of(sim);
    let outputs = &evaluated.outputs;
    for (index, var) in table.variables().iter().enumerate() {
        if let Access::Output(id) = table.access(index) {
            match outputs.value(id) {
                Some(x) if !x.is_finite() => {
                    return Err(format!(
                        "the snapshot's state gives {} = {x}: its values are beyond what the \
                         model can evaluate",
                        var.name
                    ))
                }
                _ => {}
            }
        }
    }
    if !evaluated.apparent_is_finite() {
        return Err(
            "the snapshot's state gives a non-finite apparent mass at the mount: its values are \
             beyond what the model can evaluate"
                .into(),
        );
    }
    Ok(evaluated)
}

/// A serialized FMU state: the parameter values in table order, the bytes of
/// [`AnySimulator::snapshot`], and the outputs' backward differences (table order).
type FmuSnapshot = (Vec<f64>, Vec<u8>, Vec<f64>);
