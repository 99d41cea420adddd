// Reads the shared JSON-protocol vectors and runs every case of one protocol through its
// generated Rust bindings (imported as `bindings` by the including file): the case's own
// message, the receiver's reader, the whole-protocol reader, the serde path, and the round trip
// of valid messages.
//
// `RUNNER VECTORS` prints one JSON result per case (for tests/targets/json_bindings/); `RUNNER --check VECTORS`
// compares them with the vectors' expectations itself and ends with `N passed, N failed`;
// `RUNNER --text FILE` reads each line of FILE as JSON text (Message::from_json_str).

use bindings::{Message, Party};
use serde_json::{json, Value};
use std::process::ExitCode;

/// JSON equality where numbers compare by value (0 and 0.0 are the same number).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_i64(), y.as_i64(), x.as_u64(), y.as_u64()) {
            (Some(p), Some(q), _, _) => p == q,
            (_, _, Some(p), Some(q)) => p == q,
            _ => x.as_f64() == y.as_f64(),
        },
        (Value::Array(x), Value::Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same(p, q)),
        (Value::Object(x), Value::Object(y)) => x.len() == y.len() && x.iter().all(|(k, p)| y.get(k).is_some_and(|q| same(p, q))),
        _ => a == b,
    }
}

fn run(case: &Value) -> Value {
    let v = &case["json"];
    let name = case["message"].as_str().unwrap_or_default();
    let receiver = case["receiver"].as_str().and_then(Party::from_name).unwrap_or_else(|| panic!("unknown receiver {}", case["receiver"]));
    let own = Message::from_value_named(name, v).unwrap_or_else(|| panic!("unknown message {name}"));
    let mut result = json!({"id": case["id"], "protocol": bindings::PROTOCOL});
    match own {
        Ok(m) => {
            let back = m.to_value();
            let via_serde = serde_json::to_value(&m).unwrap_or(Value::Null);
            let parsed: Option<Message> = serde_json::from_value(v.clone()).ok();
            result["valid"] = json!(true);
            result["roundtrip"] = json!(same(&back, v) && same(&via_serde, v));
            result["serde"] = json!(parsed.as_ref() == Some(&m) || parsed.is_some_and(|p| p.name() != m.name()));
            result["json_out"] = back;
        }
        Err(e) => {
            result["valid"] = json!(false);
            result["field"] = json!(e.field);
            result["rule"] = json!(e.code.as_str());
            result["error"] = json!(e.to_string());
        }
    }
    // the text reader agrees with the value reader on the case's text
    let text = Message::from_json_str(&v.to_string());
    result["text"] = json!(match (&text, Message::from_value(v)) {
        (Ok(a), Ok(b)) => a == &b,
        (Err(a), Err(b)) => a == &b,
        _ => false,
    });
    result["as_received"] = json!(Message::from_value_to(v, receiver).ok().map(|m| m.name()));
    result["as_any"] = json!(Message::from_value(v).ok().map(|m| m.name()));
    result
}

fn mismatch(case: &Value, got: &Value) -> Option<String> {
    let expected_valid = case["valid"].as_bool().unwrap_or(false);
    let mut why = Vec::new();
    if got["valid"] != case["valid"] {
        why.push(format!("valid {} (expected {})", got["valid"], case["valid"]));
    } else if expected_valid {
        if got["roundtrip"] != json!(true) {
            why.push(format!("round trip gives {}", got["json_out"]));
        }
        if got["serde"] != json!(true) {
            why.push("serde deserialisation disagrees".to_owned());
        }
    } else if got["field"] != case["field"] || got["rule"] != case["rule"] {
        why.push(format!("fault {}/{} (expected {}/{})", got["field"], got["rule"], case["field"], case["rule"]));
    }
    if got["text"] != json!(true) {
        why.push("the text reader disagrees with the value reader".to_owned());
    }
    for key in ["as_received", "as_any"] {
        if got[key] != case[key] {
            why.push(format!("{key} {} (expected {})", got[key], case[key]));
        }
    }
    (!why.is_empty()).then(|| format!("{}: {}", case["id"], why.join("; ")))
}

/// `--text FILE`: each line a JSON text, read by `Message::from_json_str`; one result per line.
fn texts(path: &str) -> ExitCode {
    let Ok(all) = std::fs::read_to_string(path) else {
        eprintln!("json-vectors-runner: cannot read {path}");
        return ExitCode::from(2);
    };
    let results: Vec<Value> = all
        .lines()
        .map(|line| match Message::from_json_str(line) {
            Ok(m) => json!({"valid": true, "message": m.name()}),
            Err(e) => json!({"valid": false, "field": e.field, "rule": e.code.as_str()}),
        })
        .collect();
    println!("{}", Value::Array(results));
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, path] = args.as_slice() {
        if flag == "--text" {
            return texts(path);
        }
    }
    let check = args.iter().any(|a| a == "--check");
    let Some(path) = args.iter().find(|a| !a.starts_with("--")) else {
        eprintln!("usage: json-vectors-runner [--check] VECTORS_JSON");
        return ExitCode::from(2);
    };
    let doc: Value = match std::fs::read_to_string(path).map_err(|e| e.to_string()).and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string())) {
        Ok(doc) => doc,
        Err(e) => {
            eprintln!("json-vectors-runner: {path}: {e}");
            return ExitCode::from(2);
        }
    };
    let cases: Vec<&Value> = doc["protocols"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|p| p["protocol"] == bindings::PROTOCOL)
        .flat_map(|p| p["cases"].as_array().into_iter().flatten())
        .collect();
    let results: Vec<Value> = cases.iter().map(|c| run(c)).collect();
    if !check {
        println!("{}", Value::Array(results));
        return ExitCode::SUCCESS;
    }
    let failures: Vec<String> = cases.iter().zip(&results).filter_map(|(c, r)| mismatch(c, r)).collect();
    for f in &failures {
        eprintln!("MISMATCH {f}");
    }
    println!("rust json vectors: {} cases", cases.len());
    println!("{} passed, {} failed", cases.len() - failures.len(), failures.len());
    if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
