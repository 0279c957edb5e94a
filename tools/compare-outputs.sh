#!/usr/bin/env bash
# compare-outputs.sh — runs one fixed set of `knit` commands (every export format of the default
# scene, the shared patterns on the built-in meshes, info, generate, small renders of every mode,
# and bad input) with two builds of the CLI and compares what they wrote, byte for byte. For
# refactors that must not change behaviour:
#
#   bash tools/compare-outputs.sh OLD_KNIT NEW_KNIT [WORK_DIR]
#
# JSON reports are compared without their timing and memory fields. stdout and stderr are
# compared too (with timings masked). Exits 1 and lists the differences when any output differs.
set -uo pipefail
old=$(realpath "$1"); new=$(realpath "$2")
work=${3:-$(mktemp -d)}
root=$(cd "$(dirname "$0")/.." && pwd)
shared="$root/../shared/patterns/hylc"
mkdir -p "$work/old" "$work/new"

run_all() {  # $1 = knit binary, $2 = folder
    local k=$1 d=$2 n=0
    cd "$d" || exit 2
    run() {  # run NAME ARGS...: stdout/stderr/exit code to NAME.out
        local name=$1; shift
        { "$k" "$@" > "$name.stdout" 2> "$name.stderr"; echo "exit $?" > "$name.rc"; }
    }
    run default build -q -o default.obj --report default.json
    run glb build -q -o plies.glb --report glb.json
    run gltf build -q -o plies.gltf
    run yarns build -q --export yarns -o yarns.obj
    run tubes build -q --export tubes -o tubes.glb
    run tubesq build -q --export tubes --quantize -o tubesq.glb
    run tubesd build -q --export tubes --draco -o tubesd.glb
    run tubesobj build -q --export tubes --sides 5 -o tubes.obj
    run tubesply build -q --export tubes -o tubes.ply
    run bcc build -q -o plies.bcc
    run pbrt build -q -o plies.pbrt
    run ply build -q -o plies.ply
    run colors build -q --export tubes --yarn-colors -o colors.glb
    for p in "$shared"/*.pyp; do
        b=$(basename "$p" .pyp)
        run "cyl_$b" build -q --pattern "$p" --mesh cylinder --repeats 12 6 --plies 3 -o "cyl_$b.bcc" --report "cyl_$b.json"
        run "info_$b" info --json "$p"
    done
    run sphere build -q --mesh sphere --repeats 20.5 10 --twist Z -o sphere.bcc
    run plane build -q --mesh plane --mesh-res 7 --no-weld -o plane.obj
    run gen generate stockinette -o gen.pyp --samples 9
    for m in curves tubes grid; do
        run "render_$m" render -q --mode "$m" --spp 2 --width 48 --height 36 --output "render_$m.png" --report "render_$m.json"
    done
    run render_back render -q --light back --spp 2 --width 48 --height 36 --output render_back.png
    run bad_pattern build -q --pattern nonexistent.pyp -o bad.obj
    run bad_mesh build -q --mesh nonexistent.obj -o bad.obj
    run bad_ext build -q -o bad.xyz
    run bad_draco build -q --draco -o bad.obj
    run bad_flag build --no-such-flag
    run help_build build --help
    run help_render render --help
}

( run_all "$old" "$work/old" )
( run_all "$new" "$work/new" )

python3 - "$work" "$old" "$new" <<'PY'
import json, os, re, sys
work, old_bin, new_bin = sys.argv[1:4]
volatile = re.compile(r'(second|time|peak|memory|rays_per|per_second|Seconds|Memory|PerSecond)', re.I)
def clean(j):
    if isinstance(j, dict): return {k: clean(v) for k, v in j.items() if not volatile.search(k)}
    if isinstance(j, list): return [clean(v) for v in j]
    return j
mask = re.compile(r'\d+\.\d+ s\b|in [0-9.]+ s|"seconds":[^,}]*|"[a-z_]*(seconds|time|peak|memory)[a-z_]*":[^,}]*', re.I)
diff = []
names = sorted(set(os.listdir(f"{work}/old")) | set(os.listdir(f"{work}/new")))
for n in names:
    a, b = f"{work}/old/{n}", f"{work}/new/{n}"
    if not (os.path.exists(a) and os.path.exists(b)):
        diff.append(f"{n}: only in {'old' if os.path.exists(a) else 'new'}"); continue
    x, y = open(a, 'rb').read(), open(b, 'rb').read()
    if n.endswith('.json'):
        try: x, y = clean(json.loads(x)), clean(json.loads(y))
        except Exception: pass
    elif n.endswith(('.stdout', '.stderr')):
        def text(raw, binary):
            lines = []
            for line in raw.decode(errors='replace').replace(binary, 'knit').splitlines():
                try: lines.append(clean(json.loads(line)))   # the render summary is one JSON line
                except Exception: lines.append(mask.sub('#', line))
            return lines
        x, y = text(x, old_bin), text(y, new_bin)
    if x != y: diff.append(f"{n}: differs")
print(f"compare-outputs: {len(names)} files, {len(diff)} differ ({work})")
for d in diff: print("  " + d)
sys.exit(1 if diff else 0)
PY
