//! `--set key.path=value` overrides on a parsed TOML tree.

use super::SceneError;

/// Sets `value` (TOML syntax; a bare word is taken as a string) at the dotted `path`
/// (e.g. `segments.1.elements`, array elements by index) of `table`.
pub fn apply_override(table: &mut toml::Table, path: &str, value: &str) -> Result<(), SceneError> {
    let parsed = parse_value(value);
    let keys: Vec<&str> = path.split('.').collect();
    if keys.iter().any(|k| k.is_empty()) {
        return Err(SceneError(format!(
            "--set {path}={value}: the path has an empty component; write e.g. segments.1.elements=16"
        )));
    }
    let (first, rest) = keys.split_first().expect("split yields at least one key");
    if rest.is_empty() {
        table.insert((*first).to_string(), parsed);
        return Ok(());
    }
    let mut cur: &mut toml::Value = table
        .entry((*first).to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    for (depth, key) in rest.iter().enumerate() {
        let last = depth + 1 == rest.len();
        let here = keys[..=depth].join(".");
        cur = match cur {
            toml::Value::Table(t) => {
                if last {
                    t.insert((*key).to_string(), parsed);
                    return Ok(());
                }
                t.entry((*key).to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            }
            toml::Value::Array(a) => {
                let i: usize = key.parse().map_err(|_| {
                    SceneError(format!(
                        "--set {path}: '{here}' is a list; index it with a number, e.g. {here}.0"
                    ))
                })?;
                let n = a.len();
                let slot = a.get_mut(i).ok_or_else(|| {
                    SceneError(format!(
                        "--set {path}: '{here}' has {n} entries, index {i} is out of range"
                    ))
                })?;
                if last {
                    *slot = parsed;
                    return Ok(());
                }
                slot
            }
            _ => {
                return Err(SceneError(format!(
                    "--set {path}: '{here}' is a value, not a table or list"
                )))
            }
        };
    }
    Ok(())
}

/// Parses a TOML scalar or array; a bare word becomes a string.
fn parse_value(v: &str) -> toml::Value {
    let doc = format!("x = {v}");
    match toml::from_str::<toml::Table>(&doc) {
        Ok(mut t) => t.remove("x").unwrap_or(toml::Value::String(v.into())),
        Err(_) => match v {
            "nan" | "NaN" => toml::Value::Float(f64::NAN),
            _ => toml::Value::String(v.into()),
        },
    }
}
