//! Analytic scenes with exact tangents, and the accuracy metric measured against them.
//!
//! A scene is a parametric surface `P(a, b)` (a torus, a sphere without its polar caps, or a
//! height field), optionally scaled non-uniformly, tessellated irregularly in parameter space:
//! grid vertices jittered by up to [`JITTER`] of a cell (or not at all), each quad split along a
//! random diagonal. Its texture map is a smooth warp `(s, t) = W(a, b)` (see [`warp`]) or the
//! identity, optionally mirrored on half the surface, so the true tangent `dP/ds` at every vertex
//! follows in closed form from the chain rule (texture coordinates jittered or quantised after the
//! map keep the map's truth: the noise counts as error):
//!
//! `dP/ds = P_a * da/ds + P_b * db/ds`, with `[da/ds, db/ds]` the first column of `inverse(DW)`,
//!
//! evaluated in f64 at the vertex's exact parameters. Normals are the exact unit normals. UV seams
//! (where the texture wraps, and on mirror lines) have their vertices duplicated, one copy per
//! side with identical position and normal, as exported assets have them; each copy's truth is
//! that of its own side.
//!
//! Shared by `crates/tbasis/tests/accuracy.rs` and `crates/compare/examples/chart.rs` and
//! `accuracy_table.rs`, so there is one metric for all; it depends on the standard library and glam
//! only.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

/// Largest jitter of a grid vertex, in cells along each parameter. At 0.2 the corners of a
/// triangle move by at most 0.4 of a cell relative to each other, which keeps every triangle's
/// orientation in parameter space (checked by `crates/tbasis/tests/accuracy.rs`).
pub const JITTER: f64 = 0.2;

/// The resolutions of the sweep, in vertices (each scene lands within a few percent).
pub const SWEEP: [usize; 5] = [500, 5_000, 50_000, 250_000, 1_000_000];

/// A minimal PCG32 (O'Neill 2014, XSH-RR output): seeded, portable, no dependency.
pub struct Pcg32 {
    state: u64,
    increment: u64,
}

impl Pcg32 {
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut rng = Pcg32 {
            state: 0,
            increment: (stream << 1) | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(self.increment);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        f64::from(self.next_u32()) / 4_294_967_296.0
    }

    /// Uniform in `[-amplitude, amplitude)`.
    pub fn symmetric(&mut self, amplitude: f64) -> f64 {
        (2.0 * self.unit() - 1.0) * amplitude
    }
}

/// The parametric surfaces. Torus and sphere are periodic in `a`; the torus also in `b`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// Major radius 1, minor radius 0.4: `a` runs around the axis, `b` around the tube.
    Torus,
    /// Unit sphere between latitudes -72 and +72 degrees (the parametrization is singular at the
    /// poles, where no true tangent exists): `a` is longitude, `b` latitude.
    Sphere,
    /// A 2 x 2 height field `z = 0.25 sin(2 pi a) cos(2 pi b)` over `[-1, 1]^2`: borders on all
    /// four sides, slopes up to about 1.6.
    HeightField,
}

/// Amplitude of [`Surface::HeightField`].
const HEIGHT: f64 = 0.25;

const TORUS_MAJOR: f64 = 1.0;
const TORUS_MINOR: f64 = 0.4;
/// The sphere's latitude is `LATITUDE_SPAN * (b - 0.5)`: +-0.4 pi, i.e. +-72 degrees.
const LATITUDE_SPAN: f64 = 0.8 * PI;

/// Position, `dP/da`, `dP/db` and unit normal at `(a, b)`. `P_a x P_b` points along the normal,
/// so a triangle wound counter-clockwise in `(a, b)` faces outwards.
fn surface_frame(surface: Surface, a: f64, b: f64) -> ([f64; 3], [f64; 3], [f64; 3], [f64; 3]) {
    match surface {
        Surface::Torus => {
            let (sin_u, cos_u) = (TAU * a).sin_cos();
            let (sin_v, cos_v) = (TAU * b).sin_cos();
            let ring = TORUS_MAJOR + TORUS_MINOR * cos_v;
            let position = [ring * cos_u, ring * sin_u, TORUS_MINOR * sin_v];
            let p_a = [-TAU * ring * sin_u, TAU * ring * cos_u, 0.0];
            let p_b = [
                -TAU * TORUS_MINOR * sin_v * cos_u,
                -TAU * TORUS_MINOR * sin_v * sin_u,
                TAU * TORUS_MINOR * cos_v,
            ];
            (position, p_a, p_b, [cos_v * cos_u, cos_v * sin_u, sin_v])
        }
        Surface::Sphere => {
            let (sin_u, cos_u) = (TAU * a).sin_cos();
            let (sin_v, cos_v) = (LATITUDE_SPAN * (b - 0.5)).sin_cos();
            let position = [cos_v * cos_u, cos_v * sin_u, sin_v];
            let p_a = [-TAU * cos_v * sin_u, TAU * cos_v * cos_u, 0.0];
            let p_b = [
                -LATITUDE_SPAN * sin_v * cos_u,
                -LATITUDE_SPAN * sin_v * sin_u,
                LATITUDE_SPAN * cos_v,
            ];
            (position, p_a, p_b, position)
        }
        Surface::HeightField => {
            let (sin_a, cos_a) = (TAU * a).sin_cos();
            let (sin_b, cos_b) = (TAU * b).sin_cos();
            let position = [2.0 * a - 1.0, 2.0 * b - 1.0, HEIGHT * sin_a * cos_b];
            let p_a = [2.0, 0.0, HEIGHT * TAU * cos_a * cos_b];
            let p_b = [0.0, 2.0, -HEIGHT * TAU * sin_a * sin_b];
            (position, p_a, p_b, normalize(cross(p_a, p_b)))
        }
    }
}

/// The texture warp `W(a, b) = (a + 0.15 sin(2 pi b), b + 0.1 a^2)`.
///
/// A diffeomorphism on `[0, 1]^2`: `W - identity` has a Jacobian of norm at most `0.3 pi < 1`, so
/// `W` is injective, and `det DW = 1 - 0.06 pi a cos(2 pi b) >= 0.81`.
pub fn warp(a: f64, b: f64) -> [f64; 2] {
    [a + 0.15 * (TAU * b).sin(), b + 0.1 * a * a]
}

/// `inverse(DW)` at `(a, b)` as its columns: `([da/ds, db/ds], [da/dt, db/dt])`.
fn warp_inverse_jacobian(a: f64, b: f64) -> ([f64; 2], [f64; 2]) {
    let ds_db = 0.3 * PI * (TAU * b).cos();
    let dt_da = 0.2 * a;
    let det = 1.0 - ds_db * dt_da;
    ([1.0 / det, -dt_da / det], [-ds_db / det, 1.0 / det])
}

/// How texture coordinates are disturbed after the warp (the truth stays the warp's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UvNoise {
    None,
    /// Each vertex's `(s, t)` moved by up to this fraction of a grid cell along each axis.
    Jitter(f64),
    /// `(s, t)` rounded to multiples of `1 / steps`, as 8- to 12-bit texture coordinates are.
    Quantize(u32),
}

/// What kind of scene to build and how finely.
#[derive(Clone, Copy, Debug)]
pub struct SceneSpec {
    pub surface: Surface,
    /// The texture of the half `a > 0.5` is mirrored: `(s, t) = W(1 - a, b)`.
    pub mirrored: bool,
    /// Roughly how many vertices (seam duplicates included).
    pub target_vertices: usize,
    pub seed: u64,
    /// Quads along `a` and `b`, when given, instead of a grid sized from `target_vertices`.
    pub grid: Option<(usize, usize)>,
    /// Positions scaled by `(x, y, z)` (normals by the inverse transpose): a non-uniform scale
    /// squashes the surface, stretching its triangles and its texture.
    pub scale: [f64; 3],
    pub uv_noise: UvNoise,
    /// How far grid vertices move, in cells ([`JITTER`] by default; 0 for a regular grid).
    pub jitter: f64,
    /// The texture map is the warp [`warp`] (by default) or the identity `(s, t) = (a, b)`.
    pub warped: bool,
}

impl SceneSpec {
    pub fn torus(target_vertices: usize) -> Self {
        SceneSpec {
            surface: Surface::Torus,
            mirrored: false,
            target_vertices,
            seed: 1,
            grid: None,
            scale: [1.0; 3],
            uv_noise: UvNoise::None,
            jitter: JITTER,
            warped: true,
        }
    }

    /// This scene on a regular grid (no jitter), with the identity texture map when `warped` is
    /// false.
    pub fn regular(self, warped: bool) -> Self {
        SceneSpec {
            jitter: 0.0,
            warped,
            ..self
        }
    }

    /// A height field of about `target_vertices`.
    pub fn height_field(target_vertices: usize) -> Self {
        SceneSpec {
            surface: Surface::HeightField,
            ..SceneSpec::torus(target_vertices)
        }
    }

    /// This scene with exactly `n_a` by `n_b` quads.
    pub fn with_grid(self, n_a: usize, n_b: usize) -> Self {
        SceneSpec {
            grid: Some((n_a, n_b)),
            ..self
        }
    }

    pub fn with_scale(self, scale: [f64; 3]) -> Self {
        SceneSpec { scale, ..self }
    }

    pub fn with_uv_noise(self, uv_noise: UvNoise) -> Self {
        SceneSpec { uv_noise, ..self }
    }

    pub fn sphere(target_vertices: usize) -> Self {
        SceneSpec {
            surface: Surface::Sphere,
            ..SceneSpec::torus(target_vertices)
        }
    }

    pub fn mirrored_torus(target_vertices: usize) -> Self {
        SceneSpec {
            mirrored: true,
            ..SceneSpec::torus(target_vertices)
        }
    }

    /// `torus`, `sphere`, `mirrored-torus`, `scaled-sphere`, `torus-uv-jitter`, ...
    pub fn name(&self) -> String {
        let surface = match self.surface {
            Surface::Torus => "torus",
            Surface::Sphere => "sphere",
            Surface::HeightField => "height-field",
        };
        let mut name = surface.to_string();
        if self.jitter == 0.0 {
            name = format!("regular-{name}");
        }
        if !self.warped {
            name.push_str("-plain-uv");
        }
        if self.scale != [1.0; 3] {
            name = format!("scaled-{name}");
        }
        if self.mirrored {
            name = format!("mirrored-{name}");
        }
        match self.uv_noise {
            UvNoise::None => {}
            UvNoise::Jitter(_) => name.push_str("-uv-jitter"),
            UvNoise::Quantize(_) => name.push_str("-uv-quantized"),
        }
        name
    }
}

/// The scenes `docs/accuracy.md` compares the default method with mikktspace.c on: the chart's
/// three at small sizes, then a set grown so that no tuning can fit one shape: coarse grids (down
/// to 12 x 8 quads, jittered and regular, with the warped or the plain texture map), a height
/// field, tori and spheres squashed by non-uniform scales, and jittered or quantised texture
/// coordinates.
pub fn accuracy_specs() -> Vec<SceneSpec> {
    let torus = SceneSpec::torus;
    let sphere = SceneSpec::sphere;
    let squashed_torus = [1.0, 0.5, 2.0];
    let squashed_sphere = [1.6, 1.0, 0.6];
    vec![
        torus(500),
        torus(5_000),
        torus(50_000),
        sphere(500),
        sphere(5_000),
        SceneSpec::mirrored_torus(500),
        SceneSpec::mirrored_torus(5_000),
        torus(0).with_grid(12, 8),
        torus(0).with_grid(12, 8).regular(true),
        torus(0).with_grid(12, 8).regular(false),
        torus(0).with_grid(24, 16).regular(false),
        torus(0).with_grid(48, 32).regular(false),
        sphere(0).with_grid(12, 8).regular(false),
        torus(0).with_grid(16, 12),
        torus(0).with_grid(24, 16),
        torus(0).with_grid(48, 32),
        sphere(0).with_grid(12, 8),
        sphere(0).with_grid(24, 16),
        SceneSpec::mirrored_torus(0).with_grid(12, 8),
        SceneSpec::mirrored_torus(0).with_grid(24, 16),
        SceneSpec::height_field(0).with_grid(12, 12),
        SceneSpec::height_field(0).with_grid(24, 24),
        SceneSpec::height_field(5_000),
        torus(0).with_grid(12, 8).with_scale(squashed_torus),
        torus(500).with_scale(squashed_torus),
        torus(5_000).with_scale(squashed_torus),
        sphere(0).with_grid(12, 8).with_scale(squashed_sphere),
        sphere(500).with_scale(squashed_sphere),
        sphere(5_000).with_scale(squashed_sphere),
        torus(500).with_uv_noise(UvNoise::Jitter(0.1)),
        torus(5_000).with_uv_noise(UvNoise::Jitter(0.1)),
        SceneSpec::height_field(5_000).with_uv_noise(UvNoise::Jitter(0.1)),
        torus(500).with_uv_noise(UvNoise::Quantize(256)),
        torus(5_000).with_uv_noise(UvNoise::Quantize(256)),
        torus(50_000).with_uv_noise(UvNoise::Quantize(1024)),
    ]
}

/// The exact frame at one vertex.
#[derive(Clone, Copy, Debug)]
pub struct Truth {
    /// `dP/ds`, unnormalized.
    pub tangent: [f64; 3],
    /// `dP/dt`, unnormalized.
    pub bitangent: [f64; 3],
    /// The exact unit normal.
    pub normal: [f64; 3],
    /// `sign(dot(cross(n, dP/ds), dP/dt))`: the handedness `w` a correct result has.
    pub sign: f64,
}

/// An indexed triangle mesh in the library's packed layout, with the truth at every vertex.
pub struct Scene {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub texcoords: Vec<[f32; 2]>,
    pub indices: Vec<u32>,
    pub truth: Vec<Truth>,
    /// Quads along `a` and along `b`.
    pub grid: (usize, usize),
}

impl Scene {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

/// Builds the scene `spec` describes; the same spec always gives the same scene.
pub fn build(spec: &SceneSpec) -> Scene {
    let surface = spec.surface;
    // Quads are kept near square in 3D: the torus is about 2.5 times longer around its axis than
    // around its tube, the sphere band about 2 times.
    let aspect = match surface {
        Surface::Torus => 2.5,
        Surface::Sphere => 2.0,
        Surface::HeightField => 1.0,
    };
    let n_b = ((spec.target_vertices as f64 / aspect).sqrt().round() as usize).max(2);
    // Even, so that the mirror line a = 0.5 falls on a grid column.
    let n_a = (2 * ((aspect * n_b as f64 / 2.0).round() as usize)).max(4);
    let (n_a, n_b) = spec.grid.unwrap_or((n_a, n_b));
    let a_periodic = surface != Surface::HeightField;
    let b_periodic = surface == Surface::Torus;
    let mut uv_rng = Pcg32::new(spec.seed, 0x0075_766e_6f69_7365);
    let texture = |a: f64, b: f64| if spec.warped { warp(a, b) } else { [a, b] };
    let rows = if b_periodic { n_b } else { n_b + 1 };

    // Jitter per distinct surface point (column i of n_a, row j of `rows`); points on a seam move
    // only along it, so that both copies of a seam vertex stay on the seam.
    let mut rng = Pcg32::new(spec.seed, 0x7462_6173_6973);
    let mut jitter = vec![[0.0f64; 2]; n_a * rows];
    for j in 0..rows {
        for i in 0..n_a {
            let mut d = [rng.symmetric(spec.jitter), rng.symmetric(spec.jitter)];
            if i == 0 || (spec.mirrored && i == n_a / 2) {
                d[0] = 0.0;
            }
            if j == 0 || j == n_b {
                d[1] = 0.0;
            }
            jitter[j * n_a + i] = d;
        }
    }
    let diagonals: Vec<bool> = (0..n_a * n_b).map(|_| rng.next_u32() & 1 == 1).collect();

    // Vertex columns: 0..=n_a, plus a second copy of column n_a / 2 when mirrored. Column c holds
    // grid column `grid_column(c)`; when mirrored, columns after the first copy of n_a / 2 (the
    // second copy included) belong to the mirrored half.
    let columns = if spec.mirrored { n_a + 2 } else { n_a + 1 };
    let half = n_a / 2;
    let grid_column = |c: usize| if spec.mirrored && c > half { c - 1 } else { c };
    let in_mirrored_half = |c: usize| spec.mirrored && c > half;

    let vertex_count = columns * (n_b + 1);
    let mut scene = Scene {
        name: spec.name(),
        positions: Vec::with_capacity(vertex_count),
        normals: Vec::with_capacity(vertex_count),
        texcoords: Vec::with_capacity(vertex_count),
        indices: Vec::with_capacity(6 * n_a * n_b),
        truth: Vec::with_capacity(vertex_count),
        grid: (n_a, n_b),
    };
    for j in 0..=n_b {
        for c in 0..columns {
            let i = grid_column(c);
            let d = jitter[(j % rows) * n_a + i % n_a];
            // Chart parameters run 0..=1 across the seams; the geometry wraps, so both copies of a
            // seam vertex get bit-identical positions and normals.
            let (a, b) = ((i as f64 + d[0]) / n_a as f64, (j as f64 + d[1]) / n_b as f64);
            let a_geometry = if a_periodic {
                ((i % n_a) as f64 + d[0]) / n_a as f64
            } else {
                a
            };
            let b_geometry = if b_periodic {
                ((j % n_b) as f64 + d[1]) / n_b as f64
            } else {
                b
            };
            let (position, p_a, p_b, normal) = surface_frame(surface, a_geometry, b_geometry);
            let (position, p_a, p_b) = (mul(position, spec.scale), mul(p_a, spec.scale), mul(p_b, spec.scale));
            let normal = if spec.scale == [1.0; 3] {
                normal
            } else {
                normalize([
                    normal[0] / spec.scale[0],
                    normal[1] / spec.scale[1],
                    normal[2] / spec.scale[2],
                ])
            };
            // The mirrored half reads the texture at a' = 1 - a, so da/ds = -da'/ds.
            let (chart_a, a_sign) = if in_mirrored_half(c) { (1.0 - a, -1.0) } else { (a, 1.0) };
            let uv = match spec.uv_noise {
                UvNoise::None => texture(chart_a, b),
                UvNoise::Jitter(cells) => {
                    let [s, t] = texture(chart_a, b);
                    let ds = uv_rng.symmetric(cells / n_a as f64);
                    [s + ds, t + uv_rng.symmetric(cells / n_b as f64)]
                }
                UvNoise::Quantize(steps) => {
                    texture(chart_a, b).map(|x| (x * f64::from(steps)).round() / f64::from(steps))
                }
            };
            let (d_ds, d_dt) = if spec.warped {
                warp_inverse_jacobian(chart_a, b)
            } else {
                ([1.0, 0.0], [0.0, 1.0])
            };
            let tangent = add(scale(p_a, a_sign * d_ds[0]), scale(p_b, d_ds[1]));
            let bitangent = add(scale(p_a, a_sign * d_dt[0]), scale(p_b, d_dt[1]));
            let sign = if dot(cross(normal, tangent), bitangent) < 0.0 {
                -1.0
            } else {
                1.0
            };
            scene.positions.push(position.map(|x| x as f32));
            scene.normals.push(normal.map(|x| x as f32));
            scene.texcoords.push(uv.map(|x| x as f32));
            scene.truth.push(Truth {
                tangent,
                bitangent,
                normal,
                sign,
            });
        }
    }
    for j in 0..n_b {
        for i in 0..n_a {
            // Quads right of the mirror line use the extra column's copy.
            let c = if spec.mirrored && i >= half { i + 1 } else { i };
            let v = |dc: usize, dj: usize| ((j + dj) * columns + c + dc) as u32;
            let (v00, v10, v11, v01) = (v(0, 0), v(1, 0), v(1, 1), v(0, 1));
            // Counter-clockwise in (a, b), so every triangle faces along the normal.
            let triangles = if diagonals[j * n_a + i] {
                [v00, v10, v11, v00, v11, v01]
            } else {
                [v00, v10, v01, v10, v11, v01]
            };
            scene.indices.extend_from_slice(&triangles);
        }
    }
    scene
}

/// How far a set of tangents is from the truth.
#[derive(Clone, Copy, Debug, Default)]
pub struct Accuracy {
    pub vertices: usize,
    /// Mean angle to the true tangent, in degrees.
    pub mean_deg: f64,
    /// 99th percentile (nearest rank), in degrees.
    pub p99_deg: f64,
    pub max_deg: f64,
    /// Vertices whose `w` does not have the true handedness's sign.
    pub wrong_handedness: usize,
    /// Vertices whose tangent is not finite or zero (counted as 180 degrees off).
    pub non_finite: usize,
}

impl Accuracy {
    pub fn wrong_handedness_share(&self) -> f64 {
        self.wrong_handedness as f64 / self.vertices.max(1) as f64
    }
}

/// The angle, in degrees, between `tangent` and the true tangent projected onto the tangent plane
/// of `normal` (the normal the method was given), or `None` when `tangent` is not finite or zero.
///
/// `atan2(|x cross y|, x . y)` keeps full precision for the tiny angles that matter here, where
/// `acos` of a dot product near 1 would lose half the digits.
pub fn angle_deg(tangent: [f32; 3], truth: &Truth, normal: [f32; 3]) -> Option<f64> {
    let t = tangent.map(f64::from);
    if !t.iter().all(|x| x.is_finite()) || dot(t, t) == 0.0 {
        return None;
    }
    let n = normalize(normal.map(f64::from));
    let projected = sub(truth.tangent, scale(n, dot(n, truth.tangent)));
    let c = cross(t, projected);
    Some(dot(c, c).sqrt().atan2(dot(t, projected)).to_degrees())
}

/// Compares per-vertex tangents (`xyz`, handedness `w`) with the scene's truth.
pub fn accuracy(scene: &Scene, tangents: &[[f32; 4]]) -> Accuracy {
    assert_eq!(tangents.len(), scene.vertex_count(), "one tangent per vertex");
    let mut errors = Vec::with_capacity(tangents.len());
    let mut result = Accuracy {
        vertices: tangents.len(),
        ..Accuracy::default()
    };
    for ((t, truth), &normal) in tangents.iter().zip(&scene.truth).zip(&scene.normals) {
        let error = angle_deg([t[0], t[1], t[2]], truth, normal).unwrap_or_else(|| {
            result.non_finite += 1;
            180.0
        });
        errors.push(error);
        // NaN w is wrong whatever the truth.
        let w_sign = if t[3] < 0.0 {
            -1.0
        } else if t[3] >= 0.0 {
            1.0
        } else {
            0.0
        };
        result.wrong_handedness += usize::from(w_sign != truth.sign);
    }
    if errors.is_empty() {
        return result;
    }
    result.mean_deg = errors.iter().sum::<f64>() / errors.len() as f64;
    result.max_deg = errors.iter().copied().fold(0.0, f64::max);
    let rank = ((0.99 * errors.len() as f64).ceil() as usize).clamp(1, errors.len()) - 1;
    result.p99_deg = *errors.select_nth_unstable_by(rank, f64::total_cmp).1;
    result
}

// Small f64 vector helpers over arrays, the scenes' storage, backed by glam.
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    (DVec3::from(a) + DVec3::from(b)).to_array()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    (DVec3::from(a) - DVec3::from(b)).to_array()
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    (DVec3::from(a) * k).to_array()
}

/// Componentwise product.
fn mul(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    DVec3::from(a).dot(DVec3::from(b))
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    DVec3::from(a).cross(DVec3::from(b)).to_array()
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    DVec3::from(a).normalize().to_array()
}
