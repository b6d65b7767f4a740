#!/usr/bin/env bash
# Installs what is missing, builds tetrender and renders the built-in demo (DIR/demo.png,
# the demo mesh as DIR/demo.vtu, its flow volume as DIR/demo_flowvol.png, and the flow fused
# with a heat plume on its own grid as DIR/demo_fused.png).
# Usage: scripts/demo.sh [-o DIR]   (outputs go to DIR, default out/)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh
out=out
while [ $# -gt 0 ]; do
  case "$1" in
    -o) out="$2"; shift ;;
    -h|--help) sed -n '2,5p' "$0"; exit 0 ;;
    *) echo "demo.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done
ensure_packages
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target tetrender
mkdir -p "$out"
build/apps/tetrender demo -o "$out/demo.png" --mesh-out "$out/demo.vtu"
build/apps/tetrender demo --flowvol -o "$out/demo_flowvol.png"
build/apps/tetrender demo --fused -o "$out/demo_fused.png"
