//! camlink's benchmarks are in `benches/` (`cargo bench -p camlink-bench
//! [--bench NAME]`); this library holds what they share.

pub mod shared;
