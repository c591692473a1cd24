//! The run as an animated binary glTF 2.0 file (`animation.glb`).
//!
//! The book's mesh changes topology during a run (a page appears when grabbed, merges when
//! released, bookmarked pages fly), so the animation is a flip-book of nodes rather than a
//! morph: every recorded frame is one node with its own mesh (one primitive per
//! [`Surface`] present, each with a plain PBR material), and one animation drives the
//! nodes' `scale` with STEP interpolation so that exactly one node is visible (scale 1,
//! the others 0) at any time. Frame $f$ is shown from $t = f/\text{fps}$ until the next
//! recorded frame's time; before any animation plays the first frame is visible.
//!
//! Layout: one buffer (the GLB's BIN chunk), one buffer view per accessor, every view and
//! chunk 4-byte aligned; positions, normals (unit) and UVs are `f32`, indices `u32`.
//! POSITION accessors and animation inputs carry `min` / `max`.

use folio_geometry::mesh::{Surface, TriMesh};
use serde_json::{Value, json};

use crate::render::texture::{COVER, PAGE_EDGES, PAPER};

/// The surfaces in material order.
const SURFACES: [Surface; 7] = [
    Surface::PageFront,
    Surface::PageBack,
    Surface::PageEdge,
    Surface::BlockTop,
    Surface::BlockBottom,
    Surface::BlockEdge,
    Surface::Cover,
];

/// glTF component type `FLOAT`.
const FLOAT: u32 = 5126;
/// glTF component type `UNSIGNED_INT`.
const UNSIGNED_INT: u32 = 5125;
/// Buffer view target `ARRAY_BUFFER` (vertex attributes).
const ARRAY_BUFFER: u32 = 34962;
/// Buffer view target `ELEMENT_ARRAY_BUFFER` (indices).
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// GLB magic `glTF`, chunk types `JSON` and `BIN\0` (little-endian).
const MAGIC: u32 = 0x4654_6C67;
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Why an animation refused a setting or a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ExportError {
    /// The frame rate is not finite and positive.
    Fps {
        /// The rate given.
        fps: f32,
    },
    /// A frame was added whose time $f / \text{fps}$ (in `f32`) is not after the last
    /// frame's.
    FrameOrder {
        /// The frame given.
        frame: u32,
        /// The last frame recorded.
        last: u32,
    },
}

impl core::fmt::Display for ExportError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Fps { fps } => write!(f, "frame rate {fps} must be finite and positive"),
            Self::FrameOrder { frame, last } => {
                write!(f, "frame {frame} does not come after frame {last}")
            }
        }
    }
}

impl core::error::Error for ExportError {}

/// The triangles of one surface of one frame, with their own compacted vertices.
#[derive(Clone, Debug, Default, PartialEq)]
struct Group {
    material: usize,
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

/// One recorded frame.
#[derive(Clone, Debug, PartialEq)]
struct Frame {
    frame: u32,
    time: f32,
    groups: Vec<Group>,
}

/// An animation being recorded (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    fps: f32,
    frames: Vec<Frame>,
}

/// The groups of `mesh`, one per surface with triangles. A triangle with an index out of
/// range or a non-finite position is dropped; a non-finite or zero normal becomes +Y, a
/// non-finite UV (0, 0); normals are renormalized.
fn groups(mesh: &TriMesh) -> Vec<Group> {
    let valid = |v: u32| {
        mesh.positions
            .get(v as usize)
            .is_some_and(|p| p.iter().all(|c| c.is_finite()))
    };
    let mut out = Vec::new();
    let mut remap = vec![u32::MAX; mesh.vertex_count()];
    for (material, &surface) in SURFACES.iter().enumerate() {
        let mut g = Group {
            material,
            ..Group::default()
        };
        for (t, &s) in mesh.triangles.iter().zip(&mesh.surfaces) {
            if s != surface || !t.iter().all(|&v| valid(v)) {
                continue;
            }
            for &v in t {
                let i = v as usize;
                if remap[i] == u32::MAX {
                    remap[i] = u32::try_from(g.positions.len()).unwrap_or(u32::MAX);
                    g.positions.push(mesh.positions[i]);
                    let n = mesh.normals.get(i).copied().unwrap_or([0.0; 3]);
                    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    g.normals.push(if len > 0.0 && len.is_finite() {
                        n.map(|c| c / len)
                    } else {
                        [0.0, 1.0, 0.0]
                    });
                    let uv = mesh.uvs.get(i).copied().unwrap_or([0.0; 2]);
                    g.uvs.push(uv.map(|c| if c.is_finite() { c } else { 0.0 }));
                }
                g.indices.push(remap[i]);
            }
        }
        // Reset the map for the next surface (vertices are not shared between surfaces).
        remap.fill(u32::MAX);
        if !g.indices.is_empty() {
            out.push(g);
        }
    }
    out
}

/// The binary buffer and the JSON arrays that describe it, built together.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    /// Appends `bytes` as a buffer view (4-byte aligned) and returns its index.
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let mut v = json!({
            "buffer": 0,
            "byteOffset": self.bin.len(),
            "byteLength": bytes.len(),
        });
        if let Some(target) = target {
            v["target"] = json!(target);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    /// Appends an accessor of `count` elements of `kind` over a new view of `bytes`.
    fn accessor(
        &mut self,
        bytes: &[u8],
        target: Option<u32>,
        component: u32,
        kind: &str,
        count: usize,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> usize {
        let view = self.view(bytes, target);
        let mut a = json!({
            "bufferView": view,
            "byteOffset": 0,
            "componentType": component,
            "count": count,
            "type": kind,
        });
        if let Some((min, max)) = bounds {
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// A `f32` accessor of `kind` over `data` (`width` floats per element), with min/max
    /// when `bounded`.
    fn floats(
        &mut self,
        data: &[f32],
        width: usize,
        kind: &str,
        target: Option<u32>,
        bounded: bool,
    ) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
        let bounds = bounded.then(|| {
            let mut min = vec![f32::MAX; width];
            let mut max = vec![f32::MIN; width];
            for element in data.chunks_exact(width) {
                for (k, &v) in element.iter().enumerate() {
                    min[k] = min[k].min(v);
                    max[k] = max[k].max(v);
                }
            }
            (min, max)
        });
        self.accessor(
            &bytes,
            target,
            FLOAT,
            kind,
            data.len() / width.max(1),
            bounds,
        )
    }
}

/// The PBR material of `surface`: base colour, not metallic, paper-like roughness.
fn material(surface: Surface) -> Value {
    let (colour, roughness) = match surface {
        Surface::PageFront | Surface::PageBack | Surface::BlockTop => (PAPER, 0.65),
        Surface::PageEdge | Surface::BlockBottom | Surface::BlockEdge => (PAGE_EDGES, 0.8),
        Surface::Cover => (COVER, 0.55),
    };
    json!({
        "name": format!("{surface:?}"),
        "pbrMetallicRoughness": {
            "baseColorFactor": [colour[0], colour[1], colour[2], 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": roughness,
        },
    })
}

impl Animation {
    /// An empty animation played at `fps` frames per second.
    ///
    /// # Errors
    /// [`ExportError::Fps`] unless `fps` is finite and positive.
    pub fn new(fps: f32) -> Result<Self, ExportError> {
        if !(fps.is_finite() && fps > 0.0) {
            return Err(ExportError::Fps { fps });
        }
        Ok(Self {
            fps,
            frames: Vec::new(),
        })
    }

    /// Records `mesh` as frame `frame` (module docs). Triangles with an out-of-range index
    /// or a non-finite position are dropped.
    ///
    /// # Errors
    /// [`ExportError::FrameOrder`] when `frame`'s time is not after the last recorded
    /// frame's; nothing is recorded.
    pub fn add_frame(&mut self, frame: u32, mesh: &TriMesh) -> Result<(), ExportError> {
        let time = frame as f32 / self.fps;
        if let Some(last) = self.frames.last() {
            if time.is_nan() || time <= last.time {
                return Err(ExportError::FrameOrder {
                    frame,
                    last: last.frame,
                });
            }
        }
        self.frames.push(Frame {
            frame,
            time,
            groups: groups(mesh),
        });
        Ok(())
    }

    /// Frames recorded.
    #[must_use]
    pub fn frames(&self) -> usize {
        self.frames.len()
    }

    /// The glTF JSON document and its binary buffer.
    fn document(&self) -> (Value, Vec<u8>) {
        let mut b = Builder::default();
        let mut nodes = Vec::new();
        let mut meshes = Vec::new();
        for (k, f) in self.frames.iter().enumerate() {
            let name = format!("frame {}", f.frame);
            let mut node = json!({ "name": name });
            if k > 0 {
                node["scale"] = json!([0.0, 0.0, 0.0]);
            }
            if !f.groups.is_empty() {
                let primitives: Vec<Value> = f
                    .groups
                    .iter()
                    .map(|g| {
                        let flat = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
                        let uvs: Vec<f32> = g.uvs.iter().flatten().copied().collect();
                        let position =
                            b.floats(&flat(&g.positions), 3, "VEC3", Some(ARRAY_BUFFER), true);
                        let normal =
                            b.floats(&flat(&g.normals), 3, "VEC3", Some(ARRAY_BUFFER), false);
                        let uv = b.floats(&uvs, 2, "VEC2", Some(ARRAY_BUFFER), false);
                        let bytes: Vec<u8> = g.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
                        let indices = b.accessor(
                            &bytes,
                            Some(ELEMENT_ARRAY_BUFFER),
                            UNSIGNED_INT,
                            "SCALAR",
                            g.indices.len(),
                            None,
                        );
                        json!({
                            "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv },
                            "indices": indices,
                            "material": g.material,
                            "mode": 4,
                        })
                    })
                    .collect();
                node["mesh"] = json!(meshes.len());
                meshes.push(json!({ "name": name, "primitives": primitives }));
            }
            nodes.push(node);
        }

        // Node k is visible (scale 1) from its own time until the next frame's.
        let n = self.frames.len();
        let times: Vec<f32> = self.frames.iter().map(|f| f.time).collect();
        let mut channels = Vec::new();
        let mut samplers = Vec::new();
        for k in 0..n {
            let mut keys: Vec<(f32, f32)> = Vec::new();
            if k > 0 {
                keys.push((times[0], 0.0));
            }
            keys.push((times[k], 1.0));
            if k + 1 < n {
                keys.push((times[k + 1], 0.0));
            }
            let input: Vec<f32> = keys.iter().map(|k| k.0).collect();
            let output: Vec<f32> = keys.iter().flat_map(|k| [k.1; 3]).collect();
            let input = b.floats(&input, 1, "SCALAR", None, true);
            let output = b.floats(&output, 3, "VEC3", None, false);
            samplers.push(json!({ "input": input, "output": output, "interpolation": "STEP" }));
            channels.push(json!({ "sampler": k, "target": { "node": k, "path": "scale" } }));
        }

        let mut doc = json!({
            "asset": { "version": "2.0", "generator": "folio" },
            "scene": 0,
            "scenes": [{ "name": "book" }],
            "materials": SURFACES.iter().map(|&s| material(s)).collect::<Vec<_>>(),
        });
        if n > 0 {
            doc["scenes"][0]["nodes"] = json!((0..n).collect::<Vec<_>>());
            doc["nodes"] = json!(nodes);
            doc["animations"] =
                json!([{ "name": "run", "channels": channels, "samplers": samplers }]);
        }
        if !meshes.is_empty() {
            doc["meshes"] = json!(meshes);
        }
        if !b.bin.is_empty() {
            doc["buffers"] = json!([{ "byteLength": b.bin.len() }]);
            doc["bufferViews"] = json!(b.views);
            doc["accessors"] = json!(b.accessors);
        }
        (doc, b.bin)
    }

    /// The animation as a GLB file (glTF 2.0 binary): a 12-byte header, the JSON chunk
    /// (padded with spaces) and, when there is geometry, the BIN chunk (padded with zeros).
    #[must_use]
    pub fn to_glb(&self) -> Vec<u8> {
        let (doc, mut bin) = self.document();
        let mut text = doc.to_string().into_bytes();
        while text.len() % 4 != 0 {
            text.push(b' ');
        }
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
        let total = 12 + 8 + text.len() + bin_chunk;
        let word = |v: usize| u32::try_from(v).unwrap_or(u32::MAX).to_le_bytes();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(&MAGIC.to_le_bytes());
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&word(total));
        out.extend_from_slice(&word(text.len()));
        out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
        out.extend_from_slice(&text);
        if !bin.is_empty() {
            out.extend_from_slice(&word(bin.len()));
            out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
            out.extend_from_slice(&bin);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use folio_geometry::QuadGrid;
    use folio_geometry::mesh::{cover_mesh, page_mesh};

    fn u32_at(b: &[u8], at: usize) -> u32 {
        u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
    }

    fn f32_at(b: &[u8], at: usize) -> f32 {
        f32::from_bits(u32_at(b, at))
    }

    /// Parses a GLB: checks the header and chunks, returns the JSON and the BIN chunk.
    fn parse(glb: &[u8]) -> (Value, Vec<u8>) {
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(u32_at(glb, 4), 2);
        assert_eq!(u32_at(glb, 8) as usize, glb.len());
        assert_eq!(glb.len() % 4, 0);
        let json_len = u32_at(glb, 12) as usize;
        assert_eq!(u32_at(glb, 16), CHUNK_JSON);
        assert_eq!(json_len % 4, 0);
        let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
        let rest = 20 + json_len;
        let bin = if rest < glb.len() {
            let bin_len = u32_at(glb, rest) as usize;
            assert_eq!(u32_at(glb, rest + 4), CHUNK_BIN);
            assert_eq!(bin_len % 4, 0);
            assert_eq!(rest + 8 + bin_len, glb.len());
            glb[rest + 8..].to_vec()
        } else {
            Vec::new()
        };
        (doc, bin)
    }

    fn components(kind: &str) -> usize {
        match kind {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            other => panic!("unexpected type {other}"),
        }
    }

    /// Every accessor fits its view, every view the buffer, every offset is 4-aligned,
    /// POSITION min/max bound the data; returns the byte range of accessor `k`.
    fn check_layout(doc: &Value, bin: &[u8]) {
        let buffer_len = doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize;
        assert!(buffer_len <= bin.len() && bin.len() < buffer_len + 4);
        let views = doc["bufferViews"].as_array().unwrap();
        for v in views {
            let (offset, len) = (
                v["byteOffset"].as_u64().unwrap() as usize,
                v["byteLength"].as_u64().unwrap() as usize,
            );
            assert!(len > 0 && offset + len <= buffer_len);
            assert_eq!(offset % 4, 0);
        }
        for a in doc["accessors"].as_array().unwrap() {
            let view = &views[a["bufferView"].as_u64().unwrap() as usize];
            let stride = 4 * components(a["type"].as_str().unwrap());
            let count = a["count"].as_u64().unwrap() as usize;
            let offset = a["byteOffset"].as_u64().unwrap() as usize;
            assert_eq!(offset % 4, 0);
            assert!(count > 0);
            assert!(offset + count * stride <= view["byteLength"].as_u64().unwrap() as usize);
        }
        for mesh in doc["meshes"].as_array().unwrap() {
            for p in mesh["primitives"].as_array().unwrap() {
                let a = &doc["accessors"][p["attributes"]["POSITION"].as_u64().unwrap() as usize];
                let view = &views[a["bufferView"].as_u64().unwrap() as usize];
                let start = view["byteOffset"].as_u64().unwrap() as usize;
                for e in 0..a["count"].as_u64().unwrap() as usize {
                    for c in 0..3 {
                        let v = f32_at(bin, start + 12 * e + 4 * c);
                        assert!(v >= a["min"][c].as_f64().unwrap() as f32);
                        assert!(v <= a["max"][c].as_f64().unwrap() as f32);
                    }
                }
                // Indices stay within the primitive's vertices.
                let ia = &doc["accessors"][p["indices"].as_u64().unwrap() as usize];
                let iv = &views[ia["bufferView"].as_u64().unwrap() as usize];
                let istart = iv["byteOffset"].as_u64().unwrap() as usize;
                for e in 0..ia["count"].as_u64().unwrap() as usize {
                    assert!((u32_at(bin, istart + 4 * e) as u64) < a["count"].as_u64().unwrap());
                }
            }
        }
    }

    /// Reads an accessor's floats.
    fn floats(doc: &Value, bin: &[u8], accessor: u64) -> Vec<f32> {
        let a = &doc["accessors"][accessor as usize];
        let view = &doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let start = view["byteOffset"].as_u64().unwrap() as usize;
        let n = a["count"].as_u64().unwrap() as usize * components(a["type"].as_str().unwrap());
        (0..n).map(|k| f32_at(bin, start + 4 * k)).collect()
    }

    fn page(lift: f64) -> TriMesh {
        let grid = QuadGrid::new(4, 5).unwrap();
        let positions: Vec<[f64; 3]> = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                [3.0 * i as f64, lift * i as f64, 3.0 * j as f64]
            })
            .collect();
        let mut m = TriMesh::new();
        page_mesh(&mut m, grid, &positions, 0.0075, 12.0).unwrap();
        m
    }

    /// Frames with and without a page and a cover: valid layout, one channel per frame
    /// node, and at each frame's time exactly that node has scale 1 (STEP evaluation).
    #[test]
    fn glb_is_valid_and_shows_one_frame_at_a_time() {
        let mut anim = Animation::new(60.0).unwrap();
        let mut cover = TriMesh::new();
        cover_mesh(
            &mut cover,
            [0.0, 0.0],
            [12.0, 0.0],
            [0.0, -1.0],
            0.06,
            17.0,
            0.25,
        )
        .unwrap();
        anim.add_frame(0, &cover).unwrap();
        anim.add_frame(10, &page(0.0)).unwrap();
        let mut both = page(0.5);
        let offset = both.vertex_count() as u32;
        both.positions.extend(&cover.positions);
        both.normals.extend(&cover.normals);
        both.uvs.extend(&cover.uvs);
        both.triangles
            .extend(cover.triangles.iter().map(|t| t.map(|v| v + offset)));
        both.surfaces.extend(&cover.surfaces);
        anim.add_frame(20, &both).unwrap();
        anim.add_frame(25, &TriMesh::new()).unwrap();
        assert_eq!(anim.frames(), 4);

        let (doc, bin) = parse(&anim.to_glb());
        assert_eq!(doc["asset"]["version"], "2.0");
        check_layout(&doc, &bin);
        let nodes = doc["nodes"].as_array().unwrap();
        assert_eq!(nodes.len(), 4);
        assert!(nodes[3].get("mesh").is_none(), "an empty frame has no mesh");
        // Primitives: cover (1), page (3 surfaces), page + cover (4).
        let meshes = doc["meshes"].as_array().unwrap();
        let prims: Vec<usize> = meshes
            .iter()
            .map(|m| m["primitives"].as_array().unwrap().len())
            .collect();
        assert_eq!(prims, [1, 3, 4]);
        assert_eq!(doc["materials"].as_array().unwrap().len(), 7);

        let animation = &doc["animations"][0];
        let channels = animation["channels"].as_array().unwrap();
        assert_eq!(channels.len(), 4);
        let scale_at = |node: usize, t: f32| -> f32 {
            let ch = channels
                .iter()
                .find(|c| c["target"]["node"] == node)
                .unwrap();
            assert_eq!(ch["target"]["path"], "scale");
            let s = &animation["samplers"][ch["sampler"].as_u64().unwrap() as usize];
            assert_eq!(s["interpolation"], "STEP");
            let input = floats(&doc, &bin, s["input"].as_u64().unwrap());
            let output = floats(&doc, &bin, s["output"].as_u64().unwrap());
            assert!(input.windows(2).all(|w| w[0] < w[1]));
            let k = input.iter().rposition(|&x| x <= t).unwrap_or(0);
            output[3 * k]
        };
        for (k, frame) in [0u32, 10, 20, 25].iter().enumerate() {
            for t in [*frame as f32 / 60.0, (*frame as f32 + 0.5) / 60.0] {
                for node in 0..4 {
                    let expected = if node == k { 1.0 } else { 0.0 };
                    assert_eq!(scale_at(node, t), expected, "node {node} at {t}");
                }
            }
        }
    }

    #[test]
    fn empty_animation_is_a_valid_glb() {
        let anim = Animation::new(30.0).unwrap();
        let (doc, bin) = parse(&anim.to_glb());
        assert!(bin.is_empty());
        assert_eq!(doc["asset"]["version"], "2.0");
        assert!(doc.get("animations").is_none() && doc.get("buffers").is_none());
    }

    #[test]
    fn bad_input_is_refused_or_dropped() {
        assert_eq!(
            Animation::new(0.0).unwrap_err(),
            ExportError::Fps { fps: 0.0 }
        );
        assert!(Animation::new(f32::NAN).is_err());
        let mut anim = Animation::new(60.0).unwrap();
        anim.add_frame(5, &page(0.0)).unwrap();
        assert_eq!(
            anim.add_frame(5, &page(0.0)).unwrap_err(),
            ExportError::FrameOrder { frame: 5, last: 5 }
        );
        // NaN positions and out-of-range indices are dropped; zero normals become +Y.
        let mut bad = page(0.0);
        bad.positions[0] = [f32::NAN; 3];
        bad.normals[1] = [0.0; 3];
        bad.triangles.push([0, 1, 100_000]);
        bad.surfaces.push(Surface::PageEdge);
        anim.add_frame(6, &bad).unwrap();
        let (doc, bin) = parse(&anim.to_glb());
        check_layout(&doc, &bin);
        assert_eq!(anim.frames(), 2);
    }
}
