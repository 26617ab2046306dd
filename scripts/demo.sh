#!/usr/bin/env bash
# Builds everything (installing missing Debian packages) and runs lafit on the bundled
# samples: a pen-drawn question mark and a scanned airfoil profile. Results in out/.
# The independent checker of the shared curve format runs too when ../shared is there.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
./build/app/lafit fit samples/question_mark.csv -o out/question_mark.json --svg out/question_mark.svg --comb \
  --csv out/question_mark.csv --dxf out/question_mark.dxf
./build/app/lafit fit samples/clark-y.dat -o out/clark-y.json --svg out/clark-y.svg --comb --y-up
if [ -f ../shared/tools/lacheck.py ]; then
  /usr/bin/python3 ../shared/tools/lacheck.py out/question_mark.json samples/question_mark.csv
fi
