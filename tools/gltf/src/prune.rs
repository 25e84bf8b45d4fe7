//! Removing what the tool's edits left unused: the TANGENT accessors `--overwrite` replaced, the
//! attributes and indices a seam split replaced by copies, and the bufferViews and buffers only
//! they used. What the input itself left unused stays: it is not the tool's to remove.

use serde_json::Value;

use crate::document;

/// A list pruned: where the document refers to its items ([`document::pointers`]), and whether
/// the remaining items keep their order.
struct List {
    name: &'static str,
    references: &'static [&'static str],
    /// Buffers keep their order: the GLB's binary chunk is buffer 0 and the tool's new buffer
    /// the last. Accessors and bufferViews instead fill the holes with the last items, mostly
    /// the tool's new ones, so that the others keep their numbers.
    keep_order: bool,
}

/// In this order: removing an accessor can leave a bufferView unused, and that a buffer.
const LISTS: [List; 3] = [
    List {
        name: "accessors",
        references: &[
            "meshes/*/primitives/*/attributes/*",
            "meshes/*/primitives/*/indices",
            "meshes/*/primitives/*/targets/*/*",
            "skins/*/inverseBindMatrices",
            "animations/*/samplers/*/input",
            "animations/*/samplers/*/output",
            "nodes/*/extensions/EXT_mesh_gpu_instancing/attributes/*",
        ],
        keep_order: false,
    },
    List {
        name: "bufferViews",
        references: &[
            "accessors/*/bufferView",
            "accessors/*/sparse/indices/bufferView",
            "accessors/*/sparse/values/bufferView",
            "images/*/bufferView",
            "meshes/*/primitives/*/extensions/KHR_draco_mesh_compression/bufferView",
        ],
        keep_order: false,
    },
    List {
        name: "buffers",
        references: &[
            "bufferViews/*/buffer",
            "bufferViews/*/extensions/EXT_meshopt_compression/buffer",
            "bufferViews/*/extensions/KHR_meshopt_compression/buffer",
        ],
        keep_order: true,
    },
];

/// Extensions (by name or prefix) that refer to accessors, bufferViews and buffers only where
/// [`LISTS`] looks, if at all. A document using another one is not pruned: its references are
/// unknown, and renumbering would break them.
const KNOWN_EXTENSIONS: [&str; 12] = [
    "KHR_materials_",
    "KHR_texture_",
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_xmp_json_ld",
    "KHR_draco_mesh_compression",
    "EXT_mesh_gpu_instancing",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "MSFT_texture_dds",
];

/// Which accessors, bufferViews and buffers something refers to.
pub struct Used([Vec<bool>; 3]);

/// What `json` uses; `None` when it uses an extension whose references are unknown.
pub fn used(json: &Value) -> Option<Used> {
    let extensions = json["extensionsUsed"].as_array().into_iter().flatten();
    let unknown = extensions
        .filter_map(Value::as_str)
        .any(|name| !KNOWN_EXTENSIONS.iter().any(|known| name.starts_with(known)));
    if unknown {
        return None;
    }
    Some(Used(std::array::from_fn(|k| used_items(json, &LISTS[k]))))
}

fn used_items(json: &Value, list: &List) -> Vec<bool> {
    let mut used = vec![false; document::count(json, list.name)];
    for path in list.references {
        for pointer in document::pointers(json, path) {
            let index = json.pointer(&pointer).and_then(Value::as_u64);
            if let Some(slot) = index.and_then(|i| used.get_mut(usize::try_from(i).ok()?)) {
                *slot = true;
            }
        }
    }
    used
}

/// Removes the items `before` (the input's) used and nothing uses now, renumbering every
/// reference; `buffers` (the buffers' bytes) loses the removed buffers too. Returns how many
/// items were removed.
pub fn remove_unused(json: &mut Value, buffers: &mut Vec<Option<Vec<u8>>>, before: &Used) -> usize {
    let mut removed = 0;
    for (list, used_before) in LISTS.iter().zip(&before.0) {
        let used_now = used_items(json, list);
        let unused: Vec<bool> = used_now
            .iter()
            .enumerate()
            .map(|(i, &now)| !now && used_before.get(i).copied().unwrap_or(false))
            .collect();
        if !unused.contains(&true) {
            continue;
        }
        let places = new_places(&unused, list.keep_order);
        for path in list.references {
            for pointer in document::pointers(json, path) {
                let Some(value) = json.pointer_mut(&pointer) else {
                    continue;
                };
                let place = value
                    .as_u64()
                    .and_then(|i| places.get(usize::try_from(i).ok()?)?.as_ref());
                if let Some(&place) = place {
                    *value = Value::from(place);
                }
            }
        }
        if let Some(items) = json.get_mut(list.name).and_then(Value::as_array_mut) {
            *items = reorder(std::mem::take(items), &places);
        }
        if list.name == "buffers" {
            *buffers = reorder(std::mem::take(buffers), &places);
        }
        removed += unused.iter().filter(|&&u| u).count();
    }
    removed
}

/// Each item's new index (`None`: removed).
fn new_places(unused: &[bool], keep_order: bool) -> Vec<Option<usize>> {
    let kept = unused.iter().filter(|&&u| !u).count();
    let mut places = vec![None; unused.len()];
    if keep_order {
        let kept_places = places.iter_mut().zip(unused).filter(|(_, &u)| !u);
        for (next, (place, _)) in kept_places.enumerate() {
            *place = Some(next);
        }
        return places;
    }
    // Kept items below `kept` stay; the kept ones above it fill the holes below it, in order.
    let mut holes = (0..kept).filter(|&i| unused[i]);
    for (i, place) in places.iter_mut().enumerate() {
        if unused[i] {
            continue;
        }
        *place = if i < kept { Some(i) } else { holes.next() };
    }
    places
}

/// `items` at their new places, the removed ones left out.
fn reorder<T>(items: Vec<T>, places: &[Option<usize>]) -> Vec<T> {
    let mut slots: Vec<Option<T>> = std::iter::repeat_with(|| None).take(items.len()).collect();
    for (item, place) in items.into_iter().zip(places) {
        if let Some(&place) = place.as_ref() {
            slots[place] = Some(item);
        }
    }
    slots.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holes_are_filled_by_the_last_items() {
        let unused = [false, true, false, true, false, false];
        assert_eq!(
            new_places(&unused, false),
            [Some(0), None, Some(2), None, Some(1), Some(3)]
        );
        assert_eq!(
            new_places(&unused, true),
            [Some(0), None, Some(1), None, Some(2), Some(3)]
        );
        assert_eq!(
            reorder(vec!['a', 'b', 'c', 'd', 'e', 'f'], &new_places(&unused, false)),
            ['a', 'e', 'c', 'f']
        );
    }
}
