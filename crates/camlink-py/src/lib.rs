//! Python bindings for camlink.
