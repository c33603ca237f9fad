//! Integration crate: see examples/, tests/ and benches/.
