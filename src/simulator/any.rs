//! The planar|spatial choice in one place ([`AnySimulator`], [`AnyOutputs`]) and the named
//! scalars callers read and write: outputs ([`OutputId`]) and inputs ([`InputId`]), named from
//! [`Space::AXES`], [`Space::MOMENT_AXES`] and the orientation's components
//! ([`Space::ATTITUDE`]).

use super::{Inputs, LoadRates, MountInput, Partner, Simulator, PARTNER_COMPONENTS};
use crate::error::SimError;
use crate::integrator::Counters;
use crate::model::{Outputs, Planar, Space, Spatial};
use crate::scene::{Scene, SpaceKind};

/// A quantity of the outputs of a state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// `tip.position.<axis>` [m], global axes.
    TipPosition,
    /// `tip.velocity.<axis>` [m/s], global axes.
    TipVelocity,
    /// Orientation of the tip section: `tip.angle` [rad] in the plane (tangent from global x,
    /// in (−π, π]), `tip.orientation.e0`–`e3` in space (Euler parameters of the tip section
    /// frame → world, scalar first).
    TipAttitude,
    /// `tip.angular_velocity.<moment axis>` [rad/s] of the tip section, global axes.
    TipAngularVelocity,
    /// `root.force.<axis>` [N]: force of the support on the beam, global axes.
    RootForce,
    /// `root.moment.<moment axis>` [N m]: moment of the support on the beam about the root.
    RootMoment,
    /// `energy.kinetic` [J].
    KineticEnergy,
    /// `energy.strain` [J].
    StrainEnergy,
    /// `energy.potential` [J] (gravity, zero at the origin).
    PotentialEnergy,
    /// `root.mass` [kg]: the beam's mass (mounted root).
    MountMass,
    /// `root.center_of_mass.<axis>` [m]: the beam's centre of mass relative to the mount
    /// point, mount frame axes (mounted root).
    MountCenterOfMass,
    /// `root.inertia.<pair>` [kg m²]: the beam's inertia tensor about the mount point, mount
    /// frame axes (`zz` in the plane; `xx yy zz xy xz yz` in space) (mounted root).
    MountInertia,
    /// `root.force_elastic.<axis>` [N]: `root.force` minus the rigid reaction of the rigid
    /// inertia at the current mount motion and gravity, global axes (mounted root).
    ElasticForce,
    /// `root.moment_elastic.<moment axis>` [N m]: `root.moment` minus the rigid one, about
    /// the mount point (mounted root).
    ElasticMoment,
}

/// One scalar output: a quantity and the index of its component (in [`Space::AXES`],
/// [`Space::MOMENT_AXES`] or [`Space::ATTITUDE_COMPONENTS`]; 0 for an energy).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct OutputId {
    /// The quantity.
    pub quantity: Quantity,
    /// The component's index.
    pub component: usize,
}

/// `stem.suffix`, or `stem` for an empty suffix.
fn dotted(stem: &str, suffix: &str) -> String {
    if suffix.is_empty() {
        stem.to_string()
    } else {
        format!("{stem}.{suffix}")
    }
}

/// `stem.suffix` and `id(what, component index)` for every suffix of every group
/// `(what, stem, suffixes)`, in order.
fn named_components<T: Copy, I>(
    groups: &[(T, &str, &[&str])],
    id: impl Fn(T, usize) -> I,
) -> Vec<(String, I)> {
    let mut out = Vec::new();
    for &(what, stem, suffixes) in groups {
        for (k, suffix) in suffixes.iter().enumerate() {
            out.push((dotted(stem, suffix), id(what, k)));
        }
    }
    out
}

impl OutputId {
    /// The scalar outputs of a space with their names, in this order: tip position, velocity,
    /// orientation, angular velocity, root force, root moment, energies.
    pub fn named(space: SpaceKind) -> Vec<(String, OutputId)> {
        Self::named_with(space, false)
    }

    /// [`OutputId::named`] and, for a mounted root, the rigid inertia at the mount after them:
    /// `root.mass`, `root.center_of_mass.<axis>`, `root.inertia.<pair>`, then the reaction
    /// beyond it: `root.force_elastic.<axis>`, `root.moment_elastic.<moment axis>`.
    pub fn named_with(space: SpaceKind, mounted: bool) -> Vec<(String, OutputId)> {
        match space {
            SpaceKind::Planar => Self::named_with_in::<Planar>(mounted),
            SpaceKind::Spatial => Self::named_with_in::<Spatial>(mounted),
        }
    }

    fn named_with_in<S: Space>(mounted: bool) -> Vec<(String, OutputId)> {
        let mut out = Self::named_in::<S>();
        if mounted {
            let inertia: Vec<&str> = S::INERTIA_COMPONENTS.iter().map(|(n, _)| *n).collect();
            let groups: [(Quantity, &str, &[&str]); 5] = [
                (Quantity::MountMass, "root.mass", &[""]),
                (Quantity::MountCenterOfMass, "root.center_of_mass", S::AXES),
                (Quantity::MountInertia, "root.inertia", &inertia),
                (Quantity::ElasticForce, "root.force_elastic", S::AXES),
                (
                    Quantity::ElasticMoment,
                    "root.moment_elastic",
                    S::MOMENT_AXES,
                ),
            ];
            out.extend(named_components(&groups, |quantity, component| OutputId {
                quantity,
                component,
            }));
        }
        out
    }

    fn named_in<S: Space>() -> Vec<(String, OutputId)> {
        use Quantity::*;
        let groups: [(Quantity, &str, &[&str]); 9] = [
            (TipPosition, "tip.position", S::AXES),
            (TipVelocity, "tip.velocity", S::AXES),
            (TipAttitude, S::ATTITUDE, S::ATTITUDE_COMPONENTS),
            (TipAngularVelocity, "tip.angular_velocity", S::MOMENT_AXES),
            (RootForce, "root.force", S::AXES),
            (RootMoment, "root.moment", S::MOMENT_AXES),
            (KineticEnergy, "energy.kinetic", &[""]),
            (StrainEnergy, "energy.strain", &[""]),
            (PotentialEnergy, "energy.potential", &[""]),
        ];
        named_components(&groups, |quantity, component| OutputId {
            quantity,
            component,
        })
    }
}

impl<S: Space> Outputs<S> {
    /// The value of one scalar output; `None` for a component this space does not have.
    pub fn value(&self, id: OutputId) -> Option<f64> {
        use Quantity::*;
        let k = id.component;
        let one = |x: f64| (k == 0).then_some(x);
        match id.quantity {
            TipPosition => self.tip_position.as_ref().get(k).copied(),
            TipVelocity => self.tip_velocity.as_ref().get(k).copied(),
            TipAttitude => S::attitude_components(&self.tip_angle).get(k).copied(),
            TipAngularVelocity => S::moment_components(&self.tip_angular_velocity)
                .get(k)
                .copied(),
            RootForce => self.root_force.as_ref().get(k).copied(),
            RootMoment => S::moment_components(&self.root_moment).get(k).copied(),
            KineticEnergy => one(self.kinetic),
            StrainEnergy => one(self.strain),
            PotentialEnergy => one(self.potential),
            MountMass => self.mount.and_then(|m| one(m.mass)),
            MountCenterOfMass => self
                .mount
                .and_then(|m| m.center_of_mass.as_ref().get(k).copied()),
            ElasticForce => self
                .mount
                .and_then(|_| self.elastic_force.as_ref().get(k).copied()),
            ElasticMoment => self
                .mount
                .and_then(|_| S::moment_components(&self.elastic_moment).get(k).copied()),
            MountInertia => self
                .mount
                .and_then(|m| S::INERTIA_COMPONENTS.get(k).map(|&(_, i)| m.inertia[i])),
        }
    }
}

impl<S: Space> Outputs<S> {
    /// The exact time derivative of one tip kinematic output at this state: the velocity of
    /// the position, the acceleration of the velocity, the angular velocity of the plane angle,
    /// ė = ½ (0, ω) ⊗ e of the Euler parameters (ω in global axes), the angular acceleration
    /// of the angular velocity. `None` for other outputs (reactions, energies, inertia).
    pub fn rate(&self, id: OutputId) -> Option<f64> {
        use Quantity::*;
        let k = id.component;
        match id.quantity {
            TipPosition => self.tip_velocity.as_ref().get(k).copied(),
            TipVelocity => self.tip_acceleration.as_ref().get(k).copied(),
            TipAttitude => {
                let w = S::moment_components(&self.tip_angular_velocity);
                let e = S::attitude_components(&self.tip_angle);
                match (e.len(), w.len()) {
                    (1, 1) => (k == 0).then_some(w[0]),
                    (4, 3) => {
                        let ev = [e[1], e[2], e[3]];
                        let rate = match k {
                            0 => -0.5 * (w[0] * ev[0] + w[1] * ev[1] + w[2] * ev[2]),
                            1..=3 => {
                                let (i, j, l) = (k - 1, k % 3, (k + 1) % 3);
                                0.5 * (e[0] * w[i] + w[j] * ev[l] - w[l] * ev[j])
                            }
                            _ => return None,
                        };
                        Some(rate)
                    }
                    _ => None,
                }
            }
            TipAngularVelocity => S::moment_components(&self.tip_angular_acceleration)
                .get(k)
                .copied(),
            _ => None,
        }
    }
}

/// The slot of the `order`-th derivative (1 or 2) of a tip load component in `rates`; `None`
/// for other inputs (gravity takes no derivatives) or components.
fn load_rate_slot<S: Space>(rates: &mut LoadRates<S>, id: InputId, order: u32) -> Option<&mut f64> {
    let o = (order as usize).checked_sub(1).filter(|o| *o < 2)?;
    match id.kind {
        InputKind::TipForce => rates.force[o].as_mut().get_mut(id.component),
        InputKind::TipMoment => {
            S::moment_components_mut(&mut rates.moment[o]).get_mut(id.component)
        }
        _ => None,
    }
}

/// An input of the equations a host may change between communication steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum InputKind {
    /// `tip.force.<axis>` [N]: total dead force at the free end, global axes.
    TipForce,
    /// `tip.moment.<moment axis>` [N m]: total dead moment at the free end, global axes (in the
    /// plane: about z, counter-clockwise).
    TipMoment,
    /// `gravity.<axis>` [m/s²], global axes.
    Gravity,
    /// `root.position.<axis>` [m]: the mount point, world axes (mounted root).
    MountPosition,
    /// The mount frame → world: `root.angle` [rad] in the plane, `root.orientation.e0`–`e3`
    /// (Euler parameters, scalar first, renormalized) in space (mounted root).
    MountAttitude,
    /// `root.velocity.<axis>` [m/s] (mounted root).
    MountVelocity,
    /// `root.angular_velocity` [rad/s] (plane; `.x/.y/.z` world axes in space).
    MountAngularVelocity,
    /// `root.acceleration.<axis>` [m/s²] (mounted root).
    MountAcceleration,
    /// `root.angular_acceleration` [rad/s²] (plane; `.x/.y/.z` world axes in space).
    MountAngularAcceleration,
    /// `root.mobility.<a>_<r>`: the host's mobility at the mount, ∂a/∂R ([`Partner`]), the
    /// acceleration `a` ∈ {ax, ay, az, alphax, alphay, alphaz} by the reaction `r` ∈ {fx, fy,
    /// fz, mx, my, mz} (the plane: ax, ay, alphaz and fx, fy, mz); component `i·6 + j` for
    /// the space's components i, j. 1/kg, 1/(kg m), 1/(kg m²).
    MountMobility,
    /// `root.reaction_reference.<r>` [N, N m]: the reaction the host's acceleration input was
    /// computed with ([`Partner`]).
    MountReactionReference,
}

impl InputKind {
    /// Whether this is an input of the partner model ([`Partner`]).
    pub fn is_partner(self) -> bool {
        matches!(
            self,
            InputKind::MountMobility | InputKind::MountReactionReference
        )
    }

    /// Whether this is a mount input (the partner's too).
    pub fn is_mount(self) -> bool {
        !matches!(
            self,
            InputKind::TipForce | InputKind::TipMoment | InputKind::Gravity
        )
    }
}

/// One scalar input: its kind and the index of its component (in [`Space::AXES`] or
/// [`Space::MOMENT_AXES`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct InputId {
    /// The input.
    pub kind: InputKind,
    /// The component's index.
    pub component: usize,
}

impl InputId {
    /// The scalar inputs of a space with their names: tip force, tip moment, gravity.
    pub fn named(space: SpaceKind) -> Vec<(String, InputId)> {
        match space {
            SpaceKind::Planar => Self::named_in::<Planar>(),
            SpaceKind::Spatial => Self::named_in::<Spatial>(),
        }
    }

    fn named_in<S: Space>() -> Vec<(String, InputId)> {
        let groups: [(InputKind, &str, &[&str]); 3] = [
            (InputKind::TipForce, "tip.force", S::AXES),
            (InputKind::TipMoment, "tip.moment", S::MOMENT_AXES),
            (InputKind::Gravity, "gravity", S::AXES),
        ];
        named_components(&groups, |kind, component| InputId { kind, component })
    }

    /// [`InputId::named`] and, for a mounted root, the mount inputs after them (planar:
    /// `root.position.{x,y}`, `root.angle`, `root.velocity.{x,y}`, `root.angular_velocity`,
    /// `root.acceleration.{x,y}`, `root.angular_acceleration`; spatial: the vectors with
    /// `.x/.y/.z` and `root.orientation.e0`–`e3`).
    pub fn named_with(space: SpaceKind, mounted: bool) -> Vec<(String, InputId)> {
        let mut out = Self::named(space);
        if mounted {
            out.extend(match space {
                SpaceKind::Planar => Self::mount_in::<Planar>(),
                SpaceKind::Spatial => Self::mount_in::<Spatial>(),
            });
        }
        out
    }

    fn mount_in<S: Space>() -> Vec<(String, InputId)> {
        use InputKind::*;
        let groups: [(InputKind, &str, &[&str]); 6] = [
            (MountPosition, "root.position", S::AXES),
            (MountAttitude, S::MOUNT_ATTITUDE, S::ATTITUDE_COMPONENTS),
            (MountVelocity, "root.velocity", S::AXES),
            (
                MountAngularVelocity,
                "root.angular_velocity",
                S::ANGULAR_SUFFIXES,
            ),
            (MountAcceleration, "root.acceleration", S::AXES),
            (
                MountAngularAcceleration,
                "root.angular_acceleration",
                S::ANGULAR_SUFFIXES,
            ),
        ];
        let mut out = named_components(&groups, |kind, component| InputId { kind, component });
        out.extend(Self::partner_in::<S>());
        out
    }

    /// The partner model's inputs: `root.mobility.<a>_<r>` row by row, then
    /// `root.reaction_reference.<r>` ([`InputKind::MountMobility`]).
    fn partner_in<S: Space>() -> Vec<(String, InputId)> {
        let acc: Vec<String> = S::AXES
            .iter()
            .map(|a| format!("a{a}"))
            .chain(S::MOMENT_AXES.iter().map(|a| format!("alpha{a}")))
            .collect();
        let reaction: Vec<String> = S::AXES
            .iter()
            .map(|a| format!("f{a}"))
            .chain(S::MOMENT_AXES.iter().map(|a| format!("m{a}")))
            .collect();
        let mut out = Vec::new();
        for (i, a) in acc.iter().enumerate() {
            for (j, r) in reaction.iter().enumerate() {
                let id = InputId {
                    kind: InputKind::MountMobility,
                    component: i * PARTNER_COMPONENTS + j,
                };
                out.push((format!("root.mobility.{a}_{r}"), id));
            }
        }
        for (j, r) in reaction.iter().enumerate() {
            let id = InputId {
                kind: InputKind::MountReactionReference,
                component: j,
            };
            out.push((format!("root.reaction_reference.{r}"), id));
        }
        out
    }

    /// The partner's slot of this input (`None` for another input or a component outside
    /// the partner's arrays).
    fn partner_slot(self, p: &mut Partner) -> Option<&mut f64> {
        let k = self.component;
        match self.kind {
            InputKind::MountMobility => p
                .mobility
                .get_mut(k / PARTNER_COMPONENTS)
                .map(|row| &mut row[k % PARTNER_COMPONENTS]),
            InputKind::MountReactionReference => p.reference.get_mut(k),
            _ => None,
        }
    }

    /// The scene's value of this input (0 where the scene leaves the component out; the
    /// mount's from `[mount]`).
    pub fn scene_value(self, scene: &Scene) -> f64 {
        let k = self.component;
        let get = |v: &Vec<f64>| v.get(k).copied().unwrap_or(0.0);
        let mount = || scene.mount_start().unwrap_or_default();
        match self.kind {
            InputKind::TipForce => get(&scene.tip.force),
            InputKind::TipMoment => get(&scene.tip.moment),
            InputKind::Gravity => get(&scene.gravity),
            InputKind::MountPosition => get(&mount().position),
            InputKind::MountAttitude => match scene.space {
                SpaceKind::Planar => mount().angle,
                SpaceKind::Spatial => mount()
                    .orientation
                    .map_or(if k == 0 { 1.0 } else { 0.0 }, |e| e[k.min(3)]),
            },
            InputKind::MountVelocity => get(&mount().velocity),
            InputKind::MountAngularVelocity => get(&mount().angular_velocity),
            InputKind::MountAcceleration => get(&mount().acceleration),
            InputKind::MountAngularAcceleration => get(&mount().angular_acceleration),
            // the partner model is not part of a scene: zero (off) until a host sets it
            InputKind::MountMobility | InputKind::MountReactionReference => 0.0,
        }
    }

    /// Writes this input into the scene (not validated; the vector gets all the components of
    /// the scene's space; a mount input into the `[mount]` start motion).
    pub fn set_in_scene(self, scene: &mut Scene, x: f64) {
        let (space, k) = (scene.space, self.component);
        if self.kind.is_mount() {
            // the start motion of a mounted scene: where `initialize` puts the beam
            if scene.root != crate::scene::Root::Mounted || self.kind.is_partner() {
                return;
            }
            // the raw table (renormalized when the simulator is built), every vector complete
            let mut m = scene.mount.clone().unwrap_or_default();
            for (v, n) in [
                (&mut m.position, space.dim()),
                (&mut m.velocity, space.dim()),
                (&mut m.acceleration, space.dim()),
                (&mut m.angular_velocity, space.moment_dim()),
                (&mut m.angular_acceleration, space.moment_dim()),
            ] {
                v.resize(n, 0.0);
            }
            if space == SpaceKind::Spatial && m.orientation.is_none() {
                m.orientation = Some([1.0, 0.0, 0.0, 0.0]);
            }
            let slot = match self.kind {
                InputKind::MountPosition => m.position.get_mut(k),
                InputKind::MountVelocity => m.velocity.get_mut(k),
                InputKind::MountAcceleration => m.acceleration.get_mut(k),
                InputKind::MountAngularVelocity => m.angular_velocity.get_mut(k),
                InputKind::MountAngularAcceleration => m.angular_acceleration.get_mut(k),
                InputKind::MountAttitude => match space {
                    SpaceKind::Planar => Some(&mut m.angle),
                    SpaceKind::Spatial => m.orientation.as_mut().and_then(|e| e.get_mut(k)),
                },
                _ => None,
            };
            if let Some(slot) = slot {
                *slot = x;
            }
            scene.mount = Some(m);
            return;
        }
        let (v, n) = match self.kind {
            InputKind::TipForce => (&mut scene.tip.force, space.dim()),
            InputKind::TipMoment => (&mut scene.tip.moment, space.moment_dim()),
            InputKind::Gravity => (&mut scene.gravity, space.dim()),
            _ => return,
        };
        v.resize(n.max(v.len()).max(k + 1), 0.0);
        v[k] = x;
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
            _ => None,
        };
        slot.map(|s| *s = x).is_some()
    }
}

impl<S: Space> MountInput<S> {
    /// The slot of one mount input component (`None`: not a mount input, or a component this
    /// space does not have).
    fn slot(&mut self, id: InputId) -> Option<&mut f64> {
        let (m, k) = (&mut self.motion, id.component);
        match id.kind {
            InputKind::MountPosition => m.position.as_mut().get_mut(k),
            InputKind::MountAttitude => S::attitude_components_mut(&mut m.attitude).get_mut(k),
            InputKind::MountVelocity => m.velocity.as_mut().get_mut(k),
            InputKind::MountAngularVelocity => {
                S::moment_components_mut(&mut m.angular_velocity).get_mut(k)
            }
            InputKind::MountAcceleration => m.acceleration.as_mut().get_mut(k),
            InputKind::MountAngularAcceleration => {
                S::moment_components_mut(&mut m.angular_acceleration).get_mut(k)
            }
            _ => None,
        }
    }

    /// The slot of a derivative of order 1 or 2 of one mount input that defines the motion:
    /// the accelerations' (jerk, snap), or, when the scene's accelerations are not inputs
    /// (`velocity_mode`), the velocities' (acceleration, jerk). `None` for the pose and for
    /// derivatives implied by other inputs.
    fn derivative_slot(
        &mut self,
        id: InputId,
        order: u32,
        velocity_mode: bool,
    ) -> Option<&mut f64> {
        let k = id.component;
        let (r, m) = (&mut self.rates, &mut self.motion);
        match (id.kind, order, velocity_mode) {
            (InputKind::MountAcceleration, 1, false) => r.jerk.as_mut().get_mut(k),
            (InputKind::MountAcceleration, 2, false) => r.snap.as_mut().get_mut(k),
            (InputKind::MountAngularAcceleration, 1, false) => {
                S::moment_components_mut(&mut r.angular_jerk).get_mut(k)
            }
            (InputKind::MountAngularAcceleration, 2, false) => {
                S::moment_components_mut(&mut r.angular_snap).get_mut(k)
            }
            (InputKind::MountVelocity, 1, true) => m.acceleration.as_mut().get_mut(k),
            (InputKind::MountVelocity, 2, true) => r.jerk.as_mut().get_mut(k),
            (InputKind::MountAngularVelocity, 1, true) => {
                S::moment_components_mut(&mut m.angular_acceleration).get_mut(k)
            }
            (InputKind::MountAngularVelocity, 2, true) => {
                S::moment_components_mut(&mut r.angular_jerk).get_mut(k)
            }
            _ => None,
        }
    }
}

/// A simulator of either space, chosen by the scene's `space`: the one type the FMU and the
/// command-line runner hold.
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

    /// The value of an input set for the next step; `None` for a component this space (or a
    /// fixed root) does not have.
    pub fn input(&self, id: InputId) -> Option<f64> {
        if id.kind.is_partner() {
            let mounted = self.mount_accelerations_given().is_some();
            let mut p = each!(self, s => s.partner());
            return id.partner_slot(&mut p).filter(|_| mounted).map(|x| *x);
        }
        if id.kind.is_mount() {
            return each!(self, s => s.mount_input().and_then(|mut m| m.slot(id).map(|x| *x)));
        }
        each!(self, s => s.inputs().get(id))
    }

    /// Sets an input (takes effect at the next step, as a jump of the inputs: see
    /// [`Simulator::advance`]; a mount input is checked there); `false` (and no change) for a
    /// component this space (or a fixed root) does not have.
    pub fn set_input(&mut self, id: InputId, x: f64) -> bool {
        if id.kind.is_partner() {
            return each!(self, s => {
                let mut p = s.partner();
                id.partner_slot(&mut p).map(|slot| *slot = x).is_some() && s.set_partner(p)
            });
        }
        if id.kind.is_mount() {
            return each!(self, s => {
                let Some(mut m) = s.mount_input() else {
                    return false;
                };
                let known = m.slot(id).map(|slot| *slot = x).is_some();
                // an input set again forgets its derivatives (they held for one step)
                let velocity_mode = s.mount_accelerations_given() == Some(false);
                for order in [1, 2] {
                    if let Some(d) = m.derivative_slot(id, order, velocity_mode) {
                        if !(velocity_mode && order == 1) {
                            *d = 0.0;
                        }
                    }
                }
                if velocity_mode
                    && matches!(id.kind, InputKind::MountVelocity | InputKind::MountAngularVelocity)
                {
                    m.accelerations = false;
                }
                known && s.set_mount_unchecked(m)
            });
        }
        each!(self, s => {
            let mut inputs = s.inputs();
            let known = inputs.set(id, x);
            if known {
                s.set_inputs(&inputs);
                // a tip load set again forgets its derivatives
                let mut rates = s.load_rates();
                for order in [1, 2] {
                    if let Some(d) = load_rate_slot(&mut rates, id, order) {
                        *d = 0.0;
                    }
                }
                s.set_load_rates(rates);
            }
            known
        })
    }

    /// Sets the derivative of order 1 or 2 of an input over the coming communication step
    /// (FMI input derivatives; they hold for the next step only). Mount inputs: the
    /// accelerations' derivatives (or, with `motion_input = "pose_velocity"`, the velocities')
    /// shape the base motion; derivatives of the pose, implied by the velocities, are accepted
    /// and not used. Tip loads: [`LoadRates`]. `false` for gravity.
    pub fn set_input_derivative(&mut self, id: InputId, order: u32, x: f64) -> bool {
        if !(1..=2).contains(&order) {
            return false;
        }
        if id.kind.is_partner() {
            // the partner model is held over a step: a derivative is accepted, not used
            return self.input(id).is_some();
        }
        if !id.kind.is_mount() {
            return each!(self, s => {
                let mut rates = s.load_rates();
                match load_rate_slot(&mut rates, id, order) {
                    Some(d) => {
                        *d = x;
                        s.set_load_rates(rates);
                        true
                    }
                    None => false,
                }
            });
        }
        each!(self, s => {
            let (Some(mut m), Some(given)) = (s.mount_input(), s.mount_accelerations_given())
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
            s.set_mount_unchecked(m)
        })
    }

    /// [`Simulator::apparent_mass`].
    pub fn apparent_mass(&mut self) -> Option<Vec<Vec<f64>>> {
        each!(self, s => s.apparent_mass())
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

    /// Writes the inputs set for the next step (tip loads, gravity and, on a mounted scene, the
    /// mount's; not the partner model's, which a scene does not hold) that differ from the scene's into `scene`: where a start of the scene begins.
    pub fn inputs_into(&self, scene: &mut Scene) {
        let mounted = scene.mount_start().is_some();
        for (_, id) in InputId::named_with(self.space(), mounted) {
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
