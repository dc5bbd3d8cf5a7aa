//! cargo-fuzz target: see [`camlink_fuzz_targets::load_json`] and fuzz/README.md.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| camlink_fuzz_targets::load_json(data));
