#!/usr/bin/env bash
# bench/fit-procedural-band-limit.sh BUILD [ARGS...] — the procedural textures' band limit from the
# noise itself (docs/method.md#the-band-limit): one octave's autocorrelation over the footprint's
# Gaussian measured by Monte Carlo, the closed form's c fitted to it for n and for |n|, then
# held-out grazing planes (75°–88°, scales 2–12) rendered band-limited at 1 spp against 16 and
# 1024 point samples per pixel. ARGS go to the program (--pairs N, --reference-spp N,
# --curves-only, --views-only). BUILD holds footprint-fit-procedural-band-limit (`make`, or
# `ninja -C BUILD footprint-fit-procedural-band-limit`). About 3 minutes on one core.
set -euo pipefail
build=${1:?usage: bench/fit-procedural-band-limit.sh BUILD [ARGS...]}
shift
exec "$build/footprint-fit-procedural-band-limit" "$@"
