//! The named scalar outputs of a state ([`OutputId`]: `tip.position.x`, `tip.orientation.e0`,
//! `root.force.z`, …), named from [`Space::AXES`], [`Space::MOMENT_AXES`] and the orientation's
//! components ([`Space::ATTITUDE`]), and how [`Outputs`] reads each (its value and, for the tip
//! kinematics, its exact rate).

use super::outputs::Outputs;
use super::space::Space;
use super::{Planar, Spatial};
use crate::scene::SpaceKind;

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
    /// `energy.potential` [J] (gravity and the line loads' −∫qᵀr dx, zero at the origin).
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
    /// `station.<name>.force.<x|y|z>` [N]: the force of the part beyond the station on the
    /// part before it, section frame (x axial); component 3·slot + axis.
    StationForce,
    /// `station.<name>.moment.<x|y|z>` [N m]: its moment about the cut, section frame (x
    /// torsion; the plane: z); component 3·slot + axis.
    StationMoment,
    /// `station.<name>.stress` [Pa]: the largest von Mises stress over the section's boundary;
    /// component = slot.
    StationStress,
    /// `beam.stress_max` [Pa] (with `outputs.stress`): the largest von Mises stress along the
    /// beam.
    BeamStressMax,
    /// `beam.stress_max_at` [m]: its arc length from the root.
    BeamStressMaxAt,
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
pub(crate) fn dotted(stem: &str, suffix: &str) -> String {
    if suffix.is_empty() {
        stem.to_string()
    } else {
        format!("{stem}.{suffix}")
    }
}

/// `stem.suffix` and `id(what, component index)` for every suffix of every group
/// `(what, stem, suffixes)`, in order.
pub(crate) fn named_components<T: Copy, I>(
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
    /// Every output of `scene`: [`OutputId::named_with`] (the mount's if mounted), then each
    /// station's `station.<name>.force.<axis>` (x, y; z in space), `.moment.<axis>` (z; x, y,
    /// z in space) and `.stress`, in `[[stations]]` order.
    pub fn of_scene(scene: &crate::scene::Scene) -> Vec<(String, OutputId)> {
        let mounted = scene.root == crate::scene::Root::Mounted;
        let mut out = Self::named_with(scene.space, mounted);
        let (forces, moments): (&[usize], &[usize]) = match scene.space {
            SpaceKind::Planar => (&[0, 1], &[2]),
            SpaceKind::Spatial => (&[0, 1, 2], &[0, 1, 2]),
        };
        const AXES: [&str; 3] = ["x", "y", "z"];
        for (slot, st) in scene.stations.iter().enumerate() {
            let id = |quantity, axis: usize| OutputId {
                quantity,
                component: 3 * slot + axis,
            };
            for &a in forces {
                let name = format!("station.{}.force.{}", st.name, AXES[a]);
                out.push((name, id(Quantity::StationForce, a)));
            }
            for &a in moments {
                let name = format!("station.{}.moment.{}", st.name, AXES[a]);
                out.push((name, id(Quantity::StationMoment, a)));
            }
            let stress = OutputId {
                quantity: Quantity::StationStress,
                component: slot,
            };
            out.push((format!("station.{}.stress", st.name), stress));
        }
        if scene.outputs.stress {
            for (name, quantity) in [
                ("beam.stress_max", Quantity::BeamStressMax),
                ("beam.stress_max_at", Quantity::BeamStressMaxAt),
            ] {
                out.push((
                    name.into(),
                    OutputId {
                        quantity,
                        component: 0,
                    },
                ));
            }
        }
        out
    }

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
            StationForce => self.stations.get(k / 3).map(|s| s.force[k % 3]),
            StationMoment => self.stations.get(k / 3).map(|s| s.moment[k % 3]),
            StationStress => self.stations.get(k).map(|s| s.stress),
            BeamStressMax => one(self.stress_max.0),
            BeamStressMaxAt => one(self.stress_max.1),
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
