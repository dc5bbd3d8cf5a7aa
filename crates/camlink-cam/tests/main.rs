//! camlink-cam's integration tests, one binary (`autotests = false`).

mod load;
