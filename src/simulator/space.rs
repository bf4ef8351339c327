//! The spaces a simulator runs in ([`SpaceModel`]): how a model is built from a scene and how
//! its orientation is named and read.

use super::*;
use serde::de::DeserializeOwned;

/// A space a [`Simulator`] runs in: builds its model from a scene and names its orientation
/// output. Implemented for [`Planar`] and [`Spatial`].
pub trait SpaceModel:
    Space<
    Vec: Serialize + DeserializeOwned,
    Moment: Serialize + DeserializeOwned,
    Attitude: Serialize + DeserializeOwned,
>
{
    /// The scene's `space` this model is built for.
    const KIND: SpaceKind;
    /// Output name of the tip section's orientation (`tip.angle` in the plane,
    /// `tip.orientation` in space) ...
    const ATTITUDE: &'static str;
    /// ... and the suffixes of its components (`[""]`: a scalar without suffix; `e0`–`e3`).
    const ATTITUDE_COMPONENTS: &'static [&'static str];
    /// Input name of the mount's orientation (`root.angle` in the plane, `root.orientation`).
    const MOUNT_ATTITUDE: &'static str;
    /// Suffixes of the mount's angular velocity and acceleration inputs (`[""]` in the plane:
    /// `root.angular_velocity`; the moment axes in space).
    const ANGULAR_SUFFIXES: &'static [&'static str];

    /// The model of a scene of this space (an error naming the space otherwise).
    fn model(scene: &Scene) -> Result<Model<Self>, SceneError>;
    /// The components of an orientation, in the order of [`SpaceModel::ATTITUDE_COMPONENTS`].
    fn attitude_components(a: &Self::Attitude) -> &[f64];
    /// The components of an orientation, mutable.
    fn attitude_components_mut(a: &mut Self::Attitude) -> &mut [f64];
    /// The orientation of a scene's `[mount]` table.
    fn attitude_from(m: &Mount) -> Self::Attitude;
}

impl SpaceModel for Planar {
    const KIND: SpaceKind = SpaceKind::Planar;
    const ATTITUDE: &'static str = "tip.angle";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &[""];
    const MOUNT_ATTITUDE: &'static str = "root.angle";
    const ANGULAR_SUFFIXES: &'static [&'static str] = &[""];

    fn model(scene: &Scene) -> Result<Model<Self>, SceneError> {
        Model::<Planar>::from_scene(scene)
    }

    fn attitude_components(a: &f64) -> &[f64] {
        std::slice::from_ref(a)
    }

    fn attitude_components_mut(a: &mut f64) -> &mut [f64] {
        std::slice::from_mut(a)
    }

    fn attitude_from(m: &Mount) -> f64 {
        m.angle
    }
}

impl SpaceModel for Spatial {
    const KIND: SpaceKind = SpaceKind::Spatial;
    const ATTITUDE: &'static str = "tip.orientation";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &["e0", "e1", "e2", "e3"];
    const MOUNT_ATTITUDE: &'static str = "root.orientation";
    const ANGULAR_SUFFIXES: &'static [&'static str] = Spatial::MOMENT_AXES;

    fn model(scene: &Scene) -> Result<Model<Self>, SceneError> {
        if scene.space != SpaceKind::Spatial {
            return Err(SceneError(
                "space = \"planar\": this scene builds a planar model, not a spatial one".into(),
            ));
        }
        Model::<Spatial>::from_scene(scene)
    }

    fn attitude_components(a: &[f64; 4]) -> &[f64] {
        a
    }

    fn attitude_components_mut(a: &mut [f64; 4]) -> &mut [f64] {
        a
    }

    fn attitude_from(m: &Mount) -> [f64; 4] {
        let e = m.orientation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
        Self::normalized_attitude(&e).unwrap_or([1.0, 0.0, 0.0, 0.0])
    }
}
