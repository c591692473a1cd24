//! The named hard-case suite of issue 20: one module per area, each case a test whose name
//! says the case, with a doc line saying what makes it hard and what bound it asserts (a
//! finite state, a residual bound, a typed error, or the previous state kept on refusal).
//! A crash the fuzzers (`fuzz/`) find becomes a case here.

mod kernels;
mod solvers;
