//! Scene → spatial model.

use super::Spatial;
use crate::model::assembly::Model;
use crate::scene::{Scene, SceneError};

impl Model<Spatial> {
    /// Builds the model of a validated spatial scene (`space = "spatial"`).
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        scene.validate()?;
        Err(SceneError(format!(
            "scene {:?}: the spatial model is not built yet",
            scene.name
        )))
    }
}
