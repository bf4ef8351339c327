//! The named scalar inputs of a simulator ([`InputId`]: `tip.force.z`, `gravity.y`,
//! `root.acceleration.x`, `root.mobility.ax_fx`, …), named from [`Space::AXES`] and
//! [`Space::MOMENT_AXES`], and their values in and back into a scene (where a start begins).
//! The outputs' names are the model's ([`crate::model::output_names`]).

use super::PARTNER_COMPONENTS;
use crate::model::output_names::named_components;
use crate::model::{Planar, Space, Spatial};
use crate::scene::{Scene, SpaceKind};

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
    /// `<segment>.line_load.<axis>` [N/m]: the uniform dead line load of a segment that
    /// declares `line_load`, global axes; component 3·slot + axis
    /// ([`InputId::line_load_slot`]).
    LineLoad,
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
            InputKind::TipForce | InputKind::TipMoment | InputKind::Gravity | InputKind::LineLoad
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

    /// The line-load input of slot `slot` ([`crate::scene::Scene::line_load_segments`]),
    /// component `axis` of [`Space::AXES`].
    pub fn line_load(slot: usize, axis: usize) -> Self {
        InputId {
            kind: InputKind::LineLoad,
            component: 3 * slot + axis,
        }
    }

    /// (slot, axis) of a line-load input's component.
    pub fn line_load_slot(component: usize) -> (usize, usize) {
        (component / 3, component % 3)
    }

    /// The line-load inputs of `scene`: `<segment>.line_load.<axis>` for each segment that
    /// declares `line_load`, in segment order.
    pub fn line_loads(scene: &Scene) -> Vec<(String, InputId)> {
        let axes = match scene.space {
            SpaceKind::Planar => Planar::AXES,
            SpaceKind::Spatial => Spatial::AXES,
        };
        let mut out = Vec::new();
        for (slot, seg) in scene.line_load_segments().into_iter().enumerate() {
            for (axis, a) in axes.iter().enumerate() {
                let name = format!("{}.line_load.{a}", scene.segments[seg].name);
                out.push((name, InputId::line_load(slot, axis)));
            }
        }
        out
    }

    /// Every input of `scene`: [`InputId::named_with`] (the mount's if mounted), then its
    /// [`InputId::line_loads`].
    pub fn of_scene(scene: &Scene) -> Vec<(String, InputId)> {
        let mounted = scene.root == crate::scene::Root::Mounted;
        let mut out = Self::named_with(scene.space, mounted);
        out.extend(Self::line_loads(scene));
        out
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
            InputKind::LineLoad => {
                let (slot, axis) = Self::line_load_slot(k);
                scene
                    .line_load_segments()
                    .get(slot)
                    .and_then(|&i| scene.segments[i].line_load.as_ref()?.get(axis).copied())
                    .unwrap_or(0.0)
            }
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
        if self.kind == InputKind::LineLoad {
            let (slot, axis) = Self::line_load_slot(k);
            let Some(&i) = scene.line_load_segments().get(slot) else {
                return;
            };
            if let Some(q) = scene.segments[i].line_load.as_mut() {
                q.resize(space.dim().max(q.len()).max(axis + 1), 0.0);
                q[axis] = x;
            }
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
