//! The model of a scene in a space given as a type: the one place a [`Space`] type meets the
//! scene's `space`. Each space builds its own model (`planar/build.rs`, `spatial/build.rs`);
//! this picks the build by [`Space::KIND`] and hands back its model as `Model<S>` (a checked
//! downcast: the build of `S::KIND` returns exactly `Model<S>`).

use super::assembly::Model;
use super::planar::Planar;
use super::space::Space;
use super::spatial::Spatial;
use crate::scene::{Scene, SceneError, SpaceKind};
use std::any::Any;

/// The model of a validated scene of the space `S` (an error naming the space otherwise).
pub fn build<S: Space>(scene: &Scene) -> Result<Model<S>, SceneError> {
    let model: Box<dyn Any> = match S::KIND {
        SpaceKind::Planar => Box::new(Model::<Planar>::from_scene(scene)?),
        SpaceKind::Spatial => {
            if scene.space != SpaceKind::Spatial {
                return Err(SceneError(
                    "space = \"planar\": this scene builds a planar model, not a spatial one"
                        .into(),
                ));
            }
            Box::new(Model::<Spatial>::from_scene(scene)?)
        }
    };
    let mut model = model.downcast::<Model<S>>().map(|m| *m).map_err(|_| {
        SceneError(format!(
            "internal: the {:?} build did not give a model of its space",
            S::KIND
        ))
    })?;
    model.set_stations(scene)?;
    Ok(model)
}
