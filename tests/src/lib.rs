//! Test support shared by Folio's integration tests.
