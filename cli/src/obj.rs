//! The torn sheet as a Wavefront OBJ file (`torn_sheet.obj`): every vertex with its 3D
//! position (`v`, sheet units: $x$ along $u$, $y$ along $v$, $z$ out of the flat sheet) and
//! its pattern point divided by the sheet size (`vt` $= (u / W, v / H)$, so that the tear
//! textures `tear-K-*.png` map onto it), and every triangle (`f`, counter-clockwise in the
//! pattern). The lips of a tear are separate vertices with the same `vt`, and a piece that
//! came off is a separate component.

use core::fmt::Write as _;

use folio_geometry::SheetMesh;
use folio_kernels::Vec3Ops;

/// The OBJ text of `mesh` on a `[W, H]` (`size`) pattern; `title` goes into the header
/// comment.
#[must_use]
pub fn sheet_obj(mesh: &SheetMesh<f64>, size: [f64; 2], title: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# {title}");
    let _ = writeln!(
        out,
        "# {} vertices, {} triangles; v: 3D (sheet units), vt: pattern / ({}, {})",
        mesh.vertex_count(),
        mesh.triangle_count(),
        size[0],
        size[1]
    );
    let _ = writeln!(out, "o sheet");
    for x in mesh.positions() {
        let _ = writeln!(out, "v {} {} {}", x.x(), x.y(), x.z());
    }
    for p in mesh.pattern() {
        let _ = writeln!(out, "vt {} {}", p[0] / size[0], p[1] / size[1]);
    }
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(out, "f {a}/{a} {b}/{b} {c}/{c}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rectangle_lists_its_vertices_and_triangles() {
        let mesh = SheetMesh::<f64>::rectangle(2.0, 1.0, 2, 1).unwrap();
        let obj = sheet_obj(&mesh, [2.0, 1.0], "test");
        let count = |prefix: &str| obj.lines().filter(|l| l.starts_with(prefix)).count();
        assert_eq!(count("v "), 6);
        assert_eq!(count("vt "), 6);
        assert_eq!(count("f "), 4);
        assert!(obj.contains("\nvt 1 1\n"));
        // Indices are 1-based and in range.
        for line in obj.lines().filter(|l| l.starts_with("f ")) {
            for corner in line.split_whitespace().skip(1) {
                let i: usize = corner.split('/').next().unwrap().parse().unwrap();
                assert!((1..=6).contains(&i));
            }
        }
    }
}
