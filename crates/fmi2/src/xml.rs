//! modelDescription.xml from the model's own [`ModelInfo`] and [`Variable`] table (the single
//! source of variables for the XML and the runtime), written with quick-xml.
//!
//! The output is deterministic (no date, variables in table order, units sorted by name) and
//! follows fmpy's copy of `fmi2ModelDescription.xsd`: element order CoSimulation,
//! UnitDefinitions, LogCategories, DefaultExperiment, ModelVariables, ModelStructure.
//!
//! ModelStructure: `<Outputs>` lists every output by 1-based index with `dependencies` = the
//! indices of the inputs in its [`Variable::depends_on`] (`dependenciesKind="dependent"` each),
//! `""` when it has none (no direct feedthrough: it depends on inputs only through the state).
//! The CoSimulation flags `canInterpolateInputs`, `maxOutputDerivativeOrder` and
//! `providesDirectionalDerivative` come from [`ModelInfo::capabilities`]. `<InitialUnknowns>`
//! lists exactly the outputs (all have `initial="calculated"`) without a `dependencies`
//! attribute, i.e. "may depend on every known", because initial outputs do depend on parameters.

use std::collections::BTreeSet;
use std::io;

use quick_xml::events::{BytesDecl, Event};
use quick_xml::Writer;

use super::log::LogCategory;
use super::model::{Causality, CoSimModel, ModelInfo, StringVariable, Variability, Variable};

/// SI base-unit exponents `[kg, m, s, A, K, mol, cd, rad]` and factor of every unit symbol a
/// [`Variable`] may use. Extend this table to use a new unit.
pub const UNITS: &[(&str, [i8; 8], f64)] = &[
    ("1", [0, 0, 0, 0, 0, 0, 0, 0], 1.0),
    ("1/(kg.m)", [-1, -1, 0, 0, 0, 0, 0, 0], 1.0),
    ("1/(kg.m2)", [-1, -2, 0, 0, 0, 0, 0, 0], 1.0),
    ("1/kg", [-1, 0, 0, 0, 0, 0, 0, 0], 1.0),
    ("1/s", [0, 0, -1, 0, 0, 0, 0, 0], 1.0),
    ("Hz", [0, 0, -1, 0, 0, 0, 0, 0], 1.0),
    ("J", [1, 2, -2, 0, 0, 0, 0, 0], 1.0),
    ("K", [0, 0, 0, 0, 1, 0, 0, 0], 1.0),
    ("N", [1, 1, -2, 0, 0, 0, 0, 0], 1.0),
    ("N.m", [1, 2, -2, 0, 0, 0, 0, 0], 1.0),
    ("N.m.s/rad", [1, 2, -1, 0, 0, 0, 0, -1], 1.0),
    ("N.m/rad", [1, 2, -2, 0, 0, 0, 0, -1], 1.0),
    ("N.m2", [1, 3, -2, 0, 0, 0, 0, 0], 1.0),
    ("N.s", [1, 1, -1, 0, 0, 0, 0, 0], 1.0),
    ("N.s/m", [1, 0, -1, 0, 0, 0, 0, 0], 1.0),
    ("N/m", [1, 0, -2, 0, 0, 0, 0, 0], 1.0),
    ("Pa", [1, -1, -2, 0, 0, 0, 0, 0], 1.0),
    ("W", [1, 2, -3, 0, 0, 0, 0, 0], 1.0),
    (
        "deg",
        [0, 0, 0, 0, 0, 0, 0, 1],
        std::f64::consts::PI / 180.0,
    ),
    ("kg", [1, 0, 0, 0, 0, 0, 0, 0], 1.0),
    ("kg.m2", [1, 2, 0, 0, 0, 0, 0, 0], 1.0),
    ("kg/m", [1, -1, 0, 0, 0, 0, 0, 0], 1.0),
    ("kg/m3", [1, -3, 0, 0, 0, 0, 0, 0], 1.0),
    ("m", [0, 1, 0, 0, 0, 0, 0, 0], 1.0),
    ("m/s", [0, 1, -1, 0, 0, 0, 0, 0], 1.0),
    ("m/s2", [0, 1, -2, 0, 0, 0, 0, 0], 1.0),
    ("m2", [0, 2, 0, 0, 0, 0, 0, 0], 1.0),
    ("m3", [0, 3, 0, 0, 0, 0, 0, 0], 1.0),
    ("m4", [0, 4, 0, 0, 0, 0, 0, 0], 1.0),
    ("rad", [0, 0, 0, 0, 0, 0, 0, 1], 1.0),
    ("rad/s", [0, 0, -1, 0, 0, 0, 0, 1], 1.0),
    ("rad/s2", [0, 0, -2, 0, 0, 0, 0, 1], 1.0),
    ("s", [0, 0, 1, 0, 0, 0, 0, 0], 1.0),
];

const BASE_UNITS: [&str; 8] = ["kg", "m", "s", "A", "K", "mol", "cd", "rad"];

/// True if `s` is a valid C identifier (what FMI requires of a modelIdentifier).
pub fn is_c_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c == '_' || c.is_ascii_alphabetic())
        && chars.all(|c| c == '_' || c.is_ascii_alphanumeric())
}

/// The default modelIdentifier for a scene file stem: every character that is not ASCII
/// alphanumeric or `_` becomes `_`, and a leading digit (or an empty stem) gets a `_` prefix.
pub fn model_identifier_from_stem(stem: &str) -> String {
    let mut id: String = stem
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c == '_' || c.is_ascii_alphabetic()) {
        id.insert(0, '_');
    }
    id
}

/// modelDescription.xml for `model` (generationTool [`CoSimModel::GENERATION_TOOL`]).
pub fn model_description_of<M: CoSimModel>(
    model: &M,
    model_identifier: &str,
    guid: &str,
) -> Result<String, String> {
    let ids = Identity {
        model_identifier,
        guid,
        generation_tool: M::GENERATION_TOOL,
    };
    model_description_with_strings(
        &model.model_info(),
        model.variables(),
        model.string_variables(),
        &ids,
    )
}

/// The identifying attributes of a modelDescription.xml.
#[derive(Debug, Clone, Copy)]
pub struct Identity<'a> {
    /// modelIdentifier (a C identifier: the binary's name).
    pub model_identifier: &'a str,
    /// guid.
    pub guid: &'a str,
    /// generationTool.
    pub generation_tool: &'a str,
}

/// Checks what the XML schema and fmpy's validation require of the variable table and
/// experiment; the error names the variable and the rule.
pub fn validate(info: &ModelInfo, vars: &[Variable], model_identifier: &str) -> Result<(), String> {
    if !is_c_identifier(model_identifier) {
        return Err(format!(
            "modelIdentifier \"{model_identifier}\" is not a valid C identifier"
        ));
    }
    let (t0, t1, h) = (info.start_time, info.stop_time, info.step_size);
    if !(t0.is_finite() && t1.is_finite() && t1 > t0 && h.is_finite() && h > 0.0) {
        return Err(format!(
            "default experiment start {t0}, stop {t1}, step {h}: need finite values, stop > start \
             and step > 0"
        ));
    }
    let mut names = BTreeSet::new();
    let mut vrs = BTreeSet::new();
    for v in vars {
        let who = format!("variable \"{}\" (value reference {})", v.name, v.vr);
        unique((&mut names, &mut vrs), (&v.name, v.vr), &who)?;
        if let Some(u) = v.unit {
            if !UNITS.iter().any(|(n, _, _)| *n == u) {
                return Err(format!("{who}: unit \"{u}\" is not in fmi::xml::UNITS"));
            }
        }
        if let Some(s) = v.start.filter(|s| !s.is_finite()) {
            return Err(format!("{who}: start = {s} is not finite"));
        }
        match (v.causality, v.variability, v.start) {
            (Causality::Parameter, Variability::Fixed | Variability::Tunable, Some(_)) => {}
            (Causality::Parameter, _, _) => {
                return Err(format!(
                    "{who}: a parameter must be fixed or tunable and have a start value"
                ))
            }
            (Causality::Input, Variability::Continuous, Some(_)) => {}
            (Causality::Input, _, _) => {
                return Err(format!(
                    "{who}: an input must be continuous with a start value"
                ))
            }
            (Causality::Output, Variability::Continuous, None) => {}
            (Causality::Output, _, _) => {
                return Err(format!(
                    "{who}: an output must be continuous without a start value (initial=calculated)"
                ))
            }
        }
        if !v.depends_on.is_empty() && v.causality != Causality::Output {
            return Err(format!(
                "{who}: only an output may list direct dependencies"
            ));
        }
        for &d in &v.depends_on {
            if !vars
                .iter()
                .any(|x| x.vr == d && x.causality == Causality::Input)
            {
                return Err(format!(
                    "{who}: depends_on lists value reference {d}, which is not an input"
                ));
            }
        }
    }
    Ok(())
}

/// Adds a variable's name and value reference to those seen; an empty or repeated name or a
/// repeated value reference is the error of `who`.
fn unique<'a>(
    (names, vrs): (&mut BTreeSet<&'a str>, &mut BTreeSet<u32>),
    (name, vr): (&'a str, u32),
    who: &str,
) -> Result<(), String> {
    if name.is_empty() || !names.insert(name) {
        return Err(format!("{who}: empty or duplicate name"));
    }
    if !vrs.insert(vr) {
        return Err(format!("{who}: duplicate value reference"));
    }
    Ok(())
}

/// Checks the String parameters: names and value references unique, also against the Real
/// variables `vars`; fixed or tunable; no NUL in the start value.
pub fn validate_strings(vars: &[Variable], strings: &[StringVariable]) -> Result<(), String> {
    let mut names: BTreeSet<&str> = vars.iter().map(|v| v.name.as_str()).collect();
    let mut vrs: BTreeSet<u32> = vars.iter().map(|v| v.vr).collect();
    for v in strings {
        let who = format!("String variable \"{}\" (value reference {})", v.name, v.vr);
        unique((&mut names, &mut vrs), (&v.name, v.vr), &who)?;
        if v.variability == Variability::Continuous {
            return Err(format!(
                "{who}: a String parameter must be fixed or tunable"
            ));
        }
        if v.start.contains('\0') {
            return Err(format!("{who}: the start value holds a NUL character"));
        }
    }
    Ok(())
}

/// modelDescription.xml (UTF-8, trailing newline) for this model information, variable table
/// and identity. Fails if [`validate`] fails.
pub fn model_description(
    info: &ModelInfo,
    vars: &[Variable],
    ids: &Identity,
) -> Result<String, String> {
    model_description_with_strings(info, vars, &[], ids)
}

/// [`model_description`] with String parameters, declared after the Real variables (so the
/// indices of the Real variables, and the ModelStructure, do not depend on them) as
/// `<ScalarVariable causality="parameter" variability="fixed|tunable" initial="exact">` with
/// `<String start="…"/>`. Fails if [`validate`] or [`validate_strings`] fails.
pub fn model_description_with_strings(
    info: &ModelInfo,
    vars: &[Variable],
    strings: &[StringVariable],
    ids: &Identity,
) -> Result<String, String> {
    validate(info, vars, ids.model_identifier)?;
    validate_strings(vars, strings)?;
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    write_document(&mut w, info, (vars, strings), ids)
        .map_err(|e| format!("writing modelDescription.xml: {e}"))?;
    let mut text = String::from_utf8(w.into_inner()).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

fn num(x: f64) -> String {
    // Debug gives the shortest round-trip form ("0.01", "100.0", "1e-7"), a valid xs:double.
    format!("{x:?}")
}

fn write_document(
    w: &mut Writer<Vec<u8>>,
    info: &ModelInfo,
    (vars, strings): (&[Variable], &[StringVariable]),
    ids: &Identity,
) -> io::Result<()> {
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let mut root = vec![
        ("fmiVersion", "2.0"),
        ("modelName", info.model_name.as_str()),
        ("guid", ids.guid),
    ];
    if !info.description.is_empty() {
        root.push(("description", info.description.as_str()));
    }
    root.extend([
        ("generationTool", ids.generation_tool),
        ("variableNamingConvention", "structured"),
        ("numberOfEventIndicators", "0"),
    ]);
    let caps = info.capabilities;
    let interpolate = if caps.input_derivative_order > 0 {
        "true"
    } else {
        "false"
    };
    let output_order = caps.output_derivative_order.to_string();
    let directional = if caps.directional_derivative {
        "true"
    } else {
        "false"
    };
    w.create_element("fmiModelDescription")
        .with_attributes(root)
        .write_inner_content(|w| {
            w.create_element("CoSimulation")
                .with_attributes([
                    ("modelIdentifier", ids.model_identifier),
                    ("needsExecutionTool", "false"),
                    ("canHandleVariableCommunicationStepSize", "true"),
                    ("canInterpolateInputs", interpolate),
                    ("maxOutputDerivativeOrder", output_order.as_str()),
                    ("canRunAsynchronuously", "false"),
                    ("canBeInstantiatedOnlyOncePerProcess", "false"),
                    ("canNotUseMemoryManagementFunctions", "true"),
                    ("canGetAndSetFMUstate", "true"),
                    ("canSerializeFMUstate", "true"),
                    ("providesDirectionalDerivative", directional),
                ])
                .write_empty()?;
            write_units(w, vars)?;
            w.create_element("LogCategories").write_inner_content(|w| {
                for c in LogCategory::ALL {
                    w.create_element("Category")
                        .with_attributes([("name", c.name()), ("description", c.description())])
                        .write_empty()?;
                }
                Ok(())
            })?;
            w.create_element("DefaultExperiment")
                .with_attributes([
                    ("startTime", num(info.start_time).as_str()),
                    ("stopTime", num(info.stop_time).as_str()),
                    ("stepSize", num(info.step_size).as_str()),
                ])
                .write_empty()?;
            w.create_element("ModelVariables")
                .write_inner_content(|w| {
                    for v in vars {
                        write_variable(w, v)?;
                    }
                    for v in strings {
                        write_string_variable(w, v)?;
                    }
                    Ok(())
                })?;
            write_structure(w, vars)?;
            Ok(())
        })?;
    Ok(())
}

pub(crate) fn write_units(w: &mut Writer<Vec<u8>>, vars: &[Variable]) -> io::Result<()> {
    let used: BTreeSet<&str> = vars.iter().filter_map(|v| v.unit).collect();
    if used.is_empty() {
        return Ok(());
    }
    w.create_element("UnitDefinitions")
        .write_inner_content(|w| {
            for (name, exps, factor) in UNITS.iter().filter(|(n, _, _)| used.contains(n)) {
                let exps: Vec<(&str, String)> = BASE_UNITS
                    .iter()
                    .zip(exps)
                    .filter(|(_, e)| **e != 0)
                    .map(|(b, e)| (*b, e.to_string()))
                    .collect();
                let factor = num(*factor);
                w.create_element("Unit")
                    .with_attribute(("name", *name))
                    .write_inner_content(|w| {
                        let mut base = w
                            .create_element("BaseUnit")
                            .with_attributes(exps.iter().map(|(b, e)| (*b, e.as_str())));
                        if factor != "1.0" {
                            base = base.with_attribute(("factor", factor.as_str()));
                        }
                        base.write_empty()?;
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

fn write_variable(w: &mut Writer<Vec<u8>>, v: &Variable) -> io::Result<()> {
    let vr = v.vr.to_string();
    let mut attrs = vec![("name", v.name.as_str()), ("valueReference", vr.as_str())];
    if !v.description.is_empty() {
        attrs.push(("description", v.description.as_str()));
    }
    let (causality, initial) = match v.causality {
        Causality::Parameter => ("parameter", Some("exact")),
        Causality::Input => ("input", None),
        Causality::Output => ("output", Some("calculated")),
    };
    let variability = match v.variability {
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Continuous => "continuous",
    };
    attrs.push(("causality", causality));
    attrs.push(("variability", variability));
    if let Some(i) = initial {
        attrs.push(("initial", i));
    }
    let start = v.start.map(num);
    w.create_element("ScalarVariable")
        .with_attributes(attrs)
        .write_inner_content(|w| {
            let mut real = w.create_element("Real");
            if let Some(u) = v.unit {
                real = real.with_attribute(("unit", u));
            }
            if let Some(s) = &start {
                real = real.with_attribute(("start", s.as_str()));
            }
            real.write_empty()?;
            Ok(())
        })?;
    Ok(())
}

fn write_string_variable(w: &mut Writer<Vec<u8>>, v: &StringVariable) -> io::Result<()> {
    let vr = v.vr.to_string();
    let mut attrs = vec![("name", v.name.as_str()), ("valueReference", vr.as_str())];
    if !v.description.is_empty() {
        attrs.push(("description", v.description.as_str()));
    }
    let variability = match v.variability {
        Variability::Tunable => "tunable",
        _ => "fixed",
    };
    attrs.extend([
        ("causality", "parameter"),
        ("variability", variability),
        ("initial", "exact"),
    ]);
    w.create_element("ScalarVariable")
        .with_attributes(attrs)
        .write_inner_content(|w| {
            w.create_element("String")
                .with_attribute(("start", v.start.as_str()))
                .write_empty()?;
            Ok(())
        })?;
    Ok(())
}

fn write_structure(w: &mut Writer<Vec<u8>>, vars: &[Variable]) -> io::Result<()> {
    // (1-based index, dependencies, dependenciesKind) of every output
    let index_of = |vr: u32| vars.iter().position(|v| v.vr == vr).map(|i| i + 1);
    let structure: Vec<(String, String, String)> = vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, v)| {
            let deps: Vec<String> = v
                .depends_on
                .iter()
                .filter_map(|&vr| index_of(vr))
                .map(|k| k.to_string())
                .collect();
            let kinds = vec!["dependent"; deps.len()].join(" ");
            ((i + 1).to_string(), deps.join(" "), kinds)
        })
        .collect();
    let outputs: Vec<&String> = structure.iter().map(|(i, _, _)| i).collect();
    w.create_element("ModelStructure")
        .write_inner_content(|w| {
            if !outputs.is_empty() {
                w.create_element("Outputs").write_inner_content(|w| {
                    for (i, deps, kinds) in &structure {
                        let mut e = w
                            .create_element("Unknown")
                            .with_attributes([("index", i.as_str()), ("dependencies", deps)]);
                        if !deps.is_empty() {
                            e = e.with_attribute(("dependenciesKind", kinds.as_str()));
                        }
                        e.write_empty()?;
                    }
                    Ok(())
                })?;
                w.create_element("InitialUnknowns")
                    .write_inner_content(|w| {
                        for i in &outputs {
                            w.create_element("Unknown")
                                .with_attribute(("index", i.as_str()))
                                .write_empty()?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn var(name: &str, vr: u32, c: Causality, v: Variability, start: Option<f64>) -> Variable {
        Variable {
            name: name.into(),
            vr,
            causality: c,
            variability: v,
            start,
            unit: Some("m"),
            description: "d <&> \"q\"".into(),
            depends_on: Vec::new(),
        }
    }

    const IDS: Identity = Identity {
        model_identifier: "m",
        guid: "{g}",
        generation_tool: "test <tool>",
    };

    fn info() -> ModelInfo {
        ModelInfo {
            model_name: "m".into(),
            description: String::new(),
            start_time: 0.0,
            stop_time: 1.0,
            step_size: 1e-3,
            capabilities: Default::default(),
        }
    }

    #[test]
    fn identifiers() {
        assert_eq!(model_identifier_from_stem("paper-case 1"), "paper_case_1");
        assert_eq!(model_identifier_from_stem("1x"), "_1x");
        assert_eq!(model_identifier_from_stem(""), "_");
        assert!(is_c_identifier("_a1") && !is_c_identifier("1a") && !is_c_identifier("a-b"));
    }

    #[test]
    fn writes_escaped_deterministic_xml() {
        let vars = vec![
            var("p", 0, Causality::Parameter, Variability::Fixed, Some(2.0)),
            var("u", 1, Causality::Input, Variability::Continuous, Some(0.0)),
            var("y", 2, Causality::Output, Variability::Continuous, None),
        ];
        let a = model_description(&info(), &vars, &IDS).unwrap();
        assert_eq!(a, model_description(&info(), &vars, &IDS).unwrap());
        assert!(a.contains("d &lt;&amp;&gt; &quot;q&quot;"));
        assert!(a.contains(r#"generationTool="test &lt;tool&gt;""#));
        assert!(a.contains(r#"<Unknown index="3" dependencies=""/>"#));
        assert!(a.contains(r#"<Real unit="m" start="2.0"/>"#));
        assert!(a.contains(r#"stepSize="0.001""#));
        let order = [
            "<CoSimulation",
            "<UnitDefinitions",
            "<LogCategories",
            "<DefaultExperiment",
            "<ModelVariables",
            "<ModelStructure",
        ];
        let pos: Vec<usize> = order.iter().map(|s| a.find(s).unwrap()).collect();
        assert!(pos.windows(2).all(|p| p[0] < p[1]));
    }

    #[test]
    fn refuses_illegal_tables() {
        let bad = [
            var(
                "p",
                0,
                Causality::Parameter,
                Variability::Continuous,
                Some(1.0),
            ),
            var("u", 0, Causality::Input, Variability::Continuous, None),
            var(
                "y",
                0,
                Causality::Output,
                Variability::Continuous,
                Some(1.0),
            ),
            Variable {
                unit: Some("furlong"),
                ..var("y", 0, Causality::Output, Variability::Continuous, None)
            },
        ];
        for v in bad {
            assert!(model_description(&info(), &[v], &IDS).is_err());
        }
        let dup = [
            var("a", 0, Causality::Output, Variability::Continuous, None),
            var("b", 0, Causality::Output, Variability::Continuous, None),
        ];
        assert!(model_description(&info(), &dup, &IDS).is_err());
        let bad_id = Identity {
            model_identifier: "not-an-id",
            ..IDS
        };
        assert!(model_description(&info(), &[], &bad_id).is_err());
    }
}
