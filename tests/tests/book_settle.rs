//! `Book::new` settles the blocks by pseudo-transient continuation
//! (`BookSettings::settle_stretch`): implicit steps from rest with the step doubling. It
//! must land on the rest that stepping the dynamics at the scene's time step reaches
//! (`settle_stretch` 1, the independent reference: the same model, a different path), in
//! far fewer steps, for books of several shapes.

use folio_book::{Book, BookParams, BookSettings};
use folio_kernels::{Real, Vec3Ops};
use folio_tests::worst;

/// Every block and cover node after `Book::new`, as `f64`, with the
/// steps the settling took.
fn rest<T: Real>(settings: BookSettings<T>) -> (Vec<[f64; 3]>, u32) {
    let book = Book::new(settings).expect("a valid book");
    let blocks = &book.state().x[..book.nodes().page_offset()];
    let x = blocks
        .iter()
        .map(|p| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()])
        .collect();
    (x, book.settle_steps())
}

/// Largest coordinate difference.
fn gap(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, worst)
}

/// The books: the default, a thin one with most pages on the left and no cover, a thick
/// one with a quarter on the left, and one of two pages (single-page blocks that fall a
/// long way from the layout).
fn books() -> Vec<(&'static str, BookParams)> {
    let d = BookParams::default();
    vec![
        ("default", d),
        (
            "thin, no cover, 9/10 left",
            BookParams {
                total_pages: 40,
                left_pages: 36,
                cover: false,
                ..d
            },
        ),
        (
            "thick, 1/4 left",
            BookParams {
                total_pages: 600,
                left_pages: 150,
                ..d
            },
        ),
        (
            "two pages",
            BookParams {
                total_pages: 2,
                left_pages: 1,
                ..d
            },
        ),
    ]
}

#[test]
fn the_continuation_lands_where_the_dynamics_come_to_rest() {
    for (name, params) in books() {
        let (reference, dynamic_steps) = rest(BookSettings::<f64> {
            params,
            settle_stretch: 1.0,
            ..BookSettings::default()
        });
        let (x64, steps64) = rest(BookSettings::<f64> {
            params,
            ..BookSettings::default()
        });
        let (x32, steps32) = rest(BookSettings::<f32> {
            params,
            ..BookSettings::default()
        });
        let (dynamic32, _) = rest(BookSettings::<f32> {
            params,
            settle_stretch: 1.0,
            ..BookSettings::default()
        });
        let (g64, g32) = (gap(&x64, &reference), gap(&x32, &reference));
        let g32_dynamic = gap(&dynamic32, &reference);
        eprintln!(
            "{name}: dynamic {dynamic_steps} steps; continuation f64 {steps64} steps, \
             {g64:.1e} from it; f32 {steps32} steps, {g32:.1e} (the f32 dynamics \
             {g32_dynamic:.1e})"
        );
        // The dynamics stop at a step that moves no node by more than 1e-9, with what is
        // left of their velocity (air drag 3/s) carrying them on by about 1e-7.
        assert!(
            g64 < 1e-5,
            "{name}: f64 rest {g64:.1e} from the dynamic rest"
        );
        // f32: rounding and the contact springs' sink g/s (1e-4 in f32).
        assert!(
            g32 < 1e-3,
            "{name}: f32 rest {g32:.1e} from the f64 dynamic rest"
        );
        assert!(
            steps64 < dynamic_steps && steps32 < dynamic_steps,
            "{name}: the continuation took {steps64} (f64) and {steps32} (f32) steps, \
             the dynamics {dynamic_steps}"
        );
        if name == "default" {
            assert!(
                steps64 * 10 < dynamic_steps && steps32 * 10 < dynamic_steps,
                "the default book settled in {steps64} (f64) and {steps32} (f32) steps"
            );
        }
    }
}

#[test]
fn a_bad_stretch_is_refused() {
    for stretch in [0.5, 0.0, -1.0, f64::NAN, f64::INFINITY] {
        let settings = BookSettings::<f64> {
            settle_stretch: stretch,
            ..BookSettings::default()
        };
        assert!(
            Book::new(settings).is_err(),
            "settle_stretch {stretch} accepted"
        );
    }
}
