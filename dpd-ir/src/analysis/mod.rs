//! Order analysis of a flattened scheme (algorithms.md section 4).
