//! [`Tears`]: the tearing step of seed `002_…` (Fig. 4, steps 1-3) on a [`SheetMesh`]:
//! potential tearing points, fracture energy (eq. 3), force split and release rate
//! (eq. 4-6), the Griffith criterion (eq. 1), one propagation, and the detail path drawn into
//! the tear's alpha textures (eq. 7).
//!
//! **One step** ([`Tears::step`]) examines every candidate ([`crate::candidates`]) with the
//! in-plane stretching gradients of the triangles from the physics, and propagates the one
//! whose release rate exceeds its fracture energy by the largest ratio
//! $E_r / E_f$ (the seed treats the candidates one after the other with a physics step
//! between; the caller does that by calling `step` again after a physics step). The step
//! length is $c_{\text{speed}} E_r$ clamped to
//! [`TearSettings::min_step`]..[`TearSettings::max_step`].
//!
//! **Fracture energy** (eq. 3): $E_f(p) = c\thinspace T_{\text{fibers}}(u, v)\thinspace d_p$ with $d_p = D$ at
//! tear tips and 1 elsewhere.
//!
//! **Tears.** A propagation from a tip extends that tear. Any other start begins a new
//! tear; when the start lies on an existing tear's path (a lip, seed Sec. 5.3: "the tear
//! could thus even branch at this point"), the new tear is a branch and its alpha textures
//! start as a copy of its parent's (Sec. 6.2).
//!
//! **The disk estimator's rules** ([`Estimator::Disk`]; the choices the seed does not make,
//! each a named constant):
//! - a boundary vertex whose pattern angle is at least [`SLIT_ANGLE`] ($1.75\pi$) is a slit
//!   (a tip or a notch): its crack runs along the slit's bisector, read where the lips
//!   leave [`LIP_READING`] (half) of the disk's radius, and turns by the kink of the mode
//!   mixity; elsewhere the tear starts along $J$;
//! - a candidate other than a tip that lies within the disk of a tip is not evaluated: its
//!   $J$ is mostly that tip's, and a kink a step behind a tip would start a branch there.

use alloc::vec::Vec;

use folio_geometry::SheetMesh;
use folio_geometry::sheet::{SheetError, pattern_distance2};
use folio_kernels::real::vec_is_finite;
use folio_kernels::{Real, Vec3Ops, math};

use crate::advance::{Advance, Edit, advance, wedge};
use crate::candidates::{Candidate, Kind, collect};
use crate::detail::{Raster, detail_path};
use crate::fiber::FiberTexture;
use crate::mixity::{kink_angle, mode_mixity};
use crate::release::{TriangleLoads, cone_weights, configurational_force};
use crate::settings::{Estimator, TearSettings, TipRemesh};
use crate::split::{Pull, Split, split_forces, unit};
use crate::texture::{AlphaPair, PathProfile, Side};
use folio_kernels::SettingError;
use folio_solvers::room::Room;

/// Smallest pattern angle (radians, $1.75\pi$) of a boundary vertex that the disk estimator
/// reads as a slit, a tip or a notch (module docs): a straight border has $\pi$, a tip
/// $2\pi$.
pub const SLIT_ANGLE: f64 = 1.75 * core::f64::consts::PI;

/// Where a slit's lips are read for its bisector, as a fraction of the disk's radius
/// (module docs): far enough that a short last step does not turn the crack's frame.
pub const LIP_READING: f64 = 0.5;

/// The release rate and direction at vertex `v` over the disk of the settings, zero for no
/// release ([`crate::release`], [`crate::mixity`]):
/// - at a slit (a tear's tip, or a notch: a pattern angle of at least $1.75\pi$), the crack
///   runs along $d$, the bisector of the slit pointing into the sheet, its lips read at
///   half the disk's radius; the tear kinks from
///   $d$ by the maximum hoop stress's $\theta_c$ for the disk's $K_{II}/K_I$, and releases
///   $E_r = J \cdot d / e$, the part of $J$ that does not count the lips;
/// - elsewhere (a border a tear would start from) $t = J / |J|$ and $E_r = |J| / e$.
///
/// `None` when $J$ is not finite (a non-finite stress in the disk).
fn disk_load<T: Real>(
    mesh: &SheetMesh<T>,
    loads: &TriangleLoads<'_, T>,
    v: u32,
    settings: &TearSettings,
    weights: &mut Vec<f64>,
) -> Option<(T, [T; 2])> {
    cone_weights(mesh, v, settings.disk_radius, loads.prescribed, weights);
    let j = configurational_force(mesh, loads, weights);
    let norm = math::sqrt(j[0] * j[0] + j[1] * j[1]);
    if !norm.is_finite() {
        return None;
    }
    if norm == 0.0 {
        return Some((T::ZERO, [T::ZERO; 2]));
    }
    let to_t = |x: [f64; 2]| [T::from_f64(x[0]), T::from_f64(x[1])];
    if let Some(d) = slit_direction(mesh, v, LIP_READING * settings.disk_radius) {
        let p = mesh.pattern()[v as usize];
        let tip = [p[0].to_f64(), p[1].to_f64()];
        let along = j[0] * d[0] + j[1] * d[1];
        if let Some(rho) = mode_mixity(mesh, loads, tip, d, weights)
            && along > 0.0
        {
            let (sin, cos) = (math::sin(kink_angle(rho)), math::cos(kink_angle(rho)));
            let t = [cos * d[0] - sin * d[1], sin * d[0] + cos * d[1]];
            return Some((T::from_f64(along / settings.thickness), to_t(t)));
        }
        return Some((T::ZERO, [T::ZERO; 2]));
    }
    Some((
        T::from_f64(norm / settings.thickness),
        to_t([j[0] / norm, j[1] / norm]),
    ))
}

/// At a boundary vertex whose pattern angle is at least $1.75\pi$ (a slit), the unit
/// pattern direction pointing into the sheet along the slit's bisector:
/// $-(\hat a + \hat b) / |\hat a + \hat b|$ for $\hat a$, $\hat b$ the directions to the
/// points where the two lips leave the distance `reach` (walking the boundary both ways;
/// the last point of a lip that ends sooner), so that a short last step of the tear does not
/// turn the crack's frame.
fn slit_direction<T: Real>(mesh: &SheetMesh<T>, v: u32, reach: f64) -> Option<[f64; 2]> {
    if mesh.pattern_angle(v).to_f64() < SLIT_ANGLE {
        return None;
    }
    let p = mesh.pattern()[v as usize];
    let offset = |w: u32| {
        let q = mesh.pattern()[w as usize];
        [(q[0] - p[0]).to_f64(), (q[1] - p[1]).to_f64()]
    };
    let mut sum = [0.0; 2];
    for forward in [true, false] {
        let mut at = v;
        let mut d = [0.0; 2];
        // At most as many steps as there are vertices (a boundary loop ends the walk).
        for _ in 0..mesh.vertex_count() {
            let (next, previous) = mesh.boundary_neighbours(at)?;
            at = if forward { next } else { previous };
            if at == v {
                break;
            }
            d = offset(at);
            if d[0] * d[0] + d[1] * d[1] >= reach * reach {
                break;
            }
        }
        let n = math::sqrt(d[0] * d[0] + d[1] * d[1]);
        if n == 0.0 || !n.is_finite() {
            return None;
        }
        sum = [sum[0] - d[0] / n, sum[1] - d[1] / n];
    }
    let n = math::sqrt(sum[0] * sum[0] + sum[1] * sum[1]);
    (n > 1e-9 && n.is_finite()).then(|| [sum[0] / n, sum[1] / n])
}

/// One tear: its path in the pattern, its tip, and its alpha textures.
#[derive(Clone, Debug)]
pub struct Tear<T> {
    /// The tear it branched from.
    pub parent: Option<usize>,
    /// The tip vertex (`None` once the tear has reached the boundary).
    pub tip: Option<u32>,
    /// Pattern points from the start to the tip.
    pub path: Vec<[T; 2]>,
    /// Unit pattern direction of the last segment.
    pub direction: [T; 2],
    /// $T_{\text{left}}$ and $T_{\text{right}}$ (Sec. 6.2).
    pub alpha: AlphaPair,
}

impl<T: Real> Tear<T> {
    /// A tear not started yet: opaque masks on `raster`, an empty path with room for
    /// [`PATH_ROOM`] points.
    fn pristine(raster: Raster) -> Self {
        Self {
            parent: None,
            tip: None,
            path: Vec::with_capacity(PATH_ROOM),
            direction: [T::ZERO; 2],
            alpha: AlphaPair::new(raster),
        }
    }
}

/// A candidate with its load and fracture energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation<T> {
    /// The point.
    pub candidate: Candidate,
    /// $E_r$, energy released per unit of new crack area (force per sheet unit): the disk's
    /// $|J| / e$ ([`crate::release`]) or the split's eq. 6, per
    /// [`TearSettings::estimator`].
    pub release_rate: T,
    /// Unit tear direction in the pattern (zero when nothing is released).
    pub direction: [T; 2],
    /// The seed's force split (eq. 4-6), when that is the estimator.
    pub split: Option<Split<T>>,
    /// $E_f$ (eq. 3).
    pub fracture_energy: T,
    /// `true` when the direction points into the sheet.
    pub inward: bool,
}

/// A propagation that happened.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Propagation<T> {
    /// Index of the tear in [`Tears::tears`].
    pub tear: usize,
    /// Why the start vertex was a candidate.
    pub kind: Kind,
    /// Pattern point of the old tip.
    pub from: [T; 2],
    /// Pattern point of the new tip.
    pub to: [T; 2],
    /// $E_r$ and $E_f$ at the start.
    pub release_rate: T,
    /// $E_f$ at the start.
    pub fracture_energy: T,
    /// What the mesh edit was.
    pub edit: Edit,
}

/// What [`Tears::step`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TearStep<T> {
    /// Candidates examined.
    pub candidates: usize,
    /// The propagation, if one happened.
    pub propagation: Option<Propagation<T>>,
    /// The last propagation the Griffith criterion allowed but the mesh refused (the sheet
    /// is unchanged by it; reported, not fatal; the next point by ratio was tried then).
    pub refused: Option<SheetError>,
    /// Candidates whose load was not finite (a non-finite stress or force in the physics'
    /// loads): not propagated, and counted here so that the caller can report them.
    pub non_finite: u32,
}

/// The tears of one sheet and the tearing step's buffers (module docs).
#[derive(Clone, Debug)]
pub struct Tears<T: Real> {
    settings: TearSettings,
    fibers: FiberTexture,
    raster: Raster,
    tears: Vec<Tear<T>>,
    candidates: Vec<Candidate>,
    evaluations: Vec<Evaluation<T>>,
    pulls: Vec<Pull<T>>,
    pixels: Vec<(u32, u32)>,
    tip_buffer: Vec<u32>,
    weights: Vec<f64>,
    /// The cuts' offset bins.
    profile: PathProfile,
    /// Tears made at setup ([`TearSettings::reserved_tears`]), opaque and with an empty
    /// path, taken by [`Tears::start_tear`] (never given back, so always pristine).
    spare: Vec<Tear<T>>,
    /// Candidates of the last evaluation whose load was not finite.
    non_finite: u32,
}

/// Path points reserved per tear: a longer path grows its buffer.
const PATH_ROOM: usize = 256;

impl<T: Real> Tears<T> {
    /// No tears yet, on a sheet whose pattern spans $[0, W] \times [0, H]$ (`size`).
    ///
    /// # Errors
    /// A [`SettingError`] for bad settings ([`TearSettings::validate`]) or a size the
    /// texture raster refuses (`sheet_width`, `sheet_height`).
    pub fn new(settings: TearSettings, size: [f64; 2]) -> Result<Self, SettingError> {
        settings.validate()?;
        let px = |x: f64| {
            // Ceiling without std: the truncation, plus one when it cut something off.
            let n = (x * settings.texture_density).clamp(1.0, 8192.0);
            let k = n as u32;
            if f64::from(k) < n { k + 1 } else { k }
        };
        let raster = Raster::new(px(size[0]), px(size[1]), size[0], size[1])?;
        // A detail path is a walk of at most the raster's longer side (it moves one pixel
        // closer to its end at every step, in both directions at once when it can).
        let longest_path = raster.width_px().max(raster.height_px()) as usize + 1;
        let mut profile = PathProfile::default();
        profile.reserve(longest_path);
        let spare = (0..settings.reserved_tears)
            .map(|_| Tear::pristine(raster))
            .collect();
        Ok(Self {
            fibers: FiberTexture::new(settings.fibers)?,
            settings,
            raster,
            tears: Vec::new(),
            candidates: Vec::new(),
            evaluations: Vec::new(),
            pulls: Vec::new(),
            pixels: Vec::with_capacity(longest_path),
            tip_buffer: Vec::new(),
            weights: Vec::new(),
            profile,
            spare,
            non_finite: 0,
        })
    }

    /// Makes room in the tearing step's buffers for a mesh of `vertices` vertices: a step
    /// on a mesh within it allocates nothing, unless it starts a tear beyond
    /// [`TearSettings::reserved_tears`].
    pub fn reserve(&mut self, vertices: usize) {
        let tears = self.tears.len() + self.spare.len();
        self.tears.room_for(tears);
        self.tip_buffer.room_for(tears);
        let candidates = self.settings.max_candidates;
        self.candidates.room_for(candidates);
        self.evaluations.room_for(candidates);
        self.pulls.room_for(vertices);
        self.weights.room_for(vertices);
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &TearSettings {
        &self.settings
    }

    /// The fiber texture.
    #[must_use]
    pub fn fibers(&self) -> &FiberTexture {
        &self.fibers
    }

    /// The raster of the alpha textures.
    #[must_use]
    pub fn raster(&self) -> &Raster {
        &self.raster
    }

    /// The tears so far.
    #[must_use]
    pub fn tears(&self) -> &[Tear<T>] {
        &self.tears
    }

    /// The candidates of the last step with their splits.
    #[must_use]
    pub fn evaluations(&self) -> &[Evaluation<T>] {
        &self.evaluations
    }

    /// Tip vertices of the open tears.
    pub fn tips(&self) -> impl Iterator<Item = u32> + '_ {
        self.tears.iter().filter_map(|t| t.tip)
    }

    /// $E_f$ at pattern point `p` (eq. 3), with $d_p = D$ for a tip.
    #[must_use]
    pub fn fracture_energy(&self, p: [T; 2], tip: bool) -> T {
        let fiber = self.fibers.value(p[0].to_f64(), p[1].to_f64());
        let damage = if tip { self.settings.damage } else { 1.0 };
        T::from_f64(self.settings.fracture * fiber * damage)
    }

    /// Examines the candidates of `mesh` (module docs). `loads` are the triangles'
    /// stretching gradients and Eshelby tensors; `fingers` are the vertices held by fingers,
    /// `junctions` the cone layer's junction points.
    pub fn evaluate(
        &mut self,
        mesh: &SheetMesh<T>,
        loads: &TriangleLoads<'_, T>,
        fingers: &[u32],
        junctions: &[u32],
    ) {
        self.tip_buffer.clear();
        self.tip_buffer
            .extend(self.tears.iter().filter_map(|t| t.tip));
        collect(
            &mut self.candidates,
            mesh,
            &self.tip_buffer,
            fingers,
            match self.settings.estimator {
                Estimator::Disk => loads.prescribed,
                Estimator::Split => &[],
            },
            junctions,
            T::from_f64(self.settings.inward_angle),
            self.settings.max_candidates,
        );
        self.evaluations.clear();
        self.non_finite = 0;
        for &candidate in &self.candidates {
            let v = candidate.vertex;
            let p = mesh.pattern()[v as usize];
            let fracture_energy = self.fracture_energy(p, candidate.kind == Kind::Tip);
            if self.settings.estimator == Estimator::Disk {
                // Not within another tip's disk (module docs).
                let radius2 = self.settings.disk_radius * self.settings.disk_radius;
                let near_tip = candidate.kind != Kind::Tip
                    && self.tip_buffer.iter().any(|&tip| {
                        let q = mesh.pattern()[tip as usize];
                        let d = [(q[0] - p[0]).to_f64(), (q[1] - p[1]).to_f64()];
                        d[0] * d[0] + d[1] * d[1] < radius2
                    });
                if near_tip {
                    continue;
                }
                let Some((release_rate, direction)) =
                    disk_load(mesh, loads, v, &self.settings, &mut self.weights)
                else {
                    self.non_finite += 1;
                    continue;
                };
                let inward = release_rate > T::ZERO && wedge(mesh, v, direction).is_some();
                self.evaluations.push(Evaluation {
                    candidate,
                    release_rate,
                    direction,
                    split: None,
                    fracture_energy,
                    inward,
                });
                continue;
            }
            self.pulls.clear();
            let mut normal = T::Vec3::ZERO;
            let mut finite_pulls = true;
            for h in mesh.fan_iter(v) {
                let t = h as usize / 3;
                let (Some(g), Some(f)) = (loads.gradients.get(t), loads.deformations.get(t)) else {
                    continue;
                };
                let corner = h as usize % 3;
                finite_pulls &= [g[corner], f[0], f[1]].into_iter().all(vec_is_finite::<T>);
                let [a, b, c] = mesh.triangles()[t].map(|i| mesh.positions()[i as usize]);
                let centroid = (a + b + c) * T::from_f64(1.0 / 3.0);
                self.pulls.push(Pull {
                    force: -g[corner],
                    toward: centroid - mesh.positions()[v as usize],
                    gradient: *f,
                });
                normal += triangle_normal(mesh, t);
            }
            let normal = unit::<T>(normal);
            let b0 = outward(mesh, v, normal);
            let split = split_forces(
                &self.pulls,
                normal,
                b0,
                T::from_f64(self.settings.thickness),
                T::from_f64(self.settings.bisector_tolerance),
            );
            let finite = finite_pulls
                && split.release_rate.is_finite()
                && split.direction[0].is_finite()
                && split.direction[1].is_finite();
            if !finite {
                self.non_finite += 1;
                continue;
            }
            let inward = split.release_rate > T::ZERO && wedge(mesh, v, split.direction).is_some();
            self.evaluations.push(Evaluation {
                candidate,
                release_rate: split.release_rate,
                direction: split.direction,
                split: Some(split),
                fracture_energy,
                inward,
            });
        }
    }

    /// Propagates the evaluation of the last [`Tears::evaluate`] that passes the Griffith
    /// criterion $E_r \ge E_f$ (eq. 1) by the largest ratio (module docs). When the mesh
    /// refuses that one (the sheet is then unchanged), the next one by ratio is tried, and
    /// so on: a refused point does not hold back the others.
    pub fn propagate(&mut self, mesh: &mut SheetMesh<T>) -> TearStep<T> {
        let mut step = TearStep {
            candidates: self.evaluations.len(),
            propagation: None,
            refused: None,
            non_finite: self.non_finite,
        };
        let tiny = T::from_f64(1e-30);
        // Walk the passing evaluations by falling ratio, ties by index, without sorting.
        let mut above: Option<(T, usize)> = None;
        loop {
            let next = self
                .evaluations
                .iter()
                .enumerate()
                .filter(|(_, e)| e.inward && e.release_rate >= e.fracture_energy)
                .map(|(i, e)| (e.release_rate / (e.fracture_energy + tiny), i))
                .filter(|&(r, i)| above.is_none_or(|(ar, ai)| r < ar || (r == ar && i > ai)))
                .fold(None, |best: Option<(T, usize)>, x| match best {
                    Some(b) if b.0 >= x.0 => Some(b),
                    _ => Some(x),
                });
            let Some((ratio, index)) = next else {
                return step;
            };
            above = Some((ratio, index));
            match self.advance_evaluation(mesh, self.evaluations[index]) {
                Ok(propagation) => {
                    step.propagation = Some(propagation);
                    return step;
                }
                Err(err) => step.refused = Some(err),
            }
        }
    }

    /// The propagation of evaluation `e`: the mesh edit, then the tear's path and textures.
    ///
    /// # Errors
    /// The edit's error; the sheet and the tears are unchanged then.
    fn advance_evaluation(
        &mut self,
        mesh: &mut SheetMesh<T>,
        e: Evaluation<T>,
    ) -> Result<Propagation<T>, SheetError> {
        let v = e.candidate.vertex;
        let from = mesh.pattern()[v as usize];
        let tear = self.tears.iter().position(|t| t.tip == Some(v));
        let t = e.direction;
        let shaped = self.settings.remesh == TipRemesh::Shaped;
        let straight = tear.is_some_and(|i| {
            let d = self.tears[i].direction;
            let cos = (d[0] * t[0] + d[1] * t[1]).to_f64().clamp(-1.0, 1.0);
            acos(cos) <= self.settings.turn_threshold || (shaped && short_segment(mesh, v))
        });
        let length = T::from_f64(
            (self.settings.speed * e.release_rate.to_f64())
                .clamp(self.settings.min_step, self.settings.max_step),
        );
        let outcome: Advance = advance(
            mesh,
            v,
            t,
            length,
            straight,
            T::from_f64(self.settings.snap),
            shaped,
        )?;
        let to = match outcome.tip {
            Some(q) => mesh.pattern()[q as usize],
            None => from_cut_end(mesh, &outcome, from),
        };
        let index = match tear {
            Some(i) => i,
            None => self.start_tear(from, t),
        };
        self.extend(index, from, to, outcome.tip);
        Ok(Propagation {
            tear: index,
            kind: e.candidate.kind,
            from,
            to,
            release_rate: e.release_rate,
            fracture_energy: e.fracture_energy,
            edit: outcome.edit,
        })
    }

    /// [`Tears::evaluate`] then [`Tears::propagate`].
    pub fn step(
        &mut self,
        mesh: &mut SheetMesh<T>,
        loads: &TriangleLoads<'_, T>,
        fingers: &[u32],
        junctions: &[u32],
    ) -> TearStep<T> {
        self.evaluate(mesh, loads, fingers, junctions);
        self.propagate(mesh)
    }

    /// A new tear starting at `from` in direction `t`: a branch when `from` lies on an
    /// existing tear's path, its textures copied from the parent's lip on the side `t`
    /// leaves to.
    fn start_tear(&mut self, from: [T; 2], t: [T; 2]) -> usize {
        let tolerance = 1e-6 * (self.raster.sheet_width() + self.raster.sheet_height());
        let parent = self.tears.iter().position(|tear| {
            tear.path
                .windows(2)
                .any(|w| segment_distance(from, w[0], w[1]) <= tolerance)
        });
        let mut tear = self
            .spare
            .pop()
            .unwrap_or_else(|| Tear::pristine(self.raster));
        if let Some(i) = parent {
            let d = self.tears[i].direction;
            let side = if d[0] * t[1] - d[1] * t[0] >= T::ZERO {
                Side::Left
            } else {
                Side::Right
            };
            tear.alpha.branch_of(&self.tears[i].alpha, side);
        }
        tear.parent = parent;
        tear.path.push(from);
        self.tears.push(tear);
        self.tears.len() - 1
    }

    /// Appends the segment `from → to` to tear `index`: path, direction, tip, detail path and
    /// alpha textures.
    fn extend(&mut self, index: usize, from: [T; 2], to: [T; 2], tip: Option<u32>) {
        let (a, b) = (
            [from[0].to_f64(), from[1].to_f64()],
            [to[0].to_f64(), to[1].to_f64()],
        );
        detail_path(
            &mut self.pixels,
            &self.raster,
            &self.fibers,
            a,
            b,
            &self.settings.detail,
        );
        // The band the cut may change: four standard deviations of the stress field and two
        // pixels.
        let pixel = self.raster.pixel_size();
        let band = 4.0 * self.settings.detail.sigma + 2.0 * pixel[0].max(pixel[1]);
        let tear = &mut self.tears[index];
        tear.alpha
            .cut_with(&mut self.profile, &self.pixels, a, b, band);
        let d = [to[0] - from[0], to[1] - from[1]];
        let len = math::sqrt(d[0] * d[0] + d[1] * d[1]);
        if len > T::ZERO {
            tear.direction = [d[0] / len, d[1] / len];
        }
        tear.path.push(to);
        tear.tip = tip;
    }
}

/// Where a separating cut ended: the pattern point of the cut's far end.
fn from_cut_end<T: Real>(mesh: &SheetMesh<T>, outcome: &Advance, from: [T; 2]) -> [T; 2] {
    outcome
        .cut
        .and_then(|c| c.splits[1])
        .map_or(from, |(q, _)| mesh.pattern()[q as usize])
}

/// $\arccos$ in f64 through the math shim (`atan2(sqrt(1 - c^2), c)`).
fn acos(c: f64) -> f64 {
    math::atan2(math::sqrt((1.0 - c * c).max(0.0)), c)
}

/// Distance from pattern point `p` to segment `a → b`.
fn segment_distance<T: Real>(p: [T; 2], a: [T; 2], b: [T; 2]) -> f64 {
    let (p, a, b) = (
        [p[0].to_f64(), p[1].to_f64()],
        [a[0].to_f64(), a[1].to_f64()],
        [b[0].to_f64(), b[1].to_f64()],
    );
    let e = [b[0] - a[0], b[1] - a[1]];
    let len2 = e[0] * e[0] + e[1] * e[1];
    let s = if len2 > 0.0 {
        (((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [a[0] + s * e[0] - p[0], a[1] + s * e[1] - p[1]];
    math::sqrt(d[0] * d[0] + d[1] * d[1])
}

/// Area-weighted normal of triangle `t` (twice its 3D area times the unit normal).
fn triangle_normal<T: Real>(mesh: &SheetMesh<T>, t: usize) -> T::Vec3 {
    let [a, b, c] = mesh.triangles()[t].map(|i| mesh.positions()[i as usize]);
    (b - a).cross(c - a)
}

/// The initial bisector $b^0$ at boundary vertex `v` (Sec. 5.1): the bisector of the two
/// boundary tangents, pointing out of the sheet; the outward normal of the border where the
/// boundary is straight.
fn outward<T: Real>(mesh: &SheetMesh<T>, v: u32, normal: T::Vec3) -> T::Vec3 {
    let Some((next, prev)) = mesh.boundary_neighbours(v) else {
        return T::Vec3::ZERO;
    };
    let x = mesh.positions();
    let p = x[v as usize];
    let u1 = unit::<T>(x[next as usize] - p);
    let u2 = unit::<T>(x[prev as usize] - p);
    let sum = u1 + u2;
    let walk = unit::<T>(x[next as usize] - x[prev as usize]);
    let normal_out = unit::<T>(walk.cross(normal));
    let angle = mesh.pattern_angle(v).to_f64();
    let margin = 0.05;
    let s = unit::<T>(sum);
    if angle > core::f64::consts::PI + margin && s != T::Vec3::ZERO {
        s
    } else if angle < core::f64::consts::PI - margin && s != T::Vec3::ZERO {
        -s
    } else {
        normal_out
    }
}

/// Whether the straight segment of the tear that ends at tip `v` (from its boundary
/// neighbour, the lips' last kink) is shorter than [`SHORT_SEGMENT`] times the longest edge
/// of `v`'s fan.
fn short_segment<T: Real>(mesh: &SheetMesh<T>, v: u32) -> bool {
    let Some((a, _)) = mesh.boundary_neighbours(v) else {
        return false;
    };
    let p = mesh.pattern();
    let o = p[v as usize];
    let longest = mesh
        .fan_iter(v)
        .map(|h| pattern_distance2(o, p[mesh.half_edge(h).1 as usize]))
        .fold(T::ZERO, |m, x| if x > m { x } else { m });
    pattern_distance2(o, p[a as usize]) < T::from_f64(SHORT_SEGMENT * SHORT_SEGMENT) * longest
}

/// A tip's straight segment shorter than this fraction of its fan's longest edge slides on
/// even where the tear turns ([`crate::TipRemesh::Shaped`]; [`crate::advance`]).
const SHORT_SEGMENT: f64 = 0.5;
