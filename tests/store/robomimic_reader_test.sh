#!/usr/bin/env bash
# Records a small tabletop session with the real CLI, exports it, and reads both the export and
# the session's own index file with robomimic_reader_check.py (h5py, as robomimic reads), from
# another working directory so the index's external links must resolve on their own.
set -euo pipefail
recon="$1"
check="$(cd "$(dirname "$0")" && pwd)/robomimic_reader_check.py"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$recon" record --session "$work/s" --world tabletop --layout wide --image-size 32 --demos 3 --play 10 \
  --seed 2 --no-calibration >/dev/null 2>&1
"$recon" session mark "$work/s" demo_2 --split valid >/dev/null
"$recon" session mark "$work/s" demo_1 --bad >/dev/null
"$recon" session export "$work/s" --out "$work/export.hdf5" >/dev/null
cd /
out=$(/usr/bin/python3 "$check" "$work/export.hdf5" --require-next-obs)
echo "$out"
grep -q "2 demos" <<<"$out" || { echo "expected the 2 good demonstrations" >&2; exit 1; }
grep -q "'camera_image'" <<<"$out" || { echo "expected the camera image key" >&2; exit 1; }
grep -q "'valid': 1" <<<"$out" || { echo "expected one validation demo" >&2; exit 1; }
out=$(/usr/bin/python3 "$check" "$work/s/session.hdf5")
echo "$out"
grep -q "2 demos" <<<"$out" || { echo "expected the index to list the 2 good demos" >&2; exit 1; }
