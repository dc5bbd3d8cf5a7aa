//! The committed JSON Schema equals what the serde structs generate.
//!
//! After changing the file format, regenerate it with
//! `CAMLINK_BLESS=1 cargo test -p camlink-model --test integration schema::`.

use std::path::Path;

#[test]
fn committed_schema_is_current() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../schema/camlink-model.schema.json");
    let generated = serde_json::to_string_pretty(&camlink_model::json_schema()).unwrap() + "\n";
    if std::env::var_os("CAMLINK_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "schema/camlink-model.schema.json is out of date; run \
         `CAMLINK_BLESS=1 cargo test -p camlink-model --test integration schema::`"
    );
}

#[test]
fn schema_describes_the_format() {
    let s = camlink_model::json_schema();
    let props = &s["properties"];
    for key in [
        "model",
        "parameters",
        "ground",
        "bodies",
        "joints",
        "drivers",
        "analysis",
    ] {
        assert!(props.get(key).is_some(), "no {key} in the schema");
    }
    assert_eq!(s["additionalProperties"], serde_json::Value::Bool(false));
    let text = s.to_string();
    for ty in [
        "revolute_translational",
        "rack_pinion",
        "translational_travel",
        "revolute_angle",
    ] {
        assert!(text.contains(ty), "{ty} missing from the schema");
    }
}
