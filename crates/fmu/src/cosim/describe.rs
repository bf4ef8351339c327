//! What the FMU declares from its scene alone, before any simulator is built: the
//! modelDescription.xml, the OSP-IS groups of a mounted beam, the model info (name, default
//! experiment, capabilities).

use fmi2::{CoSimModel, ModelInfo};

use hybeam::scene::{Root, Scene};

use super::variables::Table;

/// modelDescription.xml of the FMU of `scene_toml` with this modelIdentifier, from the
/// scene alone (its variable table and default experiment): no simulator is built.
pub fn model_description<M: CoSimModel>(
    scene_toml: &str,
    model_identifier: &str,
) -> Result<String, String> {
    let scene = Scene::from_toml(scene_toml).map_err(|e| e.0)?;
    let guid = fmi2::guid::guid::<M>(scene_toml.as_bytes());
    let ids = fmi2::xml::Identity {
        model_identifier,
        guid: &guid,
        generation_tool: M::GENERATION_TOOL,
    };
    let table = Table::of(&scene);
    fmi2::xml::model_description_with_strings(
        &model_info(&scene),
        table.variables(),
        table.string_variables(),
        &ids,
    )
}

/// A mounted scene's OSP-IS extended model description: its file name
/// (`<modelName>_OspModelDescription.xml`, where libcosim looks beside the FMU) and text.
/// The mount's groups: `LinearDisplacement` `mount.position`; the orientation
/// (`AngularDisplacement` `mount.angle` in the plane, `Generic` `mount.orientation` in
/// space); a `LinearMechanicalPort` `mount.linear` (Force `mount.force` = `root.force.*`,
/// LinearVelocity `mount.velocity`); an `AngularMechanicalPort` `mount.angular` (Torque
/// `mount.moment`, AngularVelocity `mount.angular_velocity`); with acceleration inputs,
/// `Generic` `mount.acceleration` and `mount.angular_acceleration`. All at the top level
/// (libcosim connects the groups nested in a connected group, not deeper). A host body
/// that declares the mirror groups (its outputs where the beam has inputs) connects each
/// with one `<VariableGroupConnection>`. `None` for a fixed root.
pub fn osp_model_description(scene_toml: &str) -> Result<Option<(String, String)>, String> {
    let scene = Scene::from_toml(scene_toml).map_err(|e| e.0)?;
    let Some(groups) = osp_groups(&scene) else {
        return Ok(None);
    };
    let text = fmi2::osp::model_description(&groups, Table::of(&scene).variables())?;
    Ok(Some((
        format!("{}_OspModelDescription.xml", scene.name),
        text,
    )))
}

/// The mount's OSP-IS groups of a scene ([`osp_model_description`]), `None` for a
/// fixed root.
pub fn osp_groups(scene: &Scene) -> Option<Vec<fmi2::osp::VariableGroup>> {
    use fmi2::osp::VariableGroup as G;
    if scene.root != Root::Mounted {
        return None;
    }
    let table = Table::of(scene);
    let vars = table.variables();
    let named = |stem: &str| -> Vec<&str> {
        vars.iter()
            .map(|v| v.name.as_str())
            .filter(|n| *n == stem || n.strip_prefix(stem).is_some_and(|r| r.starts_with('.')))
            .collect()
    };
    let group = |kind, name: &str, stem: &str| G::of(kind, name, &named(stem));
    let orientation = if named("root.angle").is_empty() {
        group("Generic", "mount.orientation", "root.orientation")
    } else {
        group("AngularDisplacement", "mount.angle", "root.angle")
    };
    let mut groups = vec![
        group("LinearDisplacement", "mount.position", "root.position"),
        orientation,
        G::nest(
            "LinearMechanicalPort",
            "mount.linear",
            vec![
                group("Force", "mount.force", "root.force"),
                group("LinearVelocity", "mount.velocity", "root.velocity"),
            ],
        ),
        G::nest(
            "AngularMechanicalPort",
            "mount.angular",
            vec![
                group("Torque", "mount.moment", "root.moment"),
                group(
                    "AngularVelocity",
                    "mount.angular_velocity",
                    "root.angular_velocity",
                ),
            ],
        ),
    ];
    if !named("root.acceleration").is_empty() {
        groups.push(group("Generic", "mount.acceleration", "root.acceleration"));
        groups.push(group(
            "Generic",
            "mount.angular_acceleration",
            "root.angular_acceleration",
        ));
    }
    Some(groups)
}

/// Model name, description and default experiment of a scene.
pub(super) fn model_info(scene: &Scene) -> ModelInfo {
    ModelInfo {
        model_name: scene.name.clone(),
        description: scene.description.clone(),
        start_time: 0.0,
        stop_time: scene.simulation.t_end,
        step_size: scene.simulation.output_step,
        capabilities: capabilities(scene),
    }
}

/// What the FMU of a scene can do: every beam takes input derivatives (the tip loads' and line
/// loads' make them F + Ḟτ + ½F̈τ² over a step); a mounted one's reaction depends directly on
/// the mount accelerations, which the host may interpolate with derivatives, and it gives
/// output derivatives and the apparent mass; a fixed-root beam has no direct feedthrough.
pub(super) fn capabilities(scene: &Scene) -> fmi2::Capabilities {
    if scene.root == Root::Mounted {
        fmi2::Capabilities {
            input_derivative_order: 2,
            output_derivative_order: 1,
            directional_derivative: true,
        }
    } else {
        fmi2::Capabilities {
            input_derivative_order: 2,
            ..fmi2::Capabilities::default()
        }
    }
}
