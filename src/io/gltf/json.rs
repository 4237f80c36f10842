//! Reading JSON values with their path (`accessors[3].count`), so that every error says
//! where it is.

use serde_json::{Map, Value};

use super::json_error;
use crate::error::Result;

/// A JSON object with its path, for error messages.
#[derive(Clone, Copy)]
pub(super) struct Obj<'a> {
    pub map: &'a Map<String, Value>,
    pub path: &'a str,
}

impl<'a> Obj<'a> {
    pub fn new(value: &'a Value, path: &'a str) -> Result<Obj<'a>> {
        match value {
            Value::Object(map) => Ok(Obj { map, path }),
            other => Err(json_error(
                path,
                format!("expected an object, found {}", kind(other)),
            )),
        }
    }

    pub fn field_path(&self, key: &str) -> String {
        format!("{}.{key}", self.path)
    }

    pub fn u64(&self, key: &str) -> Result<Option<u64>> {
        match self.map.get(key) {
            None => Ok(None),
            Some(v) => v.as_u64().map(Some).ok_or_else(|| {
                json_error(
                    &self.field_path(key),
                    format!("expected a non-negative integer, found {}", show(v)),
                )
            }),
        }
    }

    pub fn required_u64(&self, key: &str) -> Result<u64> {
        self.u64(key)?
            .ok_or_else(|| json_error(self.path, format!("`{key}` is missing")))
    }

    /// An index into an array of `len` elements called `target`.
    pub fn index(&self, key: &str, len: usize, target: &str) -> Result<Option<usize>> {
        let Some(i) = self.u64(key)? else {
            return Ok(None);
        };
        check_index(&self.field_path(key), i, len, target).map(Some)
    }

    pub fn required_index(&self, key: &str, len: usize, target: &str) -> Result<usize> {
        self.index(key, len, target)?
            .ok_or_else(|| json_error(self.path, format!("`{key}` is missing")))
    }

    pub fn string(&self, key: &str) -> Result<Option<&'a str>> {
        match self.map.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(v) => Err(json_error(
                &self.field_path(key),
                format!("expected a string, found {}", show(v)),
            )),
        }
    }

    pub fn bool(&self, key: &str) -> Result<bool> {
        match self.map.get(key) {
            None => Ok(false),
            Some(Value::Bool(b)) => Ok(*b),
            Some(v) => Err(json_error(
                &self.field_path(key),
                format!("expected true or false, found {}", show(v)),
            )),
        }
    }

    pub fn array(&self, key: &str) -> Result<&'a [Value]> {
        match self.map.get(key) {
            None => Ok(&[]),
            Some(Value::Array(a)) => Ok(a),
            Some(v) => Err(json_error(
                &self.field_path(key),
                format!("expected an array, found {}", show(v)),
            )),
        }
    }

    /// `len` finite numbers.
    pub fn numbers(&self, key: &str, len: usize) -> Result<Option<Vec<f64>>> {
        if !self.map.contains_key(key) {
            return Ok(None);
        }
        let path = self.field_path(key);
        let items = self.array(key)?;
        if items.len() != len {
            return Err(json_error(
                &path,
                format!("expected {len} numbers, found {}", items.len()),
            ));
        }
        items
            .iter()
            .enumerate()
            .map(|(i, v)| {
                v.as_f64().ok_or_else(|| {
                    json_error(
                        &format!("{path}[{i}]"),
                        format!("expected a number, found {}", show(v)),
                    )
                })
            })
            .collect::<Result<Vec<f64>>>()
            .map(Some)
    }
}

fn check_index(path: &str, i: u64, len: usize, target: &str) -> Result<usize> {
    if i < len as u64 {
        Ok(i as usize)
    } else {
        Err(json_error(
            path,
            format!("index {i} is out of range: there are {len} {target}"),
        ))
    }
}

/// What kind of JSON value `v` is.
fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// A short, printable rendering of a JSON value.
pub(super) fn show(v: &Value) -> String {
    match v {
        Value::Array(_) | Value::Object(_) => kind(v).to_string(),
        other => super::escape(&other.to_string()),
    }
}

/// The objects of the top-level array `key`, with their paths.
pub(super) fn objects<'a>(root: &Obj<'a>, key: &str) -> Result<Vec<(&'a Value, String)>> {
    Ok(root
        .array(key)?
        .iter()
        .enumerate()
        .map(|(i, v)| (v, format!("{key}[{i}]")))
        .collect())
}

/// An array element that is an index into `target`.
pub(super) fn index_value(path: &str, v: &Value, len: usize, target: &str) -> Result<usize> {
    let i = v.as_u64().ok_or_else(|| {
        json_error(
            path,
            format!("expected a non-negative integer, found {}", show(v)),
        )
    })?;
    check_index(path, i, len, target)
}
