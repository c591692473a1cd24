//! Shared inputs for Folio's criterion benches (see `benches/`).
