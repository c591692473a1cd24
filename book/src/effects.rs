//! The effects a book simulates (issue 6: "simulate only the effects a scene calls for").
//!
//! An effect that is off contributes no term, no KKT row and no work: its terms are never
//! built (so the symbolic analysis never sees them), and the step skips the work it needs
//! (collision detection, history snapshots). [`TermCensus`] counts what was built, and
//! [`crate::BookStepReport`] what each step did, so that both can be checked.
//!
//! The hard cover is the sixth effect a scene can name; it is part of the book's geometry
//! ([`crate::BookParams::cover`]), which decides whether the cover nodes exist.

use folio_kernels::SettingError;
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

    /// Every effect of the DOG book by the name scenes, reports, the C API's docs and the
    /// browser's panel give it, in the order they list them: the five flags of this type
    /// and `cover`, which is the book's geometry (module docs). The one list of the names.
    pub const NAMES: [&'static str; 6] = [
        "gravity",
        "glue",
        "collisions",
        "cover",
        "blocks",
        "bookmarking",
    ];

    /// The flags in the order of [`Effects::NAMES`] (`None` for `cover`).
    fn flags_mut(&mut self) -> [Option<&mut bool>; 6] {
        [
            Some(&mut self.gravity),
            Some(&mut self.glue),
            Some(&mut self.collisions),
            None,
            Some(&mut self.blocks),
            Some(&mut self.bookmarking),
        ]
    }

    /// The names of the effects that are on, in the order of [`Effects::NAMES`] (never
    /// `cover`).
    pub fn names(&self) -> impl Iterator<Item = &'static str> {
        let mut copy = *self;
        let on: [bool; 6] = copy.flags_mut().map(|flag| flag.is_some_and(|on| *on));
        Self::NAMES
            .into_iter()
            .zip(on)
            .filter_map(|(name, on)| on.then_some(name))
    }

    /// Switches the effect named `name` on; `false` for a name that is no flag of this
    /// type (`cover` is the book's geometry: see the module docs).
    pub fn enable(&mut self, name: &str) -> bool {
        let at = Self::NAMES.iter().position(|n| *n == name);
        match at.and_then(|i| self.flags_mut().into_iter().nth(i).flatten()) {
            Some(flag) => {
                *flag = true;
                true
            }
            None => false,
        }
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
    /// The glue without the blocks it joins, or an effect whose Cargo feature is off (the
    /// path is the effect's field).
    pub fn validate(&self) -> Result<(), SettingError> {
        let on = [self.collisions, self.bookmarking];
        for ((name, _, compiled), on) in FEATURES.into_iter().zip(on) {
            if on && !compiled {
                return Err(SettingError::new(
                    name,
                    "off: its Cargo feature of folio-book is not enabled",
                ));
            }
        }
        if self.glue && !self.blocks {
            return Err(SettingError::new(
                "glue",
                "off without blocks (the glue joins the two blocks)",
            ));
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

#[cfg(test)]
mod tests {
    use super::Effects;

    /// Each name switches on its own flag and no other, and reads back as itself; `cover`
    /// and unknown names switch on nothing.
    #[test]
    fn each_name_is_its_own_flag() {
        for name in Effects::NAMES {
            let mut e = Effects::NONE;
            let known = e.enable(name);
            let on: Vec<&str> = e.names().collect();
            if name == "cover" {
                assert!(!known && on.is_empty());
            } else {
                assert!(known, "{name}");
                assert_eq!(on, [name]);
            }
        }
        let mut none = Effects::NONE;
        assert!(!none.enable("tearing"));
        let all: Vec<&str> = Effects {
            collisions: true,
            bookmarking: true,
            ..Effects::ALL
        }
        .names()
        .collect();
        assert_eq!(
            all,
            ["gravity", "glue", "collisions", "blocks", "bookmarking"]
        );
    }
}
