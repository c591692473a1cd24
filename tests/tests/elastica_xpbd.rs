//! The position-based page clamped at the spine sags like the cantilever elastica (issue
//! 21): a static check of its bending calibration, $D$ to compliance
//! ([`folio_pages::xpbd::constraints`]).
//!
//! **Page.** The model itself ([`XpbdPage`]) with [`Spine::Clamp`]: the spine column fixed
//! and held in the rest plane by the mirrored ghost column (the DOG page's test on branch
//! `units` simulates the mirrored page twice as wide; the clamp is that mirror folded into
//! the stencil), no table, its default $D$, and the load set through gravity,
//! $g = \alpha D/(\rho L^3)$ with $L$ the page width (the DOG test's convention). The
//! elastica's load number is [`cantilever`]'s $\alpha = \rho g L^3/D$; the three
//! values $\{0.1, 1, 10\}$ are the same set read either way up.
//!
//! **Equilibrium.** Frames of the page's own step (its substeps and one sweep each) with a
//! drag of about twice the first cantilever mode's frequency,
//! $c = 2\cdot 3.516\sqrt{D/(\rho L^4)}$, until no particle moves by more than $10^{-9}$
//! page widths in a frame (at most 20000 frames). Drag is zero at rest, so it does not move
//! the equilibrium. The tip is the mean of the free edge's two middle particles.

use folio_pages::xpbd::{Spine, XpbdPage, XpbdSettings};
use folio_pages::{PageModel, PageStatus};
use folio_tests::elastica::cantilever;

/// One settled page.
#[derive(Debug)]
struct Sag {
    /// Tip deflection, page widths.
    tip: f64,
    /// The elastica's.
    reference: f64,
    /// Largest relative edge stretch of the particle grid.
    stretch: f64,
    /// Frames to settle.
    frames: u32,
    /// Spread of the free edge's particles' deflections, (max - min) / mean.
    spread: f64,
}

impl Sag {
    fn error(&self) -> f64 {
        self.tip / self.reference - 1.0
    }
}

/// The page of the defaults on `quads` with `substeps`, settled at load `alpha`.
fn sag(alpha: f64, quads: [usize; 2], substeps: u32) -> Sag {
    let d = XpbdSettings::<f64>::default();
    let (w, rho, bend) = (d.width, d.areal_density, d.bending_stiffness);
    let settings = XpbdSettings {
        quads_across: quads[0],
        quads_along: quads[1],
        spine: Spine::Clamp,
        floor: false,
        gravity: alpha * bend / (rho * w.powi(3)),
        damping: 2.0 * 3.516 * (bend / (rho * w.powi(4))).sqrt(),
        substeps,
        ..d
    };
    let mut page = XpbdPage::new(settings).expect("settings");
    let mut frames = 0;
    let mut before = page.positions().to_vec();
    while frames < 20_000 {
        let step = page.step().expect("step");
        assert_eq!(step.status, PageStatus::Moved);
        frames += 1;
        let moved = before
            .iter()
            .zip(page.positions())
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        before.copy_from_slice(page.positions());
        if moved < 1e-9 * w {
            break;
        }
    }
    let g = page.grid();
    let x = page.positions();
    let rows = [(g.nz - 1) / 2, g.nz / 2];
    let tip = rows
        .iter()
        .map(|&j| -x[g.index(g.nx - 1, j)].y / w)
        .sum::<f64>()
        / 2.0;
    let edge: Vec<f64> = (0..g.nz).map(|j| -x[g.index(g.nx - 1, j)].y / w).collect();
    let mean = edge.iter().sum::<f64>() / edge.len() as f64;
    let spread = (edge.iter().copied().fold(f64::MIN, f64::max)
        - edge.iter().copied().fold(f64::MAX, f64::min))
        / mean;
    let stretch = page
        .distances()
        .iter()
        .map(|c| {
            let [a, b] = c.nodes.map(|k| k as usize);
            ((x[a] - x[b]).length() / c.rest - 1.0).abs()
        })
        .fold(0.0, f64::max);
    let s = Sag {
        tip,
        reference: cantilever(alpha, 2000).tip_deflection,
        stretch,
        frames,
        spread,
    };
    eprintln!(
        "{}x{} quads, {substeps} substeps, alpha {alpha:>4}: tip {:.5} elastica {:.5} error \
         {:+.2} % stretch {:.1e} edge spread {:.2} % ({} frames)",
        quads[0],
        quads[1],
        s.tip,
        s.reference,
        100.0 * s.error(),
        s.stretch,
        100.0 * s.spread,
        s.frames
    );
    s
}

/// Within 3 % of the elastica at the default grid and substeps, from a nearly rigid page
/// (tip 1.25 % of the width below the clamp) to one that hangs 70 %. Measured: +2.58 %,
/// +2.58 %, +2.29 % at $\alpha$ = 0.1, 1, 10; of that, +1.6 % is the grid's (the same
/// five-point beam solved exactly at 8 cells) and the rest the small steps' bias. The page
/// is a cylinder: its rows' tips agree within 1 %.
#[test]
fn the_clamped_page_sags_like_the_elastica() {
    for alpha in [0.1, 1.0, 10.0] {
        let s = sag(alpha, [8, 11], XpbdSettings::<f64>::default().substeps);
        assert!(s.error().abs() < 0.03, "alpha {alpha}: {s:?}");
        assert!(s.frames < 20_000, "alpha {alpha}: did not settle, {s:?}");
        assert!(s.stretch < 1e-3, "alpha {alpha}: {s:?}");
        assert!(s.spread < 0.01, "alpha {alpha}: not a cylinder, {s:?}");
    }
}

/// At twice the resolution the page needs four times the substeps: XPBD's one sweep per
/// substep leaves a bias of order $(h\,\omega_{max})^2$, and the stiffest bending mode's
/// $\omega_{max}$ grows as the inverse square of the spacing. Measured at 16x22 quads: 29
/// substeps (the default's) +21.3 %, +20.7 %, +6.8 % (too soft); 116 substeps (the default's
/// $h\,\omega_{max}$) +1.57 %, +1.55 %, +0.88 %; with the page of $D = 240$, eight times
/// the substeps gave +0.69 %, +0.69 % and at $\alpha = 10$ the page did not settle (-1.3 %
/// after 20000 frames, still moving), so the 1 % at twice the resolution is not
/// reached. Asserted: within 2 % at four times the default's
/// substeps, and at the default substeps more than 5 % too soft (the trade-off the
/// atlas must show: a finer XPBD grid at the same cost is a softer page, not a more
/// accurate one).
#[test]
fn a_finer_grid_needs_proportionally_more_substeps() {
    for alpha in [0.1, 1.0, 10.0] {
        let default = XpbdSettings::<f64>::default().substeps;
        let fine = sag(alpha, [16, 22], 4 * default);
        assert!(fine.error().abs() < 0.02, "alpha {alpha}: {fine:?}");
        assert!(
            fine.frames < 20_000,
            "alpha {alpha}: did not settle, {fine:?}"
        );
        let cheap = sag(alpha, [16, 22], default);
        assert!(cheap.error() > 0.05, "alpha {alpha}: {cheap:?}");
    }
}
