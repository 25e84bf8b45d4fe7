//! The shared mesh corpus (`../shared/meshes/`, listed in its `MANIFEST.tsv`) as plain arrays.
//!
//! One loader per format: glTF 2.0 (`.gltf`, `.glb`) through the `gltf` crate, OBJ through `tobj`.
//! Each file becomes a list of primitives (a glTF mesh primitive, an OBJ model) holding packed
//! positions, normals, optional TEXCOORD_0, u32 indices and, when the file has them, its stored
//! tangents. Texture coordinates are kept exactly as the file stores them: glTF with V pointing
//! down, OBJ with V pointing up (see [`Primitive::v_down`]).
//!
//! Used by the crate's corpus tests, the corpus table of `crates/compare`, and `tools/gltf`'s tests,
//! which include it by path (through `tests/common/load.rs`): so it depends on nothing but the
//! standard library, `gltf` and `tobj`.

use std::fs;
use std::path::{Path, PathBuf};

/// One row of `MANIFEST.tsv`: what the corpus says about a file.
#[derive(Clone, Debug)]
pub struct ManifestRow {
    /// Path relative to the corpus folder, e.g. `khronos/Fox.glb`.
    pub path: String,
    /// `gltf`, `glb` or `obj`.
    pub format: String,
    /// Vertex count (glTF: summed over primitives; OBJ: unique v/vt/vn tuples).
    pub vertices: usize,
    /// Triangle count (polygons fan-triangulated).
    pub triangles: usize,
    /// What the stored tangents are: `mikktspace-exact`, `mikktspace-near`, `not-mikktspace`, `none`.
    pub stored_tangents: String,
}

/// One primitive as packed per-vertex arrays.
#[derive(Clone, Debug, Default)]
pub struct Primitive {
    /// `mesh 2 primitive 0` (glTF) or the OBJ model name.
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    /// The file's normals, or computed ones when `normals_computed` (see [`area_weighted_normals`]).
    pub normals: Vec<[f32; 3]>,
    /// True when the file has no normals for this primitive and `normals` were computed.
    pub normals_computed: bool,
    /// TEXCOORD_0 as stored, if the primitive has it.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// Three per triangle; unindexed glTF primitives get `0, 1, 2, ...`.
    pub indices: Vec<u32>,
    /// The glTF TANGENT attribute (xyz and handedness w), if present.
    pub stored_tangents: Option<Vec<[f32; 4]>>,
    /// True for glTF, whose texture coordinates have V pointing down; false for OBJ.
    pub v_down: bool,
}

impl Primitive {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The library's view of this primitive.
    pub fn mesh(&self) -> tbasis::Mesh<'_> {
        tbasis::Mesh {
            positions: tbasis::Strided::from_slice(&self.positions),
            normals: tbasis::Strided::from_slice(&self.normals),
            texcoords: self.texcoords.as_deref().map(tbasis::Strided::from_slice),
            indices: tbasis::Indices::U32(tbasis::Strided::from_slice(&self.indices)),
        }
    }

    /// Options for `policy`, with V pointing down for glTF.
    pub fn options(&self, policy: tbasis::DegeneratePolicy) -> tbasis::Options {
        // Policy LEGACY is the listing's: method LENGYEL.
        let method = match policy {
            tbasis::DegeneratePolicy::Legacy => tbasis::Method::Lengyel,
            _ => tbasis::Method::DEFAULT,
        };
        tbasis::Options::default()
            .with_method(method)
            .with_policy(policy)
            .with_flip_v(self.v_down)
    }
}

/// A loaded corpus file: its manifest row and its primitives.
#[derive(Clone, Debug)]
pub struct MeshFile {
    pub row: ManifestRow,
    pub primitives: Vec<Primitive>,
}

impl MeshFile {
    pub fn vertex_count(&self) -> usize {
        self.primitives.iter().map(Primitive::vertex_count).sum()
    }

    pub fn triangle_count(&self) -> usize {
        self.primitives.iter().map(Primitive::triangle_count).sum()
    }
}

/// The corpus folder, `../shared/meshes/` next to the repository, or `None` when it (or its
/// manifest) is absent: the corpus is not part of the repository, so callers skip rather than fail.
pub fn corpus_dir() -> Option<PathBuf> {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    // Whichever crate of the workspace compiles this file: the folder at or above it that holds it.
    let repo = manifest
        .ancestors()
        .find(|dir| dir.join("crates/test-support/src/load.rs").is_file())
        .unwrap_or(manifest);
    let dir = repo.join("../shared/meshes");
    dir.join("MANIFEST.tsv").is_file().then_some(dir)
}

/// Corpus files above this many vertices are checked by optimized builds only (`cargo test
/// --release`, which CI runs): a debug build takes minutes on `FlightHelmet.cc1.glb` (849k).
pub const DEBUG_MAX_VERTICES: usize = 200_000;

/// True, after saying so on stderr, when `row` is above [`DEBUG_MAX_VERTICES`] in a debug build.
pub fn left_to_optimized_builds(row: &ManifestRow) -> bool {
    let skip = cfg!(debug_assertions) && row.vertices > DEBUG_MAX_VERTICES;
    if skip {
        eprintln!(
            "skipped in debug builds: {} ({} vertices); --release checks it",
            row.path, row.vertices
        );
    }
    skip
}

/// `check` on every file of the corpus in `dir` that `wanted` keeps, loaded (or why it could not
/// be), on `workers` threads: each takes the next file until none is left, the largest first so
/// that it overlaps the rest. Returns the manifest's rows and `check`'s results, in no set order.
pub fn check_in_parallel<T: Send>(
    dir: &Path,
    workers: usize,
    wanted: impl Fn(&ManifestRow) -> bool + Sync,
    check: impl Fn(&ManifestRow, Result<MeshFile, String>) -> T + Sync,
) -> (Vec<ManifestRow>, Vec<T>) {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;

    let rows = read_manifest(dir).expect("MANIFEST.tsv");
    assert!(!rows.is_empty(), "MANIFEST.tsv lists no mesh");
    let mut order: Vec<&ManifestRow> = rows.iter().collect();
    order.sort_by_key(|row| std::cmp::Reverse(row.vertices));
    let next = AtomicUsize::new(0);
    let results = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                while let Some(&row) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
                    if wanted(row) {
                        let result = check(row, load(dir, row));
                        results.lock().unwrap().push(result);
                    }
                }
            });
        }
    });
    (rows, results.into_inner().unwrap())
}

/// Every row of `dir/MANIFEST.tsv`, in file order. Columns are found by their header name.
pub fn read_manifest(dir: &Path) -> Result<Vec<ManifestRow>, String> {
    let path = dir.join("MANIFEST.tsv");
    let text = fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines().filter(|line| !line.trim().is_empty());
    let header: Vec<&str> = lines.next().ok_or("MANIFEST.tsv is empty")?.split('\t').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|&h| h == name)
            .ok_or_else(|| format!("MANIFEST.tsv has no column {name}"))
    };
    let (path_col, format_col) = (column("path")?, column("format")?);
    let (vertices_col, triangles_col) = (column("vertices")?, column("triangles")?);
    let stored_col = column("stored_tangents")?;
    lines
        .enumerate()
        .map(|(k, line)| {
            let fields: Vec<&str> = line.split('\t').collect();
            let field = |col: usize| {
                fields
                    .get(col)
                    .copied()
                    .ok_or_else(|| format!("MANIFEST.tsv row {}: too few columns", k + 2))
            };
            let count = |col: usize| {
                field(col)?
                    .parse::<usize>()
                    .map_err(|e| format!("MANIFEST.tsv row {}: {e}", k + 2))
            };
            Ok(ManifestRow {
                path: field(path_col)?.to_string(),
                format: field(format_col)?.to_string(),
                vertices: count(vertices_col)?,
                triangles: count(triangles_col)?,
                stored_tangents: field(stored_col)?.to_string(),
            })
        })
        .collect()
}

/// Loads the file a manifest row names, with the loader its format calls for.
pub fn load(dir: &Path, row: &ManifestRow) -> Result<MeshFile, String> {
    let path = dir.join(&row.path);
    let primitives = match row.format.as_str() {
        "gltf" | "glb" => load_gltf(&path),
        "obj" => load_obj(&path),
        other => Err(format!("unknown format {other}")),
    }
    .map_err(|e| format!("{}: {e}", row.path))?;
    Ok(MeshFile {
        row: row.clone(),
        primitives,
    })
}

/// Every triangle primitive of every mesh in the document (each mesh once, whatever the number of
/// nodes that instance it), in document order.
///
/// A primitive that reads the same accessors as an earlier one (ClearCoatTest draws one sphere
/// with 18 materials) is the same geometry and loaded once, as the manifest counts it.
fn load_gltf(path: &Path) -> Result<Vec<Primitive>, String> {
    let bytes = fs::read(path).map_err(|e| e.to_string())?;
    let (json, blob) = if bytes.starts_with(b"glTF") {
        let glb = gltf::Glb::from_slice(&bytes).map_err(|e| e.to_string())?;
        (glb.json.into_owned(), glb.bin.map(|bin| bin.into_owned()))
    } else {
        (bytes, None)
    };
    let mut root: gltf::json::Root = gltf::json::deserialize::from_slice(&json).map_err(|e| e.to_string())?;
    // Validation refuses required extensions this build of `gltf` was not compiled with
    // (KHR_lights_punctual, KHR_texture_transform); none of them changes mesh data.
    root.extensions_required.clear();
    let document = gltf::Document::from_json(root).map_err(|e| e.to_string())?;
    let buffers = gltf::import_buffers(&document, path.parent(), blob).map_err(|e| e.to_string())?;

    let mut primitives = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for mesh in document.meshes() {
        for primitive in mesh.primitives() {
            use gltf::Semantic::{Normals, Positions, Tangents, TexCoords};
            let accessor = |semantic| primitive.get(&semantic).map(|a| a.index());
            let geometry = [
                accessor(Positions),
                accessor(Normals),
                accessor(TexCoords(0)),
                accessor(Tangents),
                primitive.indices().map(|a| a.index()),
            ];
            if !seen.insert(geometry) {
                continue;
            }
            let name = format!("mesh {} primitive {}", mesh.index(), primitive.index());
            if primitive.mode() != gltf::mesh::Mode::Triangles {
                return Err(format!("{name}: mode {:?} is not triangles", primitive.mode()));
            }
            let reader = primitive.reader(|buffer| Some(&buffers[buffer.index()]));
            let positions: Vec<[f32; 3]> = reader
                .read_positions()
                .ok_or_else(|| format!("{name}: no POSITION"))?
                .collect();
            let indices: Vec<u32> = match reader.read_indices() {
                Some(indices) => indices.into_u32().collect(),
                None => (0..positions.len() as u32).collect(),
            };
            let texcoords = reader.read_tex_coords(0).map(|uvs| uvs.into_f32().collect::<Vec<_>>());
            let stored_tangents = reader.read_tangents().map(|t| t.collect::<Vec<_>>());
            let (normals, normals_computed) = match reader.read_normals() {
                Some(normals) => (normals.collect(), false),
                None => (area_weighted_normals(&positions, &indices), true),
            };
            primitives.push(checked(Primitive {
                name,
                positions,
                normals,
                normals_computed,
                texcoords,
                indices,
                stored_tangents,
                v_down: true,
            })?);
        }
    }
    Ok(primitives)
}

/// Every model of the OBJ file. `single_index` makes each distinct v/vt/vn tuple of a corner its
/// own vertex (what a GPU vertex buffer holds); `triangulate` fans polygons into triangles.
fn load_obj(path: &Path) -> Result<Vec<Primitive>, String> {
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        // `p` and `l` elements (rancid_geometry.obj has 90 lines) are not surface: tobj would
        // otherwise make zero-area triangles of them.
        ignore_points: true,
        ignore_lines: true,
    };
    // Materials are not needed; a missing .mtl only fails the second result, which is dropped.
    let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| e.to_string())?;
    let mut primitives = Vec::new();
    for model in models {
        let mesh = model.mesh;
        let positions: Vec<[f32; 3]> = mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let vertex_count = positions.len();
        // tobj appends a texcoord (normal) only for vertices whose corner names one: a partial set
        // cannot be matched to its vertices, so it is an error rather than a guess.
        let texcoords: Vec<[f32; 2]> = mesh.texcoords.chunks_exact(2).map(|t| [t[0], t[1]]).collect();
        let normals: Vec<[f32; 3]> = mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]).collect();
        for (what, len) in [("texcoords", texcoords.len()), ("normals", normals.len())] {
            if len != 0 && len != vertex_count {
                return Err(format!("{}: {len} {what} for {vertex_count} vertices", model.name));
            }
        }
        let (normals, normals_computed) = if normals.is_empty() {
            (area_weighted_normals(&positions, &mesh.indices), true)
        } else {
            (normals, false)
        };
        primitives.push(checked(Primitive {
            name: model.name,
            positions,
            normals,
            normals_computed,
            texcoords: (!texcoords.is_empty()).then_some(texcoords),
            indices: mesh.indices,
            stored_tangents: None,
            v_down: false,
        })?);
    }
    Ok(primitives)
}

/// Vertex normals for files that have none: each triangle adds its unnormalized face normal
/// `(p1 - p0) x (p2 - p0)` (length twice its area, hence area-weighted) to its three corners, and
/// each sum is normalized. A vertex no triangle of nonzero area uses keeps the zero vector, which
/// the library treats as an unusable normal, like such a normal in a file.
pub fn area_weighted_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut sums = vec![[0.0f64; 3]; positions.len()];
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| positions[triangle[k] as usize].map(f64::from));
        let (e1, e2) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let face = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for &v in triangle {
            for k in 0..3 {
                sums[v as usize][k] += face[k];
            }
        }
    }
    sums.into_iter()
        .map(|s| {
            let length = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if length > 0.0 && length.is_finite() {
                s.map(|x| (x / length) as f32)
            } else {
                [0.0; 3]
            }
        })
        .collect()
}

/// Checks what the library's inputs must satisfy, so a loader slip shows up here and not as a
/// library error: matching attribute lengths, whole triangles, indices in range.
fn checked(primitive: Primitive) -> Result<Primitive, String> {
    let n = primitive.vertex_count();
    let lengths = [
        ("normals", Some(primitive.normals.len())),
        ("texcoords", primitive.texcoords.as_ref().map(Vec::len)),
        ("tangents", primitive.stored_tangents.as_ref().map(Vec::len)),
    ];
    for (what, len) in lengths {
        if let Some(len) = len.filter(|&len| len != n) {
            return Err(format!("{}: {len} {what} for {n} vertices", primitive.name));
        }
    }
    if primitive.indices.len() % 3 != 0 {
        return Err(format!("{}: {} indices", primitive.name, primitive.indices.len()));
    }
    if let Some(&bad) = primitive.indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!("{}: index {bad} for {n} vertices", primitive.name));
    }
    Ok(primitive)
}
