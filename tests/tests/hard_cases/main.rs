//! Named hard cases (issue 20), one module per area. Each case is a `#[test]` whose doc
//! line says what makes it hard and what it asserts; each asserts a bound (a finite state,
//! a residual, stretch or penetration bound, a typed error), never only "did not panic".

mod book;
