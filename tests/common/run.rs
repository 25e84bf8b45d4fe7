//! One library call on packed arrays, with outputs prefilled so that untouched ones show.

use tbasis::{Error, Mesh, Options, Output, Report, StridedMut};

/// What the outputs hold before a call; no valid output component equals it.
pub const UNTOUCHED: f32 = -7.5;

/// One call's outcome and outputs.
pub struct Run {
    pub result: Result<(), Error>,
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
        self.result.map(|()| self.report)
    }
}

/// Runs the library on `mesh` of `vertex_count` vertices, asking for tangents and bitangents.
pub fn run_mesh(mesh: &Mesh, vertex_count: usize, options: &Options) -> Run {
    let mut tangents = vec![[UNTOUCHED; 4]; vertex_count];
    let mut bitangents = vec![[UNTOUCHED; 3]; vertex_count];
    let mut report = Report::default();
    let result = {
        let mut output = Output {
            tangents: StridedMut::from_slice(&mut tangents),
            bitangents: Some(StridedMut::from_slice(&mut bitangents)),
        };
        tbasis::generate_into(mesh, options, &mut output, None, &mut report)
    };
    Run {
        result,
        report,
        tangents,
        bitangents,
    }
}
