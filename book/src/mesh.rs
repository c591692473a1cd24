//! The whole book as one render mesh (seed `000_…` Sec. 3.5 "Meshing", Fig. 9): both page
//! blocks, the hard cover, the active page and every page in flight, appended to a
//! [`TriMesh`] by the builders of [`folio_geometry::mesh`].

use alloc::vec::Vec;

use crate::layout::material_normal;
use folio_geometry::BlockSide;
use folio_geometry::mesh::{BlockProfile, MeshError, TriMesh, block_mesh, cover_mesh, page_mesh};
use folio_kernels::{Real, Vec3Ops};

use super::simulation::Book;

/// Extra offset directions at each block's binding node ([`BlockProfile::fan`]): the
/// rounded profile of "upsampling at binding" (seed Sec. 3.5, Fig. 9), here four
/// directions between the binding direction and the block's normal (22.5° apart for a
/// block lying flat).
pub const BINDING_FAN: usize = 4;

/// The XY part of a node.
fn xy<T: Real>(p: T::Vec3) -> [f64; 2] {
    [p.x().to_f64(), p.y().to_f64()]
}

/// A node in `f64`.
fn xyz<T: Real>(p: T::Vec3) -> [f64; 3] {
    [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()]
}

impl<T: Real> Book<T> {
    /// Appends the whole book to `out` (seed `000_…` Sec. 3.5), in this order:
    ///
    /// 1. the page blocks, left then right ([`block_mesh`]): profile = the block's midline
    ///    ([`Book::midline`], XY), thickness [`Book::block_thickness`], height $H$ and page
    ///    width $W$ from the layout, binding direction $b_2 - b_1$ (left) or $b_1 - b_2$
    ///    (right) from the layout's binding nodes, [`BINDING_FAN`] fan directions;
    ///    a block without pages (thickness 0) is skipped;
    /// 2. with a cover (`params.cover`, of nonzero `cover_thickness`), three boards
    ///    ([`cover_mesh`]), each `cover_thickness` deep and reaching `cover_overhang` past
    ///    the pages at head and tail: the left and right boards under the segments from each
    ///    block's binding node to its cover node (on the side away from the block's pages,
    ///    $-n_{\text{material}}$), and the spine under the binding edge from the left to the
    ///    right binding node (−Y);
    /// 3. the active page, if any ([`page_mesh`] on [`Book::page`] with the page grid and
    ///    thickness [`Book::active_thickness`]);
    /// 4. every page in flight ([`Book::flips`], [`Book::flip_page`]), one page thick.
    ///
    /// Allocates temporary `f64` copies of the nodes.
    ///
    /// # Errors
    /// The first [`MeshError`] of a builder (a NaN or too large node, a mesh beyond `u32`
    /// indices); `out` is then restored to what it held before the call.
    pub fn mesh(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        let (vertices, triangles) = (out.vertex_count(), out.triangle_count());
        let result = self.append_mesh(out);
        if result.is_err() {
            out.positions.truncate(vertices);
            out.normals.truncate(vertices);
            out.uvs.truncate(vertices);
            out.triangles.truncate(triangles);
            out.surfaces.truncate(triangles);
        }
        result
    }

    /// [`Book::mesh`] without the restore on error.
    fn append_mesh(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        self.append_blocks(out)?;
        self.append_cover(out)?;
        self.append_pages(out)
    }

    /// Step 1 of [`Book::mesh`]: the page blocks.
    fn append_blocks(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        let layout = self.layout();
        let params = &layout.params;
        let [b1, b2] = layout.binding;
        for (side, direction) in [
            (BlockSide::Left, [b2[0] - b1[0], b2[1] - b1[1]]),
            (BlockSide::Right, [b1[0] - b2[0], b1[1] - b2[1]]),
        ] {
            let thickness = self.block_thickness(side).to_f64();
            if thickness <= 0.0 {
                continue;
            }
            let midline: Vec<[f64; 2]> = self.midline(side).iter().map(|&p| xy::<T>(p)).collect();
            let profile = BlockProfile {
                midline: &midline,
                side,
                thickness,
                height: params.page_height(),
                binding_direction: direction,
                page_width: params.page_width,
                fan: BINDING_FAN,
            };
            block_mesh(out, &profile)?;
        }
        Ok(())
    }

    /// Step 2 of [`Book::mesh`]: the cover boards and the spine.
    fn append_cover(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        let params = &self.layout().params;
        if !(params.cover && params.cover_thickness > 0.0) {
            return Ok(());
        }
        let height = params.page_height();
        let nodes = self.nodes();
        let x = &self.state().x;
        let binding =
            |side: BlockSide| self.midline(side).first().map_or([0.0; 2], |&p| xy::<T>(p));
        for side in [BlockSide::Left, BlockSide::Right] {
            let from = binding(side);
            let end = nodes.cover_end(side == BlockSide::Right);
            let to = x.get(end).map_or(from, |&p| xy::<T>(p));
            let up = material_normal(side, [to[0] - from[0], to[1] - from[1]]);
            let down = [-up[0], -up[1]];
            cover_mesh(
                out,
                from,
                to,
                down,
                params.cover_thickness,
                height,
                params.cover_overhang,
            )?;
        }
        cover_mesh(
            out,
            binding(BlockSide::Left),
            binding(BlockSide::Right),
            [0.0, -1.0],
            params.cover_thickness,
            height,
            params.cover_overhang,
        )
    }

    /// Steps 3 and 4 of [`Book::mesh`]: the active page and the pages in flight.
    fn append_pages(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        let Some(page) = self.page() else {
            return Ok(());
        };
        let params = &self.layout().params;
        let width = params.page_width;
        let grid = self.nodes().grid;
        let active = self.active_thickness().to_f64();
        if active > 0.0 {
            let positions: Vec<[f64; 3]> = page.iter().map(|&p| xyz::<T>(p)).collect();
            page_mesh(out, grid, &positions, active, width)?;
        }
        let mut flying = alloc::vec![T::Vec3::ZERO; grid.len()];
        for k in 0..self.flips().len() {
            self.flip_page(k, &mut flying);
            let positions: Vec<[f64; 3]> = flying.iter().map(|&p| xyz::<T>(p)).collect();
            page_mesh(out, grid, &positions, params.page_thickness, width)?;
        }
        Ok(())
    }
}
