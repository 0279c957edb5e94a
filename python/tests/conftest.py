# Makes build/python importable when pytest runs without PYTHONPATH (ctest sets it).
import os
import sys

_build = os.environ.get("KNIT_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
sys.path.insert(0, os.path.abspath(os.path.join(_build, "python")))
