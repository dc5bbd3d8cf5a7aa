//! camlink model files (TOML and JSON).
