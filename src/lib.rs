//! dpd
