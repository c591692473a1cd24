//! The whole book as a render mesh (`Book::mesh`, seed `000_…` Sec. 3.5): at rest (blocks and
//! cover), after a grab (the active page appears), after a drag and a few steps, and with an
//! empty block; in both precisions.

use folio_book::{Book, BookSettings, GrabOutcome};
use folio_geometry::BlockSide;
use folio_geometry::mesh::{Surface, TriMesh};
use folio_kernels::{Real, Vec3Ops};

/// Every position finite, every normal of unit length, every index in range, UVs in
/// $[0, 1]^2$, one surface per triangle.
fn check_mesh(m: &TriMesh) {
    assert!(m.vertex_count() > 0 && m.triangle_count() > 0);
    assert_eq!(m.normals.len(), m.vertex_count());
    assert_eq!(m.uvs.len(), m.vertex_count());
    assert_eq!(m.surfaces.len(), m.triangle_count());
    for (k, p) in m.positions.iter().enumerate() {
        assert!(p.iter().all(|c| c.is_finite()), "vertex {k}: {p:?}");
    }
    for (k, n) in m.normals.iter().enumerate() {
        let len = n.iter().map(|c| c * c).sum::<f32>().sqrt();
        assert!((len - 1.0).abs() < 1e-4, "normal {k}: {n:?}");
    }
    for uv in &m.uvs {
        assert!(uv.iter().all(|c| (0.0..=1.0).contains(c)));
    }
    for t in &m.triangles {
        assert!(t.iter().all(|&v| (v as usize) < m.vertex_count()));
    }
}

fn count(m: &TriMesh, s: Surface) -> usize {
    m.surfaces.iter().filter(|&&x| x == s).count()
}

fn has_page(m: &TriMesh) -> bool {
    count(m, Surface::PageFront) > 0 && count(m, Surface::PageBack) > 0
}

fn at_rest_and_grabbed<T: Real>() {
    let mut book = Book::<T>::new(BookSettings::default()).expect("default book");
    let mut m = TriMesh::new();
    book.mesh(&mut m).expect("book at rest meshes");
    check_mesh(&m);
    assert!(!has_page(&m), "no active page at rest");
    assert!(count(&m, Surface::BlockTop) > 0);
    // Cover: left, right and spine boards, 12 triangles each.
    assert_eq!(count(&m, Surface::Cover), 36);
    let params = book.layout().params;
    // The blocks lie on the cover and span the page: X across both pages, Z over the height.
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &m.positions {
        for a in 0..3 {
            lo[a] = folio_tests::least(lo[a], p[a]);
            hi[a] = folio_tests::worst(hi[a], p[a]);
        }
    }
    let w = params.page_width as f32;
    assert!(lo[0] < -0.9 * w && hi[0] > 0.9 * w, "x range {lo:?} {hi:?}");
    assert!(lo[1] > -0.1 && hi[1] < 0.2 * w, "y range {lo:?} {hi:?}");
    assert!(lo[2] < 0.0 && hi[2] > params.page_height() as f32);

    let at_rest = m.triangle_count();
    let grabbed = book
        .grab_at(BlockSide::Right, [10.5, 8.5], 1)
        .expect("grab");
    assert!(matches!(
        grabbed,
        GrabOutcome::Grabbed {
            side: BlockSide::Right,
            ..
        }
    ));
    m.clear();
    book.mesh(&mut m).expect("grabbed book meshes");
    check_mesh(&m);
    assert!(has_page(&m), "the active page appears after a grab");
    assert!(count(&m, Surface::PageEdge) > 0);
    assert!(m.triangle_count() > at_rest);

    // Drag the page up and step: still a valid mesh.
    let target = T::Vec3::new(T::from_f64(6.0), T::from_f64(4.0), T::from_f64(8.5));
    book.drag_to(target).expect("drag");
    for _ in 0..10 {
        book.step().expect("step");
    }
    m.clear();
    book.mesh(&mut m).expect("dragged book meshes");
    check_mesh(&m);
    assert!(has_page(&m));
}

#[test]
fn book_meshes_at_rest_and_after_a_grab_f64() {
    at_rest_and_grabbed::<f64>();
}

#[test]
fn book_meshes_at_rest_and_after_a_grab_f32() {
    at_rest_and_grabbed::<f32>();
}

/// Appending keeps what `out` held; an empty block is skipped, not an error.
#[test]
fn mesh_appends_and_skips_an_empty_block() {
    let mut settings = BookSettings::<f64>::default();
    settings.params.left_pages = 0;
    let book = Book::new(settings).expect("book with an empty left block");
    let mut alone = TriMesh::new();
    book.mesh(&mut alone).expect("meshes");
    check_mesh(&alone);

    let full = Book::<f64>::new(BookSettings::default()).expect("default book");
    let mut both = TriMesh::new();
    full.mesh(&mut both).expect("meshes");
    let before = both.clone();
    book.mesh(&mut both).expect("appends");
    assert_eq!(
        &both.positions[..before.vertex_count()],
        &before.positions[..]
    );
    assert_eq!(
        both.vertex_count(),
        before.vertex_count() + alone.vertex_count()
    );
    // One block fewer than the full book.
    assert!(count(&alone, Surface::BlockTop) * 2 <= count(&before, Surface::BlockTop) + 2);
    assert!(alone.triangle_count() < before.triangle_count());
}

/// Without a cover there are no boards.
#[test]
fn no_cover_no_boards() {
    let mut settings = BookSettings::<f64>::default();
    settings.params.cover = false;
    let book = Book::new(settings).expect("book without cover");
    let mut m = TriMesh::new();
    book.mesh(&mut m).expect("meshes");
    check_mesh(&m);
    assert_eq!(count(&m, Surface::Cover), 0);
}
