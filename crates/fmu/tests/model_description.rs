//! The golden files in `modelDescription/` are up to date: for every `modelDescription/<id>.xml`
//! the XML generated now from `scenes/<id>.toml` is byte-identical. The shipped scenes are those
//! with a golden file (`scripts/test.sh` packages exactly these). The description of a spatial
//! scene is a function of the scene alone; it is compared with an instantiated model's once
//! the spatial model builds (until then `Model::<Spatial>::from_scene` reports "not built yet").
//! After a deliberate change (variables, units, crate version → GUID), regenerate with
//! `cargo fmu-build scenes/<id>.toml --xml-only --out modelDescription`.

use std::path::Path;

use fmi2::{guid, xml, CoSimModel};

#[test]
fn golden_model_descriptions_are_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut goldens: Vec<_> = std::fs::read_dir(root.join("modelDescription"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    goldens.sort();
    assert!(!goldens.is_empty(), "no golden modelDescription/*.xml");
    for golden_path in goldens {
        let id = golden_path
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let scene = root.join("scenes").join(format!("{id}.toml"));
        let bytes = std::fs::read(&scene).unwrap_or_else(|e| {
            panic!(
                "{} has no scene {}: {e}",
                golden_path.display(),
                scene.display()
            )
        });
        let text = std::str::from_utf8(&bytes).unwrap();
        // from the scene alone, as fmu-build writes it ...
        let now = hybeam_fmu::FmuModel::model_description(text, &id)
            .unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
        // ... and from an instantiated model, as a host sees it
        match hybeam_fmu::FmuModel::from_resource(text) {
            Ok(model) => {
                let guid = guid::guid::<hybeam_fmu::FmuModel>(&bytes);
                assert_eq!(xml::model_description_of(&model, &id, &guid).unwrap(), now);
            }
            Err(e) if e.contains("spatial model is not built yet") => {
                eprintln!("{id}: no spatial model yet, description checked from the scene only")
            }
            Err(e) => panic!("{}: {e}", scene.display()),
        }
        let golden = std::fs::read_to_string(&golden_path).unwrap();
        assert!(
            now == golden,
            "{} is stale: run `cargo fmu-build scenes/{id}.toml --xml-only --out modelDescription`",
            golden_path.display()
        );
    }
}
