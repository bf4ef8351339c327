//! An unpacked `.fmu`: the archive extracted into a temporary directory and the parts of its
//! `modelDescription.xml` the harness needs (model identifier, GUID, scalar variables).

use std::fs::File;
use std::path::{Path, PathBuf};

use quick_xml::events::{BytesStart, Event};

/// Causality of a scalar variable (FMI 2.0 `causality`; absent means `local`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// `input`: set by the host.
    Input,
    /// `output`: read by the host.
    Output,
    /// Any other causality (parameter, calculatedParameter, local, independent).
    Other,
}

/// One `ScalarVariable` of the model description.
#[derive(Debug, Clone)]
pub struct Variable {
    /// The variable's name, e.g. `tip.force.y`.
    pub name: String,
    /// Its value reference.
    pub vr: u32,
    /// Its causality.
    pub causality: Causality,
    /// The `start` attribute of its `<Real>` element, if any (SI units of the variable).
    pub start: Option<f64>,
}

/// What the harness reads from `modelDescription.xml`.
#[derive(Debug, Clone)]
pub struct ModelDescription {
    /// `CoSimulation/@modelIdentifier`: the binary's file stem.
    pub model_identifier: String,
    /// `fmiModelDescription/@guid`.
    pub guid: String,
    /// Every scalar variable, in document order.
    pub variables: Vec<Variable>,
}

impl ModelDescription {
    /// The variable called `name`, if the model has one.
    pub fn variable(&self, name: &str) -> Option<&Variable> {
        self.variables.iter().find(|v| v.name == name)
    }
}

/// An `.fmu` extracted into a temporary directory (removed on drop).
pub struct Unpacked {
    /// The temporary directory holding the archive's files.
    pub dir: tempfile::TempDir,
    /// The parsed model description.
    pub description: ModelDescription,
}

impl Unpacked {
    /// The `resources/` directory of the unpacked FMU.
    pub fn resources(&self) -> PathBuf {
        self.dir.path().join("resources")
    }

    /// `binaries/linux64/<modelIdentifier>.so`.
    pub fn binary(&self) -> PathBuf {
        self.dir
            .path()
            .join("binaries")
            .join("linux64")
            .join(format!("{}.so", self.description.model_identifier))
    }
}

/// Extracts `fmu` into a fresh temporary directory and reads its model description.
pub fn unpack(fmu: &Path) -> Result<Unpacked, String> {
    let file = File::open(fmu).map_err(|e| format!("cannot open {}: {e}", fmu.display()))?;
    let mut archive = zip::ZipArchive::new(file)
        .map_err(|e| format!("{} is not a zip archive (an .fmu): {e}", fmu.display()))?;
    let dir = tempfile::Builder::new()
        .prefix("hybeam-realtime-")
        .tempdir()
        .map_err(|e| format!("cannot create a temporary directory: {e}"))?;
    archive
        .extract(dir.path())
        .map_err(|e| format!("cannot extract {}: {e}", fmu.display()))?;
    let md = dir.path().join("modelDescription.xml");
    let text = std::fs::read_to_string(&md).map_err(|e| {
        format!(
            "{} has no readable modelDescription.xml: {e}",
            fmu.display()
        )
    })?;
    let description =
        parse(&text).map_err(|e| format!("{} modelDescription.xml: {e}", fmu.display()))?;
    Ok(Unpacked { dir, description })
}

/// The attribute `key` of `e`, unescaped.
fn attribute(e: &BytesStart, key: &str) -> Result<Option<String>, String> {
    for a in e.attributes() {
        let a = a.map_err(|e| e.to_string())?;
        if a.key.as_ref() == key {
            let v = a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|e| e.to_string())?;
            return Ok(Some(v.to_string()));
        }
    }
    Ok(None)
}

/// Parses the text of a `modelDescription.xml`.
pub fn parse(text: &str) -> Result<ModelDescription, String> {
    let mut reader = quick_xml::Reader::from_str(text);
    let (mut model_identifier, mut guid) = (None, None);
    let mut variables: Vec<Variable> = Vec::new();
    // inside a ScalarVariable element (its <Real> child carries the start value)
    let mut open_variable = false;
    loop {
        let event = reader
            .read_event()
            .map_err(|e| format!("not well-formed XML: {e}"))?;
        let (e, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(e) => {
                if e.name().as_ref() == "ScalarVariable" {
                    open_variable = false;
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        match e.name().as_ref() {
            "fmiModelDescription" => guid = attribute(&e, "guid")?,
            "CoSimulation" => model_identifier = attribute(&e, "modelIdentifier")?,
            "ScalarVariable" => {
                let name =
                    attribute(&e, "name")?.ok_or("a ScalarVariable without a name attribute")?;
                let vr = attribute(&e, "valueReference")?
                    .ok_or_else(|| format!("variable {name} has no valueReference"))?;
                let vr = vr.parse::<u32>().map_err(|_| {
                    format!("variable {name}: valueReference {vr:?} is not an unsigned integer")
                })?;
                let causality = match attribute(&e, "causality")?.as_deref() {
                    Some("input") => Causality::Input,
                    Some("output") => Causality::Output,
                    _ => Causality::Other,
                };
                variables.push(Variable {
                    name,
                    vr,
                    causality,
                    start: None,
                });
                open_variable = !empty;
            }
            "Real" if open_variable => {
                if let (Some(v), Some(s)) = (variables.last_mut(), attribute(&e, "start")?) {
                    v.start = Some(s.parse::<f64>().map_err(|_| {
                        format!("variable {}: start {s:?} is not a number", v.name)
                    })?);
                }
            }
            _ => {}
        }
    }
    Ok(ModelDescription {
        model_identifier: model_identifier
            .ok_or("no CoSimulation element with a modelIdentifier (not a co-simulation FMU)")?,
        guid: guid.ok_or("no guid attribute on fmiModelDescription")?,
        variables,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_identifier_guid_and_variables() {
        let md = parse(
            r#"<?xml version="1.0"?>
<fmiModelDescription fmiVersion="2.0" modelName="m" guid="{g}">
  <CoSimulation modelIdentifier="boom"/>
  <ModelVariables>
    <ScalarVariable name="tip.force.y" valueReference="2" causality="input" variability="continuous">
      <Real start="0.5"/>
    </ScalarVariable>
    <ScalarVariable name="tip.position.x" valueReference="10" causality="output"><Real/></ScalarVariable>
    <ScalarVariable name="a &amp; b" valueReference="7"><Real start="1e-3"/></ScalarVariable>
  </ModelVariables>
</fmiModelDescription>"#,
        )
        .unwrap();
        assert_eq!(md.model_identifier, "boom");
        assert_eq!(md.guid, "{g}");
        let f = md.variable("tip.force.y").unwrap();
        assert_eq!(
            (f.vr, f.causality, f.start),
            (2, Causality::Input, Some(0.5))
        );
        let p = md.variable("tip.position.x").unwrap();
        assert_eq!((p.vr, p.causality, p.start), (10, Causality::Output, None));
        let o = md.variable("a & b").unwrap();
        assert_eq!((o.causality, o.start), (Causality::Other, Some(1e-3)));
    }
}
