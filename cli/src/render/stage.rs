//! The stage every tile is rendered on: the camera, the point light with its shadow map,
//! the table under the book, and the rendering of one mesh into one tile (a deferred
//! pass: rasterize position, normal, UV and surface per sample, then shade each sample and
//! average the supersamples).

use folio_geometry::mesh::{Surface, TriMesh};
use glam::Vec3;

use super::camera::Camera;
use super::raster::{ATTRIBUTES, Corner, Fragment, rasterize};
use super::shading::{PagePoint, Paper, lambert_radiance, page_radiance, tone_map};
use super::shadow::{ShadowMap, corners};
use super::texture::{PAGE_EDGES, Side, TABLE, page_albedo, surface_albedo};
use super::vector::normalize_or;

/// Eye distance from the box's centre, in box diagonals (sets the perspective's strength).
const EYE_DISTANCE: f32 = 1.4;
/// Light distance from the box's centre, in box diagonals.
const LIGHT_DISTANCE: f32 = 1.2;
/// Irradiance (normal incidence) of the light at the box's centre.
const CENTRE_IRRADIANCE: f32 = 2.6;
/// Ambient radiance.
const AMBIENT: f32 = 0.15;
/// Exposure of the tone mapping ([`tone_map`]).
const EXPOSURE: f32 = 1.8;
/// Shadow map texels per side.
const SHADOW_RESOLUTION: usize = 1024;
/// Fraction of the tile left free around the framed box on each side.
const MARGIN: f32 = 0.03;
/// The table's half extent around the box's centre, in box diagonals.
const TABLE_EXTENT: f32 = 3.0;
/// Background where nothing is hit (linear RGB before tone mapping, as a radiance).
const BACKGROUND: [f32; 3] = [0.16, 0.18, 0.22];

/// What a sample shows.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Material {
    /// A surface of the book's mesh.
    Mesh(Surface),
    /// The table.
    Table,
}

/// One sample of the deferred pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    inverse_depth: f32,
    material: Option<Material>,
    attributes: [f32; ATTRIBUTES],
}

impl Sample {
    const EMPTY: Self = Self {
        inverse_depth: 0.0,
        material: None,
        attributes: [0.0; ATTRIBUTES],
    };
}

/// Keeps fragment `f` in `samples` (`width` per row) if it is nearer than what is there.
fn store(samples: &mut [Sample], width: usize, material: Material, f: &Fragment) {
    if let Some(s) = samples.get_mut(f.y * width + f.x) {
        if f.inverse_depth > s.inverse_depth {
            *s = Sample {
                inverse_depth: f.inverse_depth,
                material: Some(material),
                attributes: f.attributes,
            };
        }
    }
}

/// One rendered tile.
#[derive(Clone, Debug, PartialEq)]
pub struct TileImage {
    /// RGBA8 pixels, row by row.
    pub rgba: Vec<u8>,
    /// Samples showing a page surface (`PageFront`, `PageBack`, `PageEdge`).
    pub page_samples: u64,
    /// Samples showing paper: a page surface or a block's top.
    pub paper_samples: u64,
    /// All samples.
    pub samples: u64,
}

/// The stage (module docs).
#[derive(Clone, Debug)]
pub struct Stage {
    camera: Camera,
    light: Vec3,
    /// Radiant intensity: irradiance at distance $d$ is intensity / $d^2$.
    intensity: f32,
    shadow: ShadowMap,
    /// The table's corners, `None` when it is not drawn.
    table: Option<[Vec3; 4]>,
    paper: Paper,
    tile: [usize; 2],
    supersample: usize,
    samples: Vec<Sample>,
}

impl Stage {
    /// The stage for tiles of `tile` pixels rendered at `supersample` x `supersample`
    /// samples per pixel, framing `bounds` (finite, min <= max), seen from the direction
    /// `eye` and lit from the direction `light` (from the box's centre, unnormalized;
    /// [`super::SheetSettings`]).
    #[must_use]
    pub fn new(
        bounds: [[f32; 3]; 2],
        tile: [usize; 2],
        supersample: usize,
        paper: Paper,
        [eye, light]: [Vec3; 2],
        table: bool,
    ) -> Self {
        let [lo, hi] = bounds.map(Vec3::from);
        let centre = 0.5 * (lo + hi);
        let diagonal = (hi - lo).length().max(1e-3);
        let size = [tile[0] * supersample, tile[1] * supersample];
        let eye = centre + normalize_or(eye, Vec3::Y) * (EYE_DISTANCE * diagonal);
        let camera = Camera::framing(eye, bounds, size, MARGIN);
        let light_distance = LIGHT_DISTANCE * diagonal;
        let light = centre + normalize_or(light, Vec3::Y) * light_distance;
        let y = lo.y - 1e-4 * diagonal;
        let r = TABLE_EXTENT * diagonal;
        let (x0, x1, z0, z1) = (centre.x - r, centre.x + r, centre.z - r, centre.z + r);
        Self {
            camera,
            light,
            intensity: CENTRE_IRRADIANCE * light_distance * light_distance,
            shadow: ShadowMap::new(light, bounds, SHADOW_RESOLUTION),
            // Counter-clockwise seen from above.
            table: table.then_some([
                Vec3::new(x0, y, z0),
                Vec3::new(x0, y, z1),
                Vec3::new(x1, y, z1),
                Vec3::new(x1, y, z0),
            ]),
            paper,
            tile,
            supersample,
            samples: Vec::new(),
        }
    }

    /// Renders `mesh` into a tile; pages are `thickness` thick (page units) in the
    /// translucency term. An alpha test cuts paper out: a sample of triangle `t` of `mesh`
    /// at texture coordinates `uv` is drawn only where `keep(t, uv)` holds (the table or
    /// the paper behind shows through). Shadows ignore the test.
    pub fn render(
        &mut self,
        mesh: &TriMesh,
        thickness: f32,
        keep: impl Fn(usize, [f32; 2]) -> bool,
    ) -> TileImage {
        let (w, h) = (self.camera.width, self.camera.height);
        self.samples.clear();
        self.samples.resize(w * h, Sample::EMPTY);
        self.shadow.render(mesh);

        let camera = self.camera;
        let samples = &mut self.samples;
        if let Some(table) = self.table {
            let table = table.map(|p| Corner {
                view: camera.view_of(p),
                attributes: [p.x, p.y, p.z, 0.0, 1.0, 0.0, 0.0, 0.0],
            });
            for t in [[0, 1, 2], [0, 2, 3]] {
                rasterize(&camera, &t.map(|k| table[k]), true, |f| {
                    store(samples, w, Material::Table, &f);
                });
            }
        }
        for (k, (t, &surface)) in mesh.triangles.iter().zip(&mesh.surfaces).enumerate() {
            if let Some(c) = corners(&camera, mesh, t) {
                rasterize(&camera, &c, true, |f| {
                    if keep(k, [f.attributes[6], f.attributes[7]]) {
                        store(samples, w, Material::Mesh(surface), &f);
                    }
                });
            }
        }
        self.resolve(thickness)
    }

    /// Shades every sample and averages each pixel's supersamples.
    fn resolve(&self, thickness: f32) -> TileImage {
        let [tw, th] = self.tile;
        let ss = self.supersample;
        let w = self.camera.width;
        let mut rgba = vec![0u8; 4 * tw * th];
        let (mut page_samples, mut paper_samples) = (0, 0);
        let weight = 1.0 / (ss * ss) as f32;
        for ty in 0..th {
            for tx in 0..tw {
                let mut sum = [0.0f32; 3];
                for sy in 0..ss {
                    for sx in 0..ss {
                        let sample = &self.samples[(ty * ss + sy) * w + tx * ss + sx];
                        match sample.material {
                            Some(Material::Mesh(
                                Surface::PageFront | Surface::PageBack | Surface::PageEdge,
                            )) => {
                                page_samples += 1;
                                paper_samples += 1;
                            }
                            Some(Material::Mesh(Surface::BlockTop)) => paper_samples += 1,
                            _ => {}
                        }
                        let colour = self.shade(sample, thickness);
                        for c in 0..3 {
                            sum[c] += tone_map(colour[c], EXPOSURE);
                        }
                    }
                }
                let k = 4 * (ty * tw + tx);
                for c in 0..3 {
                    rgba[k + c] = (sum[c] * weight * 255.0).round().clamp(0.0, 255.0) as u8;
                }
                rgba[k + 3] = 255;
            }
        }
        TileImage {
            rgba,
            page_samples,
            paper_samples,
            samples: (tw * th * ss * ss) as u64,
        }
    }

    /// Outgoing radiance of one sample ([`super::shading`]).
    fn shade(&self, sample: &Sample, thickness: f32) -> [f32; 3] {
        let Some(material) = sample.material else {
            return BACKGROUND;
        };
        let a = sample.attributes;
        let p = Vec3::new(a[0], a[1], a[2]);
        let uv = [a[6], a[7]];
        let view = normalize_or(self.camera.eye - p, Vec3::Y);
        let normal = normalize_or(Vec3::new(a[3], a[4], a[5]), view);
        let to_light = self.light - p;
        let d2 = to_light.dot(to_light).max(1e-12);
        let light = to_light * (1.0 / d2.sqrt());
        let irradiance = self.intensity / d2 * self.shadow.light_at(p, normal);
        let lambert = |albedo| lambert_radiance(albedo, normal, light, irradiance, AMBIENT);
        match material {
            Material::Table => lambert(TABLE),
            Material::Mesh(surface @ (Surface::PageFront | Surface::PageBack)) => {
                let (side, other) = if surface == Surface::PageFront {
                    (Side::Front, Side::Back)
                } else {
                    (Side::Back, Side::Front)
                };
                page_radiance(
                    &self.paper,
                    &PagePoint {
                        normal,
                        view,
                        light,
                        irradiance,
                        ambient: AMBIENT,
                        albedo: page_albedo(side, uv),
                        albedo_back: page_albedo(other, [1.0 - uv[0], uv[1]]),
                        thickness,
                    },
                )
            }
            Material::Mesh(Surface::PageEdge) => lambert(PAGE_EDGES),
            Material::Mesh(surface) => lambert(surface_albedo(surface, uv, p.x)),
        }
    }
}
