#!/usr/bin/env bash
# Usage: raster_scenario.sh SOURCE_DIR OUT N
# CTest fixture of the mpi label: writes OUT/raster.msh (examples/12_particles_mpi/make_raster.py,
# N x N particles in particles.geo's row order) and OUT/scenario.toml (example 12's template:
# example 04's grains, groups, velocities, contact and time step). At N = 50 these are example
# 04's 2 500 particles, read from a .msh in ~0.2 s instead of meshed by Gmsh from particles.geo in
# ~4 s by every process of every run (the particle tests below run ~60 processes).
set -euo pipefail
src=$1 out=$2 n=$3
mkdir -p "$out"
/usr/bin/python3 "$src/examples/12_particles_mpi/make_raster.py" "$n" "$out/raster.msh" --order rows
sed -e "s/@N@/$n/g" -e "s/@END_TIME@/0.01/" -e "s/@INTERVAL@/0.0005/" \
    "$src/examples/12_particles_mpi/scenario.toml.in" >"$out/scenario.toml"
echo "OK: $out/scenario.toml"
