//! OSP-IS extended model description (`<modelName>_OspModelDescription.xml`): named, typed
//! groups of a model's variables (ports), which an OSP system structure connects with one
//! `<VariableGroupConnection>` instead of one connection per variable. libcosim reads the
//! file from beside the FMU (or beside the system structure), pairs the nested groups of two
//! connected groups in order and their variables in order, each output to the input it meets.
//!
//! Written with quick-xml; the units are those of the variables, from [`super::xml::UNITS`].

use std::io;

use quick_xml::events::{BytesDecl, Event};
use quick_xml::Writer;

use super::model::Variable;
use super::xml::write_units;

/// The OspModelDescription namespace (OSP-IS 1.0).
pub const NAMESPACE: &str = "https://open-simulation-platform.com/OspModelDescription/1.0.0";

/// A typed group of variables.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableGroup {
    /// OSP-IS group type (the element name): `Generic`, `Force`, `Torque`, `LinearVelocity`,
    /// `AngularVelocity`, `LinearDisplacement`, `AngularDisplacement`,
    /// `LinearMechanicalPort` (a Force and a LinearVelocity), `AngularMechanicalPort` (a Torque
    /// and an AngularVelocity), ...
    pub kind: &'static str,
    /// The group's name, unique in the file (a connection names it).
    pub name: String,
    /// Names of the model's variables in the group, in connection order.
    pub variables: Vec<String>,
    /// Nested groups, in connection order.
    pub groups: Vec<VariableGroup>,
}

impl VariableGroup {
    /// A group of variables.
    pub fn of(kind: &'static str, name: &str, variables: &[&str]) -> Self {
        Self {
            kind,
            name: name.to_string(),
            variables: variables.iter().map(|v| v.to_string()).collect(),
            groups: Vec::new(),
        }
    }

    /// A group of groups.
    pub fn nest(kind: &'static str, name: &str, groups: Vec<VariableGroup>) -> Self {
        Self {
            kind,
            name: name.to_string(),
            variables: Vec::new(),
            groups,
        }
    }

    fn walk<'a>(&'a self, out: &mut Vec<&'a VariableGroup>) {
        out.push(self);
        for g in &self.groups {
            g.walk(out);
        }
    }
}

/// The OspModelDescription.xml of `groups` over the model's variables `vars`: an error names a
/// group variable the model does not have or a group name used twice.
pub fn model_description(groups: &[VariableGroup], vars: &[Variable]) -> Result<String, String> {
    let mut all = Vec::new();
    for g in groups {
        g.walk(&mut all);
    }
    let mut names = std::collections::BTreeSet::new();
    let mut used = Vec::new();
    for g in &all {
        if !names.insert(g.name.as_str()) {
            return Err(format!("variable group \"{}\" is declared twice", g.name));
        }
        for name in &g.variables {
            let v = vars.iter().find(|v| &v.name == name).ok_or_else(|| {
                format!(
                    "variable group \"{}\": the model has no variable {name}",
                    g.name
                )
            })?;
            used.push(v.clone());
        }
    }
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    write(&mut w, groups, vars, &used).map_err(|e| format!("writing OspModelDescription: {e}"))?;
    let mut text = String::from_utf8(w.into_inner()).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

fn write(
    w: &mut Writer<Vec<u8>>,
    groups: &[VariableGroup],
    vars: &[Variable],
    used: &[Variable],
) -> io::Result<()> {
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    w.create_element("OspModelDescription")
        .with_attributes([("xmlns", NAMESPACE), ("version", "1.0")])
        .write_inner_content(|w| {
            write_units(w, used)?;
            w.create_element("VariableGroups")
                .write_inner_content(|w| {
                    for g in groups {
                        write_group(w, g, vars)?;
                    }
                    Ok(())
                })?;
            Ok(())
        })?;
    Ok(())
}

fn write_group(w: &mut Writer<Vec<u8>>, g: &VariableGroup, vars: &[Variable]) -> io::Result<()> {
    w.create_element(g.kind)
        .with_attribute(("name", g.name.as_str()))
        .write_inner_content(|w| {
            for g in &g.groups {
                write_group(w, g, vars)?;
            }
            for name in &g.variables {
                let unit = vars.iter().find(|v| &v.name == name).and_then(|v| v.unit);
                let mut e = w
                    .create_element("Variable")
                    .with_attribute(("ref", name.as_str()));
                if let Some(u) = unit {
                    e = e.with_attribute(("unit", u));
                }
                e.write_empty()?;
            }
            Ok(())
        })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Causality, Variability};

    fn var(name: &str, unit: &'static str, causality: Causality) -> Variable {
        Variable {
            name: name.into(),
            vr: 0,
            causality,
            variability: Variability::Continuous,
            start: None,
            unit: Some(unit),
            description: String::new(),
            depends_on: Vec::new(),
        }
    }

    /// A port nests its groups in order with the variables' units, and a missing variable or
    /// a repeated group name is an error naming it.
    #[test]
    fn groups_nest_in_order_and_name_their_errors() {
        let vars = [
            var("f", "N", Causality::Output),
            var("v", "m/s", Causality::Input),
        ];
        let port = VariableGroup::nest(
            "LinearMechanicalPort",
            "port",
            vec![
                VariableGroup::of("Force", "port.force", &["f"]),
                VariableGroup::of("LinearVelocity", "port.velocity", &["v"]),
            ],
        );
        let xml = model_description(std::slice::from_ref(&port), &vars).unwrap();
        let force = xml.find("<Force name=\"port.force\">").unwrap();
        let velocity = xml.find("<LinearVelocity name=\"port.velocity\">").unwrap();
        assert!(force < velocity, "{xml}");
        assert!(xml.contains("<Variable ref=\"f\" unit=\"N\"/>"), "{xml}");
        assert!(xml.contains("<Unit name=\"m/s\">"), "{xml}");
        let missing = VariableGroup::of("Force", "g", &["nope"]);
        let e = model_description(&[missing], &vars).unwrap_err();
        assert!(e.contains("nope") && e.contains("\"g\""), "{e}");
        let e = model_description(&[port.clone(), port], &vars).unwrap_err();
        assert!(e.contains("twice"), "{e}");
    }
}
