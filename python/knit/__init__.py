"""libknit from Python: knitted fabric at ply level on a UV-mapped triangle mesh.

    import knit
    scene = knit.build_scene("stockinette", "drape", repeats=(8, 8), plies=2)
    yarns = scene.evaluate(new_positions)        # numpy (n, 3) in, knit.Yarns out
    knit.export_scene(scene, "plies.glb")

Arrays are numpy: outputs are read-only float64 views of the library's data (no copy), kept
alive by the object they come from; inputs may be float32 or float64. Lengths are metres.
Errors raise knit.Error with the library's message. A chart that builds but deserves a
designer's second look (a float longer than max_float stitches, an intarsia repeat knitted
taller than drawn) warns with knit.ChartWarning (the warnings module), in the library's words.
"""
import warnings as _warnings

from . import _knit
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
    builtin_charts,
    builtin_meshes,
    builtin_patterns,
    export_scene,
    frame_numbers,
    load_bound_scene,
    load_mesh,
    chart_floats,
    chart_text,
    chart_warnings,
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



class ChartWarning(UserWarning):
    """A designer's warning on a chart that builds, as `knit chart` prints it: a float longer than
    max_float stitches ("NAME:LINE: row R: the float ..."), or an intarsia chart whose colour
    areas wander round the period, knitted N rows tall ("NAME: intarsia: ..."). Make them errors
    with warnings.simplefilter("error", knit.ChartWarning): they are raised before the relaxation."""


def _warn_chart(text, name, max_float, stacklevel=3):
    for message in chart_warnings(text, name=name, max_float=max_float):
        _warnings.warn(message, ChartWarning, stacklevel=stacklevel)


def _warn_chart_named(file_or_name, max_float):
    """Warns for a chart file or chart:NAME (nothing for other patterns), pointing at the caller of
    the caller (load_pattern's, build_scene's)."""
    text = chart_text(file_or_name)
    if text is not None:
        _warn_chart(text, file_or_name, max_float, stacklevel=4)


def chart_pattern(text, name="<chart text>", yarn_radius=0.001, max_float=5):
    """A stitch chart given as text (docs/charts.md) relaxed into a Pattern, cached like chart
    files; warns with knit.ChartWarning first (chart_warnings). A chart file or chart:NAME goes to
    load_pattern. Raises knit.Error naming NAME:LINE:COLUMN."""
    _warn_chart(text, name, max_float)
    return _knit.chart_pattern(text, name=name, yarn_radius=yarn_radius)


def load_pattern(file_or_name, max_float=5):
    """Loads a pattern: a .pyp / .json file, a chart (.chart / .txt file or chart:NAME, relaxed
    and cached, warning with knit.ChartWarning as chart_pattern) or a built-in name
    (builtin_patterns()). Raises knit.Error."""
    _warn_chart_named(file_or_name, max_float)
    return _knit.load_pattern(file_or_name)


def build_scene(pattern="stockinette", mesh="drape", *args, max_float=5, **kwargs):
    if isinstance(pattern, str):  # a chart file or chart:NAME warns as load_pattern, before relaxing
        _warn_chart_named(pattern, max_float)
    return _knit.build_scene(pattern, mesh, *args, **kwargs)


build_scene.__doc__ = (_knit.build_scene.__doc__ or "") + (
    "\n\nA chart file or chart:NAME as pattern warns with knit.ChartWarning first, as load_pattern "
    "(max_float: the float limit in stitches).")


__all__ = [
    "Binding", "ChartWarning", "Curves", "Error", "Mesh", "Pattern", "Plies", "Scene", "Yarns",
    "build_scene", "builtin_charts", "builtin_meshes", "chart_floats", "chart_pattern", "chart_text", "chart_warnings", "builtin_patterns", "export_scene", "frame_numbers",
    "load_bound_scene", "load_mesh", "load_pattern", "make_plies", "remove_stale_temporaries", "save_bound_scene", "uv_to_metre_scale",
    "vertex_normals",
]
