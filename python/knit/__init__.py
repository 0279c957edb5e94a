"""libknit from Python: knitted fabric at ply level on a UV-mapped triangle mesh.

    import knit
    scene = knit.build_scene("stockinette", "drape", repeats=(8, 8), plies=2)
    yarns = scene.evaluate(new_positions)        # numpy (n, 3) in, knit.Yarns out
    knit.export_scene(scene, "plies.glb")

Arrays are numpy: outputs are read-only float64 views of the library's data (no copy), kept
alive by the object they come from; inputs may be float32 or float64. Lengths are metres.
Errors raise knit.Error with the library's message.
"""
from ._knit import (  # noqa: F401
    Binding,
    Curves,
    Error,
    Mesh,
    Pattern,
    Plies,
    Scene,
    StrainTable,
    Yarns,
    build_scene,
    builtin_charts,
    builtin_meshes,
    builtin_patterns,
    export_scene,
    frame_numbers,
    load_bound_scene,
    load_mesh,
    chart_floats,
    chart_pattern,
    load_pattern,
    load_strain_table,
    make_plies,
    remove_stale_temporaries,
    strain_table,
    strain_table_at_hand,
    spell_settings,
    save_bound_scene,
    uv_to_metre_scale,
    vertex_normals,
)

__all__ = [
    "Binding", "Curves", "Error", "Mesh", "Pattern", "Plies", "Scene", "Yarns",
    "build_scene", "builtin_meshes", "builtin_patterns", "export_scene", "frame_numbers",
    "load_bound_scene", "load_mesh", "load_pattern", "make_plies", "remove_stale_temporaries", "save_bound_scene", "uv_to_metre_scale",
    "vertex_normals",
]
