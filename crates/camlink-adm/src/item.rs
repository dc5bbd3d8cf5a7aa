//! An ordered tree of values: camlink's model description as the `.adm`
//! reader writes it, serialised to TOML or JSON with keys in a readable
//! order, and read back into [`camlink_model::file::ModelFile`].

use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};

/// A value of a model description; tables keep their keys in order.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Num(f64),
    Str(String),
    Bool(bool),
    List(Vec<Item>),
    Table(Vec<(String, Item)>),
}

impl Item {
    /// `[x, y]`.
    pub fn pair(v: [f64; 2]) -> Item {
        Item::List(vec![Item::Num(v[0]), Item::Num(v[1])])
    }

    /// A table from `(key, value)` pairs.
    pub fn table<const N: usize>(entries: [(&str, Item); N]) -> Item {
        Item::Table(
            entries
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
        )
    }

    /// Appends `key = value` to a table.
    pub fn push(&mut self, key: &str, value: Item) {
        if let Item::Table(t) = self {
            t.push((key.to_string(), value));
        }
    }
}

impl Serialize for Item {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Item::Num(v) => s.serialize_f64(*v),
            Item::Str(v) => s.serialize_str(v),
            Item::Bool(v) => s.serialize_bool(*v),
            Item::List(items) => {
                let mut seq = s.serialize_seq(Some(items.len()))?;
                for i in items {
                    seq.serialize_element(i)?;
                }
                seq.end()
            }
            Item::Table(entries) => {
                let mut map = s.serialize_map(Some(entries.len()))?;
                for (k, v) in entries {
                    map.serialize_entry(k, v)?;
                }
                map.end()
            }
        }
    }
}
