//! Declared outputs: which reduction kinds there are, the fields each
//! takes, and the checks of a declaration as a study file or a program
//! gives it (`{ kind = "range", channel = "rocker.phi" }`), with messages
//! naming the output and the field at fault.

use crate::reduce::Reduction;

/// Each reduction kind, the fields it needs and the fields it may take.
pub const KINDS: &[(&str, &[&str], &[&str])] = &[
    ("max_abs", &["channel"], &[]),
    ("max", &["channel"], &[]),
    ("min", &["channel"], &[]),
    ("range", &["channel"], &[]),
    ("at", &["channel", "time"], &[]),
    ("least_transmission_angle", &["bodies"], &[]),
    ("max_pressure_angle", &["joint"], &[]),
    ("peak_effort", &["driver"], &[]),
    ("first_lift_off", &[], &["joint"]),
];

/// A field's value in a declaration, as a file or a program gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Text(String),
    Number(f64),
    Flag(bool),
    List(Vec<Value>),
    /// Anything else, as the caller shows it.
    Other(String),
}

impl Value {
    /// The value as a message quotes it: text in single quotes.
    fn shown(&self) -> String {
        match self {
            Value::Text(s) => format!("'{s}'"),
            Value::Number(x) => camlink_core::fmt_num::num(*x),
            Value::Flag(b) => if *b { "True" } else { "False" }.to_string(),
            Value::List(items) => {
                let items: Vec<String> = items.iter().map(Value::shown).collect();
                format!("[{}]", items.join(", "))
            }
            Value::Other(s) => s.clone(),
        }
    }

    fn text(&self) -> Option<&str> {
        match self {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }
}

/// The declaration `spec` (its fields, `kind` among them) of the output
/// at `field` (`outputs.swing`), checked: a known kind, only the fields of
/// that kind, those it needs, names as text, a finite time in seconds and
/// two body names. The error reads "`field`.`key`: what is wrong".
pub fn declared(field: &str, spec: &[(String, Value)]) -> Result<Reduction, String> {
    let get = |key: &str| spec.iter().find(|(k, _)| k == key).map(|(_, v)| v);
    let kind_value = get("kind");
    let Some(&(kind, needed, optional)) = KINDS
        .iter()
        .find(|(k, _, _)| Some(*k) == kind_value.and_then(Value::text))
    else {
        let names: Vec<&str> = KINDS.iter().map(|(k, _, _)| *k).collect();
        let found = kind_value.map_or("None".to_string(), Value::shown);
        return Err(format!(
            "{field}.kind: unknown output kind {found} (expected one of {})",
            names.join(", ")
        ));
    };
    for (key, _) in spec {
        if key != "kind" && !needed.contains(&key.as_str()) && !optional.contains(&key.as_str()) {
            let mut fields: Vec<&str> = needed.iter().chain(optional).copied().collect();
            fields.sort_unstable();
            return Err(format!(
                "{field}.{key}: not a field of a {kind} output (its fields: {})",
                fields.join(", ")
            ));
        }
    }
    if let Some(key) = needed.iter().find(|k| get(k).is_none()) {
        return Err(format!("{field}: a {kind} output needs `{key}`"));
    }
    // Each field's value, in the order given.
    for (key, value) in spec.iter().filter(|(k, _)| k != "kind") {
        let fits = match key.as_str() {
            "time" => matches!(value, Value::Number(t) if t.is_finite()),
            "bodies" => {
                matches!(value, Value::List(b) if b.len() == 2 && b.iter().all(|b| b.text().is_some()))
            }
            _ => value.text().is_some(),
        };
        if !fits {
            let expected = match key.as_str() {
                "time" => "a time in seconds",
                "bodies" => "two body names",
                _ => "a name (a string)",
            };
            return Err(format!(
                "{field}.{key}: expected {expected}, got {}",
                value.shown()
            ));
        }
    }
    let name = |key: &str| get(key).and_then(Value::text).map(str::to_string);
    let channel = || name("channel").unwrap_or_default();
    Ok(match kind {
        "max_abs" => Reduction::MaxAbs { channel: channel() },
        "max" => Reduction::Max { channel: channel() },
        "min" => Reduction::Min { channel: channel() },
        "range" => Reduction::Range { channel: channel() },
        "at" => Reduction::At {
            channel: channel(),
            time: match get("time") {
                Some(Value::Number(t)) => *t,
                _ => f64::NAN,
            },
        },
        "least_transmission_angle" => {
            let bodies = match get("bodies") {
                Some(Value::List(b)) => [0, 1].map(|k| b[k].text().unwrap_or_default().to_string()),
                _ => Default::default(),
            };
            Reduction::LeastTransmissionAngle { bodies }
        }
        "max_pressure_angle" => Reduction::MaxPressureAngle {
            joint: name("joint").unwrap_or_default(),
        },
        "peak_effort" => Reduction::PeakEffort {
            driver: name("driver").unwrap_or_default(),
        },
        _ => Reduction::FirstLiftOff {
            joint: name("joint"),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(fields: &[(&str, Value)]) -> Vec<(String, Value)> {
        fields
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect()
    }

    fn text(s: &str) -> Value {
        Value::Text(s.into())
    }

    #[test]
    fn every_kind_is_declared_from_its_fields() {
        for &(kind, needed, _) in KINDS {
            let mut fields = vec![("kind", text(kind))];
            for &key in needed {
                fields.push(match key {
                    "time" => (key, Value::Number(0.5)),
                    "bodies" => (key, Value::List(vec![text("a"), text("b")])),
                    _ => (key, text("x.y")),
                });
            }
            let r = declared("outputs.o", &spec(&fields)).unwrap();
            // The same declaration as the batch runner reads it.
            let json: serde_json::Map<String, serde_json::Value> = fields
                .iter()
                .map(|(k, v)| {
                    let v = match v {
                        Value::Text(s) => serde_json::json!(s),
                        Value::Number(x) => serde_json::json!(x),
                        Value::List(_) => serde_json::json!(["a", "b"]),
                        _ => unreachable!(),
                    };
                    (k.to_string(), v)
                })
                .collect();
            let text = serde_json::Value::Object(json).to_string();
            assert_eq!(r, Reduction::from_json("o", &text).unwrap(), "{kind}");
        }
    }

    #[test]
    fn errors_name_the_output_and_the_field() {
        let e = |fields: &[(&str, Value)]| declared("outputs.swing", &spec(fields)).unwrap_err();
        assert!(e(&[("kind", text("rnage"))]).starts_with(
            "outputs.swing.kind: unknown output kind 'rnage' (expected one of max_abs, "
        ));
        assert!(e(&[]).starts_with("outputs.swing.kind: unknown output kind None"));
        assert_eq!(
            e(&[("kind", text("range")), ("chanel", text("a.phi"))]),
            "outputs.swing.chanel: not a field of a range output (its fields: channel)"
        );
        assert_eq!(
            e(&[("kind", text("at")), ("channel", text("a.phi"))]),
            "outputs.swing: a at output needs `time`"
        );
        assert_eq!(
            e(&[("kind", text("range")), ("channel", Value::Number(3.0))]),
            "outputs.swing.channel: expected a name (a string), got 3"
        );
        assert_eq!(
            e(&[
                ("kind", text("at")),
                ("channel", text("a.phi")),
                ("time", Value::Flag(true))
            ]),
            "outputs.swing.time: expected a time in seconds, got True"
        );
        assert_eq!(
            e(&[
                ("kind", text("least_transmission_angle")),
                ("bodies", Value::List(vec![text("a")]))
            ]),
            "outputs.swing.bodies: expected two body names, got ['a']"
        );
        let lift = declared("o", &spec(&[("kind", text("first_lift_off"))])).unwrap();
        assert_eq!(lift, Reduction::FirstLiftOff { joint: None });
    }
}
