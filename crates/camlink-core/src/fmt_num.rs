//! Numbers in messages: camlink-expr's formatter ([`camlink_expr::fmt_num`]),
//! the project's one, so that every crate writes numbers alike.

pub use camlink_expr::fmt_num::{apart, count, num, num_digits, DIGITS};
