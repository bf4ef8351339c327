//! The golden modelDescription files in `modelDescription/` are up to date: for every scene in
//! `scenes/`, the XML generated now equals `modelDescription/<id>.xml` byte for byte.
//! After a deliberate change (variables, units, crate version → GUID), regenerate with
//! `cargo fmu-build scenes/<scene>.toml --xml-only --out modelDescription`.

use std::path::Path;

use hybeam::fmi::model::CoSimModel;
use hybeam::fmi::{guid, xml};

#[test]
fn golden_model_descriptions_are_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(!scenes.is_empty());
    for scene in scenes {
        let bytes = std::fs::read(&scene).unwrap();
        let model = hybeam::FmuModel::from_scene(std::str::from_utf8(&bytes).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
        let id = xml::model_identifier_from_stem(&scene.file_stem().unwrap().to_string_lossy());
        let now = xml::model_description_of(&model, &id, &guid::guid(&bytes)).unwrap();
        let golden_path = root.join("modelDescription").join(format!("{id}.xml"));
        let golden = std::fs::read_to_string(&golden_path).unwrap_or_default();
        assert!(
            now == golden,
            "{} is stale or missing: run `cargo fmu-build {} --xml-only --out modelDescription`",
            golden_path.display(),
            scene.strip_prefix(root).unwrap().display()
        );
    }
}
