//! The named hard cases of issue 20, one module per area. Each case says in its doc line
//! what makes it hard and what it asserts; each asserts a bound (a finite state, a
//! residual, a typed error with its place, the previous state kept), never only that
//! nothing panicked.

mod book;
mod cli;
mod gestures;
mod pages;
mod tearing;
