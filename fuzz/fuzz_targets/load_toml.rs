//! cargo-fuzz target: see [`camlink_fuzz_targets::load_toml`] and fuzz/README.md.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| camlink_fuzz_targets::load_toml(data));
