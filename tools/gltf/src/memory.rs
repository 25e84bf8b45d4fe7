//! Fallible allocation: a file's counts decide how much memory its primitives need, and a count
//! the machine cannot hold fails that file with a message instead of aborting the whole run.

use std::mem::size_of;

/// `len` copies of `value`, or what is missing for `what`.
pub fn filled<T: Clone>(len: usize, value: T, what: &str) -> Result<Vec<T>, String> {
    let mut vec = Vec::new();
    vec.try_reserve_exact(len)
        .map_err(|_| out_of_memory(len, size_of::<T>(), what))?;
    vec.resize(len, value);
    Ok(vec)
}

/// `vec` grown or cut to `len` elements, new ones `value`; on failure, `vec` as it was. Grows
/// as `Vec` does (room to spare), so that growing by small steps stays linear.
pub fn resize<T: Clone>(vec: &mut Vec<T>, len: usize, value: T, what: &str) -> Result<(), String> {
    vec.try_reserve(len.saturating_sub(vec.len()))
        .map_err(|_| out_of_memory(len, size_of::<T>(), what))?;
    vec.resize(len, value);
    Ok(())
}

/// The `len` items of `items`, room for them reserved first.
pub fn collect<T>(len: usize, items: impl Iterator<Item = T>, what: &str) -> Result<Vec<T>, String> {
    let mut vec = Vec::new();
    vec.try_reserve_exact(len)
        .map_err(|_| out_of_memory(len, size_of::<T>(), what))?;
    vec.extend(items);
    Ok(vec)
}

fn out_of_memory(len: usize, size: usize, what: &str) -> String {
    let bytes = len.saturating_mul(size);
    format!("{what}: not enough memory for {len} elements ({bytes} bytes)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_that_is_not_there_is_an_error_and_leaves_the_vector_as_it_was() {
        let mut vec = vec![1u64, 2];
        let error = resize(&mut vec, usize::MAX / 8, 0, "corners").unwrap_err();
        assert!(error.starts_with("corners: not enough memory for"), "{error}");
        assert_eq!(vec, [1, 2]);
        assert!(filled(usize::MAX / 2, 0u32, "tangents").is_err());
        assert!(collect(usize::MAX / 4, core::iter::empty::<u32>(), "indices").is_err());
        assert_eq!(filled(3, 7u8, "bytes").unwrap(), [7, 7, 7]);
        assert_eq!(collect(2, [4u16, 5].into_iter(), "indices").unwrap(), [4, 5]);
    }
}
