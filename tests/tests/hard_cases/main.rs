//! The named hard-case suite (issue 20): one module per area, each case a test whose doc
//! line says what makes it hard and what bound it asserts.

mod pages;
mod tearing;
