//! The output guarantees of every policy but LEGACY, checked in one place for every test suite.
//!
//! Per vertex: the tangent is finite and unit length, orthogonal to the normal the library uses
//! (the input normal scaled to unit length, when that normal is finite and nonzero), `w` is exactly
//! +1 or -1, and the bitangent, when asked for, is `w * cross(n, t)`. Arithmetic is in f64 so the
//! checker adds no rounding of its own, and huge or subnormal normals normalize exactly.

use glam::DVec3;

/// Largest accepted deviation of a length from 1, of a dot product from 0, and of a bitangent
/// from `w * cross(n, t)` (Euclidean distance).
pub const TOLERANCE: f64 = 1e-5;

/// The normal scaled to unit length, or `None` when it is zero or has a non-finite component
/// (the library then has no normal to be orthogonal to).
pub fn unit_normal(normal: [f32; 3]) -> Option<[f64; 3]> {
    let n = normal.map(f64::from);
    if !n.iter().all(|x| x.is_finite()) {
        return None;
    }
    let length = dot(n, n).sqrt();
    (length > 0.0).then(|| n.map(|x| x / length))
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    DVec3::from(a).dot(DVec3::from(b))
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    DVec3::from(a).cross(DVec3::from(b)).to_array()
}

fn xyz(v: [f32; 4]) -> [f64; 3] {
    [v[0], v[1], v[2]].map(f64::from)
}

/// Checks one vertex: its input normal, the tangent written for it, and the bitangent if any.
pub fn check_frame(normal: [f32; 3], tangent: [f32; 4], bitangent: Option<[f32; 3]>) -> Result<(), String> {
    if !tangent.iter().all(|x| x.is_finite()) {
        return Err(format!("tangent {tangent:?} is not finite"));
    }
    let w = tangent[3];
    if w != 1.0 && w != -1.0 {
        return Err(format!("handedness w = {w:e} is not exactly +1 or -1"));
    }
    let t = xyz(tangent);
    let length = dot(t, t).sqrt();
    if (length - 1.0).abs() > TOLERANCE {
        return Err(format!("tangent {tangent:?} has length {length}"));
    }
    let n = unit_normal(normal);
    if let Some(n) = n {
        let along = dot(t, n);
        if along.abs() > TOLERANCE {
            return Err(format!(
                "tangent {tangent:?} is not orthogonal to normal {normal:?}: dot = {along:e}"
            ));
        }
    }
    let Some(bitangent) = bitangent else {
        return Ok(());
    };
    if !bitangent.iter().all(|x| x.is_finite()) {
        return Err(format!("bitangent {bitangent:?} is not finite"));
    }
    let b = bitangent.map(f64::from);
    match n {
        Some(n) => {
            let expected = cross(n, t).map(|x| x * f64::from(w));
            let miss = [b[0] - expected[0], b[1] - expected[1], b[2] - expected[2]];
            let distance = dot(miss, miss).sqrt();
            if distance > TOLERANCE {
                return Err(format!(
                    "bitangent {bitangent:?} differs from w * cross(n, t) = {expected:?} by {distance:e}"
                ));
            }
        }
        // No usable normal: the bitangent must still complete a frame with the tangent.
        None => {
            let length = dot(b, b).sqrt();
            let along = dot(b, t);
            if (length - 1.0).abs() > TOLERANCE || along.abs() > TOLERANCE {
                return Err(format!(
                    "bitangent {bitangent:?} (no usable normal) has length {length} and dot {along:e} with the tangent"
                ));
            }
        }
    }
    Ok(())
}

/// Checks every vertex; the error names the first few failing vertices and how many failed.
pub fn check_invariants(
    normals: &[[f32; 3]],
    tangents: &[[f32; 4]],
    bitangents: Option<&[[f32; 3]]>,
) -> Result<(), String> {
    if tangents.len() != normals.len() || bitangents.is_some_and(|b| b.len() != normals.len()) {
        return Err(format!(
            "lengths differ: {} normals, {} tangents, {:?} bitangents",
            normals.len(),
            tangents.len(),
            bitangents.map(<[_]>::len)
        ));
    }
    let mut failures = Vec::new();
    let mut failed = 0usize;
    for (v, (&normal, &tangent)) in normals.iter().zip(tangents).enumerate() {
        if let Err(e) = check_frame(normal, tangent, bitangents.map(|b| b[v])) {
            failed += 1;
            if failures.len() < 5 {
                failures.push(format!("vertex {v}: {e}"));
            }
        }
    }
    if failed == 0 {
        Ok(())
    } else {
        Err(format!(
            "{failed} of {} vertices break the invariants; {}",
            normals.len(),
            failures.join("; ")
        ))
    }
}
