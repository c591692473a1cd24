//! A variant's error against the reference, at the same material points and times, as
//! fractions of the page width $W$.
//!
//! At frame $f$ with $n$ sample points $x_k$ (variant) and $r_k$ (reference):
//! - RMS position error $e_f = \sqrt{\tfrac1n \sum_k \lVert x_k - r_k\rVert^2} / W$;
//! - max position error $m_f = \max_k \lVert x_k - r_k\rVert / W$;
//! - tip error $t_f = \lVert x_{tip} - r_{tip}\rVert / W$ (the middle of the fore-edge).
//!
//! Frames where either run has not had a page yet are not compared (before the first
//! grab both lie flat on their block); a run that never has a page where the other does
//! is counted in `unmatched`. A non-finite point makes the frame's errors infinite, so a
//! broken variant can never look accurate.

use serde::Serialize;

use super::trace::{Trace, tip};

/// The errors of one variant (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Errors {
    /// Mean over frames of the RMS position error $e_f$.
    pub rms_mean: f64,
    /// Worst frame's RMS position error.
    pub rms_worst: f64,
    /// Mean over frames of the max position error $m_f$.
    pub max_mean: f64,
    /// Worst frame's max position error.
    pub max_worst: f64,
    /// RMS over frames of the tip error $t_f$ (the tip trajectory's error).
    pub tip_rms: f64,
    /// Worst frame's tip error.
    pub tip_worst: f64,
    /// Frames compared.
    pub frames: usize,
    /// Frames where one run had a page and the other had never had one.
    pub unmatched: usize,
}

/// `a`'s errors against `b` (the reference) on a page of width `width` (module docs).
#[must_use]
pub fn errors(a: &Trace, b: &Trace, width: f64) -> Errors {
    let tip = tip();
    let (mut rms_sum, mut rms_worst, mut max_sum, mut max_worst) = (0.0, 0.0_f64, 0.0, 0.0_f64);
    let (mut tip_sq, mut tip_worst) = (0.0, 0.0_f64);
    let (mut frames, mut unmatched) = (0, 0);
    // A frame one run lacks (a shorter run) counts as unmatched.
    let n = a.frames.len().max(b.frames.len());
    for f in 0..n {
        let (x, r) = match (
            a.frames.get(f).and_then(Option::as_ref),
            b.frames.get(f).and_then(Option::as_ref),
        ) {
            (Some(x), Some(r)) if x.len() == r.len() => (x, r),
            (None, None) => continue,
            _ => {
                unmatched += 1;
                continue;
            }
        };
        let distance = |k: usize| {
            let d = [x[k][0] - r[k][0], x[k][1] - r[k][1], x[k][2] - r[k][2]];
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / width;
            if l.is_finite() { l } else { f64::INFINITY }
        };
        let (mut sq, mut worst) = (0.0, 0.0_f64);
        for k in 0..x.len() {
            let d = distance(k);
            sq += d * d;
            worst = worst.max(d);
        }
        let rms = (sq / x.len().max(1) as f64).sqrt();
        let t = distance(tip.min(x.len().saturating_sub(1)));
        rms_sum += rms;
        rms_worst = rms_worst.max(rms);
        max_sum += worst;
        max_worst = max_worst.max(worst);
        tip_sq += t * t;
        tip_worst = tip_worst.max(t);
        frames += 1;
    }
    let per = |s: f64| {
        if frames == 0 {
            f64::INFINITY
        } else {
            s / frames as f64
        }
    };
    Errors {
        rms_mean: per(rms_sum),
        rms_worst,
        max_mean: per(max_sum),
        max_worst,
        tip_rms: per(tip_sq).sqrt(),
        tip_worst,
        frames,
        unmatched,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atlas::trace::sample_grid;

    fn flat(offset: [f64; 3], frames: usize) -> Vec<Option<Vec<[f64; 3]>>> {
        let grid = sample_grid();
        (0..frames)
            .map(|f| {
                (f > 0).then(|| {
                    (0..grid.len())
                        .map(|k| {
                            let (i, j) = grid.coords(k);
                            [i as f64 + offset[0], offset[1], j as f64 + offset[2]]
                        })
                        .collect()
                })
            })
            .collect()
    }

    fn trace(frames: Vec<Option<Vec<[f64; 3]>>>) -> Trace {
        let scene = folio_scene::scene::Scene::parse(
            folio_scene::builtin::scene("cone-turn").expect("built in"),
        )
        .expect("parses");
        let mut report = crate::run::run(&scene, |_, _| {}, |_, _, _| {}).expect("runs");
        report.frames.clear();
        Trace { frames, report }
    }

    #[test]
    fn a_shifted_page_errs_by_its_shift_and_a_nan_is_infinitely_wrong() {
        let a = trace(flat([0.0; 3], 5));
        let b = trace(flat([0.0, 0.3, 0.4], 5));
        let e = errors(&b, &a, 10.0);
        // Frame 0 has no page in either run.
        assert_eq!((e.frames, e.unmatched), (4, 0));
        for v in [
            e.rms_mean,
            e.rms_worst,
            e.max_mean,
            e.max_worst,
            e.tip_rms,
            e.tip_worst,
        ] {
            assert!((v - 0.05).abs() < 1e-12, "{e:?}");
        }
        assert_eq!(errors(&a, &a, 10.0).rms_worst, 0.0);
        let mut broken = flat([0.0; 3], 5);
        broken[3].as_mut().expect("a page")[7][1] = f64::NAN;
        let e = errors(&trace(broken), &a, 10.0);
        assert!(
            e.max_worst.is_infinite() && e.rms_mean.is_infinite(),
            "{e:?}"
        );
        let mut late = flat([0.0; 3], 5);
        late[1] = None;
        assert_eq!(errors(&trace(late), &a, 10.0).unmatched, 1);
    }
}
