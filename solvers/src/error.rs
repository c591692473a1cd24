//! Typed errors of the solver's setup: settings validation, the analysis of a model, and a
//! numeric factor paired with the wrong analysis.
//! A time step itself never returns an error; it reports a [`crate::StepStatus`].

use core::fmt;

use folio_kernels::SettingError;

/// Why settings were rejected or a model could not be analysed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SolverError {
    /// A setting is NaN, infinite or outside its documented range (the path is the field's
    /// in [`crate::Settings`]).
    InvalidSetting(SettingError),
    /// A term names a node the model does not have.
    NodeOutOfRange {
        /// Index of the term family in the model's visiting order.
        family: usize,
        /// Index of the term within its family.
        term: usize,
        /// The offending node index.
        node: u32,
        /// How many nodes the model has.
        node_count: usize,
    },
    /// A node with at least one free coordinate has a mass that is not positive and finite.
    NonPositiveMass {
        /// The node.
        node: usize,
    },
    /// The state's length differs from the model's node count.
    StateLength {
        /// The model's node count.
        expected: usize,
        /// Positions in the state.
        positions: usize,
        /// Velocities in the state.
        velocities: usize,
    },
    /// The model visited its term families in another order or with other sizes than at
    /// analysis without bumping its topology version.
    ModelChanged,
    /// The model has more unknowns or matrix entries than 32-bit indices address.
    TooLarge,
    /// A numeric factor ([`crate::ldlt::Ldlt`]) was handed a symbolic analysis other than
    /// the one it was made for (another pattern or ordering, even of the same order).
    SymbolicMismatch {
        /// Order of the analysis the factor was made for.
        factor_order: usize,
        /// Order of the analysis it was handed.
        symbolic_order: usize,
    },
}

impl fmt::Display for SolverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidSetting(e) => write!(f, "solver setting {e}"),
            Self::NodeOutOfRange {
                family,
                term,
                node,
                node_count,
            } => write!(
                f,
                "term {term} of family {family} names node {node}, but the model has {node_count} nodes"
            ),
            Self::NonPositiveMass { node } => {
                write!(
                    f,
                    "node {node} has free coordinates but no positive finite mass"
                )
            }
            Self::StateLength {
                expected,
                positions,
                velocities,
            } => write!(
                f,
                "the state has {positions} positions and {velocities} velocities, the model {expected} nodes"
            ),
            Self::ModelChanged => write!(
                f,
                "the model's term families changed without a new topology version"
            ),
            Self::TooLarge => write!(f, "the model exceeds 32-bit sparse indices"),
            Self::SymbolicMismatch {
                factor_order,
                symbolic_order,
            } => write!(
                f,
                "a numeric factor made for another symbolic analysis (order {factor_order}) was handed one of order {symbolic_order}"
            ),
        }
    }
}

impl core::error::Error for SolverError {}

impl From<SettingError> for SolverError {
    fn from(e: SettingError) -> Self {
        Self::InvalidSetting(e)
    }
}
