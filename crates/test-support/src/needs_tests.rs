//! What the needs say is missing: exactly what is absent, and how to get it.

use crate::needs::{missing_corpus_files, missing_programs};

#[test]
fn a_missing_program_is_named_alone_with_its_package() {
    let message = missing_programs(&[("sh", "dash"), ("tbasis-surely-absent", "tbasis-absent-package")]);
    assert_eq!(
        message.as_deref(),
        Some("tbasis-surely-absent (Debian: tbasis-absent-package)")
    );
    assert_eq!(missing_programs(&[("sh", "dash")]), None);
}

#[test]
fn the_corpus_message_names_the_absent_files_and_the_fetch_script() {
    let dir = std::env::temp_dir().join(format!("tbasis-needs-corpus-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("khronos")).unwrap();
    let files: Vec<String> = ["MANIFEST.tsv", "khronos/Fox.glb", "a.obj", "b.obj"]
        .map(String::from)
        .to_vec();
    std::fs::write(dir.join("khronos/Fox.glb"), b"glTF").unwrap();
    let message = missing_corpus_files(&dir, &files).expect("files are absent");
    assert!(
        message.contains("(MANIFEST.tsv, a.obj and 1 more absent; scripts/fetch-corpus fetches it"),
        "{message}"
    );
    // Once every file is there, nothing is missing: the need is looked for at each call.
    for file in &files {
        std::fs::write(dir.join(file), b"").unwrap();
    }
    assert_eq!(missing_corpus_files(&dir, &files), None);
    std::fs::remove_dir_all(&dir).unwrap();
}
