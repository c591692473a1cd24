//! A page block's mesh (seed `000_…` Sec. 3.5): the planar midline (the block's bottom,
//! Sec. 3.1) offset in XY by the block's thickness gives the top curve, rounded at the
//! binding by a fan of offset directions ("upsampling at binding") and length-adapted to the
//! midline ("segment length adaptation", the sheared fore-edge of Fig. 9); the profile is
//! extruded along Z.

use alloc::vec::Vec;

use folio_kernels::math;

use super::adapt::adapt_length;
use super::error::{MeshError, check_points, check_positive, check_vector};
use super::trimesh::{Surface, TriMesh};
use super::vector::{
    add, arc_parameter, dot, fill_backward, fill_forward, lift, polyline_length, scale, sub, unit,
};

/// The side of the book a page block lies on. The left block's material lies on the
/// right-hand side of its midline's direction of travel (the tangent rotated by −90°,
/// $(t_y, -t_x)$), the right block's on the left-hand side, $(-t_y, t_x)$.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockSide {
    /// The left block (X < 0).
    Left,
    /// The right block (X > 0).
    Right,
}

impl BlockSide {
    /// The other side.
    #[must_use]
    pub fn opposite(self) -> Self {
        match self {
            Self::Left => Self::Right,
            Self::Right => Self::Left,
        }
    }
}

/// The unit normal on `side`'s material side of the unit direction `t`.
fn material_normal(side: BlockSide, t: [f64; 2]) -> [f64; 2] {
    match side {
        BlockSide::Left => [t[1], -t[0]],
        BlockSide::Right => [-t[1], t[0]],
    }
}

/// The midline direction of a block lying flat, running outward from the binding:
/// −X on the left, +X on the right (material side +Y for both).
fn flat_tangent(side: BlockSide) -> [f64; 2] {
    match side {
        BlockSide::Left => [-1.0, 0.0],
        BlockSide::Right => [1.0, 0.0],
    }
}

/// A page block's profile: its planar midline (the bottom of the block, seed `000_…`
/// Sec. 3.1), starting at the block's binding node and running outward to the fore-edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockProfile<'a> {
    /// Midline nodes in XY, at least 2; `midline[0]` is the binding node.
    pub midline: &'a [[f64; 2]],
    /// Which side the block's material lies on ([`BlockSide`]).
    pub side: BlockSide,
    /// Offset distance, $> 0$ (pages times page thickness).
    pub thickness: f64,
    /// Z extent, $> 0$: the block spans $z \in [0, \text{height}]$.
    pub height: f64,
    /// Direction along the binding edge from this block's binding node into the book (for
    /// the left block $b_2 - b_1$, for the right block $b_1 - b_2$); normalized here.
    pub binding_direction: [f64; 2],
    /// Page width, $> 0$: the length scale of the texture coordinate along the profile.
    pub page_width: f64,
    /// Extra offset directions at the binding node (upsampling); 0 gives the plain offset.
    pub fan: usize,
}

/// A page block's profile curves in `f64` (seed `000_…` Sec. 3.5), before extrusion.
///
/// With midline nodes $m_0, \dots, m_{n-1}$, unit segment tangents $t_k$ and segment normals
/// $s_k$ on the material side ([`BlockSide`]), the node normal is
/// $n_k = (s_{k-1} + s_k)/\lVert\cdot\rVert$ ($s_0$ and $s_{n-2}$ at the ends). The top curve
/// is the fan $m_0 + t\thinspace d_q$, $q = 0, \dots, F$ (with $F$ = `fan`) followed by
/// $m_k + t\thinspace n_k$, $k = 1, \dots, n-1$; its part from the last fan point on (which has $n$
/// nodes, one per midline node) is then length-adapted to the midline's length
/// ([`adapt_length`]), which shears the fore-edge.
///
/// Fan ("upsampling at binding"): in the frame $e_1 = n_0$, $e_2 = -t_0$, with $d$ the unit
/// binding direction, $\beta = \operatorname{atan2}(\max(d \cdot e_2, 0),\ d \cdot e_1)
/// \in [0, \pi]$ and
/// $$d_q = \cos\theta_q\thinspace e_1 + \sin\theta_q\thinspace e_2, \qquad \theta_q = \beta\thinspace(1 - q/F),$$
/// so $d_0 = d$, $d_F = n_0$ and the directions are uniformly distributed in angle between
/// them, sweeping around the binding end of the block (a rounded profile). $F = 0$ gives the
/// single direction $n_0$ (the plain offset).
///
/// Fallbacks: zero-length segments are skipped, i.e. a node averages the normals of the
/// nearest segments of nonzero length before and after it (so coincident nodes get the same
/// offset point), and $t_0$ is the first such segment's tangent; a midline without any such
/// segment is treated as a block lying flat (tangent −X left, +X right, material side +Y);
/// a node whose two segment normals cancel (a folded midline) takes the earlier segment's
/// normal; a zero binding direction is replaced by $n_0$. A binding direction pointing
/// along the midline ($d \cdot e_2 \le 0$) is projected onto the line of $n_0$, so that the
/// fan never folds over the top: on the material side the fan collapses onto $n_0$
/// (coincident points, zero-area triangles), behind it the fan is the half turn from $-n_0$
/// through $-t_0$ to $n_0$.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockCurves {
    side: BlockSide,
    fan: usize,
    /// Unit tangents of the midline's first and last segments.
    end_tangents: [[f64; 2]; 2],
    bottom: Vec<[f64; 2]>,
    bottom_normals: Vec<[f64; 2]>,
    top: Vec<[f64; 2]>,
    top_normals: Vec<[f64; 2]>,
}

impl BlockCurves {
    /// The curves of `profile` (type docs).
    ///
    /// # Errors
    /// [`MeshError::TooFewNodes`] for fewer than 2 midline nodes, [`MeshError::NonFinite`]
    /// and [`MeshError::CoordinateTooLarge`] for a bad node, [`MeshError::NonPositive`] and
    /// [`MeshError::OutOfRange`] for a bad `thickness`, `height`, `page_width` or
    /// `binding_direction` (not finite), [`MeshError::TooManyVertices`] if the block's mesh
    /// could not have `u32` indices.
    pub fn new(profile: &BlockProfile<'_>) -> Result<Self, MeshError> {
        check_profile(profile)?;
        let BlockProfile {
            midline,
            side,
            thickness,
            fan,
            ..
        } = *profile;
        // Segment tangents, `None` for a zero-length segment; each node uses the nearest
        // valid ones before and after it.
        let raw: Vec<Option<[f64; 2]>> =
            midline.windows(2).map(|w| unit(sub(w[1], w[0]))).collect();
        let (before, after) = (fill_forward(&raw), fill_backward(&raw));
        let node_normals: Vec<[f64; 2]> = (0..midline.len())
            .map(|k| {
                let b = k
                    .checked_sub(1)
                    .and_then(|i| before.get(i))
                    .copied()
                    .flatten();
                let a = after.get(k).copied().flatten();
                node_normal(side, b, a)
            })
            .collect();
        let flat = flat_tangent(side);
        let end_tangents = [
            after.first().copied().flatten().unwrap_or(flat),
            before.last().copied().flatten().unwrap_or(flat),
        ];
        let n0 = material_normal(side, end_tangents[0]);
        let mut top_normals = fan_directions(n0, end_tangents[0], profile.binding_direction, fan);
        top_normals.extend(node_normals.iter().skip(1).copied());
        let origins =
            core::iter::repeat_n(midline[0], fan + 1).chain(midline.iter().skip(1).copied());
        let mut top: Vec<[f64; 2]> = origins
            .zip(&top_normals)
            .map(|(m, &n)| add(m, scale(n, thickness)))
            .collect();
        if let Some(adapted) = top.get_mut(fan..) {
            adapt_length(adapted, polyline_length(midline));
        }
        Ok(Self {
            side,
            fan,
            end_tangents,
            bottom: midline.to_vec(),
            bottom_normals: node_normals.iter().map(|&n| scale(n, -1.0)).collect(),
            top,
            top_normals,
        })
    }

    /// The block's side.
    #[must_use]
    pub fn side(&self) -> BlockSide {
        self.side
    }

    /// The bottom curve: the midline.
    #[must_use]
    pub fn bottom(&self) -> &[[f64; 2]] {
        &self.bottom
    }

    /// Outward unit normals of the bottom, $-n_k$.
    #[must_use]
    pub fn bottom_normals(&self) -> &[[f64; 2]] {
        &self.bottom_normals
    }

    /// The top curve: `fan + 1` fan points, then one point per midline node after the first
    /// (`midline.len() + fan` points), the last one length-adapted.
    #[must_use]
    pub fn top(&self) -> &[[f64; 2]] {
        &self.top
    }

    /// Outward unit normals of the top: the offset directions $d_q$, then $n_k$ (the normal
    /// of the offset curve of a smooth midline).
    #[must_use]
    pub fn top_normals(&self) -> &[[f64; 2]] {
        &self.top_normals
    }

    /// The fan points, `top()[..=fan]`.
    #[must_use]
    pub fn fan_points(&self) -> &[[f64; 2]] {
        self.top.get(..=self.fan).unwrap_or(&[])
    }

    /// The top curve from the last fan point on, one point per midline node.
    #[must_use]
    pub fn adapted_top(&self) -> &[[f64; 2]] {
        self.top.get(self.fan..).unwrap_or(&[])
    }

    /// Appends the extruded block to `out` ([`block_mesh`]).
    fn append(&self, out: &mut TriMesh, height: f64, page_width: f64) -> Result<(), MeshError> {
        let (n, m) = (self.bottom.len(), self.top.len());
        let (vertices, triangles) =
            mesh_counts(n, self.fan).ok_or(MeshError::TooManyVertices { needed: usize::MAX })?;
        out.reserve_for(vertices, triangles)?;
        let first_triangle = out.triangle_count();
        let u_bottom = arc_parameter(&self.bottom, page_width);
        let mut u_top = alloc::vec![0.0; self.fan];
        u_top.extend(arc_parameter(self.adapted_top(), page_width));

        // Windings are built for the left side, where the strip from a curve's z = 0 row to
        // its z = h row faces the material-side normal of the curve's direction of travel
        // (and the reverse strip faces away from it). The right side is the mirror image:
        // the same construction with every winding reversed at the end.
        let top_first = push_extruded(out, &self.top, &self.top_normals, &u_top, height);
        out.push_strip(top_first, top_first + m, m, Surface::BlockTop);
        let bottom_first =
            push_extruded(out, &self.bottom, &self.bottom_normals, &u_bottom, height);
        out.push_strip(bottom_first + n, bottom_first, n, Surface::BlockBottom);
        let (b_last, t_last) = (self.bottom[n - 1], self.top[m - 1]);
        let fore = self.cap_normal(b_last, t_last, -1.0, self.end_tangents[1]);
        let fore_first = push_extruded(out, &[b_last, t_last], &[fore; 2], &[0.0, 1.0], height);
        out.push_strip(fore_first + 2, fore_first, 2, Surface::BlockEdge);
        let (b0, t0) = (self.bottom[0], self.top[0]);
        let spine = self.cap_normal(b0, t0, 1.0, scale(self.end_tangents[0], -1.0));
        let spine_first = push_extruded(out, &[b0, t0], &[spine; 2], &[0.0, 1.0], height);
        out.push_strip(spine_first, spine_first + 2, 2, Surface::BlockEdge);
        self.push_end_cap(out, 0.0, &u_bottom, &u_top);
        let far_cap = out.triangle_count();
        self.push_end_cap(out, height, &u_bottom, &u_top);
        out.reverse_winding_from(far_cap);
        if self.side == BlockSide::Right {
            out.reverse_winding_from(first_triangle);
        }
        Ok(())
    }

    /// Unit normal of the flat face joining the bottom point `b` and the top point `t`:
    /// `sign` times the material-side normal of $t - b$ (−1 for the fore-edge, +1 for the
    /// binding face, both pointing away from the block); `fallback` if $t = b$.
    fn cap_normal(&self, b: [f64; 2], t: [f64; 2], sign: f64, fallback: [f64; 2]) -> [f64; 2] {
        unit(sub(t, b)).map_or(fallback, |e| scale(material_normal(self.side, e), sign))
    }

    /// Appends an end cap at height `z` (normal −Z, for the cap at `z = 0`): the region
    /// between the bottom and the top curves, as the fan from the binding node to the fan
    /// points followed by the strip between corresponding bottom and top nodes.
    /// UVs: $u$ as on the curves, $v = 0$ on the bottom and $1$ on the top.
    fn push_end_cap(&self, out: &mut TriMesh, z: f64, u_bottom: &[f64], u_top: &[f64]) {
        let normal = if z > 0.0 {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 0.0, -1.0]
        };
        let bottom = out.vertex_count();
        for (&p, &u) in self.bottom.iter().zip(u_bottom) {
            out.push_vertex(lift(p, z), normal, [u, 0.0]);
        }
        let top = out.vertex_count();
        for (&p, &u) in self.top.iter().zip(u_top) {
            out.push_vertex(lift(p, z), normal, [u, 1.0]);
        }
        out.push_fan(bottom, top, self.fan + 1, Surface::BlockEdge);
        out.push_strip(
            bottom,
            top + self.fan,
            self.bottom.len(),
            Surface::BlockEdge,
        );
    }
}

/// Node normal $n_k$ from the nearest valid segment tangents `before` and `after` the node
/// (type docs of [`BlockCurves`]).
fn node_normal(side: BlockSide, before: Option<[f64; 2]>, after: Option<[f64; 2]>) -> [f64; 2] {
    let normal = |t| material_normal(side, t);
    match (before.map(normal), after.map(normal)) {
        (Some(b), Some(a)) => unit(add(b, a)).unwrap_or(b),
        (Some(n), None) | (None, Some(n)) => n,
        (None, None) => normal(flat_tangent(side)),
    }
}

/// The `fan + 1` offset directions at the binding node (type docs of [`BlockCurves`]).
fn fan_directions(n0: [f64; 2], t0: [f64; 2], binding: [f64; 2], fan: usize) -> Vec<[f64; 2]> {
    let (e1, e2) = (n0, scale(t0, -1.0));
    let d = unit(binding).unwrap_or(n0);
    let beta = math::atan2::<f64>(dot(d, e2).max(0.0), dot(d, e1));
    (0..=fan)
        .map(|q| {
            let theta = if fan == 0 {
                0.0
            } else {
                beta * (1.0 - q as f64 / fan as f64)
            };
            add(
                scale(e1, math::cos::<f64>(theta)),
                scale(e2, math::sin::<f64>(theta)),
            )
        })
        .collect()
}

/// Appends the XY `curve` at $z = 0$ and at $z = h$ (two rows of `curve.len()` vertices)
/// with normals `normals` (Z = 0) and UVs $(u_k, z/h)$; returns the first row's first index.
fn push_extruded(
    out: &mut TriMesh,
    curve: &[[f64; 2]],
    normals: &[[f64; 2]],
    u: &[f64],
    height: f64,
) -> usize {
    let first = out.vertex_count();
    for (z, v) in [(0.0, 0.0), (height, 1.0)] {
        for ((&p, &n), &u) in curve.iter().zip(normals).zip(u) {
            out.push_vertex(lift(p, z), lift(n, 0.0), [u, v]);
        }
    }
    first
}

/// Vertex and triangle counts of a block with `n` midline nodes and fan `fan` (top curve
/// of $m = n + F$ points): top $2m$, bottom $2n$, fore-edge and binding faces $4 + 4$, end
/// caps $2(n + m)$ vertices; $2(m-1) + 2(n-1) + 2 + 2 + 2(F + 2(n-1))$ triangles. `None`
/// if a count overflows or exceeds `u32` indices.
fn mesh_counts(n: usize, fan: usize) -> Option<(usize, usize)> {
    let m = n.checked_add(fan)?;
    let curves = n.checked_add(m)?;
    let vertices = curves.checked_mul(4)?.checked_add(8)?;
    let cap_triangles = fan.checked_add(n.checked_sub(1)?.checked_mul(2)?)?;
    let triangles = curves
        .checked_sub(2)?
        .checked_mul(2)?
        .checked_add(4)?
        .checked_add(cap_triangles.checked_mul(2)?)?;
    u32::try_from(vertices).ok()?;
    Some((vertices, triangles))
}

/// `Ok` for a usable profile (errors of [`BlockCurves::new`]).
fn check_profile(profile: &BlockProfile<'_>) -> Result<(), MeshError> {
    let n = profile.midline.len();
    if n < 2 {
        return Err(MeshError::TooFewNodes { found: n });
    }
    check_points(profile.midline)?;
    check_positive("thickness", profile.thickness)?;
    check_positive("height", profile.height)?;
    check_positive("page_width", profile.page_width)?;
    check_vector("binding_direction", profile.binding_direction, false)?;
    mesh_counts(n, profile.fan).ok_or(MeshError::TooManyVertices { needed: usize::MAX })?;
    Ok(())
}

/// Appends a page block (seed `000_…` Sec. 3.5): the [`BlockCurves`] of `profile` extruded
/// along Z over $[0, h]$ ($h$ = `height`):
///
/// - the top surface (`BlockTop`), normals $d_q$ / $n_k$, UV $u$ = arc length from the last
///   fan point / `page_width` (0 on the fan), $v = z/h$;
/// - the bottom surface (`BlockBottom`), normals $-n_k$, UV $u$ = arc length / `page_width`;
/// - the fore-edge face joining the last bottom and top points (`BlockEdge`, normal pointing
///   forward) and the binding face joining the binding node and the first fan point
///   (`BlockEdge`, pointing back: with a fan it lies along the binding edge), UV
///   $u = 0$ bottom, $1$ top, $v = z/h$; with them the block is a closed solid;
/// - the end caps at $z = 0$ and $z = h$ (`BlockEdge`, normals ∓Z): the fan from the binding
///   node to the fan points and the strip between corresponding bottom and top nodes.
///
/// All normals point out of the block; counts as in the private `mesh_counts`:
/// $4(2n + F) + 8$ vertices and $2(2n + F - 2) + 4 + 2(F + 2n - 2)$ triangles for $n$
/// midline nodes and $F$ = `fan`.
///
/// # Errors
/// As [`BlockCurves::new`], and [`MeshError::TooManyVertices`] if `out` would exceed `u32`
/// indices. On error `out` is unchanged.
pub fn block_mesh(out: &mut TriMesh, profile: &BlockProfile<'_>) -> Result<(), MeshError> {
    BlockCurves::new(profile)?.append(out, profile.height, profile.page_width)
}
