//! camlink-cam's integration tests, one binary (`autotests = false`).

mod export;
mod load;
mod report;
mod timing;
