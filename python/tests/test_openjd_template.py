# docs/openjd/knit-bake.yaml, the farm job template of docs/scale-out.md, checked two ways:
#  1. its structure against the Open Job Description 2023-09 job template schema (the rules below
#     are the schema's required fields, allowed keys, enumerations and references, from the
#     specification's "Template Schemas [Version: 2023-09]": sections 1.1 job template, 2 job
#     parameter definitions, 3 step template, 3.4 parameter space and <IntRangeExpr>, 5 action,
#     6 embedded file, 7.1 identifiers, 7.3 format strings); no OpenJD tool is packaged in Debian,
#     so the test implements these rules itself;
#  2. its steps run as a farm would run them: the job parameters and each task's parameters
#     substituted into the format strings, the embedded files written (runnable ones executable)
#     into a session folder, the Bake tasks (2 chunks) in reverse order; the merged cache equals a
#     single `knit animate` run byte for byte.
import itertools
import os
import re
import stat
import subprocess

import pytest

yaml = pytest.importorskip("yaml")  # Debian: python3-yaml

from test_animation import knit_cli  # noqa: E402
from test_distributed import read, write_wave  # noqa: E402

KNIT = knit_cli()
TEMPLATE = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "openjd", "knit-bake.yaml")
IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")  # 7.1
REFERENCE = re.compile(r"{{\s*([A-Za-z_][A-Za-z0-9_.]*)\s*}}")  # 7.3: {{ Name.Of.Value }}


def load():
    with open(TEMPLATE) as f:
        return yaml.safe_load(f)


def format_strings(node):
    """Every string in a template subtree (the places format strings can appear)."""
    if isinstance(node, str):
        yield node
    elif isinstance(node, dict):
        for v in node.values():
            yield from format_strings(v)
    elif isinstance(node, list):
        for v in node:
            yield from format_strings(v)


def check_keys(obj, where, required, optional=()):
    assert isinstance(obj, dict), "%s: not an object" % where
    missing = [k for k in required if k not in obj]
    assert not missing, "%s: required %s missing" % (where, missing)
    extra = set(obj) - set(required) - set(optional)
    assert not extra, "%s: keys %s are not in the schema" % (where, sorted(extra))


def check_parameter(p, where):
    """2.1-2.4: STRING, PATH, INT and FLOAT job parameters."""
    common = ("description", "default", "allowedValues", "userInterface")
    by_type = {
        "STRING": common + ("minLength", "maxLength"),
        "PATH": common + ("minLength", "maxLength", "objectType", "dataFlow"),
        "INT": common + ("minValue", "maxValue"),
        "FLOAT": common + ("minValue", "maxValue"),
    }
    assert p.get("type") in by_type, "%s: type %r" % (where, p.get("type"))
    check_keys(p, where, ("name", "type"), by_type[p["type"]])
    assert IDENTIFIER.match(p["name"]), where
    if p["type"] == "PATH":
        assert p.get("objectType", "FILE") in ("FILE", "DIRECTORY"), where
        assert p.get("dataFlow", "NONE") in ("NONE", "IN", "OUT", "INOUT"), where
    if p["type"] == "INT" and "default" in p:
        assert isinstance(p["default"], int), where
        assert p.get("minValue", p["default"]) <= p["default"] <= p.get("maxValue", p["default"]), where
    if p["type"] in ("STRING", "PATH") and "default" in p:
        assert isinstance(p["default"], str) and len(p["default"]) <= 1024, where


def check_script(script, where):
    """3.5 step script: actions.onRun (an <Action>, 5) and embedded files (6)."""
    check_keys(script, where, ("actions",), ("embeddedFiles",))
    check_keys(script["actions"], where + ".actions", ("onRun",))
    check_keys(script["actions"]["onRun"], where + ".onRun", ("command",), ("args", "timeout", "cancelation"))
    files = script.get("embeddedFiles", [])
    assert files != [], where + ": embeddedFiles, if given, is not empty"
    for f in files:
        check_keys(f, where + ".embeddedFiles", ("name", "type", "data"), ("filename", "runnable"))
        assert IDENTIFIER.match(f["name"]) and f["type"] == "TEXT", where
        assert isinstance(f.get("runnable", False), bool), where
    assert len({f["name"] for f in files}) == len(files), where + ": embedded file names repeat"
    return {f["name"] for f in files}


def check_references(node, where, scope):
    for s in format_strings(node):
        for name in REFERENCE.findall(s):
            assert name in scope, "%s: {{%s}} names nothing defined here" % (where, name)


def test_the_template_follows_the_openjd_2023_09_job_template_schema():
    t = load()
    # 1.1 the job template.
    check_keys(t, "template", ("specificationVersion", "name", "steps"),
               ("$schema", "extensions", "description", "parameterDefinitions", "jobEnvironments"))
    assert t["specificationVersion"] == "jobtemplate-2023-09"
    params = t.get("parameterDefinitions", [])
    assert 1 <= len(params) <= 50
    for i, p in enumerate(params):
        check_parameter(p, "parameterDefinitions[%d]" % i)
    names = [p["name"] for p in params]
    assert len(set(names)) == len(names), "job parameter names repeat"
    job_scope = {"Param." + n for n in names} | {"RawParam." + n for n in names} | {"Session.WorkingDirectory"}
    check_references(t["name"], "name", job_scope)
    # 3 the steps: unique names, known keys, dependencies on other steps and no cycle.
    steps = t["steps"]
    assert steps, "a job has steps"
    step_names = [s.get("name") for s in steps]
    assert len(set(step_names)) == len(step_names), "step names repeat"
    for s in steps:
        where = "step %r" % s.get("name")
        check_keys(s, where, ("name", "script"),
                   ("description", "dependencies", "stepEnvironments", "hostRequirements", "parameterSpace"))
        assert 1 <= len(s["name"]) <= 64, where
        for d in s.get("dependencies", []):
            check_keys(d, where + ".dependencies", ("dependsOn",))
            assert d["dependsOn"] in step_names and d["dependsOn"] != s["name"], where
        scope = set(job_scope)
        if "parameterSpace" in s:  # 3.4
            space = s["parameterSpace"]
            check_keys(space, where + ".parameterSpace", ("taskParameterDefinitions",), ("combination",))
            assert 1 <= len(space["taskParameterDefinitions"]) <= 16, where
            for tp in space["taskParameterDefinitions"]:
                check_keys(tp, where + " task parameter", ("name", "type", "range"))
                assert IDENTIFIER.match(tp["name"]) and tp["type"] in ("INT", "FLOAT", "STRING", "PATH"), where
                check_references(tp["range"], where + " range", job_scope)  # resolved at submission
                scope |= {"Task.Param." + tp["name"], "Task.RawParam." + tp["name"]}
        files = check_script(s["script"], where + ".script")
        scope |= {"Task.File." + f for f in files}
        check_references(s["script"], where + ".script", scope)
    order = run_order(steps)  # raises on a cycle
    assert order[0]["name"] == "Bind" and order[-1]["name"] == "Merge"


def run_order(steps):
    """The steps with every one after the steps it depends on."""
    done, order = set(), []
    while len(order) < len(steps):
        ready = [s for s in steps
                 if s["name"] not in done and all(d["dependsOn"] in done for d in s.get("dependencies", []))]
        assert ready, "the step dependencies form a cycle"
        for s in ready:
            done.add(s["name"])
            order.append(s)
    return order


def int_range(expr):
    """3.4.1.1.1 <IntRangeExpr>: '1-12:6' -> [1, 7] (elements, ranges, ranges with a skip)."""
    values = []
    for element in expr.split(","):
        m = re.fullmatch(r"\s*(-?\d+)\s*(?:-\s*(-?\d+)\s*(?::\s*(-?\d+))?)?\s*", element)
        assert m, "not an <IntRangeExpr>: %r" % expr
        a = int(m.group(1))
        b = int(m.group(2)) if m.group(2) is not None else a
        n = int(m.group(3)) if m.group(3) is not None else 1
        assert n != 0
        values += list(range(a, b + (1 if n > 0 else -1), n)) or [a]
    assert len(set(values)) == len(values), "ranges overlap"
    return sorted(values)


def resolve(text, values):
    def value(m):
        assert m.group(1) in values, "{{%s}} has no value" % m.group(1)
        return str(values[m.group(1)])
    return REFERENCE.sub(value, text)


@pytest.mark.skipif(KNIT is None, reason="the knit command line is not built")
def test_the_template_run_as_a_farm_runs_it_equals_one_knit_animate(tmp_path):
    frames = tmp_path / "sim"
    frames.mkdir()
    for k in range(1, 13):
        write_wave(frames / ("frame_%04d.obj" % k), k, 8)
    job = {
        "RestMesh": str(frames / "frame_0001.obj"),
        "BindArgs": "--repeats 4 4",
        "BoundFile": str(tmp_path / "g.knitbind"),
        "Frames": str(frames / "frame_%04d.obj"),
        "FirstFrame": 1,
        "LastFrame": 12,
        "ChunkSize": 6,
        "ChunkDir": str(tmp_path / "chunks"),
        "Output": str(tmp_path / "out" / "g.pc2"),
        "Knit": KNIT,
    }
    os.makedirs(job["ChunkDir"])
    os.makedirs(os.path.dirname(job["Output"]))
    t = load()
    values = {}
    for p in t["parameterDefinitions"]:
        v = job.get(p["name"], p.get("default"))
        values["Param." + p["name"]] = values["RawParam." + p["name"]] = v
    ran = []
    for step in run_order(t["steps"]):
        tasks = [{}]
        if "parameterSpace" in step:
            axes = [[(tp["name"], v) for v in int_range(resolve(tp["range"], values))]
                    for tp in step["parameterSpace"]["taskParameterDefinitions"]]
            tasks = [dict(c) for c in itertools.product(*axes)]
        for task in reversed(tasks):  # any order: here the last chunk first
            session = tmp_path / ("session_%s_%d" % (step["name"], len(ran)))
            session.mkdir()
            scope = dict(values)
            for name, v in task.items():
                scope["Task.Param." + name] = scope["Task.RawParam." + name] = v
            for f in step["script"].get("embeddedFiles", []):
                path = session / f.get("filename", "embedded_" + f["name"])
                scope["Task.File." + f["name"]] = str(path)
            for f in step["script"].get("embeddedFiles", []):
                path = scope["Task.File." + f["name"]]
                with open(path, "w") as out:
                    out.write(resolve(f["data"], scope))
                mode = stat.S_IRUSR | (stat.S_IXUSR if f.get("runnable") else 0)
                os.chmod(path, mode)
            action = step["script"]["actions"]["onRun"]
            argv = [resolve(action["command"], scope)] + [resolve(a, scope) for a in action.get("args", [])]
            proc = subprocess.run(argv, cwd=session, capture_output=True, text=True, timeout=120)
            assert proc.returncode == 0, "%s %s: %s" % (step["name"], task, proc.stderr)
            ran.append((step["name"], task))
    assert [r[0] for r in ran] == ["Bind", "Bake", "Bake", "Merge"]
    assert sorted(os.listdir(job["ChunkDir"])) == ["chunk_00000001_00000006.obj", "chunk_00000001_00000006.pc2",
                                                    "chunk_00000007_00000012.obj", "chunk_00000007_00000012.pc2"]
    # The default deformation on both sides: `knit bind` decides it as `knit animate` does and the
    # bound file carries it (with the strain table), so the farm's frames are the single run's.
    single = subprocess.run([KNIT, "animate", "-q", "--frames", job["Frames"], "--repeats", "4", "4",
                             "-o", str(tmp_path / "one.pc2")], capture_output=True, text=True, timeout=120)
    assert single.returncode == 0, single.stderr
    assert read(job["Output"]) == read(tmp_path / "one.pc2")
    assert read(job["Output"][:-4] + ".obj") == read(tmp_path / "one.obj")
