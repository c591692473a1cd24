//! Collision handling (seed `000_…` Sec. 3.4) and the constraint projection that follows
//! it: cover and binding on the table, blocks on the cover (or the table), the active page
//! on the blocks, each node pushed out inelastically, pinned in the projection and held on
//! the surface by a contact spring in the next step.

use folio_geometry::{BlockSide, Contacts, Corner, Floor, Obstacle, Wall};
use folio_kernels::{Real, Vec3Ops};

use super::broad_phase::{PageBroadPhase, Reach};
use super::error::BookError;
use super::model::{ActiveView, RestView};
use super::simulation::Book;
use folio_solvers::step::{Correction, Pins};

impl<T: Real> Book<T> {
    /// Collision handling and the constraint projection after a step that advanced: the
    /// last step's contacts released, up to `collision_rounds` detect/resolve rounds, then
    /// projection and collision in turn. Adds to `contacts` and `correction`; returns the
    /// rounds that found contacts.
    pub(crate) fn collide_and_project(
        &mut self,
        contacts: &mut Contacts<T>,
        correction: &mut Correction<T>,
    ) -> Result<u32, BookError> {
        self.pushed.iter_mut().for_each(|p| *p = false);
        self.pushed_normal
            .iter_mut()
            .for_each(|n| *n = T::Vec3::ZERO);
        self.spring_friction();
        self.terms.clear_contacts();
        if self.active.is_some() {
            self.refresh_top_pages();
        }
        let mut rounds = self.collide(contacts, self.settings.collision_rounds);
        // Projection and collision alternate: a node the projection moves into a block
        // is pushed out and held on its surface in the next projection, up to twice
        // `collision_rounds` passes, so the step ends with both the constraints and the
        // contacts met (a landing page needs more passes than a resting one).
        for pass in 0..2 * self.settings.collision_rounds {
            let c = self.project()?;
            if pass == 0 {
                correction.before = c.before;
            }
            correction.steps += c.steps;
            correction.after = c.after;
            correction.factorizations += c.factorizations;
            correction.solves += c.solves;
            if c.steps == 0 {
                break;
            }
            let found = self.collide(contacts, 1);
            rounds += found;
            if found == 0 {
                break;
            }
        }
        Ok(rounds)
    }

    /// One [`folio_solvers::Solver::project_constraints`] of the current view, each node
    /// pushed in this step held on the surface that pushed it: weight
    /// [`crate::BookSettings::contact_pin_weight`] along the surface's normal, free along the
    /// surface, and let go when the constraints pull it off (a one-sided contact,
    /// [`folio_solvers::Pins`]); a node two surfaces pushed ([`SAME_NORMAL`]) is held in
    /// every direction.
    ///
    /// Held in every direction instead, a pushed node cannot slide, and the projection
    /// moves its free neighbours into the block, which the next collision pushes again:
    /// with the area-weighted bending and masses ([`crate::quadrature`]) each of the six
    /// passes found a contact again and the page turn ended its steps on a push, DOG
    /// residual 1.84e-3 against the 1e-3 bound (a final projection with those pins fixed
    /// the residual but pulled the pinned nodes 5.1e-3 into the block, against 7.5e-4).
    /// Held along the normal both ways (never let go), a page lying on its block could not
    /// be lifted: the projection held down the ring next to the grab, and a grabbed page
    /// stayed on its block (50 turns back and forth: turn 2 did not turn).
    fn project(&mut self) -> Result<Correction<T>, BookError> {
        let s = &self.settings;
        let (tol, max) = (s.projection_tolerance, s.projection_iterations);
        let pins = Pins {
            nodes: &self.pushed,
            normals: &self.pushed_normal,
            weight: s.contact_pin_weight,
        };
        let c = if self.active.is_some() {
            self.active_solver.project_constraints(
                &ActiveView(&self.terms),
                &mut self.state,
                pins,
                tol,
                max,
            )?
        } else {
            self.rest_solver.project_constraints(
                &RestView(&self.terms),
                &mut self.state,
                pins,
                tol,
                max,
            )?
        };
        Ok(c)
    }

    /// Up to `max_rounds` detect/resolve rounds, stopping at the first that finds nothing;
    /// returns the rounds that found contacts.
    fn collide(&mut self, total: &mut Contacts<T>, max_rounds: u32) -> u32 {
        if !self.settings.effects.collides() {
            return 0;
        }
        let mut rounds = 0;
        for _ in 0..max_rounds {
            let c = self.resolve_contacts();
            total.tested += c.tested;
            total.bounds_tested += c.bounds_tested;
            if c.resolved == 0 {
                break;
            }
            rounds += 1;
            total.resolved += c.resolved;
            if c.max_depth > total.max_depth {
                total.max_depth = c.max_depth;
            }
        }
        rounds
    }

    /// Pushes `node` out of `obstacle`, adding the displacement over the time step to its
    /// velocity (an inelastic contact); the node is pinned in this step's projection and
    /// held on the obstacle's plane by a contact spring in the next step. Page nodes feel
    /// friction ([`crate::friction`]).
    fn push_node(&mut self, node: usize, obstacle: &impl Obstacle<T>) -> Option<T> {
        let before = self.state.x[node];
        let depth = obstacle.resolve(&mut self.state.x[node])?;
        let k = self.settings.contact_stiffness * self.terms.mass(node);
        let plane = obstacle.contact_plane(self.state.x[node], k);
        self.pushed_normal[node] = if !self.pushed[node] {
            plane.normal
        } else if self.pushed_normal[node].dot(plane.normal) >= T::from_f64(SAME_NORMAL) {
            self.pushed_normal[node]
        } else {
            T::Vec3::ZERO
        };
        self.pushed[node] = true;
        self.terms.set_contact(node, plane);
        let h = self.settings.solver.time_step;
        self.state.v[node] += (self.state.x[node] - before) / h;
        self.rub(node, plane.normal, depth / h);
        Some(depth)
    }

    /// The wall of segment `k` of the block on `side`, on the block's material side, with
    /// clearance `clearance`.
    fn block_wall(&self, side: BlockSide, k: usize, clearance: T) -> Option<Wall<T>> {
        Self::wall_along(self.midline(side), side, k, clearance)
    }

    /// The wall of segment `k` of `line`, a curve from the binding out over the block on
    /// `side` (a midline or a top page), on the block's material side, with clearance
    /// `clearance`; only the line's last segment reaches on past its end.
    pub(crate) fn wall_along(
        line: &[T::Vec3],
        side: BlockSide,
        k: usize,
        clearance: T,
    ) -> Option<Wall<T>> {
        let (a, b) = (*line.get(k)?, *line.get(k + 1)?);
        let d = b - a;
        let toward = match side {
            BlockSide::Left => T::Vec3::new(d.y(), -d.x(), T::ZERO),
            BlockSide::Right => T::Vec3::new(-d.y(), d.x(), T::ZERO),
        };
        let mut wall = Wall::new(a, b, toward, clearance)?;
        wall.open_end = k + 2 == line.len();
        Some(wall)
    }

    /// The blocks' part of [`Book::resolve_contacts`]: cover and binding on the table,
    /// blocks on the cover (or the table).
    fn resolve_block_contacts(&mut self, c: &mut Contacts<T>) {
        let n = self.terms.nodes;
        let up = T::Vec3::new(T::ZERO, T::ONE, T::ZERO);
        let y0 = T::from_f64(if n.cover {
            self.layout.params.cover_thickness
        } else {
            0.0
        });
        let table = Floor { level: y0 };
        let lifted: [usize; 4] = if n.cover {
            [
                n.block(false, 0),
                n.block(true, 0),
                n.cover_end(false),
                n.cover_end(true),
            ]
        } else {
            [
                n.block(false, 0),
                n.block(true, 0),
                n.block(false, 0),
                n.block(true, 0),
            ]
        };
        for node in lifted {
            c.record(self.push_node(node, &table));
        }
        for side in [BlockSide::Left, BlockSide::Right] {
            let right = side == BlockSide::Right;
            let board = n.cover.then(|| {
                let a = self.state.x[n.block(right, 0)];
                Wall::new(a, self.state.x[n.cover_end(right)], up, T::ZERO)
            });
            for k in 1..n.midline {
                let node = n.block(right, k);
                let depth = match board {
                    Some(Some(wall)) => self.push_node(node, &wall),
                    Some(None) => None,
                    None => self.push_node(node, &table),
                };
                c.record(depth);
            }
        }
    }

    /// Walls the active page collides with: one per midline segment of each block, then
    /// one per segment of each block's top page ([`crate::Gutter::TopPage`]).
    fn page_walls(&self) -> usize {
        2 * (self.terms.nodes.midline - 1)
            + self.top_page_segments(BlockSide::Left)
            + self.top_page_segments(BlockSide::Right)
    }

    /// Wall `w` (`0..page_walls()`) the active page collides with: segment `w` of the left
    /// block's midline, then segment `w - (m - 1)` of the right block's, with the clearance
    /// $t_{block} + t_{active}/2$ (seed Sec. 3.4); then the left block's top page's
    /// segments and the right one's ([`Book::top_page_wall`]). `None` for a degenerate
    /// segment.
    fn page_wall(&self, w: usize) -> Option<Wall<T>> {
        let segments = self.terms.nodes.midline - 1;
        if w >= 2 * segments {
            let k = w - 2 * segments;
            let left = self.top_page_segments(BlockSide::Left);
            return if k < left {
                self.top_page_wall(BlockSide::Left, k)
            } else {
                self.top_page_wall(BlockSide::Right, k - left)
            };
        }
        let side = if w < segments {
            BlockSide::Left
        } else {
            BlockSide::Right
        };
        let half = self.active_thickness() * T::HALF;
        let clearance = self.block_thickness(side) + half;
        self.block_wall(side, w % segments, clearance)
    }

    /// One detect/resolve round (seed Sec. 3.4): cover and binding on the table, blocks on
    /// the cover (or the table) when the blocks are simulated, the active page on the
    /// blocks.
    fn resolve_contacts(&mut self) -> Contacts<T> {
        let mut c = Contacts::default();
        if self.settings.effects.blocks {
            self.resolve_block_contacts(&mut c);
        }
        if self.active.is_some() {
            self.resolve_page_contacts(&mut c);
        }
        c
    }

    /// Rounded corners of the blocks' clearance bands ([`Corner`]): the spine edge of each
    /// block (the start of its midline) and each inner midline node; then each inner node of
    /// each block's top page ([`crate::Gutter::TopPage`]).
    fn page_corners(&self) -> usize {
        let inner = |side| self.top_page_segments(side).saturating_sub(1);
        2 * (self.terms.nodes.midline - 1) + inner(BlockSide::Left) + inner(BlockSide::Right)
    }

    /// Corner `k` (`0..page_corners()`): for `k = i` the start cap of the left block's
    /// midline (`i = 0`) or the corner between its segments `i - 1` and `i`, then the same
    /// on the right block; then the corners between consecutive segments of the left and
    /// the right block's top page. `None` where the band turns towards the page (it leaves
    /// no gap there) or a segment is degenerate, and for the start cap of a block that has
    /// a top page: the top page leaves the hinge where the cap would clamp a page upright.
    fn page_corner(&self, k: usize) -> Option<Corner<T>> {
        let per_side = self.terms.nodes.midline - 1;
        if k >= 2 * per_side {
            let i = k - 2 * per_side;
            let left = self.top_page_segments(BlockSide::Left).saturating_sub(1);
            let (side, i) = if i < left {
                (BlockSide::Left, i)
            } else {
                (BlockSide::Right, i - left)
            };
            return Corner::new(
                &self.top_page_wall(side, i)?,
                &self.top_page_wall(side, i + 1)?,
            );
        }
        let (first, side) = if k < per_side {
            (0, BlockSide::Left)
        } else {
            (per_side, BlockSide::Right)
        };
        match k % per_side {
            0 if self.top_page_segments(side) > 0 => None,
            0 => Corner::start(&self.page_wall(first)?),
            i => Corner::new(&self.page_wall(first + i - 1)?, &self.page_wall(first + i)?),
        }
    }

    /// The active page's part of [`Book::resolve_contacts`]: each wall, then each corner,
    /// in turn against the free page nodes in node order, the columns the obstacle cannot
    /// reach skipped (the broad phase, [`crate::broad_phase::PageBroadPhase`]).
    fn resolve_page_contacts(&mut self, c: &mut Contacts<T>) {
        let n = self.terms.nodes;
        // Taken out for the loop (no allocation: the default holds empty vectors).
        let mut broad = core::mem::take(&mut self.broad);
        broad.bound(n, &self.state.x);
        for w in 0..self.page_walls() {
            if let Some(wall) = self.page_wall(w) {
                self.push_page(&mut broad, &wall, c);
            }
        }
        for k in 0..self.page_corners() {
            if let Some(corner) = self.page_corner(k) {
                self.push_page(&mut broad, &corner, c);
            }
        }
        self.broad = broad;
    }

    /// Pushes the free page nodes that `obstacle` may reach out of it, row by row.
    fn push_page<O: Obstacle<T> + Reach<T>>(
        &mut self,
        broad: &mut PageBroadPhase<T>,
        obstacle: &O,
        c: &mut Contacts<T>,
    ) {
        let n = self.terms.nodes;
        c.bounds_tested += broad.select(obstacle);
        for j in 0..n.grid.nz {
            for k in 0..broad.near().len() {
                let i = broad.near()[k];
                let node = n.page(i, j);
                let depth = self.push_node(node, obstacle);
                if depth.is_some() {
                    broad.include(i, self.state.x[node]);
                }
                c.record(depth);
            }
        }
    }

    /// Deepest penetration of an active-page node (bound column excepted) into a block's
    /// clearance band, its rounded corners included: block thickness plus half the active
    /// thickness (seed Sec. 3.4).
    #[must_use]
    pub fn penetration(&self) -> Option<T> {
        self.page()?;
        let n = self.terms.nodes;
        let mut worst = T::ZERO;
        let mut deepest = |depth: Option<T>| {
            if let Some(d) = depth.filter(|&d| d > worst) {
                worst = d;
            }
        };
        for node in n.free_page_nodes() {
            let p = self.state.x[node];
            for w in 0..self.page_walls() {
                deepest(self.page_wall(w).and_then(|wall| wall.penetration(p)));
            }
            for k in 0..self.page_corners() {
                deepest(self.page_corner(k).and_then(|corner| corner.penetration(p)));
            }
        }
        Some(worst)
    }
}

/// The cosine above which two surfaces pushing one node in a step count as one: the node
/// slides along it in the projection; pushed by two surfaces further apart (a block's
/// corner), it is held in every direction.
const SAME_NORMAL: f64 = 0.99;

#[cfg(test)]
mod broad_phase_tests;

#[cfg(test)]
mod tests {
    use crate::{Book, BookSettings};
    use folio_geometry::BlockSide;
    use folio_kernels::Vec3Ops;

    /// The default book, unsettled.
    fn book() -> Book<f64> {
        Book::new(BookSettings {
            settle_steps: 0,
            ..BookSettings::default()
        })
        .unwrap()
    }

    #[test]
    fn page_walls_run_along_the_left_then_the_right_midline() {
        let b = book();
        let segments = b.nodes().midline - 1;
        assert_eq!(b.page_walls(), 2 * segments);
        for w in 0..b.page_walls() {
            let (side, k) = if w < segments {
                (BlockSide::Left, w)
            } else {
                (BlockSide::Right, w - segments)
            };
            let wall = b
                .page_wall(w)
                .expect("the flat midlines have no degenerate segment");
            let line = b.midline(side);
            assert_eq!(wall.a, line[k]);
            assert_eq!(wall.along, line[k + 1] - line[k]);
            // Block thickness plus half the active thickness (none at rest).
            assert_eq!(wall.clearance, b.block_thickness(side));
            // Only a block's last segment reaches on past the fore-edge.
            assert_eq!(wall.open_end, k + 1 == segments, "wall {w}");
            // The allowed side is the pages' side: up, for the flat book.
            assert!(wall.normal.y() > 0.0);
        }
    }

    #[test]
    fn a_node_pushed_out_is_pinned_and_held_by_a_spring() {
        let mut b = book();
        let n = b.nodes();
        let node = n.block(true, 3);
        let floor = folio_geometry::Floor {
            level: b.state.x[node].y() + 1.0,
        };
        let depth = b
            .push_node(node, &floor)
            .expect("the node is below the floor");
        assert!((depth - 1.0).abs() < 1e-12);
        assert!(b.pushed[node]);
        assert!((b.state.x[node].y() - floor.level).abs() < 1e-12);
        // The displacement over the time step went into the velocity.
        let h = b.settings.solver.time_step;
        assert!((b.state.v[node].y() - 1.0 / h).abs() < 1e-9);
        // A node above the floor is left alone.
        assert_eq!(
            b.push_node(n.block(false, 3), &folio_geometry::Floor { level: -1.0 }),
            None
        );
    }
}
