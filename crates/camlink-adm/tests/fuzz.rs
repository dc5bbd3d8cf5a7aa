//! Mutated simEngine2D models never panic the `.adm` reader, and every one
//! that loads converts to a TOML file that loads too. The mutations are
//! those of the model files' fuzz tests (`camlink_testkit::mutate`).

use std::path::Path;

use camlink_adm::describe_str;
use camlink_model::{load_str, Format};
use camlink_testkit::mutate::{mutate, Rng};

#[test]
fn mutated_adm_never_panics_and_converts_when_it_loads() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = [
        dir.join("../../examples/simengine2d/slider_crank.adm"),
        dir.join("tests/adm/rack_pinion.adm"),
        dir.join("tests/adm/forces.adm"),
    ];
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut loaded = 0;
    for path in files {
        let base = std::fs::read_to_string(path).unwrap();
        for _ in 0..500 {
            let text = mutate(&mut rng, &base);
            let Ok(described) = describe_str(&text, "m.adm", None) else {
                continue;
            };
            if described.resolve().is_err() {
                continue;
            }
            loaded += 1;
            let toml = described.write(Format::Toml).unwrap();
            if let Err(e) = load_str(&toml, Format::Toml, "m.toml") {
                panic!("{e}\nfrom the .adm\n{text}\nconverted to\n{toml}");
            }
        }
    }
    assert!(loaded > 0);
}
