//! `docs/fmu-variables.md` states the variable table: its rows (name, VR, causality or
//! variability, unit) are exactly the rows of `Table::of(scene)` over every scene in `scenes/`,
//! with segment parameters written once as `<segment>.<field>` at VR `1000(i+1) + k`, and the
//! String parameters.

use std::collections::BTreeSet;
use std::path::Path;

use fmi2::{Causality, Variability, Variable};
use hybeam::scene::Scene;
use hybeam::simulator::{InputId, InputKind, Quantity};
use hybeam_fmu::cosim::variables::{Access, Table, LINE_LOAD_K, MASS_FIELDS, SEGMENT_FIELDS};

/// One documented row: name, VR, causality (inputs, outputs) or variability (parameters), unit.
type Row = (String, String, String, String);

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The variable rows of the document (lines starting with "| `").
fn documented() -> BTreeSet<Row> {
    let text = std::fs::read_to_string(root().join("docs/fmu-variables.md")).unwrap();
    text.lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = cells[1].split('`').nth(1).unwrap_or_default();
            let row = (name, cells[2], cells[3], cells[4]);
            (row.0.into(), row.1.into(), row.2.into(), row.3.into())
        })
        .collect()
}

fn unit(u: Option<&str>) -> String {
    u.unwrap_or("–").into()
}

fn kind(v: &Variable) -> String {
    match (v.causality, v.variability) {
        (Causality::Input, _) => "input",
        (Causality::Output, _) => "output",
        (_, Variability::Tunable) => "tunable",
        _ => "fixed",
    }
    .into()
}

fn segment_row(name: &str, k: u32, u: Option<&str>) -> Row {
    (
        format!("<segment>.{name}"),
        format!("1000(i+1) + {k}"),
        "fixed".into(),
        unit(u),
    )
}

fn mass_row(name: &str, k: u32, u: Option<&str>) -> Row {
    (
        format!("masses.<name>.{name}"),
        format!("500000 + 10i + {k}"),
        "fixed".into(),
        unit(u),
    )
}

/// The rows of the table of `scene`, segment and mass parameters in the document's generic
/// form.
fn rows_of(scene: &Scene) -> BTreeSet<Row> {
    let table = Table::of(scene);
    table
        .variables()
        .iter()
        .enumerate()
        .map(|(index, v)| match table.access(index) {
            Access::Segment(i, f) => {
                assert_eq!(v.vr, 1000 * (i as u32 + 1) + f.k, "{}", v.name);
                segment_row(f.name, f.k, v.unit)
            }
            Access::Mass(i, f) => {
                assert_eq!(v.vr, 500_000 + 10 * i as u32 + f.k, "{}", v.name);
                mass_row(f.name, f.k, v.unit)
            }
            // a segment's line-load inputs, in the segment parameters' generic form
            Access::Input(id) if id.kind == InputKind::LineLoad => {
                let axis = ["x", "y", "z"][InputId::line_load_slot(id.component).1];
                let k = LINE_LOAD_K + InputId::line_load_slot(id.component).1 as u32;
                assert_eq!(v.vr % 1000, k, "{}", v.name);
                (
                    format!("<segment>.line_load.{axis}"),
                    format!("1000(i+1) + {k}"),
                    kind(v),
                    unit(v.unit),
                )
            }
            // a station's outputs, in the generic form 600000 + 10i + k
            Access::Output(id)
                if matches!(
                    id.quantity,
                    Quantity::StationForce | Quantity::StationMoment | Quantity::StationStress
                ) =>
            {
                let k = v.vr % 10;
                let field = v.name.splitn(3, '.').nth(2).unwrap_or_default();
                (
                    format!("station.<name>.{field}"),
                    format!("600000 + 10i + {k}"),
                    kind(v),
                    unit(v.unit),
                )
            }
            // the partner model's inputs, written once each in a generic form
            Access::Input(id) if id.kind == InputKind::MountMobility => (
                "root.mobility.<a>_<r>".into(),
                "200 + 6i + j".into(),
                kind(v),
                "1/kg, 1/(kg.m), 1/(kg.m2)".into(),
            ),
            Access::Input(id) if id.kind == InputKind::MountReactionReference => (
                "root.reaction_reference.<r>".into(),
                "240 + j".into(),
                kind(v),
                "N, N.m".into(),
            ),
            _ => (v.name.clone(), v.vr.to_string(), kind(v), unit(v.unit)),
        })
        .chain(table.string_variables().iter().map(|v| {
            let kind = match v.variability {
                Variability::Tunable => "tunable",
                _ => "fixed",
            };
            (v.name.clone(), v.vr.to_string(), kind.into(), unit(None))
        }))
        .collect()
}

#[test]
fn documented_variables_are_the_table() {
    let mut scenes: Vec<_> = std::fs::read_dir(root().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 4, "scenes/ has the shipped scenes");
    let doc = documented();
    // every segment field the table can declare, whether a shipped scene uses it or not
    let mut all: BTreeSet<Row> = SEGMENT_FIELDS
        .iter()
        .map(|f| segment_row(f.name, f.k, f.unit))
        .chain(MASS_FIELDS.iter().map(|f| mass_row(f.name, f.k, f.unit)))
        .collect();
    for path in &scenes {
        let scene = Scene::from_toml(&std::fs::read_to_string(path).unwrap())
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), e.0));
        let rows = rows_of(&scene);
        let missing: Vec<_> = rows.difference(&doc).collect();
        assert!(
            missing.is_empty(),
            "{}: rows missing from docs/fmu-variables.md (or differing there): {missing:#?}",
            path.display()
        );
        all.extend(rows);
    }
    let stale: Vec<_> = doc.difference(&all).collect();
    assert!(
        stale.is_empty(),
        "docs/fmu-variables.md rows that no scene's table has: {stale:#?}"
    );
}
