//! The named hard-case suite (issue 20): one module per area, each case a test whose name
//! says the case, with a doc line saying what makes it hard and what bound it asserts.

mod gestures;
