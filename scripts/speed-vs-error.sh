#!/usr/bin/env bash
# speed-vs-error.sh — measures libknit's speed-against-error trade-offs on this machine and writes
# docs/speed-vs-error.md with its plots in docs/speed-vs-error/ (the one documented command):
#
#   bash scripts/speed-vs-error.sh
#
# Steps: install what is missing with apt-get (the build dependencies and gnuplot, Debian package
# gnuplot-nox), configure and build the measurement program (tools/speed_vs_error/) in Release,
# run it (all seven items, about 10-15 minutes on 2 cores; the garment items need ~10 GiB of memory),
# write the report and draw the plots. Every number in the report comes from this run; the
# machine (CPU, threads, memory, load average), the git commit (marked dirty when the tree has
# uncommitted changes) and the date are recorded in it. The docs are replaced only when
# everything succeeded.
#
# Environment: KNIT_BUILD_DIR (default: build), KNIT_JOBS (default: nproc),
#              KNIT_SVE_ITEMS (default: 6,7,1,4,2,3,5; e.g. "1,4" for a quick partial run),
#              KNIT_SVE_UPDATE=1: measure only KNIT_SVE_ITEMS and put them into the committed
#                docs/speed-vs-error/results.json (its other items, their images and the report's
#                header are kept; each item records the run that measured it). The views section
#                alone: KNIT_SVE_ITEMS=7 KNIT_SVE_UPDATE=1 bash scripts/speed-vs-error.sh
set -euo pipefail
start=$(date +%s)
root=$(cd "$(dirname "$0")/.." && pwd)
build=${KNIT_BUILD_DIR:-"$root/build"}
case "$build" in /*) ;; *) build="$root/$build" ;; esac
jobs=${KNIT_JOBS:-$(nproc)}
items=${KNIT_SVE_ITEMS:-6,7,1,4,2,3,5}
update=${KNIT_SVE_UPDATE:-0}

# Step 1: dependencies: the project's packages (scripts/setup.sh, idempotent) plus gnuplot.
extra=()
command -v gnuplot >/dev/null 2>&1 || extra+=(gnuplot-nox)  # any installed gnuplot will do
bash "$root/scripts/setup.sh" "${extra[@]}"

# Step 2: Release build of the measurement program only.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DKNIT_BUILD_TOOLS=ON >/dev/null
cmake --build "$build" --target speed_vs_error -j"$jobs"
built=$(date +%s)

# Step 3: measure into a staging folder (the docs stay untouched until everything succeeded).
stage="$build/speed-vs-error"
rm -rf "$stage"
mkdir -p "$stage/files" "$stage/speed-vs-error" "$stage/data"
base=()
command_text="bash scripts/speed-vs-error.sh"
if [ "$update" = 1 ]; then
  [ -f "$root/docs/speed-vs-error/results.json" ] || { echo "speed-vs-error: KNIT_SVE_UPDATE=1 needs docs/speed-vs-error/results.json" >&2; exit 1; }
  cp -r "$root/docs/speed-vs-error/." "$stage/speed-vs-error/"
  base=(--base "$stage/speed-vs-error/results.json")
  command_text="KNIT_SVE_ITEMS=$items KNIT_SVE_UPDATE=1 bash scripts/speed-vs-error.sh"
fi
commit=$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)
dirty=unknown
if [ "$commit" != unknown ]; then
  if [ -n "$(git -C "$root" --no-optional-locks status --porcelain 2>/dev/null)" ]; then dirty=1; else dirty=0; fi
fi
"$build/tools/speed_vs_error" measure \
  --results "$stage/speed-vs-error/results.json" --work "$stage/files" --images "$stage/speed-vs-error" \
  --items "$items" --commit "$commit" --dirty "$dirty" --date "$(date -u '+%Y-%m-%d %H:%M UTC')" \
  --command "$command_text" --nproc "$(nproc)" "${base[@]}"

# Step 4: report, plot data and plots.
"$build/tools/speed_vs_error" report --results "$stage/speed-vs-error/results.json" \
  --markdown "$stage/speed-vs-error.md" --images "$stage/speed-vs-error" --data "$stage/data"
gnuplot "$stage/data/plots.gp"

# Step 5: replace the docs.
mkdir -p "$root/docs"
rm -rf "$root/docs/speed-vs-error"
cp -r "$stage/speed-vs-error" "$root/docs/speed-vs-error"
cp "$stage/speed-vs-error.md" "$root/docs/speed-vs-error.md.tmp"
mv "$root/docs/speed-vs-error.md.tmp" "$root/docs/speed-vs-error.md"
rm -rf "$stage/files"
end=$(date +%s)
echo "speed-vs-error: wrote docs/speed-vs-error.md and docs/speed-vs-error/ (build $((built - start)) s, measure + report $((end - built)) s, total $((end - start)) s)"
