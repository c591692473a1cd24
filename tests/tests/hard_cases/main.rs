//! The named hard cases of issue 20, one module per area. Each case says in its doc line
//! what makes it hard and what it asserts; each asserts a bound (a finite state, a
//! residual, a typed error with its place, the previous state kept on refusal), never
//! only that nothing panicked. A crash the fuzzers (`fuzz/`) find becomes a case here.

mod book;
mod cli;
mod gestures;
mod kernels;
mod pages;
mod solvers;
mod tearing;
