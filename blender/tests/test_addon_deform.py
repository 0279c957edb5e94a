"""Headless test of Apply Knit's Deform choice (run by ctest as blender_addon_deform: blender -b
--factory-startup --python-exit-code 1 --python ...). Apart from test_addon.py because it makes
the default pattern's strain table (about 25 s of CPU), which under a loaded machine took the
whole add-on test past its timeout."""
import os
import sys
import tempfile

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import knit_blender  # noqa: E402
from addon_scene import check, make_animated_grid, points_of  # noqa: E402
from knit_blender import build  # noqa: E402


def check_deform():
    """Apply Knit's Deform choice: strain-aware yarns are the geometric ones where the surface is
    not strained (frame 1, flat, at the pattern's own shape) and move where the bulge stretches it
    (frame 10)."""
    os.environ["KNIT_CACHE_DIR"] = tempfile.mkdtemp()  # the table is made here on first use
    cloth = bpy.data.objects["Cloth"]
    pattern = build.knit_module().load_pattern("stockinette")
    repeats = (6.0, 6.0 * pattern.px / pattern.py)  # the flat square grid at the pattern's own shape
    points = {}
    for deform in ("strain", "auto", "none"):
        bpy.context.scene.frame_set(1)
        bpy.ops.object.select_all(action="DESELECT")
        bpy.context.view_layer.objects.active = cloth
        result = bpy.ops.object.knit_apply(pattern="stockinette", repeats=repeats, plies=2, deform=deform)
        check(result == {"FINISHED"}, f"knit_apply with Deform {deform} finished")
        obj = bpy.data.objects["Cloth.knit"]
        flat = points_of(obj)
        bpy.context.scene.frame_set(10)
        points[deform] = (flat, points_of(obj))
    flat = float(np.abs(points["strain"][0] - points["none"][0]).max())  # float32 round-off strains only
    check(flat < 1e-6, f"Deform strain on the flat frame: the geometric yarns ({flat:.2e} m apart)")
    moved = float(np.abs(points["strain"][1] - points["none"][1]).max())
    check(moved > 1e-4, f"Deform strain on the bulged frame moves the yarns ({moved:.2e} m)")
    check(any(f.startswith("strain-") for f in os.listdir(os.environ["KNIT_CACHE_DIR"])), "the table was cached")
    # Automatic, the default, is strain-aware for the default pattern (its table is made in seconds).
    check(bpy.ops.object.knit_apply.get_rna_type().properties["deform"].default == "auto", "Deform defaults to Automatic")
    same = all(np.array_equal(a, b) for a, b in zip(points["auto"], points["strain"]))
    check(same, "Deform Automatic gives the strain-aware yarns for the default pattern")


knit_blender.register()
make_animated_grid()
check_deform()
print("knit_blender deform: all checks passed")
