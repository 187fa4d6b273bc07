# Sourced by the benchmark scripts: the machine line every figure is read against, and the mesh
# the construction benchmarks read. WHAT is "brain" (the MRI
# isosurface of ch2better.nii.gz from mricron-data at 60, resampled 2x: 9.1M triangles), a
# triangle count (a generated bumpy torus of at least that many) or a mesh file.

# what_scratch_options ARGUMENT...: reads the scripts' arguments, WHAT [SCRATCH_DIR] [-- OPTION...],
# into $what (default brain), $given_scratch (empty when none) and the array $options (what
# follows "--", for the atp command the script runs).
what_scratch_options() {
  what=${1:-brain}
  given_scratch=
  [ $# -ge 2 ] && [ "$2" != -- ] && given_scratch=$2
  options=()
  for ((i = 1; i <= $#; ++i)); do
    if [ "${!i}" = -- ]; then
      options=("${@:i+1}")
      break
    fi
  done
}

# scratch_dir GIVEN [PREFIX]: sets $scratch to GIVEN, made if missing and kept afterwards, or
# without GIVEN to a new directory under /tmp (named PREFIX.XXXXXX, atp-bench by default), which
# remove_scratch then removes.
scratch_dir() {
  if [ -n "$1" ]; then
    scratch=$1
    mkdir -p "$scratch"
    own_scratch=
  else
    scratch=$(mktemp -d "/tmp/${2:-atp-bench}.XXXXXX")
    own_scratch=1
  fi
}

# remove_scratch FILE...: removes the files, then the scratch directory if scratch_dir made it.
remove_scratch() {
  rm -f "$@"
  [ -z "$own_scratch" ] || rmdir "$scratch" 2>/dev/null || true
}

# input_path WHAT SCRATCH: sets $input, WHAT itself for a file, else input.ply in SCRATCH.
input_path() {
  input=$2/input.ply
  if [ -f "$1" ]; then
    input=$1
  fi
}

# make_input WHAT: builds the programs if needed and writes $input unless WHAT is a file.
make_input() {
  [ -x build/bin/atp ] && [ -x build/bin/atp-bench-brain-surface ] || bash scripts/build.sh
  if [ "$input" != "$1" ]; then
    if [ "$1" = brain ]; then
      build/bin/atp-bench-brain-surface "$input" 2 60
    else
      build/bin/atp generate -n "$1" -o "$input"
    fi
  fi
}

# The machine, for every figure printed after it.
machine() {
  echo "machine: $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)$*"
}
