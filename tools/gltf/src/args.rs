//! The command line, and the list of (input, output) pairs it asks for.

use std::collections::HashSet;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};

use clap::{Parser, ValueEnum};
use tbasis::{DegeneratePolicy, Method, Options};

/// Writes a TANGENT attribute into every triangle primitive of glTF files (.gltf, .glb) that has
/// NORMAL and the texture coordinates of its normal texture, computed per corner and split at
/// seams so that each corner gets exactly its own tangent.
#[derive(Parser, Debug)]
#[command(name = "tbasis-gltf", version)]
pub struct Args {
    /// Input files, .gltf or .glb; each output is of the same kind.
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<PathBuf>,

    /// The output file, for a single input.
    #[arg(short, long, value_name = "FILE", conflicts_with = "out_dir")]
    pub output: Option<PathBuf>,

    /// The output folder: each input is written there under its own file name.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,

    /// Write nothing: report per file what would change. Exit status 0 when nothing would, 1
    /// when something would, 2 on an error.
    #[arg(long, conflicts_with_all = ["output", "out_dir"])]
    pub check: bool,

    /// Replace the TANGENT attributes primitives already have (kept otherwise).
    #[arg(long)]
    pub overwrite: bool,

    /// Replace an existing OUT.tangents.bin beside an output, which is refused otherwise: it may
    /// hold another file's data.
    #[arg(long)]
    pub force: bool,

    /// Accept buffer and image URIs that lead outside the input's folder (absolute paths, `..`,
    /// links leading out; for images, schemes other than data:), which are refused otherwise.
    /// Buffers are read from files and data: URIs only.
    #[arg(long)]
    pub allow_outside_uris: bool,

    /// How tangents are computed.
    #[arg(long, value_enum, default_value_t = MethodArg::Mikktspace)]
    pub method: MethodArg,

    /// What happens where the texture coordinates are degenerate. `skip` keeps mikktspace.c's
    /// tangents except where it writes no usable one.
    #[arg(long, value_enum, default_value_t = PolicyArg::Skip)]
    pub policy: PolicyArg,

    /// Files processed at once (default: one per core).
    #[arg(short, long, value_name = "N")]
    pub jobs: Option<NonZeroUsize>,

    /// Print errors only.
    #[arg(short, long)]
    pub quiet: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Exactly mikktspace.c per corner (what normal maps are baked against).
    Mikktspace,
    /// Corner-angle weighted face tangents.
    Angle,
    /// The original listing (Lengyel 2001).
    Lengyel,
    /// Area-weighted unit face tangents.
    Area,
    /// Unit face tangents with equal weights.
    Uniform,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PolicyArg {
    /// Exactly what the method gives, invalid tangents included (methods mikktspace and lengyel,
    /// which reproduce mikktspace.c and the listing).
    Legacy,
    /// Degenerate triangles contribute nothing; a corner left without a tangent gets one built
    /// from its normal.
    Skip,
    /// Like skip, but such a corner first takes a tangent from its neighbours.
    Inherit,
    /// Fail the file at the first degenerate triangle.
    Reject,
}

/// One file to convert.
#[derive(Clone, Debug)]
pub struct Job {
    pub input: PathBuf,
    /// Where it is written; `None` with `--check`, which writes nothing.
    pub output: Option<PathBuf>,
}

impl Args {
    /// The library's options: glTF's texture coordinates have V pointing down.
    pub fn options(&self) -> Options {
        let method = match self.method {
            MethodArg::Mikktspace => Method::Mikktspace,
            MethodArg::Angle => Method::Angle,
            MethodArg::Lengyel => Method::Lengyel,
            MethodArg::Area => Method::Area,
            MethodArg::Uniform => Method::Uniform,
        };
        let degenerate_policy = match self.policy {
            PolicyArg::Legacy => DegeneratePolicy::Legacy,
            PolicyArg::Skip => DegeneratePolicy::Skip,
            PolicyArg::Inherit => DegeneratePolicy::Inherit,
            PolicyArg::Reject => DegeneratePolicy::Reject,
        };
        Options::default()
            .with_method(method)
            .with_policy(degenerate_policy)
            .with_flip_v(true)
            // Files run in parallel (`--jobs`), then primitives within a file, then each call
            // (`convert::compute_all`).
            .with_threads(1)
    }

    /// Every (input, output) pair, or what is wrong with the command line.
    pub fn jobs(&self) -> Result<Vec<Job>, String> {
        self.options().validate().map_err(|error| error.to_string())?;
        for input in &self.inputs {
            kind_of(input)?;
        }
        if self.check {
            return Ok(self
                .inputs
                .iter()
                .map(|input| Job {
                    input: input.clone(),
                    output: None,
                })
                .collect());
        }
        if let Some(output) = &self.output {
            let [input] = self.inputs.as_slice() else {
                return Err(format!(
                    "-o names one output but {} inputs are given; use --out-dir",
                    self.inputs.len()
                ));
            };
            if kind_of(output)? != kind_of(input)? {
                return Err(format!(
                    "{}: the output must be of the input's kind ({})",
                    output.display(),
                    kind_of(input)?
                ));
            }
            return Ok(vec![Job {
                input: input.clone(),
                output: Some(output.clone()),
            }]);
        }
        let dir = self.out_dir.as_ref().ok_or(
            "no output given: -o FILE (one input) or --out-dir DIR (any number of inputs); --check writes nothing",
        )?;
        // Side buffers are named from the stem (`STEM.tangents.bin`), which `a.gltf` and `a.GLTF`
        // share. A .glb keeps its new data in its binary chunk where it has one; the rare one that
        // needs a side buffer has the name checked when it is written (`convert::SideFiles`).
        let mut stems = HashSet::new();
        self.inputs
            .iter()
            .map(|input| {
                let name = input
                    .file_name()
                    .ok_or_else(|| format!("{}: not a file name", input.display()))?;
                let stem = input.file_stem().unwrap_or(name);
                let kind = kind_of(input)?;
                if !stems.insert((stem.to_owned(), kind)) {
                    return Err(format!(
                        "two inputs are named {}.{kind}; their outputs in {} would collide",
                        stem.to_string_lossy(),
                        dir.display()
                    ));
                }
                Ok(Job {
                    input: input.clone(),
                    output: Some(dir.join(name)),
                })
            })
            .collect()
    }
}

/// `gltf` or `glb`, from the file name.
pub fn kind_of(path: &Path) -> Result<&'static str, String> {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("gltf") => Ok("gltf"),
        Some("glb") => Ok("glb"),
        _ => Err(format!("{}: not a .gltf or .glb file name", path.display())),
    }
}
