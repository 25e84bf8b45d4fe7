//! The Khronos glTF Validator (npm `gltf-validator`), through `tests/validate.js`.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

use super::needs;

/// One error (severity 0) or warning (1).
#[derive(Clone, Debug)]
pub struct Issue {
    pub code: String,
    pub severity: u64,
    pub pointer: String,
    pub message: String,
}

/// The errors and warnings the validator reports for `file`.
pub fn issues(file: &Path) -> Vec<Issue> {
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

/// The codes among `issues`.
pub fn codes(issues: &[Issue]) -> BTreeSet<String> {
    issues.iter().map(|i| i.code.clone()).collect()
}
