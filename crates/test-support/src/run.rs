//! One library call on packed arrays, with outputs prefilled so that untouched ones show.

use tbasis::{Error, ErrorKind, Mesh, Options, Output, Report, StridedMut};

/// What the outputs hold before a call; no valid output component equals it.
pub const UNTOUCHED: f32 = -7.5;

/// One call's outcome and outputs.
pub struct Run {
    /// The outcome's category (the error itself is in `error`).
    pub result: Result<(), ErrorKind>,
    /// The error, with its details, when the call failed.
    pub error: Option<Error>,
    /// Filled on success and on a REJECT refusal.
    pub report: Report,
    pub tangents: Vec<[f32; 4]>,
    pub bitangents: Vec<[f32; 3]>,
}

impl Run {
    /// True when the call wrote no output at all.
    pub fn untouched(&self) -> bool {
        self.tangents
            .iter()
            .flatten()
            .chain(self.bitangents.iter().flatten())
            .all(|&x| x == UNTOUCHED)
    }

    /// The tangent (xyz, w) of vertex `v`.
    pub fn tangent(&self, v: usize) -> [f32; 4] {
        self.tangents[v]
    }

    /// The result with the report, as `generate` returns it.
    pub fn outcome(&self) -> Result<Report, Error> {
        match &self.error {
            Some(error) => Err(error.clone()),
            None => Ok(self.report),
        }
    }
}

/// A call's result split as [`Run`] keeps it: category, error, and the report (also the one a
/// REJECT refusal carries).
pub fn split_outcome(outcome: Result<Report, Error>) -> (Result<(), ErrorKind>, Option<Error>, Report) {
    match outcome {
        Ok(report) => (Ok(()), None, report),
        Err(error) => {
            let report = match &error {
                Error::DegenerateUv { report, .. } => *report,
                _ => Report::default(),
            };
            (Err(error.kind()), Some(error), report)
        }
    }
}

/// Runs the library on `mesh` of `vertex_count` vertices, asking for tangents and bitangents.
pub fn run_mesh(mesh: &Mesh, vertex_count: usize, options: &Options) -> Run {
    let mut tangents = vec![[UNTOUCHED; 4]; vertex_count];
    let mut bitangents = vec![[UNTOUCHED; 3]; vertex_count];
    let outcome = {
        let mut output = Output {
            tangents: StridedMut::from_slice(&mut tangents),
            bitangents: Some(StridedMut::from_slice(&mut bitangents)),
        };
        tbasis::generate(mesh, options, &mut output)
    };
    let (result, error, report) = split_outcome(outcome);
    Run {
        result,
        error,
        report,
        tangents,
        bitangents,
    }
}

/// [`tbasis::generate`], or [`tbasis::generate_with_scratch`] with `scratch`, in the shape the
/// tests compare: the report written to `report` (also the one a REJECT refusal carries), the
/// error as its kind.
pub fn generate_into(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), ErrorKind> {
    let outcome = match scratch {
        Some(bytes) => tbasis::generate_with_scratch(mesh, options, output, bytes),
        None => tbasis::generate(mesh, options, output),
    };
    into_report(outcome, report)
}

/// [`generate_into`] for the per-corner output.
pub fn generate_corners_into(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), ErrorKind> {
    let outcome = match scratch {
        Some(bytes) => tbasis::generate_corners_with_scratch(mesh, options, tangents, bytes),
        None => tbasis::generate_corners(mesh, options, tangents),
    };
    into_report(outcome, report)
}

/// Writes the report an outcome has (on success or REJECT refusal) to `report`.
fn into_report(outcome: Result<Report, Error>, report: &mut Report) -> Result<(), ErrorKind> {
    let (result, error, found) = split_outcome(outcome);
    if result.is_ok() || matches!(error, Some(Error::DegenerateUv { .. })) {
        *report = found;
    }
    result
}

/// A frame as tests print it: its floats, then their bits.
pub fn frame_with_bits(t: [f32; 4]) -> String {
    let bits = t.map(f32::to_bits);
    format!(
        "{t:?} [{:08x} {:08x} {:08x} {:08x}]",
        bits[0], bits[1], bits[2], bits[3]
    )
}
