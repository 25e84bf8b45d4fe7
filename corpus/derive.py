"""The corpus files made with Blender (derived/ in corpus/MANIFEST.tsv), from two fetched files.

    blender --background --factory-startup --python corpus/derive.py -- CORPUS OUT

CORPUS holds the fetched corpus (khronos/NormalTangentTest.glb, khronos/FlightHelmet/); the files
are written to OUT/derived/. The recorded ones were made by Blender 3.4.1 (Debian bookworm's
blender 3.4.1+dfsg-2+b1) with its glTF add-on 3.4.50; scripts/fetch-corpus runs this script and
checks the hashes of what it writes.

- NormalTangentTest.blender-mikk.glb: Khronos's NormalTangentTest imported and exported again
  with the tangents Blender computes (its MikkTSpace port), so that the corpus has a file whose
  stored tangents come from that port.
- FlightHelmet.cc1.glb: every mesh of FlightHelmet subdivided once (Catmull-Clark), exported with
  its tangents: 849k vertices, for the benchmark.

Both are exported without materials or images: only the geometry and its attributes matter.
"""

import os
import sys

import bpy


def reset() -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)


def export(path: str) -> None:
    os.makedirs(os.path.dirname(path), exist_ok=True)
    bpy.ops.export_scene.gltf(
        filepath=path,
        export_format="GLB",
        export_tangents=True,
        export_materials="NONE",
        export_apply=True,
    )


def main(corpus: str, out: str) -> None:
    reset()
    bpy.ops.import_scene.gltf(filepath=os.path.join(corpus, "khronos", "NormalTangentTest.glb"))
    export(os.path.join(out, "derived", "NormalTangentTest.blender-mikk.glb"))

    reset()
    bpy.ops.import_scene.gltf(filepath=os.path.join(corpus, "khronos", "FlightHelmet", "FlightHelmet.gltf"))
    for obj in bpy.context.scene.objects:
        if obj.type == "MESH":
            subdivision = obj.modifiers.new(name="cc1", type="SUBSURF")
            subdivision.subdivision_type = "CATMULL_CLARK"
            subdivision.levels = 1
            subdivision.render_levels = 1
    export(os.path.join(out, "derived", "FlightHelmet.cc1.glb"))


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1 :]
    main(arguments[0], arguments[1])
