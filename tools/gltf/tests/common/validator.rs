//! The Khronos glTF Validator (npm `gltf-validator`), through `tests/validate.js`.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use super::needs;

/// One error (severity 0), warning (1) or information (2).
#[derive(Clone, Debug)]
pub struct Issue {
    pub code: String,
    pub severity: u64,
    pub pointer: String,
    pub message: String,
}

/// The errors and warnings the validator reports for `file`.
pub fn issues(file: &Path) -> Vec<Issue> {
    let mut issues = report(file);
    issues.retain(|issue| issue.severity <= 1);
    issues
}

/// The errors, warnings and informations (severity 2) the validator reports for `file`.
pub fn report(file: &Path) -> Vec<Issue> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/validate.js");
    let module = needs::repo_dir().join(needs::GLTF_VALIDATOR_MODULE);
    let output = Command::new("node")
        .arg(script)
        .arg(module)
        .arg(file)
        .output()
        .expect("node starts");
    assert!(
        output.status.success(),
        "validator on {}: {}",
        file.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("the script prints JSON");
    assert_eq!(report["truncated"], false, "{}: report truncated", file.display());
    report["issues"]
        .as_array()
        .expect("issues")
        .iter()
        .map(|issue| Issue {
            code: issue["code"].as_str().unwrap_or_default().to_string(),
            severity: issue["severity"].as_u64().unwrap_or(0),
            pointer: issue["pointer"].as_str().unwrap_or_default().to_string(),
            message: issue["message"].as_str().unwrap_or_default().to_string(),
        })
        .collect()
}

/// The issues of `after` beyond those of `before`, code by code: where `after` has more issues
/// of a code than `before`, all of that code, described. Counted, not a set of codes: a file
/// that already had one IO_ERROR must not hide a second.
pub fn new_issues(before: &[Issue], after: &[Issue]) -> Vec<String> {
    let counts = |issues: &[Issue]| {
        let mut counts = BTreeMap::new();
        for issue in issues {
            *counts.entry(issue.code.clone()).or_insert(0usize) += 1;
        }
        counts
    };
    let (had, has) = (counts(before), counts(after));
    after
        .iter()
        .filter(|issue| has[&issue.code] > had.get(&issue.code).copied().unwrap_or(0))
        .map(|issue| {
            format!(
                "{} {} at {}: {}",
                issue.code, issue.severity, issue.pointer, issue.message
            )
        })
        .collect()
}
