//! The planar|spatial choice in one place: [`AnySimulator`] and [`AnyOutputs`] dispatch each
//! call to the simulator of the scene's space. The named scalars they read and write are
//! [`OutputId`] (the model's, [`crate::model::output_names`]) and [`InputId`] ([`super::names`]);
//! what setting one input means is the simulator's ([`Simulator::set_input`]).

use super::{InputId, Partner, Simulator, PARTNER_COMPONENTS};
use crate::error::SimError;
use crate::integrator::Counters;
use crate::model::{OutputId, Outputs, Planar, Spatial};
use crate::scene::{Scene, SpaceKind};

/// A simulator of either space, chosen by the scene's `space`: the one type the FMU and the
/// command-line runner hold.
// both variants hold a few kB of fixed-size inputs and load rates (the line-load slots); the
// spatial one's are larger by its third components, which boxing would not save
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
pub enum AnySimulator {
    /// `space = "planar"`.
    Planar(Simulator<Planar>),
    /// `space = "spatial"`.
    Spatial(Simulator<Spatial>),
}

/// The outputs of a state of either space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyOutputs {
    /// Of a planar simulator.
    Planar(Outputs<Planar>),
    /// Of a spatial simulator.
    Spatial(Outputs<Spatial>),
}

/// `$body` with `$s` bound to the simulator inside `$any`, whichever its space.
macro_rules! each {
    ($any:expr, $s:ident => $body:expr) => {
        match $any {
            AnySimulator::Planar($s) => $body,
            AnySimulator::Spatial($s) => $body,
        }
    };
}

/// A matrix at the mount, force then moment components by acceleration then angular
/// acceleration components, in the first `n` rows and columns ([`PARTNER_COMPONENTS`]).
pub type MountMatrix = [[f64; PARTNER_COMPONENTS]; PARTNER_COMPONENTS];

impl AnySimulator {
    /// [`Simulator::start_at`] in the scene's space.
    pub fn start_at(scene: Scene, t0: f64) -> Result<Self, SimError> {
        Ok(match scene.space {
            SpaceKind::Planar => Self::Planar(Simulator::start_at(scene, t0)?),
            SpaceKind::Spatial => Self::Spatial(Simulator::start_at(scene, t0)?),
        })
    }

    /// [`Simulator::start_at`] at t = 0 in the scene's space.
    pub fn new(scene: Scene) -> Result<Self, SimError> {
        Self::start_at(scene, 0.0)
    }

    /// [`Simulator::restorable`] in the scene's space.
    pub fn restorable(scene: Scene) -> Result<Self, SimError> {
        Ok(match scene.space {
            SpaceKind::Planar => Self::Planar(Simulator::restorable(scene)?),
            SpaceKind::Spatial => Self::Spatial(Simulator::restorable(scene)?),
        })
    }

    /// The space.
    pub fn space(&self) -> SpaceKind {
        match self {
            Self::Planar(_) => SpaceKind::Planar,
            Self::Spatial(_) => SpaceKind::Spatial,
        }
    }

    /// [`Simulator::scene`].
    pub fn scene(&self) -> &Scene {
        each!(self, s => s.scene())
    }

    /// [`Simulator::time`].
    pub fn time(&self) -> f64 {
        each!(self, s => s.time())
    }

    /// [`Simulator::counters`].
    pub fn counters(&self) -> Counters {
        each!(self, s => s.counters())
    }

    /// [`Simulator::min_step_used`](Simulator#structfield.min_step_used).
    pub fn min_step_used(&self) -> f64 {
        each!(self, s => s.min_step_used)
    }

    /// [`Simulator::advance`].
    pub fn advance(&mut self, t_end: f64) -> Result<(), SimError> {
        each!(self, s => s.advance(t_end))
    }

    /// [`Simulator::solve_static`].
    pub fn solve_static(&mut self) -> Result<usize, SimError> {
        each!(self, s => s.solve_static())
    }

    /// [`Simulator::snapshot`].
    pub fn snapshot(&self) -> Vec<u8> {
        each!(self, s => s.snapshot())
    }

    /// [`Simulator::restore_snapshot`].
    pub fn restore_snapshot(&mut self, bytes: &[u8]) -> Result<(), SimError> {
        each!(self, s => s.restore_snapshot(bytes))
    }

    /// Outputs of the current state.
    pub fn outputs(&self) -> AnyOutputs {
        match self {
            Self::Planar(s) => AnyOutputs::Planar(s.outputs()),
            Self::Spatial(s) => AnyOutputs::Spatial(s.outputs()),
        }
    }

    /// The beam's shape at the current state ([`crate::simulator::Simulator::shape`]).
    pub fn shape(&self, per_element: usize) -> crate::model::Shape {
        each!(self, s => s.shape(per_element))
    }

    /// [`Simulator::input`].
    pub fn input(&self, id: InputId) -> Option<f64> {
        each!(self, s => s.input(id))
    }

    /// [`Simulator::set_input`].
    pub fn set_input(&mut self, id: InputId, x: f64) -> bool {
        each!(self, s => s.set_input(id, x))
    }

    /// [`Simulator::set_input_derivative`].
    pub fn set_input_derivative(&mut self, id: InputId, order: u32, x: f64) -> bool {
        each!(self, s => s.set_input_derivative(id, order, x))
    }

    /// [`Simulator::apparent_mass`].
    pub fn apparent_mass(&mut self) -> Option<Vec<Vec<f64>>> {
        each!(self, s => s.apparent_mass())
    }

    /// [`Simulator::apparent_mass_array`]: the apparent mass in a fixed array (rows and
    /// columns `..n`), without allocating.
    pub fn apparent_mass_array(&mut self) -> Option<(MountMatrix, usize)> {
        each!(self, s => s.apparent_mass_array())
    }

    /// [`Simulator::rigid_mass_array`] of `outputs` (as [`AnySimulator::rigid_mass_matrix`]),
    /// without allocating.
    pub fn rigid_mass_array(&self, outputs: &AnyOutputs) -> Option<(MountMatrix, usize)> {
        match (self, outputs) {
            (Self::Planar(s), AnyOutputs::Planar(o)) => s.rigid_mass_array(o),
            (Self::Spatial(s), AnyOutputs::Spatial(o)) => s.rigid_mass_array(o),
            _ => None,
        }
    }

    /// [`Simulator::rigid_mass_matrix`] of `outputs` (this state's, [`AnySimulator::outputs`];
    /// `None` for outputs of the other space).
    pub fn rigid_mass_matrix(&self, outputs: &AnyOutputs) -> Option<Vec<Vec<f64>>> {
        match (self, outputs) {
            (Self::Planar(s), AnyOutputs::Planar(o)) => s.rigid_mass_matrix(o),
            (Self::Spatial(s), AnyOutputs::Spatial(o)) => s.rigid_mass_matrix(o),
            _ => None,
        }
    }

    /// [`Simulator::mount_acceleration_change`].
    pub fn mount_acceleration_change(&self) -> Option<Vec<f64>> {
        each!(self, s => s.mount_acceleration_change())
    }

    /// Whether the mount's accelerations are inputs (`None` for a fixed root).
    pub fn mount_accelerations_given(&self) -> Option<bool> {
        each!(self, s => s.mount_accelerations_given())
    }

    /// [`Simulator::partner`].
    pub fn partner(&self) -> Partner {
        each!(self, s => s.partner())
    }

    /// [`Simulator::set_partner`].
    pub fn set_partner(&mut self, partner: Partner) -> bool {
        each!(self, s => s.set_partner(partner))
    }

    /// Writes the inputs set for the next step (tip loads, gravity, line loads and, on a mounted
    /// scene, the mount's; not the partner model's, which a scene does not hold) that differ from the scene's into `scene`: where a start of the scene begins.
    pub fn inputs_into(&self, scene: &mut Scene) {
        for (_, id) in InputId::of_scene(scene) {
            if let Some(x) = self.input(id).filter(|x| *x != id.scene_value(scene)) {
                id.set_in_scene(scene, x);
            }
        }
    }
}

impl AnyOutputs {
    /// The value of one scalar output; `None` for a component this space does not have.
    pub fn value(&self, id: OutputId) -> Option<f64> {
        match self {
            Self::Planar(o) => o.value(id),
            Self::Spatial(o) => o.value(id),
        }
    }

    /// The exact time derivative of a tip kinematic output ([`Outputs::rate`]).
    pub fn rate(&self, id: OutputId) -> Option<f64> {
        match self {
            Self::Planar(o) => o.rate(id),
            Self::Spatial(o) => o.rate(id),
        }
    }

    /// Tip position [m], global axes (2 or 3 components).
    pub fn tip_position(&self) -> &[f64] {
        match self {
            Self::Planar(o) => &o.tip_position,
            Self::Spatial(o) => &o.tip_position,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulator::{InputKind, Inputs, Quantity};

    fn names(v: Vec<(String, impl Sized)>) -> Vec<String> {
        v.into_iter().map(|(n, _)| n).collect()
    }

    #[test]
    fn names_follow_the_axes_and_the_attitude() {
        assert_eq!(
            names(OutputId::named(SpaceKind::Planar)).join(" "),
            "tip.position.x tip.position.y tip.velocity.x tip.velocity.y tip.angle \
             tip.angular_velocity.z root.force.x root.force.y root.moment.z energy.kinetic \
             energy.strain energy.potential"
        );
        assert_eq!(
            names(OutputId::named(SpaceKind::Spatial)).join(" "),
            "tip.position.x tip.position.y tip.position.z tip.velocity.x tip.velocity.y \
             tip.velocity.z tip.orientation.e0 tip.orientation.e1 tip.orientation.e2 \
             tip.orientation.e3 tip.angular_velocity.x tip.angular_velocity.y \
             tip.angular_velocity.z root.force.x root.force.y root.force.z root.moment.x \
             root.moment.y root.moment.z energy.kinetic energy.strain energy.potential"
        );
        assert_eq!(
            names(InputId::named(SpaceKind::Planar)).join(" "),
            "tip.force.x tip.force.y tip.moment.z gravity.x gravity.y"
        );
        assert_eq!(
            names(InputId::named(SpaceKind::Spatial)).join(" "),
            "tip.force.x tip.force.y tip.force.z tip.moment.x tip.moment.y tip.moment.z \
             gravity.x gravity.y gravity.z"
        );
    }

    /// Every named output reads its own field and component (distinct values in, the same
    /// values out), and no component beyond the space's exists.
    #[test]
    fn outputs_read_their_own_component() {
        let o = Outputs::<Spatial> {
            tip_position: [1.0, 2.0, 3.0],
            tip_velocity: [4.0, 5.0, 6.0],
            tip_angle: [7.0, 8.0, 9.0, 10.0],
            tip_angular_velocity: [11.0, 12.0, 13.0],
            root_force: [14.0, 15.0, 16.0],
            root_moment: [17.0, 18.0, 19.0],
            kinetic: 20.0,
            strain: 21.0,
            potential: 22.0,
            mount: None,
            ..Default::default()
        };
        let read: Vec<f64> = OutputId::named(SpaceKind::Spatial)
            .iter()
            .map(|(_, id)| o.value(*id).unwrap())
            .collect();
        assert_eq!(read, (1..=22).map(f64::from).collect::<Vec<_>>());
        let p = Outputs::<Planar> {
            tip_position: [1.0, 2.0],
            tip_velocity: [3.0, 4.0],
            tip_angle: 5.0,
            tip_angular_velocity: 6.0,
            root_force: [7.0, 8.0],
            root_moment: 9.0,
            kinetic: 10.0,
            strain: 11.0,
            potential: 12.0,
            mount: None,
            ..Default::default()
        };
        let read: Vec<f64> = OutputId::named(SpaceKind::Planar)
            .iter()
            .map(|(_, id)| p.value(*id).unwrap())
            .collect();
        assert_eq!(read, (1..=12).map(f64::from).collect::<Vec<_>>());
        let z = OutputId {
            quantity: Quantity::TipPosition,
            component: 2,
        };
        assert_eq!((p.value(z), o.value(z)), (None, Some(3.0)));
    }

    #[test]
    fn inputs_by_component_and_into_the_scene() {
        let mut i = Inputs::<Spatial> {
            tip_force: [0.0; 3],
            tip_moment: [0.0; 3],
            gravity: [0.0; 3],
            line_loads: Default::default(),
        };
        let named = InputId::named(SpaceKind::Spatial);
        for (k, (_, id)) in named.iter().enumerate() {
            assert!(i.set(*id, k as f64 + 1.0));
        }
        assert_eq!(
            (i.tip_force, i.tip_moment, i.gravity),
            ([1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0])
        );
        let mut p = Inputs::<Planar> {
            tip_force: [0.0; 2],
            tip_moment: 0.0,
            gravity: [0.0; 2],
            line_loads: Default::default(),
        };
        let mz = InputId {
            kind: InputKind::TipMoment,
            component: 0,
        };
        assert!(p.set(mz, 0.5) && p.tip_moment == 0.5);
        let fz = InputId {
            kind: InputKind::TipForce,
            component: 2,
        };
        assert!(!p.set(fz, 1.0) && p.get(fz).is_none());
        let mut scene = Scene::from_toml(
            "name = \"t\"\n[[segments]]\nname = \"a\"\nkind = \"ancf\"\nlength = 0.4\n\
             section = \"round\"\ndiameter = 0.002\nyoungs_modulus = 2.1e11\ndensity = 7850.0\n\
             elements = 2\n",
        )
        .unwrap();
        mz.set_in_scene(&mut scene, 0.25);
        assert_eq!(
            (scene.tip.moment.clone(), mz.scene_value(&scene)),
            (vec![0.25], 0.25)
        );
    }
}
