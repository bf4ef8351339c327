//! Every `f64` of a serializable value checked for finiteness, naming the first that is not:
//! what a restored snapshot must pass, whatever fields it gains (the value is walked through
//! its `Serialize` form, so a new field cannot be forgotten).

use serde::Serialize;
use serde_value::Value;

/// The path (e.g. `memory.mount.base.acceleration[0]`) and value of a non-finite `f64` of `x`,
/// if there is one (struct fields are visited in name order, so the answer is deterministic).
pub fn first_non_finite<T: Serialize>(x: &T) -> Option<(String, f64)> {
    // serialization into a value tree fails only for types this crate never snapshots (maps
    // with non-value keys); such a value is reported rather than passed
    let value = match serde_value::to_value(x) {
        Ok(v) => v,
        Err(e) => return Some((format!("(not walkable: {e})"), f64::NAN)),
    };
    let mut path = String::new();
    walk(&value, &mut path)
}

fn walk(v: &Value, path: &mut String) -> Option<(String, f64)> {
    let found = |x: f64, path: &String| (!x.is_finite()).then(|| (path.clone(), x));
    match v {
        Value::F64(x) => found(*x, path),
        Value::F32(x) => found(f64::from(*x), path),
        Value::Option(Some(inner)) | Value::Newtype(inner) => walk(inner, path),
        Value::Seq(items) => items.iter().enumerate().find_map(|(k, item)| {
            let len = path.len();
            path.push_str(&format!("[{k}]"));
            let r = walk(item, path);
            path.truncate(len);
            r
        }),
        Value::Map(fields) => fields.iter().find_map(|(key, item)| {
            let len = path.len();
            match key {
                Value::String(name) if path.is_empty() => path.push_str(name),
                Value::String(name) => path.push_str(&format!(".{name}")),
                other => path.push_str(&format!("[{other:?}]")),
            }
            let r = walk(item, path);
            path.truncate(len);
            r
        }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Inner {
        a: [f64; 2],
        b: Option<Vec<f64>>,
    }

    #[derive(Serialize)]
    struct Outer {
        t: f64,
        inner: Inner,
        pair: Option<(f64, Inner)>,
    }

    #[test]
    fn names_the_first_non_finite_field() {
        let ok = || Inner {
            a: [1.0, 2.0],
            b: Some(vec![3.0]),
        };
        let mut x = Outer {
            t: 0.5,
            inner: ok(),
            pair: Some((1.0, ok())),
        };
        assert_eq!(first_non_finite(&x), None);
        x.pair.as_mut().unwrap().1.b = Some(vec![0.0, f64::INFINITY]);
        assert_eq!(
            first_non_finite(&x),
            Some(("pair[1].b[1]".to_owned(), f64::INFINITY))
        );
        x.inner.a[1] = f64::NAN;
        let (path, v) = first_non_finite(&x).unwrap();
        assert_eq!(path, "inner.a[1]");
        assert!(v.is_nan());
    }
}
