//! Typed reads from one table of a design file, each failure naming its
//! field (`segments[1].span_deg`); a key that no read asked for is refused
//! with the nearest known key.

use std::collections::BTreeSet;

use camlink_core::fmt_num::num;
use camlink_core::names::did_you_mean;
use toml::{Table as Map, Value};

use crate::limits::MAX_LENGTH;

/// What is wrong, and at which field (`None`: the file as a whole).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Fail {
    pub field: Option<String>,
    pub message: String,
}

pub(crate) type R<T> = Result<T, Fail>;

/// A failure at `field`.
pub(crate) fn fail<T>(field: impl Into<String>, message: impl Into<String>) -> R<T> {
    Err(Fail {
        field: Some(field.into()),
        message: message.into(),
    })
}

/// The bounds of a number: positive, and at most `most` in size (`unit`
/// names its unit in the message, with its leading space).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Num {
    pub positive: bool,
    pub most: Option<(f64, &'static str)>,
}

impl Num {
    /// Any finite number.
    pub(crate) const ANY: Num = Num {
        positive: false,
        most: None,
    };
    /// A positive number.
    pub(crate) const POSITIVE: Num = Num {
        positive: true,
        most: None,
    };
    /// A length (m), at most [`MAX_LENGTH`] in size.
    pub(crate) const LENGTH: Num = Num::ANY.most(MAX_LENGTH, " m");
    /// A positive length (m).
    pub(crate) const POSITIVE_LENGTH: Num = Num::POSITIVE.most(MAX_LENGTH, " m");

    /// These bounds, and at most `most` (`unit`) in size.
    pub(crate) const fn most(self, most: f64, unit: &'static str) -> Num {
        Num {
            most: Some((most, unit)),
            ..self
        }
    }
}

/// One table of the file and the keys read from it.
pub(crate) struct Table<'a> {
    /// Its path (`segments[0]`); empty for the top level.
    pub path: String,
    data: Option<&'a Map>,
    used: BTreeSet<String>,
}

impl<'a> Table<'a> {
    /// The top level of the file.
    pub(crate) fn root(doc: &'a Map) -> Self {
        Table {
            path: String::new(),
            data: Some(doc),
            used: BTreeSet::new(),
        }
    }

    /// The table at `path`; an empty one when the file gives none.
    pub(crate) fn new(path: impl Into<String>, value: Option<&'a Value>) -> R<Self> {
        let path = path.into();
        let data = match value {
            None => None,
            Some(Value::Table(t)) => Some(t),
            Some(_) => return fail(path, "must be a table"),
        };
        Ok(Table {
            path,
            data,
            used: BTreeSet::new(),
        })
    }

    /// The sub-table `key` of this one (marked as read).
    pub(crate) fn table(&mut self, key: &str) -> R<Table<'a>> {
        self.mark(key);
        Table::new(self.field(key), self.get(key))
    }

    /// The path of `key` in this table.
    pub(crate) fn field(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    /// A failure at `key`.
    pub(crate) fn fail<T>(&self, key: &str, message: impl Into<String>) -> R<T> {
        fail(self.field(key), message)
    }

    /// The value at `key`, not marked as read.
    pub(crate) fn get(&self, key: &str) -> Option<&'a Value> {
        self.data.and_then(|d| d.get(key))
    }

    pub(crate) fn has(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// The keys the file gives here.
    pub(crate) fn keys(&self) -> impl Iterator<Item = &'a String> {
        self.data.into_iter().flat_map(|d| d.keys())
    }

    /// Marks `key` as read.
    pub(crate) fn mark(&mut self, key: &str) {
        self.used.insert(key.to_string());
    }

    /// The number at `key` (or `default`), within `bounds`.
    pub(crate) fn number(&mut self, key: &str, default: Option<f64>, bounds: Num) -> R<f64> {
        self.mark(key);
        let v = match self.get(key) {
            None => match default {
                Some(d) => d,
                None => return self.fail(key, "is required"),
            },
            Some(Value::Integer(i)) => *i as f64,
            Some(Value::Float(f)) if f.is_finite() => *f,
            Some(other) => return self.fail(key, format!("must be a number, got {}", repr(other))),
        };
        if bounds.positive && v <= 0.0 {
            return self.fail(key, format!("must be positive, got {}", num(v)));
        }
        if let Some((most, unit)) = bounds.most {
            if v.abs() > most {
                return self.fail(
                    key,
                    format!(
                        "must be at most {}{unit} in size, got {}",
                        num(most),
                        num(v)
                    ),
                );
            }
        }
        Ok(v)
    }

    /// The number at `key` within `bounds`, or `None` when not given.
    pub(crate) fn optional(&mut self, key: &str, bounds: Num) -> R<Option<f64>> {
        if !self.has(key) {
            self.mark(key);
            return Ok(None);
        }
        self.number(key, None, bounds).map(Some)
    }

    /// The text at `key` (or `default`), one of `choices` when they are
    /// given.
    pub(crate) fn text(&mut self, key: &str, default: Option<&str>, choices: &[&str]) -> R<String> {
        self.mark(key);
        let v = match (self.get(key), default) {
            (Some(Value::String(s)), _) => s.clone(),
            (None, Some(d)) => d.to_string(),
            (None, None) => return self.fail(key, "is required"),
            (Some(other), _) => {
                return self.fail(key, format!("must be a string, got {}", repr(other)))
            }
        };
        if !choices.is_empty() && !choices.contains(&v.as_str()) {
            return self.fail(
                key,
                format!(
                    "'{v}' is not one of {}{}",
                    choices.join(", "),
                    did_you_mean(&v, choices.iter().copied())
                ),
            );
        }
        Ok(v)
    }

    /// The value of the choice named at `key` (or of the one named
    /// `default`): one of the names of `choices`.
    pub(crate) fn choice<T: Copy>(
        &mut self,
        key: &str,
        default: Option<&str>,
        choices: &[(&str, T)],
    ) -> R<T> {
        let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
        let name = self.text(key, default, &names)?;
        match choices.iter().find(|(n, _)| *n == name) {
            Some((_, v)) => Ok(*v),
            None => self.fail(key, format!("'{name}' is not one of {}", names.join(", "))),
        }
    }

    /// The true or false at `key`, or `default`.
    pub(crate) fn flag(&mut self, key: &str, default: bool) -> R<bool> {
        self.mark(key);
        match self.get(key) {
            None => Ok(default),
            Some(Value::Boolean(b)) => Ok(*b),
            Some(other) => self.fail(key, format!("must be true or false, got {}", repr(other))),
        }
    }

    /// Refuses a key that no read asked for, naming the nearest known one.
    pub(crate) fn finish(self) -> R<()> {
        let mut extra: Vec<&String> = self.keys().filter(|k| !self.used.contains(*k)).collect();
        extra.sort();
        let Some(first) = extra.first().copied() else {
            return Ok(());
        };
        let known: Vec<&str> = self
            .used
            .iter()
            .map(String::as_str)
            .filter(|k| !k.starts_with('_'))
            .collect();
        self.fail(
            first,
            format!(
                "unknown key{}; the keys here are {}",
                did_you_mean(first, known.iter().copied()),
                known.join(", ")
            ),
        )
    }
}

/// A value as a message quotes it: text in single quotes, numbers as
/// [`num`] writes them, arrays and tables as TOML writes them inline.
pub(crate) fn repr(v: &Value) -> String {
    match v {
        Value::String(s) => format!("'{s}'"),
        Value::Integer(i) => i.to_string(),
        Value::Float(f) => num(*f),
        Value::Boolean(b) => b.to_string(),
        Value::Datetime(d) => d.to_string(),
        Value::Array(a) => format!("[{}]", a.iter().map(repr).collect::<Vec<_>>().join(", ")),
        Value::Table(t) => format!(
            "{{ {} }}",
            t.iter()
                .map(|(k, v)| format!("{k} = {}", repr(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}
