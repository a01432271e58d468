#!/usr/bin/env bash
# The denoiser against converged references (issue 25's table): for each scene, a reference of
# REF_SPP samples (cached in build/denoise-refs/), a render of SPP samples with --denoise, and
# the true MSE and relMSE of the noisy and the denoised beauty. "equal time" scales the noisy
# MSE by render / (render + denoise) seconds, as an unbiased render's MSE falls with 1 / time.
# The reference's own noise is removed from both MSEs with its variance layer (E[(a - r)^2] =
# MSE(a) + Var(r) for independent noise), so a reference of moderate sample count serves.
# Usage: bench/denoise_table.sh [SPP] [REF_SPP] [SCENE...]   (defaults 16, 256, five built-ins)
set -euo pipefail
cd "$(dirname "$0")/.."
caligo=build/release/apps/caligo/caligo
spp=${1:-16} ref_spp=${2:-256}
shift $(( $# > 2 ? 2 : $# ))
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(default stage many-lamps cloud hdri-fog)
res=${RES:-200x150}
refs=build/denoise-refs out=build/denoise-table
mkdir -p "$refs" "$out"
echo "MSE: against the reference, less its own variance; relMSE: raw"
echo
echo "| scene | spp | MSE noisy | MSE denoised | ratio | ratio at equal time | relMSE noisy | relMSE denoised | render s | denoise s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  ref="$refs/$s-$res-$ref_spp.exr"
  [ -f "$ref" ] || "$caligo" render "$s" --res $res --spp "$ref_spp" --seed 1234567 --aov default,variance -q -o "$ref"
  log=$("$caligo" render "$s" --res $res --spp "$spp" --denoise -o "$out/$s.exr" 2>&1 >/dev/null)
  render=$(sed -n 's/.*two halves in \([0-9.]*\) s.*/\1/p' <<<"$log")
  denoise=$(sed -n 's/.*denoised in \([0-9.]*\) s.*/\1/p' <<<"$log")
  m=$("$caligo" denoise "$out/$s.exr" -o "$out/$s-d.exr" --reference "$ref" -q)
  get() { sed -n "s/^$1 //p" <<<"$m"; }
  python3 - "$s" "$spp" "$(get mse_noisy_corrected)" "$(get mse_denoised_corrected)" "$(get relmse_noisy)" "$(get relmse_denoised)" "$render" "$denoise" <<'PY'
import sys
s, spp, mn, md, rn, rd, tr, td = sys.argv[1:]
mn, md, rn, rd, tr, td = map(float, (mn, md, rn, rd, tr, td))
eq = mn * tr / (tr + td)
print(f"| {s} | {spp} | {mn:.4g} | {md:.4g} | {mn/md:.1f}x | {eq/md:.1f}x | {rn:.4g} | {rd:.4g} | {tr:.2f} | {td:.2f} |")
PY
done
echo
echo "strips (noisy | denoised | reference | error): $out/*-d.strip.png"
