#!/usr/bin/env bash
# Builds everything (installing missing Debian packages) and runs lafit on the bundled
# sample, then checks the result with the independent checker when shared/ is beside us.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
./build/app/lafit segment --alpha -0.5 0,0 4,0 5.5,3 -o out/segment.json --svg out/segment.svg --comb --csv out/segment.csv --dxf out/segment.dxf
if [ -f ../shared/tools/lacheck.py ]; then
  /usr/bin/python3 ../shared/tools/lacheck.py out/segment.json
fi
