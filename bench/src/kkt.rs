//! DOG-shaped KKT systems for the solver benches and the `kkt_report` example, and faer's
//! sparse and dense factorizations of the same matrices as baselines.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, Par, Side};
use folio_solvers::{Kkt, Ordering, Parallelism, Settings, Solver, State};
use folio_tests::models::DogSheet;
use std::process::ExitCode;
use std::time::Instant;

/// The DOG sheet sizes the issue asks for (quads across, quads along the binding).
pub const SIZES: [(usize, usize); 4] = [(11, 8), (16, 12), (22, 16), (32, 24)];

/// Parses a grid `WxH` (quads across, quads along the binding; both at least 1), as in
/// `--grid 22x16`.
///
/// # Errors
/// A message naming the bad text when it is not two positive integers joined by `x`.
pub fn parse_grid(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--grid expects WxH with W, H >= 1 quads (e.g. 22x16), not {text:?}");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: usize = w.trim().parse().map_err(|_| bad())?;
    let h: usize = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(bad());
    }
    Ok((w, h))
}

/// The median wall time of `reps` calls of `f` (after one untimed call), in microseconds.
pub fn median_us(reps: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// An example's exit: success, or `program: error` on stderr and a failure code.
#[must_use]
pub fn exit_code(program: &str, result: Result<(), Box<dyn core::error::Error>>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{program}: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The value after `flag` in `args`, if the flag is there.
///
/// # Errors
/// When the flag is the last argument.
pub fn flag_value<'a>(args: &'a [String], flag: &str) -> Result<Option<&'a str>, String> {
    match args.iter().position(|a| a == flag) {
        None => Ok(None),
        Some(i) => args
            .get(i + 1)
            .map(|v| Some(v.as_str()))
            .ok_or_else(|| format!("{flag} needs a value")),
    }
}

/// A DOG sheet of `quads` (page width 12, rolled on a radius-6 cylinder, the pull at the
/// grabbed node's position), its state, and the first KKT system of a step with its RHS.
pub struct DogKkt {
    /// The model.
    pub sheet: DogSheet<f64>,
    /// The rolled state.
    pub state: State<f64>,
    /// The assembled and analysed KKT system.
    pub kkt: Kkt<f64>,
    /// Its right-hand side.
    pub rhs: Vec<f64>,
    /// The settings it was built with.
    pub settings: Settings<f64>,
}

impl DogKkt {
    /// Builds and analyses the system with `ordering`.
    ///
    /// # Panics
    /// If [`DogKkt::try_new`] fails (a bench fixture of a valid size).
    #[must_use]
    pub fn new(quads: (usize, usize), ordering: Ordering) -> Self {
        Self::try_new(quads, ordering).expect("a valid DOG sheet")
    }

    /// Builds and analyses the system of `quads` (at least 1x1) with `ordering`.
    ///
    /// # Errors
    /// A zero size, or a model the solver cannot linearize, as a message.
    pub fn try_new(quads: (usize, usize), ordering: Ordering) -> Result<Self, String> {
        if quads.0 == 0 || quads.1 == 0 {
            return Err(format!(
                "a DOG sheet needs at least 1x1 quads, not {}x{}",
                quads.0, quads.1
            ));
        }
        let mut sheet = DogSheet::<f64>::new(quads.0, quads.1, 12.0 / quads.0 as f64);
        let state = sheet.rolled(6.0);
        sheet.set_target(state.x[sheet.grabbed_node()]);
        let settings = Settings {
            ordering,
            parallelism: Parallelism::One,
            ..Settings::default()
        };
        let mut solver = Solver::new(settings).map_err(|e| format!("settings: {e}"))?;
        let grid = format!("{}x{}", quads.0, quads.1);
        match solver.linearize(&sheet, &state) {
            Ok(true) => {}
            Ok(false) => {
                return Err(format!(
                    "the {grid} sheet: no KKT system, or non-finite terms"
                ));
            }
            Err(e) => return Err(format!("the {grid} sheet: {e}")),
        }
        let kkt = solver.kkt().ok_or("no KKT after linearize")?.clone();
        let rhs = solver.rhs().ok_or("no RHS after linearize")?.to_vec();
        Ok(Self {
            sheet,
            state,
            kkt,
            rhs,
            settings,
        })
    }

    /// Refactorizes on the reused symbolic analysis and solves with refinement.
    pub fn refactor_and_solve(&mut self, z: &mut [f64]) -> f64 {
        let s = self.settings;
        self.kkt.factorize(s.pivot_epsilon, s.regularization);
        self.kkt
            .solve_refined(z, &self.rhs, s.refinement_steps, s.refinement_tolerance)
            .relative_residual
    }

    /// The expected pivot signs in the natural order (+1 primal, -1 constraint row).
    #[must_use]
    pub fn signs(&self) -> Vec<i8> {
        let p = self.kkt.pattern();
        (0..p.order())
            .map(|k| if k < p.dofs() { 1 } else { -1 })
            .collect()
    }

    /// faer's view of the upper-triangle matrix.
    #[must_use]
    pub fn faer_matrix(&self) -> SparseColMatRef<'_, u32, f64> {
        let p = self.kkt.pattern();
        let n = p.order();
        let symbolic = SymbolicSparseColMatRef::new_checked(n, n, p.col_ptr(), None, p.row_idx());
        SparseColMatRef::new(symbolic, self.kkt.values())
    }

    /// The dense symmetric matrix (for the dense LU baseline).
    #[must_use]
    pub fn dense(&self) -> Mat<f64> {
        let p = self.kkt.pattern();
        let n = p.order();
        let mut m = Mat::<f64>::zeros(n, n);
        for c in 0..n {
            for s in p.col_ptr()[c] as usize..p.col_ptr()[c + 1] as usize {
                let r = p.row_idx()[s] as usize;
                m[(r, c)] = self.kkt.values()[s];
                m[(c, r)] = self.kkt.values()[s];
            }
        }
        m
    }
}

/// faer's symbolic Cholesky analysis (AMD) of `system`, simplicial or supernodal.
#[must_use]
pub fn faer_symbolic(system: &DogKkt, supernodal: Option<bool>) -> SymbolicCholesky<u32> {
    let threshold = match supernodal {
        None => SupernodalThreshold::AUTO,
        Some(true) => SupernodalThreshold::FORCE_SUPERNODAL,
        Some(false) => SupernodalThreshold::FORCE_SIMPLICIAL,
    };
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: threshold,
        ..CholeskySymbolicParams::default()
    };
    factorize_symbolic_cholesky(
        system.faer_matrix().symbolic(),
        Side::Upper,
        SymmetricOrdering::Amd,
        params,
    )
    .expect("symbolic analysis")
}

/// Scratch memory for [`faer_factor`] and [`faer_solve`] on `symbolic`.
#[must_use]
pub fn faer_scratch(symbolic: &SymbolicCholesky<u32>, par: Par) -> MemBuffer {
    MemBuffer::new(
        symbolic
            .factorize_numeric_ldlt_scratch::<f64>(par, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, par)),
    )
}

/// faer's numeric $LDL^\top$ of `system` into `l_values` on `symbolic`, with the same
/// sign-aware regularization as Folio.
pub fn faer_factor(
    system: &DogKkt,
    symbolic: &SymbolicCholesky<u32>,
    l_values: &mut [f64],
    signs: &[i8],
    par: Par,
    stack: &mut MemStack,
) {
    let scale = system.kkt.primal_scale();
    let regularization = LdltRegularization {
        dynamic_regularization_signs: Some(signs),
        dynamic_regularization_delta: system.settings.regularization * scale,
        dynamic_regularization_epsilon: system.settings.pivot_epsilon * scale,
    };
    symbolic
        .factorize_numeric_ldlt(
            l_values,
            system.faer_matrix(),
            Side::Upper,
            regularization,
            par,
            stack,
            Default::default(),
        )
        .expect("numeric factorization");
}

/// Solves the system's right-hand side into `z` with faer's factor `l_values` (no
/// refinement).
pub fn faer_solve(
    system: &DogKkt,
    symbolic: &SymbolicCholesky<u32>,
    l_values: &[f64],
    z: &mut [f64],
    par: Par,
    stack: &mut MemStack,
) {
    let n = system.kkt.pattern().order();
    z.copy_from_slice(&system.rhs);
    let rhs = MatMut::from_column_major_slice_mut(z, n, 1);
    LdltRef::new(symbolic, l_values).solve_in_place_with_conj(Conj::No, rhs, par, stack);
}

/// [`faer_factor`], then [`faer_solve`].
pub fn faer_factor_and_solve(
    system: &DogKkt,
    symbolic: &SymbolicCholesky<u32>,
    l_values: &mut [f64],
    signs: &[i8],
    z: &mut [f64],
    par: Par,
) {
    let mut buffer = faer_scratch(symbolic, par);
    let stack = MemStack::new(&mut buffer);
    faer_factor(system, symbolic, l_values, signs, par, stack);
    faer_solve(system, symbolic, l_values, z, par, stack);
}

/// faer from scratch: AMD analysis, numeric factorization and solve.
pub fn faer_from_scratch(system: &DogKkt, signs: &[i8], z: &mut [f64]) {
    let symbolic = faer_symbolic(system, None);
    let mut l = vec![0.0; symbolic.len_val()];
    faer_factor_and_solve(system, &symbolic, &mut l, signs, z, Par::Seq);
}
