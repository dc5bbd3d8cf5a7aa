//! Issue 32: the `[machine]` table of model files and the machine analysis
//! of `examples/machine_slider_crank.toml`.

use std::path::Path;

use camlink_model::{load_path, load_str, Format};

fn example() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/machine_slider_crank.toml");
    std::fs::read_to_string(p).unwrap()
}

fn error_of(edit: (&str, &str)) -> String {
    let text = example().replace(edit.0, edit.1);
    assert_ne!(text, example(), "the edit {edit:?} changes the file");
    load_str(&text, Format::Toml, "m.toml")
        .unwrap_err()
        .to_string()
}

#[test]
fn issue32_machine_example_sizes_everything() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/machine_slider_crank.toml");
    let loaded = load_path(&p).unwrap();
    let spec = loaded.machine.clone().unwrap();
    assert_eq!(spec.driver, "motor");
    assert!((spec.speed - 2.0 * std::f64::consts::PI * 5.0).abs() < 1e-12);
    let r = camlink_core::machine::analyse(&loaded.model, &spec).unwrap();
    let f = r.flywheel.as_ref().unwrap();
    assert!(r.shaking.peak_dynamic > 100.0);
    assert!(r.balanced_peak_force.unwrap() <= 1e-9 * r.shaking.peak_dynamic);
    assert!(
        f.cs_run <= f.cs,
        "the forward run keeps the band: {} > {}",
        f.cs_run,
        f.cs
    );
    assert_eq!(r.checks.len(), 5, "{:?}", r.checks);
}

#[test]
fn issue32_flywheel_band_of_zero() {
    let e = error_of(("speed_band = 0.02 ", "speed_band = 0 "));
    assert!(
        e.contains("m.toml:") && e.contains("machine.speed_band"),
        "{e}"
    );
    assert!(e.contains("band of zero"), "{e}");
}

#[test]
fn issue32_motor_curve_short_of_the_speed() {
    let e = error_of(("[60, 45], [85, 40], [95, 0]]", "[60, 45], [80, 0]]"));
    assert!(e.contains("machine.motor.curve"), "{e}");
    assert!(e.contains("never reaches the motor speed"), "{e}");
}

#[test]
fn issue32_machine_table_names_bad_fields() {
    let e = error_of(("driver = \"motor\"\nspeed", "driver = \"motr\"\nspeed"));
    assert!(
        e.contains("machine.driver") && e.contains("did you mean 'motor'"),
        "{e}"
    );
    let e = error_of(("speed = \"w\"", "speed = \"-w\""));
    assert!(e.contains("machine.speed") && e.contains("positive"), "{e}");
    let e = error_of(("gear_ratio = 3 ", "gear_rattio = 3 "));
    assert!(e.contains("gear_rattio"), "{e}");
    let e = error_of(("[60, 45], [85, 40]", "[85, 45], [60, 40]"));
    assert!(
        e.contains("machine.motor.curve[2]") && e.contains("increase"),
        "{e}"
    );
}

/// A joint, driver or body named `shaking` would share the namespace of
/// the shaking channels (a joint's reaction `shaking.fx` is the shaking
/// force's name): refused, naming the field.
#[test]
fn issue32_shaking_is_a_reserved_name() {
    let e = error_of((
        "name = \"B\"\ntype = \"revolute\"",
        "name = \"shaking\"\ntype = \"revolute\"",
    ));
    assert!(e.contains("joints[2].name"), "{e}");
    assert!(
        e.contains("joint name 'shaking' is reserved for the shaking channels shaking.fx, shaking.fy, shaking.moment"),
        "{e}"
    );
    let e = error_of(("\"slider\"", "\"shaking\""));
    assert!(
        e.contains("bodies[2].name") && e.contains("body name 'shaking' is reserved"),
        "{e}"
    );
    let text = example()
        .replace("name = \"motor\"", "name = \"shaking\"")
        .replace("driver = \"motor\"", "driver = \"shaking\"");
    let e = load_str(&text, Format::Toml, "m.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("drivers[0].name") && e.contains("driver name 'shaking' is reserved"),
        "{e}"
    );
}
