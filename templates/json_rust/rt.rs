//! The checks every message applies, in this order: object, required keys, unknown keys, a
//! command's `cmd`, then per field its JSON type, its declared type's range (or a string's
//! length), and its documented values. The same in every generated crate: a protocol uses the
//! checks its field types need.
#![allow(dead_code)]

use super::{ErrorCode, ValidationError};
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};
use std::cell::RefCell;
use std::fmt;

pub(crate) fn err(
    message: &'static str,
    field: &str,
    value: &Value,
    code: ErrorCode,
    rule: &'static str,
) -> ValidationError {
    ValidationError {
        message,
        field: field.to_owned(),
        value: value.clone(),
        code,
        rule,
    }
}

pub(crate) fn object<'a>(
    message: &'static str,
    v: &'a Value,
    keys: &[&str],
    unexpected: &'static str,
) -> Result<&'a Map<String, Value>, ValidationError> {
    let Some(obj) = v.as_object() else {
        return Err(err(
            message,
            "",
            v,
            ErrorCode::Object,
            "must be a JSON object",
        ));
    };
    if let Some(key) = keys.iter().find(|k| !obj.contains_key(**k)) {
        return Err(err(
            message,
            key,
            &Value::Null,
            ErrorCode::Required,
            "is required",
        ));
    }
    // The least unknown key in code-point order, as every binding reports it (whatever
    // order serde_json's map keeps).
    if let Some((key, value)) = obj
        .iter()
        .filter(|(k, _)| !keys.contains(&k.as_str()))
        .min_by(|a, b| a.0.cmp(b.0))
    {
        return Err(err(message, key, value, ErrorCode::Unexpected, unexpected));
    }
    Ok(obj)
}

/// The integer a JSON number denotes (`2.0` is the integer 2), if it is one.
pub(crate) fn integral(v: &Value) -> Option<i128> {
    if let Some(i) = v.as_i64() {
        return Some(i128::from(i));
    }
    if let Some(u) = v.as_u64() {
        return Some(i128::from(u));
    }
    let f = v.as_f64()?;
    if !f.is_finite() || f.fract() != 0.0 {
        return None;
    }
    // Beyond ±1e38 no declared type reaches: saturate (still out of every range).
    Some(if f.abs() > 1e38 {
        if f > 0.0 {
            i128::MAX
        } else {
            i128::MIN
        }
    } else {
        f as i128
    })
}

pub(crate) fn integer(
    message: &'static str,
    key: &str,
    v: &Value,
    lo: i128,
    hi: i128,
    type_rule: &'static str,
    range_rule: &'static str,
) -> Result<i128, ValidationError> {
    if !v.is_number() {
        return Err(err(message, key, v, ErrorCode::Type, type_rule));
    }
    let n = integral(v).ok_or_else(|| err(message, key, v, ErrorCode::Type, type_rule))?;
    if n < lo || n > hi {
        return Err(err(message, key, v, ErrorCode::TypeRange, range_rule));
    }
    Ok(n)
}

pub(crate) fn number(
    message: &'static str,
    key: &str,
    v: &Value,
    lo: Option<f64>,
    hi: Option<f64>,
    type_rule: &'static str,
    range_rule: &'static str,
) -> Result<f64, ValidationError> {
    let x = v
        .as_f64()
        .ok_or_else(|| err(message, key, v, ErrorCode::Type, type_rule))?;
    if !x.is_finite() {
        return Err(err(message, key, v, ErrorCode::Type, type_rule));
    }
    if lo.is_some_and(|lo| x < lo) || hi.is_some_and(|hi| x > hi) {
        return Err(err(message, key, v, ErrorCode::TypeRange, range_rule));
    }
    Ok(x)
}

pub(crate) fn boolean(
    message: &'static str,
    key: &str,
    v: &Value,
    type_rule: &'static str,
) -> Result<bool, ValidationError> {
    v.as_bool()
        .ok_or_else(|| err(message, key, v, ErrorCode::Type, type_rule))
}

pub(crate) fn string<'a>(
    message: &'static str,
    key: &str,
    v: &'a Value,
    lo: usize,
    hi: usize,
    type_rule: &'static str,
    length_rule: &'static str,
) -> Result<&'a str, ValidationError> {
    let s = v
        .as_str()
        .ok_or_else(|| err(message, key, v, ErrorCode::Type, type_rule))?;
    let n = s.chars().count();
    if n < lo || n > hi {
        return Err(err(message, key, v, ErrorCode::Length, length_rule));
    }
    Ok(s)
}

/// A documented range check; `ok` tells whether the value lies within it (or is a sentinel).
pub(crate) fn documented(
    message: &'static str,
    key: &str,
    v: &Value,
    ok: bool,
    rule: &'static str,
) -> Result<(), ValidationError> {
    if ok {
        Ok(())
    } else {
        Err(err(message, key, v, ErrorCode::Range, rule))
    }
}

/// JSON text as a `Value`, refusing what `serde_json::from_str` lets through: a key given twice
/// in an object (it keeps the last). NaN and Infinity are no JSON: refused as text that is not
/// JSON, naming the key they stand at.
pub(crate) fn parse_text(text: &str) -> Result<Value, ValidationError> {
    let fault = RefCell::new(None);
    let mut de = serde_json::Deserializer::from_str(text);
    let parsed = Strict(&fault)
        .deserialize(&mut de)
        .and_then(|v| de.end().map(|()| v));
    match (parsed, fault.into_inner()) {
        (Ok(v), _) => Ok(v),
        (Err(_), Some(Fault::Duplicate(key, value))) => Err(err(
            "message",
            &key,
            &value,
            ErrorCode::Duplicate,
            "appears twice in one object",
        )),
        (Err(e), at) => {
            let key = match at {
                Some(Fault::Syntax(key)) => key,
                _ => String::new(),
            };
            Err(err(
                "message",
                &key,
                &Value::String(e.to_string()),
                ErrorCode::Json,
                "(the text is not JSON; numbers are finite)",
            ))
        }
    }
}

/// Where reading the text failed first: a key given twice (with its second value), or the key
/// whose value is not JSON.
enum Fault {
    Duplicate(String, Value),
    Syntax(String),
}

/// Builds a `Value` like serde_json's own, recording the innermost fault.
struct Strict<'a>(&'a RefCell<Option<Fault>>);

impl<'de> DeserializeSeed<'de> for Strict<'_> {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Strict<'_> {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }

    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::Number(v.into()))
    }

    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::Number(v.into()))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Value, E> {
        Number::from_f64(v)
            .map(Value::Number)
            .ok_or_else(|| E::custom("a number that is not finite"))
    }

    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }

    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut out = Vec::new();
        while let Some(v) = seq.next_element_seed(Strict(self.0))? {
            out.push(v);
        }
        Ok(Value::Array(out))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            let value = match map.next_value_seed(Strict(self.0)) {
                Ok(value) => value,
                Err(e) => {
                    self.0.borrow_mut().get_or_insert(Fault::Syntax(key));
                    return Err(e);
                }
            };
            if out.contains_key(&key) {
                self.0
                    .borrow_mut()
                    .get_or_insert(Fault::Duplicate(key, value));
                return Err(de::Error::custom("a key given twice"));
            }
            out.insert(key, value);
        }
        Ok(Value::Object(out))
    }
}
