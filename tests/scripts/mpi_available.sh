#!/usr/bin/env bash
# Exits 77 (CTest's "skipped") unless mpirun is installed and GLINT_BINARY can join an MPI
# job; the MPI tests run it first. Usage: mpi_available.sh GLINT_BINARY
if ! command -v mpirun >/dev/null; then
  echo "SKIPPED: mpirun is not installed (scripts/install-deps.sh installs openmpi-bin)"
  exit 77
fi
if ! "$1" --version | grep -q "(with MPI)"; then
  echo "SKIPPED: $1 was built without MPI"
  exit 77
fi
