//! The effects a book simulates (issue 6: "simulate only the effects a scene calls for").
//!
//! An effect that is off contributes no term, no KKT row and no work: its terms are never
//! built (so the symbolic analysis never sees them), and the step skips the work it needs
//! (collision detection, history snapshots). [`TermCensus`] counts what was built, and
//! [`crate::BookStepReport`] what each step did, so that both can be checked.
//!
//! The hard cover is the sixth effect a scene can name; it is part of the book's geometry
//! ([`crate::BookParams::cover`]), which decides whether the cover nodes exist.

use super::error::BookError;
use folio_kernels::{Constraint, Potential, Real};
use folio_solvers::model::{ConstraintSet, PotentialSet, TermVisitor};

/// Which effects the book simulates. [`Effects::default`] is all of them.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Effects {
    /// Gravity on blocks, cover and page (seed `000_…` eq. 12). Off: no gravity term.
    pub gravity: bool,
    /// The binding glue between the two blocks (eq. 11). Off: no glue term. Needs
    /// `blocks`.
    pub glue: bool,
    /// Collision handling (Sec. 3.4) and the contact springs that carry its force into the
    /// next step. Off: no contact term, no collision test; a page then passes through the
    /// blocks and blocks through the table.
    pub collisions: bool,
    /// The page blocks as simulated midline curves (Sec. 3.1, eq. 6, 8, 10). Off: the
    /// blocks (and the cover) keep their rest layout as fixed geometry, every block node is
    /// eliminated, and a book at rest simulates nothing at all.
    pub blocks: bool,
    /// Finger-bookmarking (Sec. 4.1, Fig. 11): the held page's history of snapshots. Off:
    /// no snapshot is taken and [`crate::Book::bookmark`] answers `Disabled`.
    pub bookmarking: bool,
}

impl Default for Effects {
    fn default() -> Self {
        Self::ALL
    }
}

/// Effects a Cargo feature can compile out: (scene name, feature, compiled in).
const FEATURES: [(&str, &str, bool); 2] = [
    ("collisions", "collisions", cfg!(feature = "collisions")),
    ("bookmarking", "bookmarking", cfg!(feature = "bookmarking")),
];

impl Effects {
    /// Every effect compiled in (the features `collisions` and `bookmarking` compile two
    /// of them out).
    pub const ALL: Self = Self {
        gravity: true,
        glue: true,
        collisions: cfg!(feature = "collisions"),
        blocks: true,
        bookmarking: cfg!(feature = "bookmarking"),
    };

    /// None: the active page alone, hanging from a fixed binding.
    pub const NONE: Self = Self {
        gravity: false,
        glue: false,
        collisions: false,
        blocks: false,
        bookmarking: false,
    };

    /// The scene names of the effects that are on, in a fixed order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        [
            ("gravity", self.gravity),
            ("glue", self.glue),
            ("collisions", self.collisions),
            ("blocks", self.blocks),
            ("bookmarking", self.bookmarking),
        ]
        .into_iter()
        .filter_map(|(name, on)| on.then_some(name))
    }

    /// Switches the effect with scene name `name` on; `false` for an unknown name (`cover`
    /// is not one of these: see the module docs).
    pub fn enable(&mut self, name: &str) -> bool {
        let flag = match name {
            "gravity" => &mut self.gravity,
            "glue" => &mut self.glue,
            "collisions" => &mut self.collisions,
            "blocks" => &mut self.blocks,
            "bookmarking" => &mut self.bookmarking,
            _ => return false,
        };
        *flag = true;
        true
    }

    /// Collision handling is on and compiled in. Every guard of collision work tests this:
    /// without the feature it is the constant `false`, and the optimizer drops the work.
    #[inline]
    #[must_use]
    pub fn collides(&self) -> bool {
        cfg!(feature = "collisions") && self.collisions
    }

    /// Finger-bookmarking is on and compiled in (as [`Effects::collides`]).
    #[inline]
    #[must_use]
    pub fn bookmarks(&self) -> bool {
        cfg!(feature = "bookmarking") && self.bookmarking
    }

    /// Checks that every effect that is on has what it needs.
    ///
    /// # Errors
    /// [`BookError::InvalidSetting`] for the glue without the blocks it joins, or an effect
    /// whose Cargo feature is off.
    pub fn validate(&self) -> Result<(), BookError> {
        let on = [self.collisions, self.bookmarking];
        for ((name, _, compiled), on) in FEATURES.into_iter().zip(on) {
            if on && !compiled {
                return Err(BookError::InvalidSetting {
                    field: name,
                    requirement: "off: its Cargo feature of folio-solvers is not enabled",
                });
            }
        }
        if self.glue && !self.blocks {
            return Err(BookError::InvalidSetting {
                field: "effects.glue",
                requirement: "off without effects.blocks (the glue joins the two blocks)",
            });
        }
        Ok(())
    }
}

/// How many terms of each kind a view of the book visits (the same every step: the
/// pattern never changes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TermCensus {
    /// Potential terms (kernel instances).
    pub potentials: usize,
    /// Constraint terms.
    pub constraints: usize,
    /// Constraint rows.
    pub rows: usize,
}

impl<T: Real> TermVisitor<T> for TermCensus {
    fn potentials<P: Potential<T, N>, const N: usize>(&mut self, set: &PotentialSet<T, P, N>) {
        self.potentials += set.terms().len();
    }
    fn constraints<C: Constraint<T, R, N>, const R: usize, const N: usize>(
        &mut self,
        set: &ConstraintSet<C, N>,
    ) {
        self.constraints += set.terms().len();
        self.rows += R * set.terms().len();
    }
}
