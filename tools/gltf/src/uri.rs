//! URIs of buffers and images: data URIs, relative file references, and rewriting a relative
//! reference for a document written to another folder.

use std::path::{Component, Path, PathBuf};

use base64::Engine;
use serde_json::Value;

/// The bytes of a `data:` URI, `None` when `uri` is not one; an error when it is one but cannot
/// be decoded.
pub fn data(uri: &str) -> Option<Result<Vec<u8>, String>> {
    let rest = uri.strip_prefix("data:")?;
    let Some((header, payload)) = rest.split_once(',') else {
        return Some(Err("a data URI without a comma".into()));
    };
    Some(if header.ends_with(";base64") {
        base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| format!("a data URI that is not valid base64: {e}"))
    } else {
        Ok(decode_percent(payload))
    })
}

/// A `data:` URI holding `bytes`.
pub fn encode_data(bytes: &[u8]) -> String {
    let payload = base64::engine::general_purpose::STANDARD.encode(bytes);
    format!("data:application/octet-stream;base64,{payload}")
}

/// Whether `uri` is a relative reference to a file (no scheme such as `data:` or `https:`).
pub fn is_relative_file(uri: &str) -> bool {
    let scheme_end = uri.find(':');
    let path_start = uri.find(['/', '?', '#']).unwrap_or(uri.len());
    match scheme_end {
        // "C:/x" is no URI; a colon after the first slash belongs to the path.
        Some(colon) => colon > path_start,
        None => true,
    }
}

/// Whether the tool can read `uri` at all: a `data:` URI or a relative path (what
/// [`crate::buffers::load`] reads; any other scheme it refuses).
pub fn readable(uri: &str) -> bool {
    uri.starts_with("data:") || is_relative_file(uri)
}

/// Every buffer and image URI of a document: (`buffer` or `image`, its index, the URI).
pub fn document_uris(json: &Value) -> impl Iterator<Item = (&'static str, usize, &str)> {
    [("buffers", "buffer"), ("images", "image")]
        .into_iter()
        .flat_map(move |(list, singular)| {
            json[list]
                .as_array()
                .into_iter()
                .flatten()
                .enumerate()
                .filter_map(move |(index, item)| Some((singular, index, item["uri"].as_str()?)))
        })
}

/// How `uri`, met in a document in folder `dir`, leads out of that folder (`it is an absolute
/// path`), or `None` when it stays inside: a `data:` URI, or a relative path to a file in `dir`
/// or below it, links followed.
pub fn outside(dir: &Path, uri: &str) -> Option<&'static str> {
    if uri.starts_with("data:") {
        return None;
    }
    if !is_relative_file(uri) {
        return Some("has a scheme other than data:");
    }
    let path = decoded_path(uri);
    // `//host/x` (a network path) has a root; `C:/x` on Windows, a prefix.
    if path.has_root() || path.components().any(|c| matches!(c, Component::Prefix(_))) {
        return Some("is an absolute path");
    }
    // What `resolve` reads: `..` resolved without the file system.
    let relative = normalize(&path);
    if relative.starts_with("..") {
        return Some("climbs out with ..");
    }
    // A link inside the folder may still lead out; what does not exist is read from nowhere.
    let (Ok(dir), Ok(file)) = (dir.canonicalize(), dir.join(&relative).canonicalize()) else {
        return None;
    };
    (!file.starts_with(dir)).then_some("goes through a link")
}

/// The file a relative reference names, against the folder of its document.
pub fn resolve(dir: &Path, uri: &str) -> PathBuf {
    normalize(&dir.join(decoded_path(uri)))
}

/// The reference that names, from a document in `to_dir`, the file `uri` names from a document in
/// `from_dir`: both folders must be absolute (canonical), and the result uses `/` and escapes
/// what a URI cannot hold. `None` when no relative path leads there (another drive).
pub fn rebase(uri: &str, from_dir: &Path, to_dir: &Path) -> Option<String> {
    let target = normalize(&from_dir.join(decoded_path(uri)));
    let relative = relative_path(to_dir, &target)?;
    let parts: Vec<String> = relative
        .components()
        .map(|c| match c {
            Component::ParentDir => "..".to_string(),
            other => encode_segment(&other.as_os_str().to_string_lossy()),
        })
        .collect();
    Some(parts.join("/"))
}

/// The path part of a relative reference, percent-decoded (UTF-8 where it decodes as such).
fn decoded_path(uri: &str) -> PathBuf {
    let path = uri.split(['?', '#']).next().unwrap_or(uri);
    PathBuf::from(String::from_utf8_lossy(&decode_percent(path)).into_owned())
}

/// `%XX` escapes decoded; a `%` not followed by two hex digits stays as it is.
fn decode_percent(text: &str) -> Vec<u8> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            if let (Some(hi), Some(lo)) = (hex(bytes[i + 1]), hex(bytes[i + 2])) {
                out.push((hi * 16 + lo) as u8);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    out
}

/// One path segment, with everything but unreserved and a few safe characters escaped.
pub fn encode_segment(segment: &str) -> String {
    let mut out = String::with_capacity(segment.len());
    for &b in segment.as_bytes() {
        if b.is_ascii_alphanumeric() || b"-._~!$&'()*+,;=@".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// `path` with `.` and `..` resolved without asking the file system (the file may not exist).
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// The path from folder `from` to `to`, both absolute and normalized.
fn relative_path(from: &Path, to: &Path) -> Option<PathBuf> {
    let from: Vec<Component> = from.components().collect();
    let to: Vec<Component> = to.components().collect();
    // Different roots (drives) have no relative path.
    if from.first() != to.first() {
        return None;
    }
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..from.len() {
        out.push("..");
    }
    for component in &to[common..] {
        out.push(component);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_references() {
        assert!(is_relative_file("a b.bin"));
        assert!(is_relative_file("../x/y.png"));
        assert!(is_relative_file("dir/a:b.png"));
        assert!(!is_relative_file("data:application/octet-stream;base64,AAAA"));
        assert!(!is_relative_file("https://example.com/a.bin"));
    }

    #[test]
    fn rebasing_escapes_and_climbs() {
        let from = Path::new("/m/in");
        assert_eq!(
            rebase("a%20b.bin", from, Path::new("/m/out")).unwrap(),
            "../in/a%20b.bin"
        );
        assert_eq!(rebase("tex/n.png", from, Path::new("/m/in")).unwrap(), "tex/n.png");
        assert_eq!(
            rebase("../t/n.png", from, Path::new("/m/out/deep")).unwrap(),
            "../../t/n.png"
        );
        assert_eq!(rebase("x#frag", from, Path::new("/")).unwrap(), "m/in/x");
    }

    #[test]
    fn uris_leading_out_of_the_folder() {
        let dir = Path::new("/m/in");
        assert_eq!(outside(dir, "data:application/octet-stream;base64,AAAA"), None);
        assert_eq!(outside(dir, "a.bin"), None);
        assert_eq!(outside(dir, "sub/../a%20b.bin"), None);
        assert_eq!(outside(dir, "/etc/passwd"), Some("is an absolute path"));
        assert_eq!(outside(dir, "//host/share/x.bin"), Some("is an absolute path"));
        assert_eq!(outside(dir, "../x.bin"), Some("climbs out with .."));
        assert_eq!(outside(dir, "sub/../../x.bin"), Some("climbs out with .."));
        assert_eq!(outside(dir, "%2E%2E/x.bin"), Some("climbs out with .."));
        assert!(outside(dir, "file:///etc/passwd").is_some());
        assert!(outside(dir, "https://example.com/a.bin").is_some());
    }

    #[test]
    fn data_uris() {
        assert_eq!(
            data("data:application/octet-stream;base64,AAEC").unwrap().unwrap(),
            [0, 1, 2]
        );
        assert_eq!(data(&encode_data(&[9, 8, 7, 6])).unwrap().unwrap(), [9, 8, 7, 6]);
        assert!(data("data:;base64,@@").unwrap().is_err());
        assert!(data("x.bin").is_none());
    }
}
