//! The book as a [`Model`] (seed `000_…` Sec. 3.1-3.3): node numbering, masses, eliminated
//! coordinates and every term family, and the two views the book steps: the blocks alone
//! (a book at rest) and the blocks with the active page.
//!
//! Nodes: the left block's midline from $b_1$ outward (`0..m`), the right block's from $b_2$
//! outward (`m..2m`), the outer ends of the left and right cover boards (with a cover), then
//! the active page's grid (`i + nx j`, column `i = 0` bound to the binding). Z is eliminated
//! for every midline and cover node and for the bound column (Sec. 3.1).

use crate::BookLayout;
use alloc::vec::Vec;
use folio_geometry::{QuadGrid, Star};
use folio_kernels::binding::Binding;
use folio_kernels::contact::ContactPlane;
use folio_kernels::curve_laplacian::{self, CurveLaplacian};
use folio_kernels::dog_laplacian::{DogLaplacianBoundary, DogLaplacianInner};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::gravity::Gravity;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::{KernelError, Real, Vec3Ops};

use super::effects::Effects;
use super::pad::{PadQuad, PadSample, corners, pad_weight};
use super::quadrature::{self, PageBending};
use super::settings::BookSettings;
use super::terms::{Contact, DogBoundary, DogInner, Grip, Isometry, PadGrip, PlanarFix, Pull};
use folio_solvers::model::{ConstraintSet, Model, PotentialSet, TermVisitor};

/// Where each kind of node lives in the state (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeMap {
    /// Nodes per block midline, binding node included.
    pub midline: usize,
    /// Whether the two cover nodes exist.
    pub cover: bool,
    /// The active page's grid.
    pub grid: QuadGrid,
}

impl NodeMap {
    /// Node `k` of the left (`right = false`) or right block's midline, from the binding.
    #[inline]
    #[must_use]
    pub fn block(&self, right: bool, k: usize) -> usize {
        if right { self.midline + k } else { k }
    }
    /// The outer node of the left or right cover board (only with a cover).
    #[inline]
    #[must_use]
    pub fn cover_end(&self, right: bool) -> usize {
        2 * self.midline + usize::from(right)
    }
    /// First node of the active page.
    #[inline]
    #[must_use]
    pub fn page_offset(&self) -> usize {
        2 * self.midline + if self.cover { 2 } else { 0 }
    }
    /// Node of page vertex `(i, j)`.
    #[inline]
    #[must_use]
    pub fn page(&self, i: usize, j: usize) -> usize {
        self.page_offset() + self.grid.index(i, j)
    }
    /// All nodes.
    #[inline]
    #[must_use]
    pub fn total(&self) -> usize {
        self.page_offset() + self.grid.len()
    }
    /// `true` for a page node of the bound column.
    #[inline]
    #[must_use]
    pub fn is_bound(&self, node: usize) -> bool {
        node >= self.page_offset() && (node - self.page_offset()) % self.grid.nx == 0
    }
    /// The page nodes off the bound column, in node order (the ones that collide).
    #[inline]
    pub fn free_page_nodes(&self) -> impl Iterator<Item = usize> + use<> {
        let n = *self;
        (n.page_offset()..n.total()).filter(move |&node| !n.is_bound(node))
    }
}

/// The book's term families (see [`BookTerms::count`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Family {
    /// Gravity on block, cover and page nodes (eq. 12).
    Gravity,
    /// The binding glue (eq. 11).
    Glue,
    /// Contact springs on block, cover and page nodes.
    Contacts,
    /// Curve-Laplacian bending of the block midlines (eq. 10).
    BlockBending,
    /// Inextensible block and cover links (eq. 6).
    BlockLinks,
    /// The binding-midpoint fix (eq. 8).
    BindingFix,
    /// DOG constraints of the page (Sec. 3.2).
    Dog,
    /// The bound column's binding (eq. 7).
    Binding,
    /// DOG-Laplacian bending of the page (eq. 10), area-weighted ([`quadrature`]).
    PageBending,
    /// Soft isometry of the page (eq. 13).
    PageIso,
    /// The grab pulls (eq. 14).
    Pull,
    /// The finger's pad, one per quad where the settings ask for one ([`crate::pad`]).
    Pad,
}

/// Every term of the book (seed eq. 5 and 9), built once; parameters (masses, $q$, the
/// grab) change between steps through the `set_*` methods, stencils never do.
#[derive(Clone, Debug)]
pub struct BookTerms<T: Real> {
    /// Node numbering.
    pub nodes: NodeMap,
    /// Mass of every node (page masses).
    pub masses: Vec<T>,
    /// The effects these terms simulate.
    pub effects: Effects,
    g: T,
    iso2d: ConstraintSet<Iso2d<T>, 2>,
    fix: ConstraintSet<PlanarFix<T>, 2>,
    bend_blocks: PotentialSet<T, CurveLaplacian<T>, 3>,
    glue: PotentialSet<T, Glue<T>, 4>,
    block_gravity: PotentialSet<T, Gravity<T>, 1>,
    /// DOG constraints on inner stars.
    pub dog_inner: ConstraintSet<DogInner<T>, 5>,
    /// DOG constraints on 3-neighbour boundary stars.
    pub dog_boundary: ConstraintSet<DogBoundary<T>, 4>,
    binding: ConstraintSet<Binding<T>, 3>,
    bend_inner: PotentialSet<T, DogLaplacianInner<T>, 5>,
    bend_boundary: PotentialSet<T, DogLaplacianBoundary<T>, 3>,
    iso3d: PotentialSet<T, Isometry<T>, 2>,
    page_gravity: PotentialSet<T, Gravity<T>, 1>,
    pull: PotentialSet<T, Pull<T>, 1>,
    pull_nodes: Vec<usize>,
    /// The finger's pad, one per quad (none unless [`BookSettings::pad_radius`] is
    /// positive), weighted by [`pad_weight`].
    pad: PotentialSet<T, PadGrip<T>, 4>,
    /// The weights of the page's bending, iso3D and pull, its grip and the pad's weight, for
    /// one page (see [`BookTerms::set_stack`]).
    page_weights: [T; 5],
    /// The largest force of the pull (page masses times page units per s²; see
    /// [`BookTerms::grip_force`]), for the active stack.
    grip: T,
    /// The page's isometry assembles its projected Hessian
    /// ([`crate::IsometryHessian::Projected`]).
    projected_isometry: bool,
    /// One per block and cover node, in node order.
    block_contacts: PotentialSet<T, Contact<T>, 1>,
    /// One per page node, in grid order.
    page_contacts: PotentialSet<T, Contact<T>, 1>,
}

fn as_u32<const N: usize>(nodes: [usize; N]) -> [u32; N] {
    nodes.map(|k| k as u32)
}

impl<T: Real> BookTerms<T> {
    /// The terms of the book `layout` with the page grid and weights of `settings`; page
    /// spacing `spacing = [across, along]`.
    ///
    /// # Errors
    /// A kernel parameter that cannot be used (a non-finite weight or mass, zero spacing).
    pub fn new(
        layout: &BookLayout,
        settings: &BookSettings<T>,
        grid: QuadGrid,
    ) -> Result<Self, KernelError> {
        let p = &layout.params;
        let nodes = NodeMap {
            midline: p.midline_nodes,
            cover: p.cover,
            grid,
        };
        let mut t = Self::empty(nodes, settings);
        t.push_blocks(layout)?;
        t.push_page(layout, settings)?;
        t.push_pulls()?;
        if cfg!(feature = "pad") && settings.pad_radius > T::ZERO {
            t.push_pads();
        }
        t.push_contacts()?;
        Ok(t)
    }

    /// Every family empty, with its weight from `settings`; masses zero.
    fn empty(nodes: NodeMap, settings: &BookSettings<T>) -> Self {
        let w = &settings.weights;
        Self {
            nodes,
            masses: alloc::vec![T::ZERO; nodes.total()],
            effects: settings.effects,
            g: settings.gravity,
            iso2d: ConstraintSet::new(),
            fix: ConstraintSet::new(),
            bend_blocks: PotentialSet::new(w.bend_blocks),
            glue: PotentialSet::new(w.glue),
            block_gravity: PotentialSet::new(T::ONE),
            dog_inner: ConstraintSet::new(),
            dog_boundary: ConstraintSet::new(),
            binding: ConstraintSet::new(),
            bend_inner: PotentialSet::new(w.bend_page),
            bend_boundary: PotentialSet::new(w.bend_page),
            iso3d: PotentialSet::new(w.iso_page * T::from_f64(settings.iso_scale())),
            page_gravity: PotentialSet::new(T::ONE),
            pull: PotentialSet::new(w.pull),
            pull_nodes: Vec::new(),
            pad: PotentialSet::new(pad_weight(w.pull, w.bend_page, settings.pad_radius)),
            page_weights: [
                w.bend_page,
                w.iso_page * T::from_f64(settings.iso_scale()),
                w.pull,
                Self::grip_force(settings),
                pad_weight(w.pull, w.bend_page, settings.pad_radius),
            ],
            grip: Self::grip_force(settings),
            projected_isometry: settings.isometry_hessian == crate::IsometryHessian::Projected,
            block_contacts: PotentialSet::new(T::ONE),
            page_contacts: PotentialSet::new(T::ONE),
        }
    }

    /// Blocks: inextensible midlines (eq. 6), curve bending at inner nodes (eq. 10; the
    /// binding nodes are left to the glue), the binding width, the cover boards, the
    /// binding-midpoint fix (eq. 8), the glue (eq. 11) and gravity (eq. 12); none without
    /// simulated blocks.
    fn push_blocks(&mut self, layout: &BookLayout) -> Result<(), KernelError> {
        let p = &layout.params;
        let m = self.nodes.midline;
        let fx = self.effects;
        let seg = T::from_f64(p.page_width / (m - 1) as f64);
        let block_rights: &[bool] = if fx.blocks { &[false, true] } else { &[] };
        for &right in block_rights {
            for k in 0..m - 1 {
                let nodes = [self.nodes.block(right, k), self.nodes.block(right, k + 1)];
                self.iso2d.push(Iso2d::new(seg)?, as_u32(nodes));
            }
            for k in 1..m - 1 {
                let nodes = [k, k - 1, k + 1].map(|q| self.nodes.block(right, q));
                self.bend_blocks
                    .push(curve_laplacian::new([seg, seg])?, as_u32(nodes));
            }
        }
        if fx.blocks {
            let binding_width = T::from_f64(layout.binding[1][0] - layout.binding[0][0]);
            self.iso2d.push(Iso2d::new(binding_width)?, as_u32([0, m]));
            if p.cover {
                let board = T::from_f64(p.page_width + p.cover_overhang);
                for right in [false, true] {
                    let nodes = [self.nodes.block(right, 0), self.nodes.cover_end(right)];
                    self.iso2d.push(Iso2d::new(board)?, as_u32(nodes));
                }
            }
            let mid = T::Vec3::new(
                T::from_f64(0.5 * (layout.binding[0][0] + layout.binding[1][0])),
                T::from_f64(layout.binding[0][1]),
                T::ZERO,
            );
            self.fix.push(PlanarFix(Fix::new(mid)?), as_u32([0, m]));
        }
        if fx.glue && fx.blocks {
            self.glue.push(Glue::new(), as_u32([1, 0, m, m + 1]));
        }
        if fx.gravity && fx.blocks {
            for node in 0..self.nodes.page_offset() {
                self.block_gravity
                    .push(Gravity::new(self.g, T::ZERO)?, as_u32([node]));
            }
        }
        Ok(())
    }

    /// Active page: DOG constraints and DOG-Laplacian bending per star, binding of the
    /// bound column (eq. 7), iso3D on grid edges (eq. 13) and gravity.
    fn push_page(
        &mut self,
        layout: &BookLayout,
        settings: &BookSettings<T>,
    ) -> Result<(), KernelError> {
        let p = &layout.params;
        let grid = self.nodes.grid;
        let m = self.nodes.midline;
        let spacing = [
            T::from_f64(p.page_width / settings.quads_across as f64),
            T::from_f64(p.page_height() / settings.quads_along as f64),
        ];
        let rest_of = |a: usize, b: usize| {
            let (ga, gb) = (grid.coords(a), grid.coords(b));
            if ga.1 == gb.1 { spacing[0] } else { spacing[1] }
        };
        let po = self.nodes.page_offset();
        let rest_spacing = settings.grid_spacing();
        for star in grid.stars() {
            match star {
                Star::Inner(s) => {
                    self.dog_inner
                        .push(DogInner::default(), as_u32(s.map(|k| po + k)));
                }
                Star::Boundary(s) => {
                    self.dog_boundary
                        .push(DogBoundary::default(), as_u32(s.map(|k| po + k)));
                }
                Star::Corner(_) => {}
            }
            match quadrature::bending(grid, rest_spacing, star)? {
                Some(PageBending::Inner(lap, s)) => {
                    self.bend_inner.push(lap, as_u32(s.map(|k| po + k)));
                }
                Some(PageBending::Boundary(lap, s)) => {
                    self.bend_boundary.push(lap, as_u32(s.map(|k| po + k)));
                }
                None => {}
            }
        }
        for j in 0..grid.nz {
            let node = self.nodes.page(0, j);
            self.binding
                .push(Binding::new(T::HALF)?, as_u32([node, 0, m]));
        }
        for [a, b] in grid.edges() {
            let edge = Isometry {
                edge: Iso3d::new(rest_of(a, b))?,
                projected: self.projected_isometry,
            };
            self.iso3d.push(edge, as_u32([po + a, po + b]));
        }
        if self.effects.gravity {
            for k in 0..grid.len() {
                self.page_gravity
                    .push(Gravity::new(self.g, T::ZERO)?, as_u32([po + k]));
            }
        }
        Ok(())
    }

    /// The grip of one page: the pull's largest force, the tension that stretches one grid
    /// edge by [`BookSettings::grip_strain`] $\varepsilon_g$. An iso3D edge of rest length
    /// $\ell_0$ stretched by $\varepsilon$ pulls with $\partial_\ell\, w(\ell^2 -
    /// \ell_0^2)^2 \approx 8 w \ell_0^3 \varepsilon$ (eq. 13), so
    /// $F_g = 8\, w_{\mathrm{iso}}\, \ell_{min}^3\, \varepsilon_g$ with the grid's weight
    /// (see [`BookSettings::iso_scale`]) and its shorter spacing. Defaults: $8 \cdot 4000
    /// \cdot 1.5^3 \cdot 0.0075 = 810$, above the default pull's largest force on the
    /// leash, $2 w_{\mathrm{pos}} r = 800$, so the default grab never slips.
    #[must_use]
    pub fn grip_force(settings: &BookSettings<T>) -> T {
        let [across, along] = settings.grid_spacing();
        let l = across.min(along);
        let iso = settings.weights.iso_page.to_f64() * settings.iso_scale();
        T::from_f64(8.0 * iso * l * l * l) * settings.grip_strain
    }

    /// The grab pulls (eq. 14), one per node of the page's second ring, all off.
    fn push_pulls(&mut self) -> Result<(), KernelError> {
        let po = self.nodes.page_offset();
        for k in self.nodes.grid.second_ring() {
            let pull = Pull {
                kernel: Grip {
                    target: T::Vec3::ZERO,
                    radius: T::MAX,
                },
                active: false,
            };
            self.pull.push(pull, as_u32([po + k]));
            self.pull_nodes.push(po + k);
        }
        Ok(())
    }

    /// The pad's quads ([`crate::pad`]), one per quad of the page, all off.
    fn push_pads(&mut self) {
        let (grid, po) = (self.nodes.grid, self.nodes.page_offset());
        let off = PadGrip {
            kernel: PadQuad::ZERO,
            active: false,
        };
        for quad in 0..(grid.nx - 1) * (grid.nz - 1) {
            let nodes = corners(quad, grid.nx).map(|k| po + k);
            self.pad.push(off, as_u32(nodes));
        }
    }

    /// The contact springs, all off: one per block and cover node (with simulated blocks)
    /// and one per page node, when collisions are on.
    fn push_contacts(&mut self) -> Result<(), KernelError> {
        let fx = self.effects;
        let po = self.nodes.page_offset();
        let off = Contact {
            kernel: ContactPlane::new(
                T::Vec3::ZERO,
                T::Vec3::new(T::ZERO, T::ONE, T::ZERO),
                T::ZERO,
                T::ZERO,
            )?,
            active: false,
        };
        let contact_nodes = match (fx.collides(), fx.blocks) {
            (false, _) => 0..0,
            (true, true) => 0..self.nodes.total(),
            (true, false) => po..self.nodes.total(),
        };
        for node in contact_nodes {
            let set = if node < po {
                &mut self.block_contacts
            } else {
                &mut self.page_contacts
            };
            set.push(off, as_u32([node]));
        }
        Ok(())
    }

    /// The number of terms of `family`.
    #[must_use]
    pub fn count(&self, family: Family) -> usize {
        match family {
            Family::Gravity => self.block_gravity.terms().len() + self.page_gravity.terms().len(),
            Family::Glue => self.glue.terms().len(),
            Family::Contacts => {
                self.block_contacts.terms().len() + self.page_contacts.terms().len()
            }
            Family::BlockBending => self.bend_blocks.terms().len(),
            Family::BlockLinks => self.iso2d.terms().len(),
            Family::BindingFix => self.fix.terms().len(),
            Family::Dog => self.dog_inner.terms().len() + self.dog_boundary.terms().len(),
            Family::Binding => self.binding.terms().len(),
            Family::PageBending => self.bend_inner.terms().len() + self.bend_boundary.terms().len(),
            Family::PageIso => self.iso3d.terms().len(),
            Family::Pull => self.pull.terms().len(),
            Family::Pad => self.pad.terms().len(),
        }
    }

    /// The mass of `node` (page masses).
    #[must_use]
    pub fn mass(&self, node: usize) -> T {
        self.masses[node]
    }

    /// Sets the mass of `node` and its gravity term.
    fn set_mass(&mut self, node: usize, mass: T) {
        self.masses[node] = mass;
    }

    /// Spreads `left` and `right` block masses over their midlines, `cover` on each cover
    /// node, and `page` over the page grid by the nodes' dual-cell areas
    /// ([`quadrature::mass_fraction`]: a quarter cell at a corner, half on an edge);
    /// updates the gravity terms.
    pub fn set_masses(&mut self, left: T, right: T, cover: T, page: T) {
        let n = self.nodes;
        let per = |total: T, count: usize| total / T::from_f64(count as f64);
        for k in 0..n.midline {
            self.set_mass(n.block(false, k), per(left, n.midline));
            self.set_mass(n.block(true, k), per(right, n.midline));
        }
        if n.cover {
            self.set_mass(n.cover_end(false), cover);
            self.set_mass(n.cover_end(true), cover);
        }
        for k in 0..n.grid.len() {
            let share = T::from_f64(quadrature::mass_fraction(n.grid, k));
            self.set_mass(n.page_offset() + k, page * share);
        }
        let g = self.g;
        let masses = &self.masses;
        for (kernel, &m) in self.block_gravity.kernels_mut().zip(masses.iter()) {
            kernel.weight = g * m;
        }
        let po = n.page_offset();
        for (kernel, &m) in self.page_gravity.kernels_mut().zip(masses[po..].iter()) {
            kernel.weight = g * m;
        }
    }

    /// Scales the active page's bending, isometry and pull weights for a stack of `pages`
    /// pages (at least 1). Loose sheets slide over each other, so a stack of $k$ bends $k$
    /// times as stiffly as one sheet (not $k^3$, as a glued board would), stretches $k$
    /// times as stiffly, and weighs $k$ times as much ([`BookTerms::set_masses`]): every
    /// term of the page's energy scales with $k$ and the stack moves as one page does
    /// under the same grab. With the pull left at one page's weight, a 45-page stack sags
    /// out of the grab under 45 pages of gravity and falls back. The grip, a force the
    /// stack's stretch stiffness bounds, scales with it.
    pub fn set_stack(&mut self, pages: T) {
        let [bend, iso, pull, grip, pad] = self.page_weights.map(|w| w * pages);
        self.bend_inner.weight = bend;
        self.bend_boundary.weight = bend;
        self.iso3d.weight = iso;
        self.pull.weight = pull;
        self.pad.weight = pad;
        self.grip = grip;
    }

    /// Sets the binding parameter $q$ of the bound column (clamped to `[0, 1]`).
    pub fn set_binding_parameter(&mut self, q: T) {
        let q = folio_kernels::real::clamp_keep_nan(q, T::ZERO, T::ONE);
        for b in self.binding.kernels_mut() {
            b.q = q;
        }
    }

    /// The nodes that can be grabbed (the page's second ring), in pull order.
    #[must_use]
    pub fn pull_nodes(&self) -> &[usize] {
        &self.pull_nodes
    }

    /// Holds `node` at `target` (or releases every node with `None`), with the grip's
    /// radius $\rho = F_g / (2 w_{\mathrm{pos}})$ ([`Grip`], [`BookTerms::grip_force`]).
    pub fn set_pull(&mut self, held: Option<(usize, T::Vec3)>) {
        let w = self.pull.weight;
        let radius = if w > T::ZERO {
            self.grip / (T::TWO * w)
        } else {
            T::MAX
        };
        for (kernel, &node) in self.pull.kernels_mut().zip(&self.pull_nodes) {
            match held {
                Some((h, target)) if h == node => {
                    kernel.active = true;
                    kernel.kernel = Grip { target, radius };
                }
                _ => kernel.active = false,
            }
        }
    }

    /// Whether the book holds its page with a pad ([`BookSettings::pad_radius`]).
    #[must_use]
    pub fn has_pad(&self) -> bool {
        cfg!(feature = "pad") && !self.pad.terms().is_empty()
    }

    /// Holds the pad's points `samples` at `targets` (one each, page units), or lets the
    /// pad go with `None`: the quads that hold a point get [`PadQuad`]'s sums, the others are
    /// switched off.
    pub fn set_pad(&mut self, held: Option<(&[PadSample], &[T::Vec3])>) {
        for kernel in self.pad.kernels_mut() {
            kernel.active = false;
            kernel.kernel = PadQuad::ZERO;
        }
        let Some((samples, targets)) = held else {
            return;
        };
        for (s, &p) in samples.iter().zip(targets) {
            let Some(kernel) = self.pad.kernel_mut(s.quad) else {
                continue;
            };
            let q = &mut kernel.kernel;
            let a = T::from_f64(s.share);
            for k in 0..4 {
                let nk = T::from_f64(s.shape[k]);
                for l in 0..4 {
                    q.a[k][l] += a * nk * T::from_f64(s.shape[l]);
                }
                q.b[k] += p * (a * nk);
            }
            q.c += a * p.dot(p);
            kernel.active = true;
        }
    }

    /// Switches every contact spring off.
    pub fn clear_contacts(&mut self) {
        let sets = [&mut self.block_contacts, &mut self.page_contacts];
        for kernel in sets.into_iter().flat_map(PotentialSet::kernels_mut) {
            kernel.active = false;
        }
    }

    /// The plane of page node `node`'s contact spring (global index), while it is on.
    #[must_use]
    pub fn page_contact(&self, node: usize) -> Option<ContactPlane<T>> {
        let po = self.nodes.page_offset();
        let term = self.page_contacts.terms().get(node.checked_sub(po)?)?;
        term.kernel.active.then_some(term.kernel.kernel)
    }

    /// Holds `node` against `plane` in the next steps, until [`BookTerms::clear_contacts`].
    pub fn set_contact(&mut self, node: usize, plane: ContactPlane<T>) {
        let po = self.nodes.page_offset();
        let kernel = if node < po {
            self.block_contacts.kernel_mut(node)
        } else {
            self.page_contacts.kernel_mut(node - po)
        };
        if let Some(kernel) = kernel {
            kernel.kernel = plane;
            kernel.active = true;
        }
    }

    /// The target of the pull on `node`, if that node is held.
    #[must_use]
    pub fn pull_target(&self, node: usize) -> Option<T::Vec3> {
        self.pull
            .terms()
            .iter()
            .find(|t| t.nodes[0] as usize == node && t.kernel.active)
            .map(|t| t.kernel.kernel.target)
    }

    /// Largest $\lvert C_{\mathrm{DOG}}\rvert$ over the page's stars at `x`.
    #[must_use]
    pub fn dog_residual(&self, x: &[T::Vec3]) -> T {
        use folio_kernels::Constraint;
        let mut worst = T::ZERO;
        let mut note = |v: T| {
            let a = folio_kernels::math::abs(v);
            // A non-finite residual must show.
            if a > worst || !a.is_finite() {
                worst = a;
            }
        };
        for t in self.dog_inner.terms() {
            let local = t.nodes.map(|k| x[k as usize]);
            t.kernel.value(&local).into_iter().for_each(&mut note);
        }
        for t in self.dog_boundary.terms() {
            let local = t.nodes.map(|k| x[k as usize]);
            t.kernel.value(&local).into_iter().for_each(&mut note);
        }
        worst
    }
}

/// The blocks alone: every page node is eliminated and no page term is visited.
#[derive(Clone, Copy, Debug)]
pub struct RestView<'a, T: Real>(pub &'a BookTerms<T>);

/// The blocks and the active page.
#[derive(Clone, Copy, Debug)]
pub struct ActiveView<'a, T: Real>(pub &'a BookTerms<T>);

impl<T: Real> Model<T> for RestView<'_, T> {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.0.nodes.total()
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        axis == 2 || node >= self.0.nodes.page_offset() || !self.0.effects.blocks
    }
    fn mass(&self, node: usize) -> T {
        self.0.masses[node]
    }
    fn visit_terms<V: TermVisitor<T>>(&self, v: &mut V) {
        visit_blocks(self.0, v);
    }
}

impl<T: Real> Model<T> for ActiveView<'_, T> {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.0.nodes.total()
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        let n = &self.0.nodes;
        let block = node < n.page_offset();
        (block && !self.0.effects.blocks) || (axis == 2 && (block || n.is_bound(node)))
    }
    fn mass(&self, node: usize) -> T {
        self.0.masses[node]
    }
    fn visit_terms<V: TermVisitor<T>>(&self, v: &mut V) {
        let t = self.0;
        visit_blocks(t, v);
        v.potentials(&t.bend_inner);
        v.potentials(&t.bend_boundary);
        v.potentials(&t.iso3d);
        v.potentials(&t.page_gravity);
        v.potentials(&t.pull);
        if cfg!(feature = "pad") {
            v.potentials(&t.pad);
        }
        v.potentials(&t.page_contacts);
        v.constraints(&t.dog_inner);
        v.constraints(&t.dog_boundary);
        v.constraints(&t.binding);
    }
}

fn visit_blocks<T: Real, V: TermVisitor<T>>(t: &BookTerms<T>, v: &mut V) {
    v.potentials(&t.bend_blocks);
    v.potentials(&t.glue);
    v.potentials(&t.block_gravity);
    v.potentials(&t.block_contacts);
    v.constraints(&t.iso2d);
    v.constraints(&t.fix);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BookParams, Effects};

    fn map(cover: bool) -> NodeMap {
        NodeMap {
            midline: 5,
            cover,
            grid: QuadGrid::new(3, 2).unwrap(),
        }
    }

    #[test]
    fn node_map_numbers_every_node_once() {
        for cover in [true, false] {
            let n = map(cover);
            let mut all: Vec<usize> = (0..n.midline)
                .flat_map(|k| [n.block(false, k), n.block(true, k)])
                .collect();
            if cover {
                all.extend([n.cover_end(false), n.cover_end(true)]);
            }
            assert_eq!(all.len(), n.page_offset());
            for j in 0..n.grid.nz {
                for i in 0..n.grid.nx {
                    all.push(n.page(i, j));
                }
            }
            all.sort_unstable();
            assert_eq!(all, (0..n.total()).collect::<Vec<_>>());
        }
    }

    #[test]
    fn node_map_layout_is_the_documented_one() {
        let n = map(true);
        // Left midline 0..m, right m..2m, cover ends, then the grid i + nx j.
        assert_eq!((n.block(false, 0), n.block(false, 4)), (0, 4));
        assert_eq!((n.block(true, 0), n.block(true, 4)), (5, 9));
        assert_eq!((n.cover_end(false), n.cover_end(true)), (10, 11));
        assert_eq!(n.page_offset(), 12);
        assert_eq!((n.grid.nx, n.grid.nz), (4, 3));
        assert_eq!(n.page(0, 0), 12);
        assert_eq!(n.page(3, 0), 15);
        assert_eq!(n.page(1, 2), 12 + 1 + 4 * 2);
        assert_eq!(n.total(), 12 + 12);
        assert_eq!(map(false).page_offset(), 10);
    }

    #[test]
    fn only_column_zero_is_bound() {
        let n = map(true);
        for node in 0..n.total() {
            let bound = node >= n.page_offset() && n.grid.coords(node - n.page_offset()).0 == 0;
            assert_eq!(n.is_bound(node), bound, "node {node}");
        }
        let free: Vec<usize> = n.free_page_nodes().collect();
        assert_eq!(free.len(), n.grid.len() - n.grid.nz);
        assert!(free.windows(2).all(|w| w[0] < w[1]));
        assert!(free.iter().all(|&k| k >= n.page_offset() && !n.is_bound(k)));
    }

    fn settings(effects: Effects) -> BookSettings<f64> {
        BookSettings {
            params: BookParams {
                midline_nodes: 5,
                ..BookParams::default()
            },
            quads_across: 3,
            quads_along: 2,
            effects,
            ..BookSettings::default()
        }
    }

    fn terms(effects: Effects) -> BookTerms<f64> {
        let s = settings(effects);
        let layout = BookLayout::new(s.params).unwrap();
        let grid = QuadGrid::new(s.quads_across, s.quads_along).unwrap();
        BookTerms::new(&layout, &s, grid).unwrap()
    }

    #[test]
    fn term_counts_follow_the_grid_and_the_midlines() {
        let t = terms(Effects::ALL);
        let (m, grid) = (t.nodes.midline, t.nodes.grid);
        // Links: 2 (m - 1) midline segments, the binding width, two cover boards.
        assert_eq!(t.count(Family::BlockLinks), 2 * (m - 1) + 1 + 2);
        assert_eq!(t.count(Family::BlockBending), 2 * (m - 2));
        assert_eq!(t.count(Family::BindingFix), 1);
        assert_eq!(t.count(Family::Glue), 1);
        assert_eq!(t.count(Family::Binding), grid.nz);
        assert_eq!(t.count(Family::PageIso), grid.edges().len());
        let corners = 4;
        assert_eq!(t.count(Family::Dog), grid.stars().len() - corners);
        assert_eq!(t.count(Family::PageBending), t.count(Family::Dog));
        assert_eq!(t.count(Family::Gravity), t.nodes.total());
        assert_eq!(t.count(Family::Contacts), t.nodes.total());
        assert_eq!(t.count(Family::Pull), grid.second_ring().len());
        assert_eq!(t.pull_nodes().len(), t.count(Family::Pull));
        assert!(t.pull_nodes().iter().all(|&k| k >= t.nodes.page_offset()));
    }

    #[test]
    fn fixed_blocks_build_no_block_terms() {
        let mut fx = Effects::ALL;
        fx.blocks = false;
        let t = terms(fx);
        for family in [
            Family::BlockLinks,
            Family::BlockBending,
            Family::BindingFix,
            Family::Glue,
        ] {
            assert_eq!(t.count(family), 0, "{family:?}");
        }
        assert_eq!(t.count(Family::Gravity), t.nodes.grid.len());
        assert_eq!(t.count(Family::Contacts), t.nodes.grid.len());
    }

    #[test]
    fn masses_spread_and_the_pull_holds_one_node() {
        let mut t = terms(Effects::ALL);
        let n = t.nodes;
        t.set_masses(5.0, 10.0, 3.0, 1.0);
        let m = n.midline as f64;
        assert_eq!(t.mass(n.block(false, 1)), 5.0 / m);
        assert_eq!(t.mass(n.block(true, 1)), 10.0 / m);
        assert_eq!(t.mass(n.cover_end(true)), 3.0);
        let cells = ((n.grid.nx - 1) * (n.grid.nz - 1)) as f64;
        assert_eq!(t.mass(n.page(1, 1)), 1.0 / cells);
        assert_eq!(t.mass(n.page(0, 0)), 0.25 / cells);
        let [a, b] = [t.pull_nodes()[0], t.pull_nodes()[1]];
        let target = <f64 as Real>::Vec3::new(1.0, 2.0, 3.0);
        t.set_pull(Some((a, target)));
        assert_eq!(t.pull_target(a), Some(target));
        assert_eq!(t.pull_target(b), None);
        t.set_pull(None);
        assert_eq!(t.pull_target(a), None);
    }
}
