//! [`TearSettings`]: the parameters of the tearing step (seed `002_…` Sec. 4-6), with their
//! units and the choices the seed leaves open.

use crate::detail::DetailSettings;
use crate::fiber::FiberSettings;
use folio_kernels::setting::{SettingError, require_range};

/// How the tearing step reads the load on a potential tearing point.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// The energy released over a disk of [`TearSettings::disk_radius`] around the point,
    /// the $J$-integral ([`crate::release`]): independent of the mesh.
    Disk,
    /// The seed's force split on the point's own triangles (Sec. 5.1-5.2, eq. 4-6,
    /// [`crate::split`]): nodal forces, which shrink on a finer mesh.
    Split,
}

/// How a propagation remeshes around the tip ([`crate::advance`]).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TipRemesh {
    /// The seed's edits only (Sec. 5.3, Fig. 8): a step shorter than the mesh leaves
    /// slivers (a triangle of 0.16° after the first step of `tear-curved`).
    Seed,
    /// The seed's edits, kept well shaped: flips around the tip, slides that flip their way
    /// on, a new tip snapped onto a near edge, short straight segments slid rather than
    /// split (module docs of [`crate::advance`]).
    Shaped,
}

/// Parameters of [`crate::Tears`]. Lengths in sheet units; forces in the physics' force
/// units; release rates and fracture energies in force units per sheet unit.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TearSettings {
    /// Paper thickness $e$ of eq. 6 (sheet units).
    pub thickness: f64,
    /// How the load on a tearing point is read: the disk's energy release or the seed's
    /// force split.
    pub estimator: Estimator,
    /// Radius $R$ of the disk of [`Estimator::Disk`] (sheet units): the paper's flaw size
    /// (a new tear from a border releases $W R$), and the size below which the tear does not
    /// see detail. Keep it smaller than the distance from a tip to the fingers.
    pub disk_radius: f64,
    /// The material constant $c$ of eq. 3 (seed default 0.005).
    pub fracture: f64,
    /// The damage $D \in [0, 1]$ at tear tips, eq. 3 (1 elsewhere): lower makes an existing
    /// tear easier to extend than a new one to start.
    pub damage: f64,
    /// The propagation speed constant $c$ of $p_{\text{next}} = p + c\thinspace E_r\thinspace t$ (sheet units
    /// per unit of $E_r$).
    pub speed: f64,
    /// Shortest propagation step (sheet units): a step that the Griffith criterion allows is
    /// at least this long (the seed leaves it open; a vanishing step would make slivers).
    pub min_step: f64,
    /// Longest propagation step (sheet units; the seed leaves it open). A step also ends at
    /// the far edge of the triangle it starts in, so a tear crosses at most one triangle per
    /// propagation.
    pub max_step: f64,
    /// How a propagation remeshes around the tip. Default [`TipRemesh::Seed`] until the
    /// tests that read the seed's artifacts are replaced (see the issue-22 notes).
    pub remesh: TipRemesh,
    /// Turn (radians) above which the tip splits into two lips instead of moving on (seed
    /// Sec. 5.3: 0.1).
    pub turn_threshold: f64,
    /// Tolerance $\varepsilon$ on the change of the bisector (Sec. 5.1).
    pub bisector_tolerance: f64,
    /// Most potential tearing points examined per step (Sec. 4.1: about ten); tear tips
    /// first, then fingers, junctions, inward angles.
    pub max_candidates: usize,
    /// Boundary angle (radians) beyond $\pi$ above which a vertex is an inward angle.
    pub inward_angle: f64,
    /// Snap distance for new vertices, relative to the longest edge of the triangle that
    /// holds them: a point this close to a vertex or an edge goes onto it (no slivers).
    pub snap: f64,
    /// The fiber texture of eq. 3 and eq. 7.
    pub fibers: FiberSettings,
    /// The detail path of eq. 7.
    pub detail: DetailSettings,
    /// Alpha texture resolution (pixels per sheet unit), in $[1, 4096]$; each side is
    /// at most 8192 pixels. Default 176: 2112 x 1584 texels on the default 12 x 9 sheet, at
    /// least the seed's 2048 on the long side (Sec. 7.4, Fig. 19: 2048 x 1476 for an A4
    /// sheet), a texel of 0.1 mm on a page 21 cm wide. At 32 texels per unit the detail
    /// path kept within a texel of the straight segment and the edge read as a clean cut;
    /// at 176 it strays by 3-8 texels on a step, on average by direction (test
    /// `the_edge_is_fibrous_in_every_direction`).
    pub texture_density: f64,
    /// Tears whose alpha textures and path are allocated at setup ([`crate::Tears::new`]), so
    /// that starting one inside a frame allocates nothing; a tear beyond these allocates its
    /// own when it starts. In [0, 64]. Default 2: on the default sheet and texture density
    /// a tear's two masks take 6.7 MB, so the default reserves 13.4 MB.
    pub reserved_tears: usize,
}

impl Default for TearSettings {
    /// The seed's $c = 0.005$ and 0.1 rad, with a thickness of 0.01, damage 0.5, speed
    /// 50 (a step of 0.125 at $E_r = E_f$ for a mean fiber value) and steps between 0.05 and 0.6 sheet units, ten candidates, inward angles
    /// beyond $\pi + 0.3$, snap 0.12, 176 texture pixels per sheet unit, two tears reserved.
    fn default() -> Self {
        Self {
            thickness: 0.01,
            estimator: Estimator::Split,
            disk_radius: 1.0,
            fracture: 0.005,
            damage: 0.5,
            speed: 50.0,
            min_step: 0.05,
            max_step: 0.6,
            remesh: TipRemesh::Seed,
            turn_threshold: 0.1,
            bisector_tolerance: 1e-6,
            max_candidates: 10,
            inward_angle: 0.3,
            snap: 0.12,
            fibers: FiberSettings::default(),
            detail: DetailSettings::default(),
            texture_density: 176.0,
            reserved_tears: 2,
        }
    }
}

impl TearSettings {
    /// Checks every field.
    ///
    /// # Errors
    /// The first field out of its range (`fibers.scale` for the fibers' and `detail.sigma`
    /// for the detail path's), the range and the value.
    pub fn validate(&self) -> Result<(), SettingError> {
        require_range("thickness", self.thickness, 1e-9, 1e3)?;
        require_range("disk_radius", self.disk_radius, 1e-6, 1e6)?;
        require_range("fracture", self.fracture, 0.0, 1e12)?;
        require_range("damage", self.damage, 0.0, 1.0)?;
        require_range("speed", self.speed, 0.0, 1e6)?;
        require_range("min_step", self.min_step, 1e-6, 1e6)?;
        require_range("max_step", self.max_step, self.min_step, 1e6)?;
        require_range("turn_threshold", self.turn_threshold, 0.0, 3.2)?;
        require_range("bisector_tolerance", self.bisector_tolerance, 0.0, 1.0)?;
        require_range("max_candidates", self.max_candidates as f64, 1.0, 1e4)?;
        require_range("inward_angle", self.inward_angle, 0.0, 3.2)?;
        require_range("snap", self.snap, 0.0, 0.3)?;
        require_range("texture_density", self.texture_density, 1.0, 4096.0)?;
        require_range("reserved_tears", self.reserved_tears as f64, 0.0, 64.0)?;
        self.fibers.validate().map_err(|e| e.within("fibers"))?;
        self.detail.validate().map_err(|e| e.within("detail"))
    }
}
