//! camlink's benchmarks are in `benches/` (`cargo bench -p camlink-bench`); this library is empty.
