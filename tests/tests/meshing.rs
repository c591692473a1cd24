//! Meshing for rendering (seed `000_…` Sec. 3.5, `folio_geometry::mesh`): the active page's
//! offset surfaces and rim, length adaptation of its rows, page blocks with the rounded
//! binding fan and the sheared fore-edge, the left/right mirror symmetry, the cover box, and
//! bad or degenerate input (typed errors or finite output, never a panic).
//!
//! Every mesh is checked for the `TriMesh` contract (finite data, unit normals, UVs in
//! [0, 1]^2, valid indices, every triangle counter-clockwise seen from its vertex normals)
//! and, where the mesh is a closed solid, for watertightness and a positive enclosed volume
//! equal to the solid's analytic volume (which fails if any face is inside out).

use core::f64::consts::PI;
use std::collections::HashMap;

use folio_geometry::QuadGrid;
use folio_geometry::mesh::{
    BlockCurves, BlockProfile, BlockSide, MIN_END_FRACTION, MeshError, PageSurfaces, Surface,
    TriMesh, adapt_length, block_mesh, cover_mesh, page_mesh,
};
use folio_tests::Rng;

const T_PAGE: f64 = 0.0075;
const WIDTH: f64 = 12.0;

// ---------------------------------------------------------------------------------------
// Helpers

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn len<const D: usize>(a: [f64; D]) -> f64 {
    a.iter().map(|c| c * c).sum::<f64>().sqrt()
}

fn dist<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    len(core::array::from_fn::<f64, D, _>(|k| a[k] - b[k]))
}

fn polyline<const D: usize>(p: &[[f64; D]]) -> f64 {
    p.windows(2).map(|w| dist(w[0], w[1])).sum()
}

fn f64v(v: [f32; 3]) -> [f64; 3] {
    v.map(f64::from)
}

/// Corners of triangle `t` in f64.
fn corners(m: &TriMesh, t: usize) -> [[f64; 3]; 3] {
    m.triangles[t].map(|v| f64v(m.positions[v as usize]))
}

/// Geometric (unnormalized) normal of triangle `t`: `(b - a) x (c - a)`.
fn face_normal(m: &TriMesh, t: usize) -> [f64; 3] {
    let [a, b, c] = corners(m, t);
    cross3(sub3(b, a), sub3(c, a))
}

/// The `TriMesh` contract. Triangles with an area above `min_area` must face the side their
/// vertex normals point to; with `no_degenerate`, every triangle must have that area.
fn check_mesh(m: &TriMesh, min_area: f64, no_degenerate: bool) {
    let nv = m.vertex_count();
    assert_eq!(m.normals.len(), nv);
    assert_eq!(m.uvs.len(), nv);
    assert_eq!(m.surfaces.len(), m.triangle_count());
    for k in 0..nv {
        assert!(m.positions[k].iter().all(|c| c.is_finite()), "position {k}");
        let n = f64v(m.normals[k]);
        assert!(
            (len(n) - 1.0).abs() < 1e-6,
            "normal {k} = {n:?} is not unit"
        );
        assert!(
            m.uvs[k].iter().all(|&c| (0.0..=1.0).contains(&c)),
            "uv {k} = {:?}",
            m.uvs[k]
        );
    }
    for t in 0..m.triangle_count() {
        assert!(m.triangles[t].iter().all(|&v| (v as usize) < nv));
        let g = face_normal(m, t);
        let area = 0.5 * len(g);
        if no_degenerate {
            assert!(
                area > min_area,
                "triangle {t} is degenerate (area {area:e})"
            );
        }
        if area > min_area {
            for v in m.triangles[t] {
                let n = f64v(m.normals[v as usize]);
                assert!(
                    dot3(g, n) > 0.0,
                    "triangle {t} ({:?}) faces against vertex {v}'s normal {n:?}",
                    m.surfaces[t]
                );
            }
        }
    }
}

/// `true` if every directed edge (by vertex position) is matched by its reverse: the mesh is
/// a closed, consistently oriented surface.
fn is_watertight(m: &TriMesh) -> bool {
    let key = |v: u32| m.positions[v as usize].map(f32::to_bits);
    let mut edges: HashMap<([u32; 3], [u32; 3]), i64> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
            if a == b {
                continue;
            }
            *edges.entry((a, b)).or_default() += 1;
            *edges.entry((b, a)).or_default() -= 1;
        }
    }
    edges.values().all(|&c| c == 0)
}

/// Enclosed volume by the divergence theorem; positive for outward-facing triangles.
fn signed_volume(m: &TriMesh) -> f64 {
    (0..m.triangle_count())
        .map(|t| {
            let [a, b, c] = corners(m, t);
            dot3(a, cross3(b, c)) / 6.0
        })
        .sum()
}

/// Area enclosed by a closed XY polygon (shoelace), positive counter-clockwise.
fn shoelace(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        / 2.0
}

fn count(m: &TriMesh, s: Surface) -> usize {
    m.surfaces.iter().filter(|&&x| x == s).count()
}

/// Vertex indices used by the triangles of surface `s`.
fn vertices_of(m: &TriMesh, s: Surface) -> Vec<usize> {
    let mut v: Vec<usize> = (0..m.triangle_count())
        .filter(|&t| m.surfaces[t] == s)
        .flat_map(|t| m.triangles[t].map(|v| v as usize))
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// A flat page on y = 0: `nx x nz` vertices, spacing `hx` along X (i) and `hz` along Z (j).
fn flat_page(nx: usize, nz: usize, hx: f64, hz: f64) -> (QuadGrid, Vec<[f64; 3]>) {
    let grid = QuadGrid { nx, nz };
    let p = (0..nx * nz)
        .map(|k| {
            let (i, j) = grid.coords(k);
            [i as f64 * hx, 0.0, j as f64 * hz]
        })
        .collect();
    (grid, p)
}

/// A page rolled onto the cylinder of radius `r` about the axis (0, r, z): rulings along Z,
/// arc length `s_i = i * h` across the page, tangent +X at the binding, bending up.
fn cylinder_page(nx: usize, nz: usize, h: f64, r: f64) -> (QuadGrid, Vec<[f64; 3]>) {
    let grid = QuadGrid { nx, nz };
    let p = (0..nx * nz)
        .map(|k| {
            let (i, j) = grid.coords(k);
            let phi = i as f64 * h / r;
            [r * phi.sin(), r * (1.0 - phi.cos()), j as f64 * 1.5]
        })
        .collect();
    (grid, p)
}

/// A left block's midline: from the binding node `b`, outward along −X with length `length`,
/// bending down on a circle of radius `r` (its top, the material side, is convex).
fn arc_midline(b: [f64; 2], nodes: usize, length: f64, r: f64) -> Vec<[f64; 2]> {
    (0..nodes)
        .map(|k| {
            let phi = length * k as f64 / (nodes - 1) as f64 / r;
            [b[0] - r * phi.sin(), b[1] - r * (1.0 - phi.cos())]
        })
        .collect()
}

fn left_profile<'a>(midline: &'a [[f64; 2]], fan: usize) -> BlockProfile<'a> {
    BlockProfile {
        midline,
        side: BlockSide::Left,
        thickness: 0.375,
        height: 17.0,
        binding_direction: [1.0, 0.0],
        page_width: WIDTH,
        fan,
    }
}

fn mirror_x2(p: [f64; 2]) -> [f64; 2] {
    [-p[0], p[1]]
}

// ---------------------------------------------------------------------------------------
// TriMesh

#[test]
fn trimesh_new_clear_and_counts() {
    let mut m = TriMesh::new();
    assert_eq!((m.vertex_count(), m.triangle_count()), (0, 0));
    assert_eq!(m, TriMesh::default());
    cover_mesh(
        &mut m,
        [0.0, 0.0],
        [12.0, 0.0],
        [0.0, -1.0],
        0.06,
        17.0,
        0.25,
    )
    .unwrap();
    assert_eq!((m.vertex_count(), m.triangle_count()), (24, 12));
    let capacity = m.positions.capacity();
    m.clear();
    assert_eq!((m.vertex_count(), m.triangle_count()), (0, 0));
    assert!(m.surfaces.is_empty() && m.uvs.is_empty() && m.normals.is_empty());
    assert_eq!(m.positions.capacity(), capacity, "clear keeps the storage");
}

// ---------------------------------------------------------------------------------------
// Active page

/// The seed's flat page (9 x 12 vertices, 1.5 x 1.545 spacing): front at +t/2 with normals
/// +Y, back at −t/2 with normals −Y, UVs as documented (back mirrored), rim normals along
/// the outward axes, exact counts, a closed solid of volume width x height x t.
#[test]
fn flat_page_offsets_normals_uvs_and_counts() {
    let (nx, nz) = (9, 12);
    let (grid, p) = flat_page(nx, nz, 1.5, 1.545);
    let mut m = TriMesh::new();
    page_mesh(&mut m, grid, &p, T_PAGE, WIDTH).unwrap();

    let n = nx * nz;
    assert_eq!(m.vertex_count(), 2 * n + 4 * (nx + nz));
    assert_eq!(
        m.triangle_count(),
        4 * (nx - 1) * (nz - 1) + 4 * (nx + nz - 2)
    );
    assert_eq!(count(&m, Surface::PageFront), 2 * (nx - 1) * (nz - 1));
    assert_eq!(count(&m, Surface::PageBack), 2 * (nx - 1) * (nz - 1));
    assert_eq!(count(&m, Surface::PageEdge), 4 * (nx + nz - 2));
    check_mesh(&m, 1e-6, true);

    let front = vertices_of(&m, Surface::PageFront);
    let back = vertices_of(&m, Surface::PageBack);
    assert_eq!((front.len(), back.len()), (n, n));
    for (k, (&f, &b)) in front.iter().zip(&back).enumerate() {
        let (i, j) = grid.coords(k);
        let expect = |y: f64| [p[k][0], y, p[k][2]];
        assert!(dist(f64v(m.positions[f]), expect(T_PAGE / 2.0)) < 1e-6);
        assert!(dist(f64v(m.positions[b]), expect(-T_PAGE / 2.0)) < 1e-6);
        assert_eq!(m.normals[f], [0.0, 1.0, 0.0]);
        assert_eq!(m.normals[b], [0.0, -1.0, 0.0]);
        let (u, v) = (i as f32 / (nx - 1) as f32, j as f32 / (nz - 1) as f32);
        assert!((m.uvs[f][0] - u).abs() < 1e-6 && (m.uvs[f][1] - v).abs() < 1e-6);
        assert!((m.uvs[b][0] - (1.0 - u)).abs() < 1e-6 && (m.uvs[b][1] - v).abs() < 1e-6);
    }

    // Rim normals are the outward axes; rim UV v is 1 on the front, 0 on the back.
    for v in vertices_of(&m, Surface::PageEdge) {
        let [x, y, z] = f64v(m.positions[v]);
        let n = f64v(m.normals[v]);
        let axis_ok = (z == 0.0 && n == [0.0, 0.0, -1.0])
            || ((z - 11.0 * 1.545).abs() < 1e-5 && n == [0.0, 0.0, 1.0])
            || (x == 0.0 && n == [-1.0, 0.0, 0.0])
            || ((x - WIDTH).abs() < 1e-5 && n == [1.0, 0.0, 0.0]);
        assert!(
            axis_ok,
            "rim vertex {v} at {:?} has normal {n:?}",
            [x, y, z]
        );
        assert_eq!(m.uvs[v][1], if y > 0.0 { 1.0 } else { 0.0 });
    }

    assert!(is_watertight(&m));
    let volume = WIDTH * 11.0 * 1.545 * T_PAGE;
    assert!((signed_volume(&m) - volume).abs() < 1e-4 * volume);
}

/// A page bent onto a cylinder with rows stretched (or shrunk) against the page width: after
/// adaptation every row of both surfaces is exactly `page_width` long (f64), front and back
/// stay `t` apart away from the outer end, normals point to the concave side, and the mesh
/// (f32) keeps the rows' length to f32 accuracy and stays a closed, outward-facing solid.
#[test]
fn cylinder_page_rows_adapted_to_page_width() {
    let (nx, nz, r) = (11, 8, 5.0);
    for stretch in [1.11, 0.93] {
        let h = stretch * WIDTH / (nx - 1) as f64;
        let (grid, p) = cylinder_page(nx, nz, h, r);
        let s = PageSurfaces::new(grid, &p, T_PAGE, WIDTH).unwrap();
        assert_eq!(s.grid(), grid);
        for j in 0..nz {
            let row = grid.index(0, j)..grid.index(0, j) + nx;
            for surface in [s.front(), s.back()] {
                let before = polyline(&surface[row.clone()]);
                assert!(
                    (before - WIDTH).abs() < 1e-9,
                    "stretch {stretch}: row {j} is {before}"
                );
            }
            for k in row.clone().take(nx - 1) {
                assert!((dist(s.front()[k], s.back()[k]) - T_PAGE).abs() < 1e-12);
                // Midway between front and back lies the node itself.
                let mid = [0, 1, 2].map(|c| 0.5 * (s.front()[k][c] + s.back()[k][c]));
                assert!(dist(mid, p[k]) < 1e-12);
                // Unit normal towards the cylinder's axis (the concave side).
                let to_axis = sub3([0.0, r, p[k][2]], p[k]);
                let n = s.normals()[k];
                assert!((len(n) - 1.0).abs() < 1e-12);
                // One-sided differences at the binding tilt it by half a segment angle.
                assert!(dot3(n, to_axis) / r > 0.98, "normal {n:?} at {k}");
            }
            // The outer vertex moved along the last segment: still on the line through it.
            let (a, b, c) = (p[row.end - 2], p[row.end - 1], s.front()[row.end - 1]);
            let d = sub3(b, a);
            let line_dist = len(cross3(sub3(c, a), d)) / len(d);
            assert!(
                line_dist < 0.6 * T_PAGE,
                "outer vertex left its segment's line"
            );
        }

        let mut m = TriMesh::new();
        page_mesh(&mut m, grid, &p, T_PAGE, WIDTH).unwrap();
        check_mesh(&m, 1e-6, true);
        assert!(is_watertight(&m));
        for surface in [Surface::PageFront, Surface::PageBack] {
            let v = vertices_of(&m, surface);
            for j in 0..nz {
                let row: Vec<[f64; 3]> = v[nx * j..nx * (j + 1)]
                    .iter()
                    .map(|&k| f64v(m.positions[k]))
                    .collect();
                assert!((polyline(&row) - WIDTH).abs() < 1e-5 * WIDTH);
            }
        }
        let volume = WIDTH * 7.0 * 1.5 * T_PAGE;
        assert!(
            (signed_volume(&m) - volume).abs() < 0.02 * volume,
            "stretch {stretch}"
        );
    }
}

/// A twisted, randomly jittered page keeps the contract (every triangle faces its normals)
/// and the page rows are adapted on both sides.
#[test]
fn jittered_page_keeps_contract() {
    let mut rng = Rng::new(7);
    let (grid, mut p) = cylinder_page(12, 9, 1.1, 9.0);
    for q in &mut p {
        let twist = 0.005 * q[2] * q[0];
        q[1] += twist + rng.uniform(-0.01, 0.01);
        q[0] += rng.uniform(-0.01, 0.01);
    }
    let s = PageSurfaces::new(grid, &p, 0.02, WIDTH).unwrap();
    for row in s.front().chunks(12).chain(s.back().chunks(12)) {
        assert!(
            (polyline(row) - WIDTH).abs() < 1e-9,
            "{} {:?}",
            polyline(row),
            row
        );
    }
    let mut m = TriMesh::new();
    page_mesh(&mut m, grid, &p, 0.02, WIDTH).unwrap();
    check_mesh(&m, 1e-6, true);
    assert!(is_watertight(&m));
    assert!(signed_volume(&m) > 0.0);
}

// ---------------------------------------------------------------------------------------
// Segment length adaptation

#[test]
fn adapt_length_moves_the_end_along_the_last_segment() {
    // Stretch and shrink: exact length, end on the last segment's ray.
    for target in [3.0, 7.5] {
        let mut c = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [3.0, 1.0]];
        adapt_length(&mut c, target);
        assert!((polyline(&c) - target).abs() < 1e-12);
        assert!((c[3][1] - 1.0).abs() < 1e-15 && c[3][0] > 2.0);
    }
    // The other segments already exceed the target: the end keeps MIN_END_FRACTION.
    let mut c = [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [5.0, 2.0, 0.0]];
    adapt_length(&mut c, 1.0);
    assert!((c[2][1] - 2.0 * MIN_END_FRACTION).abs() < 1e-12);
    // A zero-length last segment moves along the previous direction.
    let mut c = [[0.0, 0.0], [0.0, 2.0], [0.0, 2.0]];
    adapt_length(&mut c, 5.0);
    assert_eq!(c[2], [0.0, 5.0]);
    // Nothing to adapt: unchanged.
    for target in [f64::NAN, -1.0, f64::INFINITY] {
        let mut c = [[0.0, 0.0], [1.0, 0.0]];
        adapt_length(&mut c, target);
        assert_eq!(c, [[0.0, 0.0], [1.0, 0.0]]);
    }
    let mut single = [[1.0, 2.0]];
    adapt_length(&mut single, 3.0);
    assert_eq!(single, [[1.0, 2.0]]);
    let mut coincident = [[1.0, 2.0]; 4];
    adapt_length(&mut coincident, 3.0);
    assert_eq!(coincident, [[1.0, 2.0]; 4]);
    adapt_length::<2>(&mut [], 1.0);
}

// ---------------------------------------------------------------------------------------
// Page blocks

/// An arc-shaped left block: the fan has `fan + 1` points at distance `t` from the binding
/// node, from the binding direction to the first normal in equal angle steps; the other top
/// nodes are at distance `t` from their midline nodes; the adapted top is as long as the
/// midline, which shears the fore-edge (the top end falls behind the bottom end on the
/// convex side); top normals point to the material side.
#[test]
fn arc_block_curves_fan_and_shear() {
    let b = [-0.375, 0.06];
    let midline = arc_midline(b, 15, WIDTH, 10.0);
    let fan = 4;
    let profile = left_profile(&midline, fan);
    let c = BlockCurves::new(&profile).unwrap();
    let t = profile.thickness;
    assert_eq!(c.side(), BlockSide::Left);
    assert_eq!(c.bottom(), &midline[..]);
    assert_eq!(c.top().len(), midline.len() + fan);

    let fans = c.fan_points();
    assert_eq!(fans.len(), fan + 1);
    // The first segment's normal on the left block's material side, (t_y, -t_x).
    let t0 = [midline[1][0] - b[0], midline[1][1] - b[1]];
    let n0 = [t0[1] / len(t0), -t0[0] / len(t0)];
    assert!(
        dist(fans[0], [b[0] + t, b[1]]) < 1e-12,
        "first fan point on the binding"
    );
    assert!(dist(fans[fan], [b[0] + t * n0[0], b[1] + t * n0[1]]) < 1e-12);
    let angle = |p: [f64; 2]| (p[1] - b[1]).atan2(p[0] - b[0]);
    for (f, d) in fans.iter().zip(c.top_normals()) {
        assert!((dist(*f, b) - t).abs() < 1e-12);
        assert!(dist(*d, [(f[0] - b[0]) / t, (f[1] - b[1]) / t]) < 1e-12);
    }
    let step = angle(fans[1]) - angle(fans[0]);
    assert!(
        step > 0.0,
        "the fan turns from the binding direction towards n0"
    );
    for w in fans.windows(2) {
        assert!((angle(w[1]) - angle(w[0]) - step).abs() < 1e-9);
    }

    let top = c.adapted_top();
    assert_eq!(top.len(), midline.len());
    for k in 1..midline.len() - 1 {
        assert!((dist(top[k], midline[k]) - t).abs() < 1e-12, "node {k}");
    }
    assert!((polyline(top) - polyline(&midline)).abs() < 1e-9);
    // Sheared: along the last tangent, the top end lies behind the bottom end.
    let n = midline.len();
    let tl = [
        midline[n - 1][0] - midline[n - 2][0],
        midline[n - 1][1] - midline[n - 2][1],
    ];
    let along =
        (top[n - 1][0] - midline[n - 1][0]) * tl[0] + (top[n - 1][1] - midline[n - 1][1]) * tl[1];
    assert!(along < -0.1 * len(tl), "fore-edge not sheared: {along}");

    // Top normals point to the material side of the midline: up-left of travel (t_y, -t_x).
    for k in 1..n {
        let tk = [
            midline[k][0] - midline[k - 1][0],
            midline[k][1] - midline[k - 1][1],
        ];
        let material = [tk[1], -tk[0]];
        let d = c.top_normals()[fan + k];
        assert!((d[0] * material[0] + d[1] * material[1]) > 0.9 * len(tk));
        let bn = c.bottom_normals()[k];
        assert!(dist(bn, [-d[0], -d[1]]) < 1e-15);
    }
}

/// The block mesh of an arc profile: exact counts, the contract (outward normals, no
/// degenerate triangle), a closed solid whose volume is the profile's area times the height,
/// UV u along the top from the last fan point.
#[test]
fn arc_block_mesh_is_a_closed_outward_solid() {
    let midline = arc_midline([-0.375, 0.06], 15, WIDTH, 10.0);
    for fan in [0, 1, 4, 9] {
        let profile = left_profile(&midline, fan);
        let mut m = TriMesh::new();
        block_mesh(&mut m, &profile).unwrap();
        let n = midline.len();
        assert_eq!(m.vertex_count(), 4 * (2 * n + fan) + 8);
        assert_eq!(
            m.triangle_count(),
            2 * (2 * n + fan - 2) + 4 + 2 * (fan + 2 * n - 2)
        );
        assert_eq!(count(&m, Surface::BlockTop), 2 * (n + fan - 1));
        assert_eq!(count(&m, Surface::BlockBottom), 2 * (n - 1));
        check_mesh(&m, 1e-9, true);
        assert!(is_watertight(&m), "fan {fan}");

        let c = BlockCurves::new(&profile).unwrap();
        let mut outline: Vec<[f64; 2]> = c.bottom().to_vec();
        outline.extend(c.top().iter().rev());
        let area = shoelace(&outline).abs();
        let volume = signed_volume(&m);
        assert!(
            (volume - area * profile.height).abs() < 1e-4 * volume,
            "fan {fan}"
        );

        // z-extent and top UVs: u = 0 on the fan, 1 at the top's end (length = page width).
        for (k, p) in m.positions.iter().enumerate() {
            assert!((0.0..=17.0).contains(&p[2]), "vertex {k}");
        }
        let top = vertices_of(&m, Surface::BlockTop);
        let u_max = top
            .iter()
            .map(|&v| m.uvs[v][0])
            .fold(0.0, folio_tests::worst);
        assert!((f64::from(u_max) - polyline(&midline) / WIDTH).abs() < 1e-6);
        let u_zero = top.iter().filter(|&&v| m.uvs[v][0] == 0.0).count();
        assert_eq!(u_zero, 2 * (fan + 1), "the fan and its z copies have u = 0");
    }
}

/// An L-shaped midline (left 6, then down 6): the corner node is offset along the bisector,
/// the block mesh keeps the contract and is a closed solid.
#[test]
fn l_shaped_block() {
    let midline: Vec<[f64; 2]> = (0..=6)
        .map(|k| [-(k as f64), 0.0])
        .chain((1..=6).map(|k| [-6.0, -(k as f64)]))
        .collect();
    let profile = left_profile(&midline, 3);
    let c = BlockCurves::new(&profile).unwrap();
    let t = profile.thickness;
    let corner = c.adapted_top()[6];
    let s = t / 2f64.sqrt();
    assert!(
        dist(corner, [-6.0 - s, s]) < 1e-12,
        "corner offset {corner:?}"
    );
    for (k, &m) in midline.iter().enumerate().take(midline.len() - 1) {
        assert!((dist(c.adapted_top()[k], m) - t).abs() < 1e-12);
    }
    assert!((polyline(c.adapted_top()) - 12.0).abs() < 1e-12);
    let mut m = TriMesh::new();
    block_mesh(&mut m, &profile).unwrap();
    check_mesh(&m, 1e-9, true);
    assert!(is_watertight(&m));
    assert!(signed_volume(&m) > 0.0);
}

/// The right block is the mirror image of the left one: mirroring a left profile in X and
/// switching the side mirrors every position and normal, keeps the UVs and surfaces, and
/// reverses every triangle's winding.
#[test]
fn right_block_mirrors_left_block() {
    let left_mid = arc_midline([-0.375, 0.06], 15, WIDTH, 10.0);
    let right_mid: Vec<[f64; 2]> = left_mid.iter().map(|&p| mirror_x2(p)).collect();
    for fan in [0, 5] {
        let left = left_profile(&left_mid, fan);
        let right = BlockProfile {
            midline: &right_mid,
            side: BlockSide::Right,
            binding_direction: mirror_x2(left.binding_direction),
            ..left
        };
        let (mut l, mut r) = (TriMesh::new(), TriMesh::new());
        block_mesh(&mut l, &left).unwrap();
        block_mesh(&mut r, &right).unwrap();
        check_mesh(&r, 1e-9, true);
        assert_eq!(l.vertex_count(), r.vertex_count());
        assert_eq!(l.surfaces, r.surfaces);
        assert_eq!(l.uvs, r.uvs);
        let mirror3 = |v: [f32; 3]| [-v[0], v[1], v[2]];
        for k in 0..l.vertex_count() {
            assert!(dist(f64v(mirror3(l.positions[k])), f64v(r.positions[k])) < 1e-6);
            assert!(dist(f64v(mirror3(l.normals[k])), f64v(r.normals[k])) < 1e-6);
        }
        for (a, b) in l.triangles.iter().zip(&r.triangles) {
            assert_eq!([a[0], a[2], a[1]], *b);
        }
        assert!((signed_volume(&l) - signed_volume(&r)).abs() < 1e-6 * signed_volume(&l));
    }
}

/// The flat layout of two blocks (seed Sec. 3.1): both fans start at the binding's middle
/// and the two blocks together with their binding faces cover the binding edge.
#[test]
fn flat_blocks_meet_at_the_binding_middle() {
    let (b1, b2) = ([-0.375, 0.06], [0.375, 0.06]);
    let left_mid: Vec<[f64; 2]> = (0..15)
        .map(|k| [b1[0] - k as f64 * WIDTH / 14.0, b1[1]])
        .collect();
    let right_mid: Vec<[f64; 2]> = left_mid.iter().map(|&p| mirror_x2(p)).collect();
    let left = left_profile(&left_mid, 4);
    let right = BlockProfile {
        midline: &right_mid,
        side: BlockSide::Right,
        binding_direction: [-1.0, 0.0],
        ..left
    };
    let (l, r) = (
        BlockCurves::new(&left).unwrap(),
        BlockCurves::new(&right).unwrap(),
    );
    assert!(dist(l.top()[0], [0.0, 0.06]) < 1e-15);
    assert!(dist(r.top()[0], [0.0, 0.06]) < 1e-15);
    assert!(dist(l.fan_points()[4], [b1[0], b1[1] + 0.375]) < 1e-15);
    assert!(dist(r.fan_points()[4], [b2[0], b2[1] + 0.375]) < 1e-15);
    // Flat: no shear, the top is the midline lifted by t.
    for (top, mid) in l.adapted_top().iter().zip(&left_mid) {
        assert!(dist(*top, [mid[0], mid[1] + 0.375]) < 1e-12);
    }
    let mut m = TriMesh::new();
    block_mesh(&mut m, &left).unwrap();
    block_mesh(&mut m, &right).unwrap();
    check_mesh(&m, 1e-9, true);
    assert!(is_watertight(&m));
    let quarter_disc = 0.375 * 0.375 * (PI / 4.0);
    let expect = 2.0 * (WIDTH * 0.375 + quarter_disc) * 17.0;
    // The fan's polygon is inscribed in the quarter circle: a little less area.
    let v = signed_volume(&m);
    assert!(
        v < expect && v > expect - 2.0 * quarter_disc * 17.0 * 0.05,
        "{v} vs {expect}"
    );
}

// ---------------------------------------------------------------------------------------
// Cover

#[test]
fn cover_is_an_outward_box() {
    let cases: [([f64; 2], [f64; 2], [f64; 2]); 3] = [
        ([-0.375, 0.06], [-12.625, 0.06], [0.0, -1.0]),
        ([0.375, 0.06], [10.0, 5.0], [0.3, -1.0]), // slanted `down`: made perpendicular
        ([0.0, 0.0], [0.0, 3.0], [1.0, 0.0]),
    ];
    for (from, to, down) in cases {
        let mut m = TriMesh::new();
        cover_mesh(&mut m, from, to, down, 0.06, 17.0, 0.25).unwrap();
        assert_eq!((m.vertex_count(), m.triangle_count()), (24, 12));
        assert!(m.surfaces.iter().all(|&s| s == Surface::Cover));
        check_mesh(&m, 1e-9, true);
        assert!(is_watertight(&m));
        let volume = dist(from, to) * 0.06 * 17.5;
        assert!((signed_volume(&m) - volume).abs() < 1e-4 * volume);
        // The top face contains the segment and faces away from `down`.
        let z = m.positions.iter().map(|p| p[2]);
        let (zmin, zmax) = z.fold((f32::MAX, f32::MIN), |(a, b), z| {
            (folio_tests::least(a, z), folio_tests::worst(b, z))
        });
        assert_eq!((zmin, zmax), (-0.25, 17.25));
        let up = m
            .normals
            .iter()
            .filter(|n| f64::from(n[0]) * down[0] + f64::from(n[1]) * down[1] < -0.9 * len(down));
        assert_eq!(up.count(), 4);
    }
}

// ---------------------------------------------------------------------------------------
// Bad and degenerate input

#[test]
fn page_bad_input_gives_typed_errors_and_keeps_the_mesh() {
    let (grid, p) = flat_page(4, 3, 1.0, 1.0);
    let mut m = TriMesh::new();
    cover_mesh(&mut m, [0.0, 0.0], [1.0, 0.0], [0.0, -1.0], 0.1, 1.0, 0.0).unwrap();
    let before = m.clone();
    let mut bad = |grid: QuadGrid, p: &[[f64; 3]], t: f64, w: f64| {
        let e = page_mesh(&mut m, grid, p, t, w).unwrap_err();
        assert!(!e.to_string().is_empty());
        e
    };
    assert_eq!(
        bad(QuadGrid { nx: 1, nz: 3 }, &p[..3], T_PAGE, WIDTH),
        MeshError::TooFewNodes { found: 1 }
    );
    assert_eq!(
        bad(QuadGrid { nx: 0, nz: 0 }, &[], T_PAGE, WIDTH),
        MeshError::TooFewNodes { found: 0 }
    );
    assert_eq!(
        bad(
            QuadGrid {
                nx: usize::MAX,
                nz: 3
            },
            &p,
            T_PAGE,
            WIDTH
        ),
        MeshError::TooManyVertices { needed: usize::MAX }
    );
    assert_eq!(
        bad(grid, &p[1..], T_PAGE, WIDTH),
        MeshError::PositionCount {
            expected: 12,
            found: 11
        }
    );
    for (value, expected) in [
        (f64::NAN, MeshError::NonFinite { index: 5 }),
        (f64::NEG_INFINITY, MeshError::NonFinite { index: 5 }),
        (1e30, MeshError::CoordinateTooLarge { index: 5 }),
    ] {
        let mut q = p.clone();
        q[5][1] = value;
        assert_eq!(bad(grid, &q, T_PAGE, WIDTH), expected);
    }
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            bad(grid, &p, t, WIDTH),
            MeshError::NonPositive { field: "thickness" }
        );
    }
    assert_eq!(
        bad(grid, &p, 1e30, WIDTH),
        MeshError::OutOfRange { field: "thickness" }
    );
    assert_eq!(
        bad(grid, &p, T_PAGE, 0.0),
        MeshError::NonPositive {
            field: "page_width"
        }
    );
    assert_eq!(m, before, "a failed build leaves the mesh unchanged");
    assert!(PageSurfaces::new(grid, &p[2..], T_PAGE, WIDTH).is_err());
}

/// Coincident nodes, duplicated columns and rows, collinear rows: finite output with the
/// documented normal fallback (nearest earlier vertex, else +Y).
#[test]
fn degenerate_pages_give_finite_meshes() {
    let (grid, flat) = flat_page(5, 4, 1.0, 1.0);
    // Everything at one point: every normal falls back to +Y.
    let s = PageSurfaces::new(grid, &[[1.0, 2.0, 3.0]; 20], T_PAGE, WIDTH).unwrap();
    assert!(s.normals().iter().all(|&n| n == [0.0, 1.0, 0.0]));
    // A column collapsed onto its neighbour and a row collapsed onto its neighbour.
    let mut dup = flat.clone();
    for j in 0..4 {
        dup[grid.index(2, j)] = dup[grid.index(1, j)];
    }
    for i in 0..5 {
        dup[grid.index(i, 3)] = dup[grid.index(i, 2)];
    }
    // All nodes on one line (collinear differences): no normal anywhere.
    let line: Vec<[f64; 3]> = (0..20).map(|k| [k as f64, 0.0, 0.0]).collect();
    for p in [vec![[1.0, 2.0, 3.0]; 20], dup, line] {
        let mut m = TriMesh::new();
        page_mesh(&mut m, grid, &p, T_PAGE, WIDTH).unwrap();
        check_mesh(&m, 1e-9, false);
        let s = PageSurfaces::new(grid, &p, T_PAGE, WIDTH).unwrap();
        assert!(s.normals().iter().all(|n| (len(*n) - 1.0).abs() < 1e-12));
    }
    // A single degenerate vertex takes the normal of the vertex before it in index order:
    // (2, 1) loses its X difference when (3, 1) moves onto (1, 1), whose normal is tilted
    // by a bump at (1, 0).
    let mut p = flat.clone();
    p[grid.index(1, 0)][1] = 0.3;
    p[grid.index(3, 1)] = p[grid.index(1, 1)];
    let s = PageSurfaces::new(grid, &p, T_PAGE, WIDTH).unwrap();
    let tilted = s.normals()[grid.index(1, 1)];
    assert!(tilted[1] < 0.99 && (len(tilted) - 1.0).abs() < 1e-12);
    assert_eq!(s.normals()[grid.index(2, 1)], tilted);
}

#[test]
fn block_bad_input_gives_typed_errors() {
    let midline = arc_midline([0.0, 0.0], 5, WIDTH, 10.0);
    let mut m = TriMesh::new();
    let mut bad = |p: BlockProfile<'_>| {
        let e = block_mesh(&mut m, &p).unwrap_err();
        assert!(!e.to_string().is_empty());
        e
    };
    let ok = left_profile(&midline, 4);
    assert_eq!(
        bad(BlockProfile { midline: &[], ..ok }),
        MeshError::TooFewNodes { found: 0 }
    );
    assert_eq!(
        bad(BlockProfile {
            midline: &midline[..1],
            ..ok
        }),
        MeshError::TooFewNodes { found: 1 }
    );
    let mut nan = midline.clone();
    nan[3][0] = f64::NAN;
    assert_eq!(
        bad(BlockProfile {
            midline: &nan,
            ..ok
        }),
        MeshError::NonFinite { index: 3 }
    );
    assert_eq!(
        bad(BlockProfile {
            thickness: 0.0,
            ..ok
        }),
        MeshError::NonPositive { field: "thickness" }
    );
    assert_eq!(
        bad(BlockProfile { height: -1.0, ..ok }),
        MeshError::NonPositive { field: "height" }
    );
    assert_eq!(
        bad(BlockProfile {
            page_width: f64::NAN,
            ..ok
        }),
        MeshError::NonPositive {
            field: "page_width"
        }
    );
    assert_eq!(
        bad(BlockProfile {
            binding_direction: [f64::INFINITY, 0.0],
            ..ok
        }),
        MeshError::OutOfRange {
            field: "binding_direction"
        }
    );
    assert!(matches!(
        bad(BlockProfile {
            fan: usize::MAX,
            ..ok
        }),
        MeshError::TooManyVertices { .. }
    ));
    assert!(matches!(
        bad(BlockProfile { fan: 1 << 31, ..ok }),
        MeshError::TooManyVertices { .. }
    ));
    assert_eq!(m, TriMesh::new());
    let e: &dyn core::error::Error = &MeshError::TooFewNodes { found: 1 };
    assert!(e.to_string().contains('1'));
}

/// Duplicate nodes, a fully collapsed midline, a zero or collinear or reversed binding
/// direction, a folded midline: finite meshes (zero-area triangles allowed where points
/// coincide), and every triangle with area faces its normals.
#[test]
fn degenerate_blocks_give_finite_meshes() {
    let arc = arc_midline([-0.375, 0.06], 8, WIDTH, 10.0);
    let mut dup = arc.clone();
    dup.insert(0, dup[0]);
    dup.insert(4, dup[4]);
    dup.push(*dup.last().unwrap());
    let folded = vec![[0.0, 0.0], [-3.0, 0.0], [0.0, 0.0], [-3.0, 0.0]];
    let collapsed = vec![[0.5, 0.5]; 6];
    // (midline, binding direction, triangles with area face their normals)
    let cases: Vec<(Vec<[f64; 2]>, [f64; 2], bool)> = vec![
        (dup, [1.0, 0.0], true),
        (collapsed, [1.0, 0.0], true),
        (arc.clone(), [0.0, 0.0], true), // zero: the fan collapses onto n0
        (arc.clone(), [0.0, 1.0], true), // nearly n0: a narrow fan
        (arc.clone(), [0.0, -1.0], true), // against n0: the half turn behind the binding
        (arc.clone(), [-1.0, 0.0], true), // along the midline: projected, collapses
        (arc.clone(), [-1.0, -1e-300], true),
        (folded, [1.0, 0.0], false), // folded onto itself: only finite
    ];
    for (midline, dir, oriented) in cases {
        for side in [BlockSide::Left, BlockSide::Right] {
            let p = BlockProfile {
                side,
                binding_direction: dir,
                ..left_profile(&midline, 4)
            };
            let c = BlockCurves::new(&p).unwrap();
            for q in c.fan_points() {
                let b = midline[0];
                assert!(
                    (dist(*q, b) - p.thickness).abs() < 1e-12,
                    "{midline:?} {dir:?}"
                );
            }
            let mut m = TriMesh::new();
            block_mesh(&mut m, &p).unwrap();
            if oriented {
                check_mesh(&m, 1e-9, false);
            } else {
                assert!(
                    m.positions
                        .iter()
                        .chain(&m.normals)
                        .flatten()
                        .all(|c| c.is_finite())
                );
            }
        }
    }
    // The half turn: fan points from -n0 through -t0 to n0, all behind the binding node.
    let p = BlockProfile {
        binding_direction: [0.0, -1.0],
        ..left_profile(&arc, 4)
    };
    let c = BlockCurves::new(&p).unwrap();
    let b = arc[0];
    let t0 = [
        (arc[1][0] - b[0]) / dist(arc[1], b),
        (arc[1][1] - b[1]) / dist(arc[1], b),
    ];
    let n0 = [t0[1], -t0[0]];
    let at = |d: [f64; 2]| [b[0] + 0.375 * d[0], b[1] + 0.375 * d[1]];
    let fans = c.fan_points();
    assert!(dist(fans[0], at([-n0[0], -n0[1]])) < 1e-12);
    assert!(dist(fans[2], at([-t0[0], -t0[1]])) < 1e-12);
    assert!(dist(fans[4], at(n0)) < 1e-12);
    let behind = |q: &[f64; 2]| (q[0] - b[0]) * t0[0] + (q[1] - b[1]) * t0[1] <= 1e-12;
    assert!(fans.iter().all(behind));
}

#[test]
fn cover_bad_and_degenerate_input() {
    let mut m = TriMesh::new();
    let (a, b, d) = ([0.0, 0.0], [5.0, 0.0], [0.0, -1.0]);
    let err = |m: &mut TriMesh, from, to, down, t, h, o| {
        cover_mesh(m, from, to, down, t, h, o).unwrap_err()
    };
    assert_eq!(
        err(&mut m, [f64::NAN, 0.0], b, d, 0.1, 1.0, 0.0),
        MeshError::OutOfRange { field: "from" }
    );
    assert_eq!(
        err(&mut m, a, [1e21, 0.0], d, 0.1, 1.0, 0.0),
        MeshError::OutOfRange { field: "to" }
    );
    assert_eq!(
        err(&mut m, a, b, [0.0, f64::NAN], 0.1, 1.0, 0.0),
        MeshError::OutOfRange { field: "down" }
    );
    assert_eq!(
        err(&mut m, a, b, d, 0.0, 1.0, 0.0),
        MeshError::NonPositive { field: "thickness" }
    );
    assert_eq!(
        err(&mut m, a, b, d, 0.1, 0.0, 0.0),
        MeshError::NonPositive { field: "height" }
    );
    assert_eq!(
        err(&mut m, a, b, d, 0.1, 1.0, -0.1),
        MeshError::OutOfRange { field: "overhang" }
    );
    assert_eq!(m, TriMesh::new());
    // Zero-length segment, zero `down`, `down` along the segment: finite boxes.
    for (from, to, down) in [(a, a, d), (a, b, [0.0, 0.0]), (a, b, [2.0, 0.0])] {
        let mut m = TriMesh::new();
        cover_mesh(&mut m, from, to, down, 0.1, 1.0, 0.0).unwrap();
        check_mesh(&m, 1e-9, false);
    }
    // The fallback `down` for a zero vector is the clockwise perpendicular: −Y under +X.
    let mut m = TriMesh::new();
    cover_mesh(&mut m, a, b, [0.0, 0.0], 0.1, 1.0, 0.0).unwrap();
    assert!(m.positions.iter().all(|p| p[1] <= 0.0));
}

/// Random input, including NaN, infinities, huge and tiny values and duplicate nodes: every
/// builder returns an error or a mesh with finite data, and never panics.
#[test]
fn random_input_never_panics_or_yields_nan() {
    let mut rng = Rng::new(2024);
    let special = [
        f64::NAN,
        f64::INFINITY,
        -1e25,
        1e19,
        0.0,
        -0.0,
        1e-300,
        5e-324,
    ];
    let value = |rng: &mut Rng| -> f64 {
        match rng.next_u64() % 10 {
            0 => special[(rng.next_u64() % special.len() as u64) as usize],
            1 => 0.0,
            _ => rng.uniform(-3.0, 3.0),
        }
    };
    let finite = |m: &TriMesh| {
        m.positions
            .iter()
            .chain(&m.normals)
            .all(|v| v.iter().all(|c| c.is_finite()))
            && m.uvs.iter().all(|v| v.iter().all(|c| c.is_finite()))
    };
    for _ in 0..300 {
        let nx = (rng.next_u64() % 5) as usize;
        let nz = (rng.next_u64() % 5) as usize;
        let grid = QuadGrid { nx, nz };
        let p: Vec<[f64; 3]> = (0..nx * nz)
            .map(|_| [value(&mut rng), value(&mut rng), value(&mut rng)])
            .collect();
        let mut m = TriMesh::new();
        if page_mesh(&mut m, grid, &p, value(&mut rng).abs(), value(&mut rng)).is_ok() {
            assert!(finite(&m));
        }

        let n = (rng.next_u64() % 6) as usize;
        let midline: Vec<[f64; 2]> = (0..n).map(|_| [value(&mut rng), value(&mut rng)]).collect();
        let profile = BlockProfile {
            midline: &midline,
            side: if rng.next_u64() % 2 == 0 {
                BlockSide::Left
            } else {
                BlockSide::Right
            },
            thickness: value(&mut rng).abs(),
            height: value(&mut rng).abs(),
            binding_direction: [value(&mut rng), value(&mut rng)],
            page_width: value(&mut rng).abs(),
            fan: (rng.next_u64() % 6) as usize,
        };
        let mut m = TriMesh::new();
        if block_mesh(&mut m, &profile).is_ok() {
            assert!(finite(&m));
        }

        let mut m = TriMesh::new();
        let v2 = |rng: &mut Rng| [value(rng), value(rng)];
        let (from, to, down) = (v2(&mut rng), v2(&mut rng), v2(&mut rng));
        let (t, h, o) = (value(&mut rng), value(&mut rng), value(&mut rng));
        if cover_mesh(&mut m, from, to, down, t, h, o).is_ok() {
            assert!(finite(&m));
        }
    }
}

/// Builders append: indices of a later part point past the earlier parts' vertices.
#[test]
fn builders_append_to_one_mesh() {
    let (grid, p) = flat_page(4, 3, 4.0, 1.0);
    let midline = arc_midline([-0.375, 0.06], 6, WIDTH, 10.0);
    let mut m = TriMesh::new();
    page_mesh(&mut m, grid, &p, T_PAGE, WIDTH).unwrap();
    let (v1, t1) = (m.vertex_count(), m.triangle_count());
    block_mesh(&mut m, &left_profile(&midline, 2)).unwrap();
    let (v2, t2) = (m.vertex_count(), m.triangle_count());
    cover_mesh(
        &mut m,
        [0.0, 0.0],
        [-12.0, 0.0],
        [0.0, -1.0],
        0.06,
        17.0,
        0.25,
    )
    .unwrap();
    assert!(
        m.triangles[..t1]
            .iter()
            .flatten()
            .all(|&v| (v as usize) < v1)
    );
    assert!(
        m.triangles[t1..t2]
            .iter()
            .flatten()
            .all(|&v| (v1..v2).contains(&(v as usize)))
    );
    assert!(
        m.triangles[t2..]
            .iter()
            .flatten()
            .all(|&v| (v as usize) >= v2)
    );
    check_mesh(&m, 1e-9, true);
    assert!(is_watertight(&m));
}
