//! Fuzz target `tearing`: sequences of edits of a small tearing sheet
//! ([`SheetMesh::rectangle`], 1 to 4 quads a side, two triangles each): vertex insertions
//! in a triangle, on an edge and at a point, edge cuts, vertex moves, edge flips and tear
//! advances ([`advance`]), with indices and points anywhere (out of range, outside the
//! sheet, on corners and borders, NaN). Asserts after every edit: the sheet is a valid
//! manifold with boundary ([`SheetMesh::check`]), or the edit was refused and the sheet is
//! unchanged.

use folio_geometry::sheet::SheetMesh;
use folio_tearing::advance::advance;

use super::Input;

/// Edits one input may make.
pub const MAX_EDITS: usize = 32;

/// Decodes a sheet and a sequence of edits from `data` and checks the sheet after each.
///
/// # Panics
/// When an edit leaves an invalid sheet, or changes it and reports an error.
pub fn run(data: &[u8]) {
    let mut input = Input::new(data);
    let (nx, ny) = (1 + input.below(4), 1 + input.below(4));
    let width = input.log_uniform(1e-3, 1e3);
    let height = width * input.log_uniform(0.25, 4.0);
    // A rectangle too thin for its quads is refused (sliver triangles): a typed error.
    let Ok(mut mesh) = SheetMesh::<f64>::rectangle(width, height, nx, ny) else {
        return;
    };
    for _ in 0..MAX_EDITS {
        if input.is_empty() {
            break;
        }
        let before = mesh.clone();
        let (vertices, triangles) = (mesh.vertex_count(), mesh.triangle_count());
        // Indices a little beyond the valid range, points a little beyond the sheet.
        let vertex = |input: &mut Input<'_>| input.below(vertices + 2) as u32;
        let point = |input: &mut Input<'_>| {
            if input.byte() == 255 {
                [f64::NAN, 0.0]
            } else {
                [
                    input.uniform(-0.1, 1.1) * width,
                    input.uniform(-0.1, 1.1) * height,
                ]
            }
        };
        let changed = match input.below(7) {
            0 => {
                let t = input.below(triangles + 1);
                mesh.insert_in_triangle(t, point(&mut input)).is_ok()
            }
            1 => {
                let h = input.below(3 * triangles + 2) as u32;
                mesh.insert_on_edge(h, input.uniform(-0.1, 1.1)).is_ok()
            }
            2 => {
                let p = point(&mut input);
                mesh.insert_at(p, input.uniform(0.0, 0.5)).is_ok()
            }
            3 => {
                let (a, b) = (vertex(&mut input), vertex(&mut input));
                mesh.cut_edge(a, b).is_ok()
            }
            4 => {
                let v = vertex(&mut input);
                mesh.move_vertex(v, point(&mut input)).is_ok()
            }
            5 => mesh
                .flip_edge(input.below(3 * triangles + 2) as u32)
                .is_ok(),
            _ => {
                let p = vertex(&mut input);
                let angle = input.uniform(0.0, core::f64::consts::TAU);
                let length = input.log_uniform(1e-6, 1.0) * width.max(height);
                let (straight, snap) = (input.flag(), input.uniform(0.0, 0.5));
                advance(
                    &mut mesh,
                    p,
                    [angle.cos(), angle.sin()],
                    length,
                    straight,
                    snap,
                    input.flag(),
                )
                .is_ok()
            }
        };
        if changed {
            let mut checked = mesh.clone();
            if let Err(e) = checked.check() {
                panic!("an accepted edit left an invalid sheet: {e}");
            }
        } else {
            assert_unchanged(&before, &mesh);
        }
    }
}

/// `after` has the pattern, positions, velocities and triangles of `before`.
fn assert_unchanged(before: &SheetMesh<f64>, after: &SheetMesh<f64>) {
    let same = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    };
    let flat2 = |m: &SheetMesh<f64>| m.pattern().iter().flatten().copied().collect::<Vec<_>>();
    let flat3 = |v: &[glam::DVec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<_>>();
    assert!(
        same(&flat2(before), &flat2(after)),
        "a refused edit moved the pattern"
    );
    assert!(
        same(&flat3(before.positions()), &flat3(after.positions())),
        "a refused edit moved the sheet"
    );
    assert!(
        same(&flat3(before.velocities()), &flat3(after.velocities())),
        "a refused edit changed velocities"
    );
    assert_eq!(
        before.triangles(),
        after.triangles(),
        "a refused edit changed the triangles"
    );
}
