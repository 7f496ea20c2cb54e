#!/usr/bin/env bash
# One-shot GPU run: every benchmark (each registered technique and the whole frame at 1280x720 and
# 1920x1080) and the error-against-cost sweep, with an already built `caustics` binary (a GPU
# machine may have no network and no Rust toolchain: nothing is built here). Writes CSV, Markdown
# and SVG into DIR, and DIR/summary.md with both tables. Meant to finish in under 8 minutes on a
# real GPU; --quick shrinks it for a software rasteriser (lavapipe).
#
#   CAUSTICS_BIN=path/to/caustics docs/gpu-bench.sh DIR [--quick]
#   docs/gpu-bench.sh DIR [--quick] [path/to/caustics]
#
# Without CAUSTICS_BIN or a path: target/release/caustics, then `caustics` on PATH.
set -euo pipefail
usage() { echo "usage: [CAUSTICS_BIN=bin] $0 DIR [--quick] [BIN]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out=$1; shift
small=()
bin=${CAUSTICS_BIN:-}
for a in "$@"; do
  case "$a" in
    --quick) small=(--quick) ;;
    -*) usage ;;
    *) bin=$a ;;
  esac
done
if [ -z "$bin" ]; then
  here=$(cd "$(dirname "$0")/.." && pwd)
  if [ -x "$here/target/release/caustics" ]; then bin=$here/target/release/caustics
  else bin=$(command -v caustics || true); fi
fi
[ -n "$bin" ] && [ -x "$bin" ] || { echo "no caustics binary (set CAUSTICS_BIN)" >&2; exit 2; }
mkdir -p "$out"
# Mesa prints an error line without a runtime dir; give it a private one.
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
start=$(date +%s)
"$bin" bench "${small[@]}" --out "$out" | tee "$out/bench.log"
"$bin" bench --tradeoff "${small[@]}" --out "$out" | tee "$out/tradeoff.log"
# yuksel's settings against the paper's at three map sizes: time and memory.
if [ ${#small[@]} -eq 0 ]; then
  "$bin" bench --technique yuksel --technique yuksel:subsamples=1 --technique yuksel:subsamples=2 \
    --technique yuksel:split=0 --technique yuksel:preset=paper --technique yuksel-targets \
    --map-size 640x360,1280x720,1920x1080 --frames 10 --warmup 2 --no-frame --out "$out/yuksel" \
    | tee "$out/yuksel.log"
  # The whole frame with the water's normals filtered by each sample's footprint: the
  # slope moments' pyramid and the filtered shading, against the frame rows above.
  "$bin" bench --technique yuksel --filter-water --image-size 1280x720,1920x1080 --frames 10 \
    --warmup 2 --out "$out/filtered" | tee "$out/filtered.log"
fi
end=$(date +%s)
{
  echo "# caustics gpu-bench"
  echo
  echo "$("$bin" --version), $(date -u +%Y-%m-%dT%H:%MZ), $((end - start)) s in all${small:+ (--quick)}."
  echo
  echo "## Every technique and the frame"
  echo
  sed '1,2d' "$out/bench.md"
  echo
  echo "## Error against cost"
  echo
  cat "$out/tradeoff.md"
  echo
  echo "![error against cost](tradeoff.svg)"
  if [ -f "$out/yuksel/bench.md" ]; then
    echo
    echo "## yuksel's settings"
    echo
    sed '1,2d' "$out/yuksel/bench.md" | sed 's/(bench.svg)/(yuksel\/bench.svg)/'
  fi
  if [ -f "$out/filtered/bench.md" ]; then
    echo
    echo "## The frame with the water's normals filtered"
    echo
    sed '1,2d' "$out/filtered/bench.md" | sed 's/(bench.svg)/(filtered\/bench.svg)/'
  fi
} > "$out/summary.md"
echo "wrote $out/summary.md ($((end - start)) s)"
