//! Grab and drag (seed `000_…` Sec. 3.3, 4.1): a grab by ray or by material point turns the
//! top pages of a block into the active page laid on that block and holds one of its ring
//! nodes; a drag moves the held node's target through the drag plane and the tent, and each
//! step pulls the node towards it on a leash.

use crate::layout::{distance, offset_curve, resample, spine_arc, walk_chords};
use alloc::vec::Vec;
use folio_geometry::BlockSide;
use folio_kernels::{Real, Vec3Ops, math};

use super::error::BookError;
use super::interaction::{Ray, Tent};
use super::outcome::{DragOutcome, GrabOutcome};
use super::pad::{interpolate, pad_point, pad_samples};
use super::simulation::{ActivePage, Book, Hold};

/// The node of `nodes` with the smallest `distance` (NaN counts as farthest); `None` only
/// for no nodes. Always one of `nodes`, whatever the distances: a grab never holds a node
/// that is not a page node.
fn nearest(nodes: &[usize], distance: impl Fn(usize) -> f64) -> Option<usize> {
    nodes
        .iter()
        .map(|&node| (distance(node), node))
        .min_by(|a, b| match (a.0.is_nan(), b.0.is_nan()) {
            (false, false) => a.0.total_cmp(&b.0),
            (a_nan, _) => a_nan.cmp(&b.0.is_nan()),
        })
        .map(|(_, node)| node)
}

/// `true` when every coordinate of `v` is finite.
fn vec_finite<T: Real>(v: T::Vec3) -> bool {
    v.x().is_finite() && v.y().is_finite() && v.z().is_finite()
}

impl<T: Real> Book<T> {
    /// The top surface of the block on `side` offset by `extra`, as an XY curve from the
    /// binding outward.
    fn block_surface(&self, side: BlockSide, extra: T) -> Vec<[f64; 2]> {
        let midline: Vec<[f64; 2]> = self
            .midline(side)
            .iter()
            .map(|p| [p.x().to_f64(), p.y().to_f64()])
            .collect();
        offset_curve(
            &midline,
            side,
            (self.block_thickness(side) + extra).to_f64(),
        )
    }

    /// Lays the page grid on the block on `side` as it is now, `k` pages thick: each grid
    /// column on the curve half the stack above the block's top, from the bound column at
    /// the binding parameter around the block's rounded spine edge ([`spine_arc`], the
    /// collisions' start cap) with columns a grid spacing apart ([`walk_chords`]) when that
    /// edge is at least one grid column long; else straight to the block's top past the
    /// edge, columns at equal arc lengths ([`resample`]), rows at equal steps along Z. The
    /// shape is a generalized cylinder with rulings along Z, an exact DOG.
    ///
    /// Under [`crate::Gutter::TopPage`] the columns lie half the stack above the block's top
    /// page ([`Book::top_page_walls`]), at equal arc lengths from the bound column.
    ///
    /// The edge's radius is the block's thickness (plus half the stack): 0.38 for the
    /// default book's 50 pages a side, a quarter of a grid column (1.5), which cannot bend
    /// round it: laid around it, or straight with exact chords, the default page turn's
    /// largest stretch went from 1.1 % to 5.7 % (5.9 % in the first step after the grab).
    /// Laid straight across a wide edge, the page lies inside the block and the first
    /// collision stretched it: by 46 % for 1000 pages a side (edge radius 7.5); over a
    /// turn, 11.3 % for 240 a side (with the edge two columns long as the switch, before it
    /// was one), 5.3 % now (`hard_cases` `book::thick_books_turn_within_the_guard`).
    pub(crate) fn place_page(&mut self, side: BlockSide, k: u32) {
        self.terms.clear_contacts();
        let n = self.terms.nodes;
        let p = self.layout.params;
        let half = T::from_f64(0.5 * f64::from(k) * p.page_thickness);
        let surface = self.block_surface(side, half);
        let q = self.layout.binding_parameter(self.counts.left, k);
        let (b1, b2) = (
            self.state.x[n.block(false, 0)],
            self.state.x[n.block(true, 0)],
        );
        let bound = b1 * T::from_f64(1.0 - q) + b2 * T::from_f64(q);
        let hx = p.page_width / self.settings.quads_across as f64;
        let spine = self.midline(side)[0];
        let (bound, spine) = (
            [bound.x().to_f64(), bound.y().to_f64()],
            [spine.x().to_f64(), spine.y().to_f64()],
        );
        // On the block's top page where the book keeps one (`Gutter::TopPage`); else around
        // the spine edge where the grid has a column or more on it; else straight from the
        // binding to the block's top, past the edge.
        let top_page: Vec<[f64; 2]> = if cfg!(feature = "gutter") && self.counts.active > 0 {
            self.refresh_top_pages();
            self.top_page_walls(side)
                .iter()
                .map(|p| [p.x().to_f64(), p.y().to_f64()])
                .collect()
        } else {
            Vec::new()
        };
        let edge = 0.5 * core::f64::consts::PI * distance(spine, surface[0]);
        let columns = if top_page.len() >= 2 {
            let mut curve = offset_curve(&top_page, side, half.to_f64());
            curve[0] = bound;
            resample(&curve, hx, n.grid.nx)
        } else if edge >= hx {
            let mut curve = spine_arc(bound, spine, surface[0], 0.125 * hx);
            curve.extend_from_slice(&surface[1..]);
            walk_chords(&curve, hx, n.grid.nx)
        } else {
            let mut curve = surface;
            curve[0] = bound;
            resample(&curve, hx, n.grid.nx)
        };
        let hz = p.page_height() / self.settings.quads_along as f64;
        for j in 0..n.grid.nz {
            for (i, c) in columns.iter().enumerate() {
                let node = n.page(i, j);
                self.state.x[node] = T::Vec3::new(
                    T::from_f64(c[0]),
                    T::from_f64(c[1]),
                    T::from_f64(hz * j as f64),
                );
                self.state.v[node] = T::Vec3::ZERO;
            }
        }
    }

    /// Grabs the book where `ray` first hits a block's top surface (seed Sec. 3.3, 4.1): the
    /// top `pages` pages of that block become the active page, and the page node one ring
    /// in from the border closest to the ray is held. With an active page already present,
    /// its closest ring node is held instead. `forward` is the camera's forward direction:
    /// the drag plane passes through the held node with that normal.
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite or zero ray or direction, or zero pages;
    /// the book is unchanged.
    pub fn grab(
        &mut self,
        ray: &Ray<T>,
        forward: T::Vec3,
        pages: u32,
    ) -> Result<GrabOutcome, BookError> {
        if !ray.is_valid() {
            return Err(BookError::InvalidInput { what: "grab ray" });
        }
        let forward_ok = vec_finite::<T>(forward) && forward.dot(forward) > T::LENGTH_FLOOR;
        if !forward_ok {
            return Err(BookError::InvalidInput {
                what: "camera forward direction",
            });
        }
        let pick = if self.active.is_none() {
            self.hit_block(ray)
        } else {
            None
        };
        let side = match self.grab_side(pages, pick)? {
            Ok(side) => side,
            Err(outcome) => return Ok(outcome),
        };
        let nearest = nearest(self.terms.pull_nodes(), |node| {
            ray.distance_sq(self.state.x[node]).to_f64()
        });
        Ok(nearest.map_or(GrabOutcome::Missed, |node| {
            let at = self.material_point(node);
            self.hold_node(side, node, forward, at)
        }))
    }

    /// Grabs `pages` pages from the block on `side` (a stack when more than one) by the
    /// grab-ring node nearest the material point `at` $= (u, v)$ (page units: $u$ across from
    /// the spine, $v$ along it), as if seen from above. For callers that place the finger
    /// themselves ([`Book::drag_to`]), such as the page models.
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite point or zero pages.
    pub fn grab_at(
        &mut self,
        side: BlockSide,
        at: [f64; 2],
        pages: u32,
    ) -> Result<GrabOutcome, BookError> {
        if !(at[0].is_finite() && at[1].is_finite()) {
            return Err(BookError::InvalidInput { what: "grab point" });
        }
        let side = match self.grab_side(pages, Some(side))? {
            Ok(side) => side,
            Err(outcome) => return Ok(outcome),
        };
        let n = self.terms.nodes;
        let spacing = self.grid_spacing();
        let nearest = nearest(self.terms.pull_nodes(), |node| {
            let (i, j) = n.grid.coords(node - n.page_offset());
            let du = i as f64 * spacing[0] - at[0];
            let dv = j as f64 * spacing[1] - at[1];
            du * du + dv * dv
        });
        let down = T::Vec3::new(T::ZERO, -T::ONE, T::ZERO);
        Ok(nearest.map_or(GrabOutcome::Missed, |node| {
            self.hold_node(side, node, down, at)
        }))
    }

    /// The block a grab holds: the active page's, or else `pick` after `pages` pages of it
    /// became the active page. `Ok(Err(outcome))` when nothing was grabbed.
    fn grab_side(
        &mut self,
        pages: u32,
        pick: Option<BlockSide>,
    ) -> Result<Result<BlockSide, GrabOutcome>, BookError> {
        if pages == 0 {
            return Err(BookError::InvalidInput {
                what: "pages to grab (zero)",
            });
        }
        if let Some(a) = self.active {
            return Ok(Ok(a.from));
        }
        let Some(side) = pick else {
            return Ok(Err(GrabOutcome::Missed));
        };
        if !self.take_pages(side, pages) {
            return Ok(Err(GrabOutcome::NotEnoughPages));
        }
        Ok(Ok(side))
    }

    /// Makes the top `pages` pages of the block on `side` the active page, laid on the block;
    /// `false` (nothing changes) when the block holds fewer.
    fn take_pages(&mut self, side: BlockSide, pages: u32) -> bool {
        if self.counts.block(side) < pages {
            return false;
        }
        *self.counts.block_mut(side) -= pages;
        self.counts.active = pages;
        self.place_page(side, pages);
        self.update_masses();
        let po = self.terms.nodes.page_offset();
        self.history.restart(&self.state.x[po..]);
        self.active = Some(ActivePage {
            from: side,
            hold: None,
            slow_frames: 0,
        });
        true
    }

    /// The material point $(u, v)$ of page node `node` (global index), page units.
    fn material_point(&self, node: usize) -> [f64; 2] {
        let n = self.terms.nodes;
        let (i, j) = n.grid.coords(node - n.page_offset());
        let spacing = self.grid_spacing();
        [i as f64 * spacing[0], j as f64 * spacing[1]]
    }

    /// Holds page node `node` (global index) where it is, with the drag plane facing
    /// `forward` (unit or not; checked by the callers) and the tent over the binding. A book
    /// with a pad ([`crate::BookSettings::pad_radius`]) holds the pad centred on the
    /// material point `at` instead of the node alone, and the hold's target is the pad's
    /// centre.
    fn hold_node(
        &mut self,
        side: BlockSide,
        node: usize,
        forward: T::Vec3,
        at: [f64; 2],
    ) -> GrabOutcome {
        let n = self.terms.nodes;
        let held = if self.terms.has_pad() {
            self.grab_pad(at)
        } else {
            self.state.x[node]
        };
        let (i, _) = n.grid.coords(node - n.page_offset());
        let p = self.layout.params;
        let thicker = if self.counts.left > self.counts.right {
            BlockSide::Left
        } else {
            BlockSide::Right
        };
        let b = self.state.x[n.block(false, 0)] + self.state.x[n.block(true, 0)];
        let tent = Tent {
            center: b.x() * T::HALF,
            reach: T::from_f64(p.page_width * i as f64 / self.settings.quads_across as f64),
            base: b.y() * T::HALF
                + self.block_thickness(thicker)
                + self.active_thickness() * T::HALF,
            height: self.settings.tent_height,
            page_height: T::from_f64(p.page_height()),
        };
        let normal = forward / math::length::<T>(forward);
        let hold = Hold {
            node,
            target: held,
            plane_point: held,
            plane_normal: normal,
            tent,
        };
        if !self.terms.has_pad() {
            self.terms.set_pull(Some((node, held)));
        }
        if let Some(a) = self.active.as_mut() {
            a.hold = Some(hold);
            a.slow_frames = 0;
        }
        GrabOutcome::Grabbed {
            side,
            node: node - n.page_offset(),
        }
    }

    /// Puts the pad ([`crate::pad`]) on the material point `at` and holds its points where
    /// they lie; returns where its centre lies.
    fn grab_pad(&mut self, at: [f64; 2]) -> T::Vec3 {
        let n = self.terms.nodes;
        let quads = [self.settings.quads_across, self.settings.quads_along];
        let spacing = self.grid_spacing();
        let size = self.page_size();
        let page = &self.state.x[n.page_offset()..];
        let samples = pad_samples(at, self.settings.pad_radius.to_f64(), size, spacing, quads);
        let center = pad_point(
            [at[0].clamp(0.0, size[0]), at[1].clamp(0.0, size[1])],
            spacing,
            quads,
            1.0,
        );
        let c = interpolate::<T>(&center, page, n.grid.nx);
        let pad = &mut self.pad;
        pad.offsets.clear();
        pad.offsets.extend(
            samples
                .iter()
                .map(|s| interpolate::<T>(s, page, n.grid.nx) - c),
        );
        pad.samples = samples;
        pad.center = Some(center);
        pad.grabbed = c;
        let row = folio_kernels::math::floor::<f64>(at[1] / spacing[1] + 0.5);
        pad.row = (row.max(0.0) as usize).min(n.grid.nz - 1);
        pad.aim(c, c);
        self.terms.set_pad(Some((&pad.samples, &pad.targets)));
        c
    }

    /// The block whose top surface `ray` hits first, if any.
    fn hit_block(&self, ray: &Ray<T>) -> Option<BlockSide> {
        let height = T::from_f64(self.layout.params.page_height());
        let mut best: Option<(T, BlockSide)> = None;
        for side in [BlockSide::Left, BlockSide::Right] {
            let top = self.block_surface(side, T::ZERO);
            for w in top.windows(2) {
                let a = T::Vec3::new(T::from_f64(w[0][0]), T::from_f64(w[0][1]), T::ZERO);
                let b = T::Vec3::new(T::from_f64(w[1][0]), T::from_f64(w[1][1]), T::ZERO);
                let d = b - a;
                let normal = T::Vec3::new(-d.y(), d.x(), T::ZERO);
                let Some(hit) = ray.hit_plane(a, normal) else {
                    continue;
                };
                let s = (hit - a).dot(d) / d.dot(d);
                let inside = s >= T::ZERO && s <= T::ONE && hit.z() >= T::ZERO && hit.z() <= height;
                if !inside {
                    continue;
                }
                let dist = math::length::<T>(hit - ray.origin);
                if best.is_none_or(|(t, _)| dist < t) {
                    best = Some((dist, side));
                }
            }
        }
        best.map(|(_, side)| side)
    }

    /// Moves the held node's target to where `ray` meets the drag plane, projected onto the
    /// tent (seed Sec. 3.3, Fig. 7).
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite or zero ray; the target is unchanged.
    pub fn drag(&mut self, ray: &Ray<T>) -> Result<DragOutcome, BookError> {
        if !ray.is_valid() {
            return Err(BookError::InvalidInput { what: "drag ray" });
        }
        let Some(hold) = self.active.and_then(|a| a.hold) else {
            return Ok(DragOutcome::NotHeld);
        };
        let Some(hit) = ray.hit_plane(hold.plane_point, hold.plane_normal) else {
            return Ok(DragOutcome::Missed);
        };
        let target = hold.tent.project(hit);
        if !vec_finite::<T>(target) {
            return Err(BookError::InvalidInput {
                what: "drag target",
            });
        }
        self.set_target(target);
        Ok(DragOutcome::Moved)
    }

    /// Moves the held node's target to `target` itself, without the drag plane or the tent:
    /// for callers that own the finger's path (the page models).
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite target; the target is unchanged.
    pub fn drag_to(&mut self, target: T::Vec3) -> Result<DragOutcome, BookError> {
        if !vec_finite::<T>(target) {
            return Err(BookError::InvalidInput {
                what: "drag target",
            });
        }
        if self.active.and_then(|a| a.hold).is_none() {
            return Ok(DragOutcome::NotHeld);
        }
        self.set_target(target);
        Ok(DragOutcome::Moved)
    }

    /// Stores the user's target of the held node (applied on the leash at the next step).
    fn set_target(&mut self, target: T::Vec3) {
        if let Some(hold) = self.active.as_mut().and_then(|a| a.hold.as_mut()) {
            hold.target = target;
        }
    }

    /// Sets the pull of the held node to its target on the leash
    /// $r = \min(r_{max}, \omega h \rho)$, [`BookSettings::pull_reach`] $r_{max}$ or the
    /// turn [`BookSettings::pull_turn_rate`] $\omega$ allows in one step $h$ at the held
    /// node's distance $\rho$ from the binding along the flat page:
    /// $p = x_i + (t - x_i)\min(1, r / \lVert t - x_i\rVert)$.
    ///
    /// [`BookSettings::pull_reach`]: crate::BookSettings::pull_reach
    /// [`BookSettings::pull_turn_rate`]: crate::BookSettings::pull_turn_rate
    pub(crate) fn leash_pull(&mut self) {
        let Some(hold) = self.active.and_then(|a| a.hold) else {
            return;
        };
        let n = self.terms.nodes;
        let x = match &self.pad.center {
            Some(c) if self.terms.has_pad() => {
                interpolate::<T>(c, &self.state.x[n.page_offset()..], n.grid.nx)
            }
            _ => self.state.x[hold.node],
        };
        let d = hold.target - x;
        let len = math::length::<T>(d);
        let s = &self.settings;
        let turn = s.pull_turn_rate * s.solver.time_step * hold.tent.reach;
        let reach = if turn < s.pull_reach {
            turn
        } else {
            s.pull_reach
        };
        let p = if len > reach {
            x + d * (reach / len)
        } else {
            hold.target
        };
        if self.terms.has_pad() && self.pad.center.is_some() {
            let hinge = self.state.x[n.page(0, self.pad.row)];
            self.pad.aim(hinge, p);
            self.terms
                .set_pad(Some((&self.pad.samples, &self.pad.targets)));
        } else {
            self.terms.set_pull(Some((hold.node, p)));
        }
    }

    /// The held node (index into the page grid), if one is held.
    #[must_use]
    pub fn held_node(&self) -> Option<usize> {
        let hold = self.active.and_then(|a| a.hold)?;
        Some(hold.node - self.terms.nodes.page_offset())
    }

    /// The held node's current target (where the user wants it), if a node is held.
    #[must_use]
    pub fn target(&self) -> Option<T::Vec3> {
        Some(self.active.and_then(|a| a.hold)?.target)
    }
}

#[cfg(test)]
mod tests {
    use super::nearest;

    #[test]
    fn nearest_is_always_one_of_the_nodes() {
        assert_eq!(nearest(&[], |_| 0.0), None);
        assert_eq!(nearest(&[4, 7, 9], |k| (k as f64 - 6.5).abs()), Some(7));
        // Ties go to the first node.
        assert_eq!(nearest(&[4, 7, 9], |_| 1.0), Some(4));
        // NaN counts as farthest, infinity still counts.
        let d = |k: usize| match k {
            4 => f64::NAN,
            7 => f64::INFINITY,
            _ => f64::NAN,
        };
        assert_eq!(nearest(&[4, 7, 9], d), Some(7));
        assert_eq!(nearest(&[4, 9], |_| f64::NAN), Some(4));
    }
}
